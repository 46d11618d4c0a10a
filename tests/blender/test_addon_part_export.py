"""Export STEP and Export Drawing (Results panel) on a run collection: the run's stored file written byte for
byte, and bad paths as one report sentence with nothing written.

The run collection carries hand-made files the way Generate stores write_outputs' folder (the PDF, binary, as
base64 text), so the operators are tested apart from the native writers; the writers' own tests check the
STEP and PDF contents.

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
"""
import json
import os
import tempfile
import unittest

import bpy

from test_addon_support import clean_scene, enable_addon

STEP = "ISO-10303-21;\nHEADER;\nFILE_NAME('avionics_box');\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n"
PDF = b"%PDF-1.5\n%\xe2\xe3\xcf\xd3\n1 0 obj\n<<>>\nendobj\n\x00\xff trailer\n%%EOF\n"


def run_collection():
    from sheetgen_blender import results
    from sheetgen_blender.core import jsonio
    clean_scene()
    col = bpy.data.collections.new("sheetgen run 1")
    bpy.context.scene.collection.children.link(col)
    col[results.KEY_RESULT] = json.dumps({"format": "sheetgen-result/1",
                                          "parts": [{"load": "avionics_box", "status": "ok"},
                                                    {"load": "psu", "status": "no_valid_part"}]})
    col[results.KEY_FILES] = {"result.json": "{}",
                              "avionics_box/part.step": jsonio.file_to_text(STEP.encode()),
                              "avionics_box/flat.step": jsonio.file_to_text(STEP.replace("box", "box flat").encode()),
                              "avionics_box/drawing.pdf": jsonio.file_to_text(PDF)}
    bpy.context.scene.sheetgen.result_collection = col
    return col


class PartExport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        enable_addon()

    def setUp(self):
        run_collection()

    def test_step_flat_step_and_drawing(self):
        with tempfile.TemporaryDirectory() as d:
            self.assertEqual(bpy.ops.sheetgen.export_step(load="avionics_box", filepath=os.path.join(d, "part")),
                             {'FINISHED'})
            self.assertEqual(bpy.ops.sheetgen.export_step(load="avionics_box", flat=True,
                                                          filepath=os.path.join(d, "flat.stp")), {'FINISHED'})
            self.assertEqual(bpy.ops.sheetgen.export_drawing(load="avionics_box",
                                                             filepath=os.path.join(d, "sheet.pdf")), {'FINISHED'})
            self.assertEqual(sorted(os.listdir(d)), ["flat.stp", "part.step", "sheet.pdf"])
            with open(os.path.join(d, "part.step")) as f:
                self.assertEqual(f.read(), STEP)
            with open(os.path.join(d, "flat.stp")) as f:
                self.assertIn("avionics_box flat", f.read())
            with open(os.path.join(d, "sheet.pdf"), "rb") as f:
                self.assertEqual(f.read(), PDF)

    def test_bad_paths_are_one_sentence_and_write_nothing(self):
        with tempfile.TemporaryDirectory() as d:
            cases = [
                (dict(load="avionics_box", filepath=os.path.join(d, "no", "such", "p.step")),
                 "cannot write %s: the folder %s does not exist" % (os.path.join(d, "no", "such", "p.step"),
                                                                    os.path.join(d, "no", "such"))),
                (dict(load="avionics_box", filepath=d), "%s is a folder: give a file name for the bent part STEP" % d),
                (dict(load="psu", filepath=os.path.join(d, "p.step")),
                 "load 'psu' has no valid part in this run, so no bent part STEP"),
            ]
            for kwargs, message in cases:
                with self.assertRaises(RuntimeError) as ctx:     # an ERROR report, not a traceback
                    bpy.ops.sheetgen.export_step(**kwargs)
                self.assertEqual(str(ctx.exception).strip(), "Error: " + message)
            with self.assertRaises(RuntimeError) as ctx:
                bpy.ops.sheetgen.export_drawing(load="avionics_box", filepath="/proc/sheetgen_drawing.pdf")
            self.assertTrue(str(ctx.exception).startswith("Error: cannot write /proc/sheetgen_drawing.pdf: "))
            self.assertEqual(os.listdir(d), [])


if __name__ == "__main__":
    unittest.main()
