"""Finding the native module ``_sheetgen_native`` (no bpy).

Looked for first beside this package (scripts/install_addon.sh copies it
there), then on sys.path (e.g. BUILD_DIR/python in the tests). A module that
cannot be loaded never breaks add-on registration: ``error()`` holds one
sentence that the panel shows and operators report.
"""
import importlib
import os
import sys
import sysconfig

MODULE = "_sheetgen_native"
_HERE = os.path.dirname(os.path.abspath(__file__))
_module = None
_error = None
_tried = False


def _load():
    global _module, _error, _tried
    _tried = True
    errors = []
    suffix = sysconfig.get_config_var("EXT_SUFFIX") or ".so"
    if os.path.exists(os.path.join(_HERE, MODULE + suffix)):
        try:
            _module = importlib.import_module(__package__ + "." + MODULE)
            return
        except ImportError as e:
            errors.append("beside the add-on: %s" % e)
    try:
        _module = importlib.import_module(MODULE)
        return
    except ImportError as e:
        if not errors:
            others = [f for f in os.listdir(_HERE) if f.startswith(MODULE)] if os.path.isdir(_HERE) else []
            hint = (" (found %s, but this Blender's Python %d.%d needs %s%s)"
                    % (", ".join(others), sys.version_info[0], sys.version_info[1], MODULE, suffix)) if others else ""
            errors.append("not beside the add-on in %s%s, nor on sys.path" % (_HERE, hint))
        else:
            errors.append("on sys.path: %s" % e)
    _error = ("sheetgen native module %s could not be loaded: %s. Build it (cmake --build build --target %s) "
              "and run scripts/install_addon.sh" % (MODULE, "; ".join(errors), MODULE))


def get():
    """The native module, or None (then ``error()`` says why)."""
    if not _tried:
        _load()
    return _module


def error():
    """Why the native module is missing, or None when it loaded."""
    get()
    return _error


def reset():
    """Forget the previous attempt (tests; a rebuilt module still needs a Blender restart)."""
    global _module, _error, _tried
    _module, _error, _tried = None, None, False
