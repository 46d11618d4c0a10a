"""The bpy-free core of the sheetgen add-on (docs/code-style.md point 9).

Everything here is plain Python (no ``bpy``, no numpy) and is tested outside
Blender by ``tests/python/test_addon_core_*.py``:

- ``model``: the scene as plain data (meshes in world space, rivet-area ids per
  triangle, load boxes with their cases and mass, the envelope, settings with
  the defaults of docs/problem-format.md);
- ``problem``: scene data <-> ``sheetgen-problem/1`` dict, with validation
  messages that name the object and the field;
- ``geometry``: triangle areas, quaternions, float32 number cleaning;
- ``jsonio``: compact JSON text and atomic file writes;
- ``result``: a ``sheetgen-result/1`` document -> plain mesh data (bent part,
  flat pattern split at its bend lines, rivet markers) and report numbers;
- ``flatplot``: the flat pattern as a PNG (matplotlib, imported lazily);
- ``modes``: a part's buckling and vibration modes (from the native
  ``part_modes``) as a mesh with shape-key positions;
- ``part_export``: Export STEP / Export Drawing, one of a run's files of a
  load written to a path the user names (checked, atomic, one-sentence errors).
"""
