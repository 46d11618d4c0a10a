#!/usr/bin/env python3
"""Writes the sample problems in sample_scenes/ (problem JSON + OBJ meshes).

Run from anywhere: python3 scripts/make_sample_scenes.py. Pure standard library.
Every mesh is a grid of quads split into triangles, so rivet areas are exact
face subsets. Numbers (all SI):
  * load: an avionics box of 4 kg under a 9 g design load factor
    (4 kg * 9 * 9.81 m/s^2 = 353 N), mostly downward with a lateral share;
  * deflection limit 1 mm at the load;
  * Al 2024-T3 sheet 1.6 mm (the defaults of DESIGN.md).
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(os.path.dirname(HERE), "sample_scenes")


class Mesh:
    def __init__(self):
        self.v = []
        self.f = []

    def grid(self, origin, u, v, nu, nv):
        """A planar grid origin + a*u + b*v, a,b in [0,1]; returns the face ids per cell [i][j]."""
        base = len(self.v)
        for j in range(nv + 1):
            for i in range(nu + 1):
                self.v.append([origin[k] + u[k] * i / nu + v[k] * j / nv for k in range(3)])
        cells = {}
        for j in range(nv):
            for i in range(nu):
                a = base + j * (nu + 1) + i
                b, c, d = a + 1, a + nu + 2, a + nu + 1
                cells[(i, j)] = [len(self.f), len(self.f) + 1]
                self.f.append([a, b, c])
                self.f.append([a, c, d])
        return cells

    def box(self, lo, hi):
        """A closed axis-aligned box, outward normals."""
        base = len(self.v)
        for k in range(8):
            self.v.append([hi[0] if k & 1 else lo[0], hi[1] if k & 2 else lo[1], hi[2] if k & 4 else lo[2]])
        quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
        for q in quads:
            self.f.append([base + q[0], base + q[1], base + q[2]])
            self.f.append([base + q[0], base + q[2], base + q[3]])

    def write(self, path):
        with open(path, "w") as out:
            out.write("# sheetgen sample scene mesh, metres\n")
            for p in self.v:
                out.write("v %.9g %.9g %.9g\n" % tuple(p))
            for t in self.f:
                out.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def faces_in(cells, i_range, j_range):
    out = []
    for (i, j), fs in sorted(cells.items()):
        if i_range[0] <= i < i_range[1] and j_range[0] <= j < j_range[1]:
            out.extend(fs)
    return out


G = 9.81
LOAD_FORCE = [0.0, 0.0, -4.0 * 9.0 * G]  # 4 kg box, 9 g down


def write_problem(name, meshes, rivet_areas, loads, description):
    folder = os.path.join(OUT, name)
    os.makedirs(folder, exist_ok=True)
    entries = []
    for mname, mesh in meshes:
        mesh.write(os.path.join(folder, mname + ".obj"))
        entries.append({"name": mname, "file": mname + ".obj"})
    problem = {
        "format": "sheetgen-problem/1",
        "name": name,
        "description": description,
        "units": "m",
        "environment": {"meshes": entries},
        "rivet_areas": rivet_areas,
        "loads": loads,
        "requirements": {"max_deflection": 1.0e-3, "min_margin_of_safety": 0.0},
        "search": {"chains": 10, "iterations": 1000, "beam_width": 8, "seed": 1},
    }
    with open(os.path.join(folder, "problem.json"), "w") as out:
        json.dump(problem, out, indent=2)
        out.write("\n")


def corner(name, with_obstacle):
    # Wall in the plane x = 0 (facing +x), floor in z = 0 (facing +z); 0.6 m cells of 0.05 m.
    wall, floor = Mesh(), Mesh()
    wall_cells = wall.grid([0, -0.3, 0], [0, 0.6, 0], [0, 0, 0.6], 12, 12)   # normal (0.6,0,0)x... = +x
    floor_cells = floor.grid([0, -0.3, 0], [0.6, 0, 0], [0, 0.6, 0], 12, 12)  # normal +z
    meshes = [("wall", wall), ("floor", floor)]
    ras = [
        # wall strip y in [-0.15, 0.15], z in [0.20, 0.40]
        {"name": "wall_rivets", "mesh": "wall", "faces": faces_in(wall_cells, (3, 9), (4, 8))},
        # floor strip x in [0.15, 0.45], y in [-0.30, -0.20] and [0.20, 0.30] split in two areas
        {"name": "floor_left", "mesh": "floor", "faces": faces_in(floor_cells, (3, 9), (0, 2))},
        {"name": "floor_right", "mesh": "floor", "faces": faces_in(floor_cells, (3, 9), (10, 12))},
    ]
    if with_obstacle:
        obstacle = Mesh()
        obstacle.box([0.06, -0.08, 0.18], [0.12, 0.08, 0.42])  # a pipe housing between load and wall
        meshes.append(("obstacle", obstacle))
    loads = [{"name": "avionics_box", "center": [0.26, 0.0, 0.34], "size": [0.16, 0.12, 0.08],
              "rotation": [1, 0, 0, 0], "force": LOAD_FORCE, "moment": [0, 0, 0]}]
    desc = "Wall and floor corner, one 4 kg box at 9 g" + (", a pipe housing between box and wall" if with_obstacle else "")
    write_problem(name, meshes, ras, loads, desc)


def slanted(name):
    # A rivet plane tilted 45 degrees (a sloped frame web), plus a floor.
    s = math.sqrt(0.5)
    plane, floor = Mesh(), Mesh()
    # Plane through the line x = 0, z = 0 rising along +x+z at 45 degrees, spanning y in [-0.3, 0.3].
    cells = plane.grid([0, 0.3, 0], [0, -0.6, 0], [0.5 * s, 0, 0.5 * s], 12, 10)  # normal (-s,0,s): faces up-left
    floor_cells = floor.grid([0.45, -0.3, 0], [0.35, 0, 0], [0, 0.6, 0], 7, 12)
    ras = [
        {"name": "slope_rivets", "mesh": "slope", "faces": faces_in(cells, (2, 10), (5, 9))},
        {"name": "floor_rivets", "mesh": "floor", "faces": faces_in(floor_cells, (2, 6), (2, 10))},
    ]
    loads = [{"name": "avionics_box", "center": [0.2, 0.0, 0.42], "size": [0.14, 0.12, 0.08],
              "rotation": [1, 0, 0, 0], "force": LOAD_FORCE, "moment": [0, 0, 0]}]
    write_problem(name, [("slope", plane), ("floor", floor)], ras, loads,
                  "A rivet plane at 45 degrees and a floor strip, one 4 kg box at 9 g")


if __name__ == "__main__":
    corner("corner", with_obstacle=False)
    corner("corner_obstacle", with_obstacle=True)
    slanted("slanted")
    print("wrote", OUT)
