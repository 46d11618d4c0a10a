"""scripts/install_addon.sh puts the add-on and the native module into a Blender scripts folder.

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
"""
import filecmp
import os
import subprocess
import tempfile
import unittest

from test_addon_support import ROOT


class InstallScript(unittest.TestCase):
    def test_copy_install_layout(self):
        import _sheetgen_native  # BUILD_DIR/python, put on sys.path by run.py
        so = os.path.abspath(_sheetgen_native.__file__)
        build_dir = os.path.dirname(os.path.dirname(so))
        with tempfile.TemporaryDirectory() as scripts:
            run = subprocess.run(["bash", os.path.join(ROOT, "scripts", "install_addon.sh"), "--build-dir", build_dir,
                                  "--scripts-dir", scripts], capture_output=True, text=True, timeout=120)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(run.stderr, "")          # no "does not match this Blender's Python" warning
            dest = os.path.join(scripts, "addons", "sheetgen_blender")
            src = os.path.join(ROOT, "blender_addon", "sheetgen_blender")
            want = sorted(os.path.relpath(os.path.join(d, f), src) for d, _, fs in os.walk(src)
                          for f in fs if f.endswith(".py"))
            got = sorted(os.path.relpath(os.path.join(d, f), dest) for d, _, fs in os.walk(dest) for f in fs)
            self.assertEqual(got, sorted(want + [os.path.basename(so)]))
            self.assertTrue(filecmp.cmp(so, os.path.join(dest, os.path.basename(so)), shallow=False))


if __name__ == "__main__":
    unittest.main()
