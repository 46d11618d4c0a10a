"""The native module `_sheetgen_native` of a build folder, for the tests that
check the add-on's pure-Python core against it and skip when it is not built."""
import os
import sys

from . import paths


def native_or_none(needs=None):
    """_sheetgen_native from $SHEETGEN_BUILD_DIR/python (default: build/), or
    None when it is not built or, with `needs`, lacks that attribute (a build
    older than the function a test checks)."""
    build = os.environ.get("SHEETGEN_BUILD_DIR", paths.DEFAULT_BUILD)
    sys.path.insert(0, os.path.join(build, "python"))
    try:
        import _sheetgen_native
        return _sheetgen_native if needs is None or hasattr(_sheetgen_native, needs) else None
    except ImportError:
        return None
    finally:
        sys.path.pop(0)
