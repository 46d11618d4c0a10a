"""sheetgen: design sheet-metal brackets from a tagged Blender scene.

Panels in the 3D View sidebar, tab "Sheet Metal". Everything that computes is
in the native module ``_sheetgen_native`` (found beside this package or on
sys.path, see native.py); the scene <-> problem conversion is the bpy-free
``core`` package. Importing this package does not import bpy: the core can be
tested outside Blender.
"""

bl_info = {
    "name": "sheetgen",
    "author": "sheetgen",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Sheet Metal",
    "description": "Tag rivet areas and loads, generate sheet-metal brackets, render and export them",
    "category": "Object",
}

_MODULES = ("properties", "operators", "generate", "panels")


def _modules():
    import importlib
    return [importlib.import_module(__name__ + "." + m) for m in _MODULES]


def register():
    from . import native
    for m in _modules():
        m.register()
    if native.error():
        # Registration still succeeds: the panel shows the sentence, Check reports it.
        print("sheetgen: " + native.error())


def unregister():
    for m in reversed(_modules()):
        m.unregister()
