"""The place for Generate (not implemented: it waits for the native ``generate()``).

Nothing here is registered. When ``_sheetgen_native.generate(problem, progress)``
exists (DESIGN.md "Interfaces"), the operator goes in this module:

- ``execute()``: synchronous (``blender -b`` calls it even for INVOKE_DEFAULT):
  ``problem, warnings = operators.build_problem(context)`` -> ``native.get().generate(problem, progress)``
  -> result import.
- ``invoke()``: the same problem dict built on the main thread, ``generate`` run
  in a worker thread (the native code releases the GIL), a modal timer polls the
  progress and Esc sets the cancel flag; the worker never touches ``bpy``
  (NOTES.md "Blender 3.4 facts").
- Result import (a bpy-free ``core/result.py`` for ``sheetgen-result/1`` ->
  plain parts, plus a bpy builder): bent object with Solidify to the thickness,
  flat-pattern object with bend lines as an EDGE attribute / seams, the report
  numbers on the objects; marked ``sheetgen.exclude`` so a later problem does
  not treat them as environment (or, per DESIGN.md, as obstacles for the next load).

Then register the class in ``__init__.py`` and replace the disabled label in
``panels.SHEETGEN_PT_main`` by the operator button.
"""
