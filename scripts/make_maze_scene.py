#!/usr/bin/env python3
"""Writes sample_scenes/maze (problem JSON + OBJ meshes): the ablation scene of
Barda et al. 2023, Fig. 13(a), for the discovery policies (docs/ablation_discovery.md).

Run from anywhere: python3 scripts/make_maze_scene.py. Pure standard library.
A corridor along +x (floor z = 0, side walls y = +-0.2 m) divided by four
baffles into five cells; each baffle leaves a 0.16 m gap at alternating sides,
so the path from the load (above the first cell's left end) to the far cells
winds. Five floor rivet areas RA1..RA5, one per cell, at increasing distance
from the load: the near ones are easy to reach, the far ones need long,
bent feelers. Numbers (SI): load as in make_sample_scenes.py (4 kg at 9 g).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_sample_scenes import Mesh, faces_in, write_problem, LOAD_FORCE  # noqa: E402

CELL = 0.25      # m, cell length along x
HEIGHT = 0.45    # m, side wall height
BAFFLE = 0.20    # m, baffle height: below the base tab (z = 0.27 m), so feelers pass over and dive into the cells
GAP = 0.16       # m, opening left by each baffle


def maze():
    floor, sides, baffles = Mesh(), Mesh(), Mesh()
    # floor x in [0, 1.25], y in [-0.2, 0.2], 0.05 m cells (normal +z)
    cells = floor.grid([0, -0.2, 0], [5 * CELL, 0, 0], [0, 0.4, 0], 25, 8)
    # side walls facing into the corridor
    sides.grid([0, -0.2, 0], [0, 0, HEIGHT], [5 * CELL, 0, 0], 5, 5)       # y = -0.2, normal +y
    sides.grid([0, 0.2, 0], [5 * CELL, 0, 0], [0, 0, HEIGHT], 5, 5)        # y = +0.2, normal -y
    # baffles: thin closed boxes 10 mm thick at x = k * CELL, gap alternating at +y / -y
    for k in range(1, 5):
        x = k * CELL
        if k % 2 == 1:
            baffles.box([x - 0.005, -0.2, 0.0], [x + 0.005, 0.2 - GAP, BAFFLE])
        else:
            baffles.box([x - 0.005, -0.2 + GAP, 0.0], [x + 0.005, 0.2, BAFFLE])
    # RA_i: 0.1 x 0.2 m floor patch in the middle of cell i (grid cells of 0.05 m)
    ras = []
    for i in range(5):
        i0 = 5 * i + 1
        ras.append({"name": "RA%d" % (i + 1), "mesh": "floor", "faces": faces_in(cells, (i0, i0 + 3), (2, 6))})
    loads = [{"name": "avionics_box", "center": [0.09, 0.0, 0.30], "size": [0.12, 0.10, 0.06],
              "rotation": [1, 0, 0, 0], "force": LOAD_FORCE, "moment": [0, 0, 0]}]
    write_problem("maze", [("floor", floor), ("sides", sides), ("baffles", baffles)], ras, loads,
                  "Maze for the discovery ablation (paper Fig. 13): five floor rivet areas in a row "
                  "behind alternating baffles, away from the load")


if __name__ == "__main__":
    maze()
    print("wrote maze")
