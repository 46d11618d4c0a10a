"""sample_scenes/ is what sheetgen_tools.scenes writes: every problem.json and
OBJ file regenerated into a temporary folder is byte for byte the committed
one, and the generator writes every scene folder there is (scene.blend, made
from the problem inside Blender by scripts/make_sample_blends.py, aside)."""
import contextlib
import filecmp
import io
import os
import tempfile
import unittest

from sheetgen_tools import paths, scenes


class ScenesReproduce(unittest.TestCase):
    def test_generator_writes_the_committed_scenes(self):
        with tempfile.TemporaryDirectory() as out:
            with contextlib.redirect_stdout(io.StringIO()):
                self.assertEqual(scenes.main(["--out", out]), 0)
            self.assertEqual(sorted(os.listdir(out)), paths.sample_scene_names())
            for name in sorted(os.listdir(out)):
                written = sorted(os.listdir(os.path.join(out, name)))
                committed = sorted(f for f in os.listdir(os.path.join(paths.SAMPLE_SCENES, name)) if f != "scene.blend")
                self.assertEqual(written, committed, name)
                _, mismatch, errors = filecmp.cmpfiles(os.path.join(out, name), os.path.join(paths.SAMPLE_SCENES, name),
                                                       written, shallow=False)
                self.assertEqual(mismatch + errors, [], name)

    def test_library_order_names_every_scene(self):
        self.assertEqual(sorted(scenes.LIBRARY), paths.sample_scene_names())


if __name__ == "__main__":
    unittest.main()
