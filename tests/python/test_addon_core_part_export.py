"""The add-on core's per-part exports (core/part_export.py: Export STEP, Export Drawing), outside Blender.

Run: /usr/bin/python3 -m unittest discover -s tests/python -p 'test_addon_core_*.py'

A run's files as the run collection stores them (jsonio.file_to_text: the PDF, binary, as base64
text): every kind is written byte for byte; every bad path or missing file is one sentence and
leaves the target folder as it was.
"""
import os
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

from sheetgen_blender.core import jsonio  # noqa: E402
from sheetgen_blender.core import part_export as E  # noqa: E402

STEP = "ISO-10303-21;\nHEADER;\nFILE_NAME('bracket');\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n"
FLAT = STEP.replace("bracket", "bracket flat pattern")
PDF = b"%PDF-1.5\n%\xe2\xe3\xcf\xd3\n1 0 obj\n<<>>\nendobj\n\x00\xff trailer\n%%EOF\n"   # not UTF-8
DOC = {"parts": [{"load": "radio box", "status": "ok"}, {"load": "psu", "status": "no_valid_part"}]}


def run_files():
    return {"result.json": "{}", "radio box/part.step": jsonio.file_to_text(STEP.encode()),
            "radio box/flat.step": jsonio.file_to_text(FLAT.encode()),
            "radio box/drawing.pdf": jsonio.file_to_text(PDF)}


class Writes(unittest.TestCase):
    def test_each_kind_byte_for_byte(self):
        self.assertTrue(run_files()["radio box/drawing.pdf"].startswith("base64:"))
        with tempfile.TemporaryDirectory() as d:
            for kind, name, data in (("PART_STEP", "a.step", STEP.encode()), ("FLAT_STEP", "b.stp", FLAT.encode()),
                                     ("DRAWING", "c.pdf", PDF)):
                path = E.export(run_files(), DOC, "radio box", kind, os.path.join(d, name))
                self.assertEqual(path, os.path.join(d, name))
                with open(path, "rb") as f:
                    self.assertEqual(f.read(), data)
            self.assertEqual(sorted(os.listdir(d)), ["a.step", "b.stp", "c.pdf"])   # no temporary file left

    def test_extension_added_when_missing_and_file_replaced(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "bracket.step"), "w") as f:
                f.write("old")
            self.assertEqual(E.export(run_files(), DOC, "radio box", "PART_STEP", os.path.join(d, "bracket")),
                             os.path.join(d, "bracket.step"))
            self.assertEqual(E.export(run_files(), DOC, "radio box", "DRAWING", os.path.join(d, "sheet.PDF")),
                             os.path.join(d, "sheet.PDF"))
            self.assertEqual(E.export(run_files(), DOC, "radio box", "DRAWING", os.path.join(d, "sheet")),
                             os.path.join(d, "sheet.pdf"))
            with open(os.path.join(d, "bracket.step")) as f:
                self.assertEqual(f.read(), STEP)
            self.assertEqual(sorted(os.listdir(d)), ["bracket.step", "sheet.PDF", "sheet.pdf"])

    def test_default_names(self):
        self.assertEqual(E.default_name("radio box", "PART_STEP"), "radio_box.step")
        self.assertEqual(E.default_name("radio box", "FLAT_STEP"), "radio_box_flat.step")
        self.assertEqual(E.default_name("a/b", "DRAWING"), "a_b_drawing.pdf")


class Errors(unittest.TestCase):
    def fails(self, message, path, load="radio box", kind="PART_STEP", files=None):
        with tempfile.TemporaryDirectory() as d:
            before = sorted(os.listdir(d))
            with self.assertRaises(E.ExportError) as ctx:
                E.export(run_files() if files is None else files, DOC, load, kind, path.replace("TMP", d))
            self.assertEqual(str(ctx.exception), message.replace("TMP", d))
            self.assertNotIn("\n", str(ctx.exception))
            self.assertEqual(sorted(os.listdir(d)), before)   # nothing written, nothing half-written

    def test_bad_paths(self):
        self.fails("no file name given for the bent part STEP", "")
        self.fails("TMP is a folder: give a file name for the bent part STEP", "TMP")
        self.fails("TMP/ is a folder: give a file name for the drawing sheet", "TMP/", kind="DRAWING")
        self.fails("cannot write TMP/nowhere/p.step: the folder TMP/nowhere does not exist", "TMP/nowhere/p.step")

    def test_a_file_where_the_folder_should_be(self):
        with tempfile.NamedTemporaryFile() as f:
            self.fails("cannot write %s/p.step: the folder %s does not exist" % (f.name, f.name), f.name + "/p.step")

    def test_unwritable_folder(self):
        # /proc refuses new files even to root (the tests may run as root, for whom chmod 0555 is no bar).
        with self.assertRaises(E.ExportError) as ctx:
            E.export(run_files(), DOC, "radio box", "DRAWING", "/proc/sheetgen_drawing.pdf")
        self.assertRegex(str(ctx.exception), r"^cannot write /proc/sheetgen_drawing\.pdf: [A-Z][a-z ]+$")
        self.assertFalse(any(n.startswith(".sheetgen_drawing") for n in os.listdir("/proc")))
        if os.geteuid() != 0:
            with tempfile.TemporaryDirectory() as d:
                os.chmod(d, 0o555)
                try:
                    with self.assertRaises(E.ExportError) as ctx:
                        E.export(run_files(), DOC, "radio box", "DRAWING", os.path.join(d, "x.pdf"))
                    self.assertEqual(str(ctx.exception), "cannot write %s/x.pdf: Permission denied" % d)
                    self.assertEqual(os.listdir(d), [])
                finally:
                    os.chmod(d, 0o755)

    def test_loads_and_files_the_run_does_not_have(self):
        self.fails("load 'fan' is not in this run (loads: psu, radio box)", "TMP/p.step", load="fan")
        self.fails("load 'psu' has no valid part in this run, so no drawing sheet", "TMP/p.pdf", load="psu",
                   kind="DRAWING")
        refused = {k: v for k, v in run_files().items() if k != "radio box/part.step"}
        refused["radio box/part_step_error.txt"] = "BRepCheck: the offset solid is not valid (face 12)\n"
        self.fails("no bent part STEP for 'radio box': BRepCheck: the offset solid is not valid (face 12)",
                   "TMP/p.step", files=refused)
        with tempfile.TemporaryDirectory() as d:   # the flat pattern's STEP is still there
            E.export(refused, DOC, "radio box", "FLAT_STEP", os.path.join(d, "f.step"))
        old = {k: v for k, v in run_files().items() if not k.endswith(".step")}
        self.fails("this run has no flat pattern STEP for 'radio box' (radio box/flat.step): it was made before "
                   "sheetgen wrote one; Re-run to make it", "TMP/p.step", kind="FLAT_STEP", files=old)


class Make(unittest.TestCase):
    """``make``: the writer the add-on passes for a run without the file (the native write_drawing)."""

    def old_run(self):
        return {k: v for k, v in run_files().items() if k.endswith(".json")}

    def test_used_only_when_the_run_lacks_the_file(self):
        calls = []

        def make(kind, load, path):
            calls.append((kind, load, os.path.basename(path)))
            with open(path, "wb") as f:
                f.write(b"%PDF-made")
        with tempfile.TemporaryDirectory() as d:
            E.export(run_files(), DOC, "radio box", "DRAWING", os.path.join(d, "a.pdf"), make=make)
            self.assertEqual(calls, [])                        # the run's own file first
            path = E.export(self.old_run(), DOC, "radio box", "DRAWING", os.path.join(d, "b"), make=make)
            self.assertEqual(calls, [("DRAWING", "radio box", "b.pdf")])
            with open(path, "rb") as f:
                self.assertEqual(f.read(), b"%PDF-made")
            with self.assertRaises(E.ExportError):             # no valid part: make is not asked
                E.export(self.old_run(), DOC, "psu", "DRAWING", os.path.join(d, "c.pdf"), make=make)
            self.assertEqual(len(calls), 1)

    def test_its_errors_are_one_sentence(self):
        def cannot(kind, load, path):
            raise NotImplementedError(kind)

        def fails(kind, load, path):
            raise RuntimeError("cannot write %s: No space left on device\n(detail)" % path)
        with tempfile.TemporaryDirectory() as d:
            with self.assertRaises(E.ExportError) as ctx:
                E.export(self.old_run(), DOC, "radio box", "PART_STEP", os.path.join(d, "p.step"), make=cannot)
            self.assertEqual(str(ctx.exception), "this run has no bent part STEP for 'radio box' "
                             "(radio box/part.step): it was made before sheetgen wrote one; Re-run to make it")
            with self.assertRaises(E.ExportError) as ctx:
                E.export(self.old_run(), DOC, "radio box", "DRAWING", os.path.join(d, "p.pdf"), make=fails)
            self.assertEqual(str(ctx.exception), "cannot write %s: No space left on device" % os.path.join(d, "p.pdf"))
            self.assertEqual(os.listdir(d), [])


if __name__ == "__main__":
    unittest.main()
