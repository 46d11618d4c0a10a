"""Runs every tests/blender/test_*.py inside Blender with unittest.

blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
Exits non-zero (through --python-exit-code) when any test fails: pytest is not
importable in Blender's Python here (docs/platform.md).
"""
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
build_dir = os.path.abspath(argv[0]) if argv else os.path.join(os.path.dirname(os.path.dirname(HERE)), "build")
sys.path.insert(0, os.path.join(build_dir, "python"))
sys.path.insert(0, HERE)

suite = unittest.defaultTestLoader.discover(HERE, pattern="test_*.py")
result = unittest.TextTestRunner(verbosity=2).run(suite)
print("blender tests: %d passed, %d failed" % (result.testsRun - len(result.failures) - len(result.errors) - len(result.skipped),
                                               len(result.failures) + len(result.errors)))
if not result.wasSuccessful() or result.testsRun == 0:
    raise SystemExit(1)
