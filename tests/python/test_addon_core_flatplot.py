"""The add-on core's flat-pattern plot, outside Blender: bend labels stay readable.

Run: /usr/bin/python3 -m unittest discover -s tests/python -p 'test_addon_core_*.py'

A 120 x 80 mm plate with a leg and its flange folded off one side: two parallel
bend lines 16 mm apart, whose labels printed over each other before the plot
placed them clear of one another (the right-angle bay's battery).
"""
import itertools
import os
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

from sheetgen_blender.core import flatplot  # noqa: E402


def part(bends):
    outline = [[0.0, 0.0], [0.12, 0.0], [0.12, 0.08], [0.0, 0.08]]
    return {"load": "box", "status": "ok", "area_m2": 0.0096,
            "flat_pattern": {"area_m2": 0.0096, "outline": [outline], "reliefs": [],
                             "bends": [{"a": [x, 0.0], "b": [x, 0.08], "angle": 1.5708, "direction": "down",
                                        "number": i + 1} for i, x in enumerate(bends)]}}


def label_boxes(p):
    fig, labels = flatplot.build_figure(p)
    fig.canvas.draw()  # the final layout, as savefig would make it
    renderer = fig.canvas.get_renderer()
    return [label.get_window_extent(renderer) for label in labels]


class FlatPlotLabels(unittest.TestCase):
    def test_matplotlib_is_there(self):
        self.assertTrue(flatplot.available(), "python3-matplotlib is a dependency (scripts/install_deps.sh)")

    def test_labels_of_close_bends_do_not_overlap(self):
        boxes = label_boxes(part([0.096, 0.104, 0.112]))  # 8 mm apart, closer than a label is wide
        self.assertEqual(len(boxes), 3)
        for a, b in itertools.combinations(boxes, 2):
            self.assertFalse(a.overlaps(b), "labels overlap: %s and %s" % (a, b))

    def test_a_lone_bend_keeps_its_label_next_to_the_line(self):
        fig, labels = flatplot.build_figure(part([0.06]))
        self.assertEqual(len(labels), 1)
        # The first place tried: 14 points beside the line, none along it.
        dx, dy = labels[0].xyann
        self.assertAlmostEqual(abs(dx), 14.0, places=6)
        self.assertAlmostEqual(dy, 0.0, places=6)

    def test_holes_are_circles_of_their_diameter(self):
        p = part([0.06])
        p["flat_pattern"]["holes"] = [{"kind": "flange", "centre": [0.03, 0.04], "diameter": 0.004},
                                      {"kind": "self", "centre": [0.09, 0.04], "diameter": 0.004}]
        fig, _ = flatplot.build_figure(p)
        from matplotlib.patches import Circle
        circles = [c for c in fig.axes[0].patches if isinstance(c, Circle)]
        self.assertEqual([(c.center, c.radius) for c in circles], [((30.0, 40.0), 2.0), ((90.0, 40.0), 2.0)])  # mm
        self.assertNotEqual(circles[0].get_edgecolor(), circles[1].get_edgecolor())

    def test_draw_writes_a_png(self):
        import tempfile
        with tempfile.TemporaryDirectory() as tmp:
            path = flatplot.draw(part([0.03, 0.09]), os.path.join(tmp, "flat.png"))
            with open(path, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
