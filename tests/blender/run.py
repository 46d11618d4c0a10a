"""Runs every tests/blender/test_*.py inside Blender with unittest.

blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
Exits non-zero (through --python-exit-code) when any test fails: pytest is not
importable in Blender's Python here (docs/platform.md).
"""
import os
import sys
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
build_dir = os.path.abspath(argv[0]) if argv else os.path.join(os.path.dirname(os.path.dirname(HERE)), "build")
sys.path.insert(0, os.path.join(build_dir, "python"))
sys.path.insert(0, HERE)



class TimedResult(unittest.TextTestResult):
    """Keeps each test's wall time (Blender's Python 3.10 has no --durations), to find where the suite spends it."""

    def startTest(self, test):
        self._t0 = time.monotonic()
        super().startTest(test)

    def stopTest(self, test):
        super().stopTest(test)
        self.times = getattr(self, "times", []) + [(time.monotonic() - self._t0, test.id())]


suite = unittest.defaultTestLoader.discover(HERE, pattern="test_*.py")
result = unittest.TextTestRunner(verbosity=2, resultclass=TimedResult).run(suite)
print("slowest blender tests:")
for seconds, name in sorted(getattr(result, "times", []), reverse=True)[:10]:
    print("  %6.1f s  %s" % (seconds, name))
print("blender tests: %d passed, %d failed" % (result.testsRun - len(result.failures) - len(result.errors) - len(result.skipped),
                                               len(result.failures) + len(result.errors)))
if not result.wasSuccessful() or result.testsRun == 0:
    raise SystemExit(1)
