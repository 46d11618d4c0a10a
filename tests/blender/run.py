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
    """Keeps each test's wall time (Blender's Python 3.10 has no --durations), to find where the suite spends it.

    A class's time also counts the gaps between its tests: setUpClass and
    tearDownClass run there, and most of the Blender tests' time is a search
    their setUpClass runs once."""

    def startTestRun(self):
        self._last_stop = time.monotonic()   # the first class's setUpClass runs before its first test
        super().startTestRun()

    def startTest(self, test):
        now = time.monotonic()
        self._t0 = now
        self._gap = now - self._last_stop
        super().startTest(test)

    def stopTest(self, test):
        super().stopTest(test)
        now = time.monotonic()
        self._last_stop = now
        self.times = getattr(self, "times", []) + [(now - self._t0, test.id())]
        cls = test.id().rsplit(".", 1)[0]
        self.class_times = getattr(self, "class_times", {})
        self.class_times[cls] = self.class_times.get(cls, 0.0) + (now - self._t0) + self._gap


suite = unittest.defaultTestLoader.discover(HERE, pattern="test_*.py")
result = unittest.TextTestRunner(verbosity=2, resultclass=TimedResult).run(suite)
print("slowest blender tests:")
for seconds, name in sorted(getattr(result, "times", []), reverse=True)[:10]:
    print("  %6.1f s  %s" % (seconds, name))
print("slowest blender test classes (setUpClass included):")
for name, seconds in sorted(getattr(result, "class_times", {}).items(), key=lambda kv: -kv[1])[:10]:
    print("  %6.1f s  %s" % (seconds, name))
print("blender tests: %d passed, %d failed" % (result.testsRun - len(result.failures) - len(result.errors) - len(result.skipped),
                                               len(result.failures) + len(result.errors)))
if not result.wasSuccessful() or result.testsRun == 0:
    raise SystemExit(1)
