"""Writes the scene library in sample_scenes/ (problem JSON + OBJ meshes).

    PYTHONPATH=tools python3 -m sheetgen_tools.scenes [SCENE ...] [--out DIR]

Without SCENE it writes every scene; --out writes into another folder (the
test that the committed scenes are this module's output uses it). The
scene.blend beside each problem is made from the problem by
scripts/make_sample_blends.py inside Blender. Pure standard library.

The library, by increasing difficulty (docs/scenes.md says what each one is and
where every number comes from):

  shelf           a box held 60 mm above a shelf, two rivet strips on the shelf
  corner          wall + floor corner
  wall_standoff   light box near a wall, far from the floor: paper Fig. 9
  corner_obstacle corner with a pipe housing in the way
  slanted         rivet plane at 45 degrees
  sharp_angles    an overhanging plane (60 deg, facing down) and a 70 deg plane, turned 25 deg about z
  boxed_in        box walled in by equipment, one 100 mm tall slot out
  bulkhead_hole   rivet areas only behind a lightening hole in a bulkhead
  maze            five rivet areas in a row behind baffles (paper Fig. 13, docs/ablation_discovery.md)
  avionics_bay    ten boxes between frames, stringers, a shelf and equipment

Every mesh is a grid of quads split in two triangles (rivet areas are exact
face subsets of one plane) or a closed box (obstacles). Geometry in metres.

Loads: a box of mass m under the emergency-landing envelope of FAR/CS
25.561(b)(3) (load_cases with the "far25.561" preset: 9 g forward, 1.5 g
rearward, 3 g either side, 6 g down, 3 g up; the aircraft's forward is -x in
the bay and +x in the single scenes, up is +z), deflection limit 1 mm along
each case's force (requirements.max_deflection), MS >= 0 at safety factor 1.5,
no buckling below ultimate load (min_buckling_factor defaults to the safety
factor), first natural frequency at least FREQUENCY_FLOOR_HZ (docs/scenes.md
says where each number comes from), Al 2024-T3 1.6 mm sheet (the defaults).
"""
import argparse
import json
import math
import os

from . import paths

DEFLECTION_LIMIT = 1.0e-3  # m
# Hz: above the < 30 Hz band of an airframe's damaging flexible modes
# (docs/scenes.md "Where the numbers come from").
FREQUENCY_FLOOR_HZ = 30.0
UP = [0, 0, 1]
FORWARD_SINGLE = [1, 0, 0]  # the single scenes: +x is the aircraft's forward
FORWARD_BAY = [-1, 0, 0]    # the bay: the forward bulkhead is at x = 0, the aft one at x = 1.2
SEARCH = {"chains": 10, "iterations": 1000, "beam_width": 8, "seed": 1}  # the paper's settings


class Mesh:
    """Triangles of grids and boxes, written as an OBJ file."""

    def __init__(self):
        self.v = []
        self.f = []

    def grid(self, origin, u, v, nu, nv, hole=None):
        """A planar grid origin + a*u + b*v, a,b in [0,1], of nu x nv cells;
        cells (i, j) for which hole(i, j) is true get no faces. Returns the
        face ids per cell {(i, j): [two faces]}."""
        base = len(self.v)
        for j in range(nv + 1):
            for i in range(nu + 1):
                self.v.append([origin[k] + u[k] * i / nu + v[k] * j / nv for k in range(3)])
        cells = {}
        for j in range(nv):
            for i in range(nu):
                if hole is not None and hole(i, j):
                    continue
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
    """The faces of the grid cells with i_range[0] <= i < i_range[1] and likewise j."""
    out = []
    for (i, j), fs in sorted(cells.items()):
        if i_range[0] <= i < i_range[1] and j_range[0] <= j < j_range[1]:
            out.extend(fs)
    return out


def load(name, mass_kg, center, size):
    """A load entry: a uniform box of `size` (m) and mass_kg at `center` (m); its cases are the envelope's."""
    return {"name": name, "center": [round(c, 6) for c in center], "size": list(size),
            "rotation": [1, 0, 0, 0], "mass": mass_kg}


def rot_z(p, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]


def write_problem(out, name, meshes, rivet_areas, loads, description, forward=FORWARD_SINGLE):
    """out/<name>/problem.json and one OBJ per (mesh name, Mesh); `forward` is the aircraft's forward axis."""
    folder = os.path.join(out, name)
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
        "load_cases": {"forward": list(forward), "up": list(UP), "factors": "far25.561"},
        "requirements": {"max_deflection": DEFLECTION_LIMIT, "min_margin_of_safety": 0.0,
                         "min_frequency_hz": FREQUENCY_FLOOR_HZ},
        "search": dict(SEARCH),
    }
    with open(os.path.join(folder, "problem.json"), "w") as f:
        json.dump(problem, f, indent=2)
        f.write("\n")
    print("wrote", folder)


# --------------------------------------------------------------------------- scenes

def corner(out, name, with_obstacle):
    """Wall in the plane x = 0 (facing +x), floor in z = 0 (facing +z); 0.6 m squares of 0.05 m cells."""
    wall, floor = Mesh(), Mesh()
    wall_cells = wall.grid([0, -0.3, 0], [0, 0.6, 0], [0, 0, 0.6], 12, 12)   # normal +x
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
    loads = [load("avionics_box", 4.0, [0.26, 0.0, 0.34], [0.16, 0.12, 0.08])]
    desc = "Wall and floor corner, one 4 kg box" + (", a pipe housing between box and wall" if with_obstacle else "")
    write_problem(out, name, meshes, ras, loads, desc)


def slanted(out):
    """A rivet plane tilted 45 degrees (a sloped frame web), plus a floor."""
    s = math.sqrt(0.5)
    plane, floor = Mesh(), Mesh()
    # Plane through the line x = 0, z = 0 rising along +x+z at 45 degrees, spanning y in [-0.3, 0.3].
    cells = plane.grid([0, 0.3, 0], [0, -0.6, 0], [0.5 * s, 0, 0.5 * s], 12, 10)  # normal (-s,0,s): faces up-left
    floor_cells = floor.grid([0.45, -0.3, 0], [0.35, 0, 0], [0, 0.6, 0], 7, 12)
    ras = [
        {"name": "slope_rivets", "mesh": "slope", "faces": faces_in(cells, (2, 10), (5, 9))},
        {"name": "floor_rivets", "mesh": "floor", "faces": faces_in(floor_cells, (2, 6), (2, 10))},
    ]
    loads = [load("avionics_box", 4.0, [0.2, 0.0, 0.42], [0.14, 0.12, 0.08])]
    write_problem(out, "slanted", [("slope", plane), ("floor", floor)], ras, loads,
                  "A rivet plane at 45 degrees and a floor strip, one 4 kg box")


def shelf(out):
    """A 5 kg box held 60 mm above a shelf; rivet strips left and right of it; a back wall."""
    shelf_m, wall = Mesh(), Mesh()
    cells = shelf_m.grid([-0.25, -0.20, 0.0], [0.5, 0, 0], [0, 0.4, 0], 10, 8)     # z = 0, normal +z
    wall.grid([-0.25, 0.22, 0.0], [0, 0, 0.35], [0.5, 0, 0], 5, 4)                  # y = 0.22, normal -y
    ras = [
        {"name": "shelf_left", "mesh": "shelf", "faces": faces_in(cells, (1, 3), (1, 7))},   # x -0.20..-0.10, y -0.15..0.15
        {"name": "shelf_right", "mesh": "shelf", "faces": faces_in(cells, (7, 9), (1, 7))},  # x 0.10..0.20
    ]
    loads = [load("avionics_box", 5.0, [0.0, 0.0, 0.06 + 0.05], [0.16, 0.20, 0.10])]
    write_problem(out, "shelf", [("shelf", shelf_m), ("wall", wall)], ras, loads,
                  "A 5 kg box held 60 mm above a shelf; two rivet strips on the shelf beside it, a back wall")


def wall_standoff(out):
    """Paper Fig. 9: a light box close to a wall but far above the floor."""
    wall, floor = Mesh(), Mesh()
    wcells = wall.grid([0, -0.3, 0], [0, 0.6, 0], [0, 0, 0.8], 12, 16)   # x = 0, normal +x
    fcells = floor.grid([0, -0.3, 0], [0.6, 0, 0], [0, 0.6, 0], 12, 12)  # z = 0, normal +z
    ras = [
        {"name": "wall_rivets", "mesh": "wall", "faces": faces_in(wcells, (3, 9), (9, 14))},    # y -0.15..0.15, z 0.45..0.70
        {"name": "floor_rivets", "mesh": "floor", "faces": faces_in(fcells, (2, 8), (3, 9))},  # x 0.10..0.40, y -0.15..0.15
    ]
    loads = [load("sensor_box", 1.5, [0.12, 0.0, 0.60], [0.12, 0.10, 0.06])]
    write_problem(out, "wall_standoff", [("wall", wall), ("floor", floor)], ras, loads,
                  "Paper Fig. 9: a 1.5 kg box 60 mm from a wall and 0.57 m above the floor")


def _sloped_grid(mesh, centre, normal, slope, u, turn):
    """A 0.5 x 0.4 m grid of 10 x 8 cells about `centre` in the plane of unit
    `normal`: its long side `u`, its short side up the slope (`slope` points
    down it), flipped along u when its faces would look away from `normal`;
    the whole turned `turn` deg about z. Returns the cells."""
    v = [-0.4 * slope[k] for k in range(3)]
    origin = [centre[k] + 0.2 * slope[k] - 0.5 * u[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    if sum(n[k] * normal[k] for k in range(3)) < 0:  # make the face normal look at the box
        origin = [origin[k] + u[k] for k in range(3)]
        u = [-x for x in u]
    return mesh.grid(rot_z(origin, turn), rot_z(u, turn), rot_z(v, turn), 10, 8)


def sharp_angles(out):
    """Two rivet planes at sharp angles, neither aligned with the box: an overhanging web whose
    face looks 30 degrees below the horizontal (60 degrees from horizontal, leaning over the box),
    and a 70 degree web on the other side; the whole frame is turned 25 degrees about z."""
    turn = 25.0
    over, steep = Mesh(), Mesh()
    # Overhanging plane A through (0.20, 0, 0.30): normal (-cos30, 0, -sin30), slope direction (down, +x).
    ra_cells_A = _sloped_grid(over, [0.20, 0.0, 0.30], [-math.cos(math.radians(30)), 0, -math.sin(math.radians(30))],
                              [math.sin(math.radians(30)), 0, -math.cos(math.radians(30))], [0, 0.5, 0], turn)
    # Steep plane B through (-0.18, 0, 0.22): 70 degrees from horizontal, facing +x and up.
    ra_cells_B = _sloped_grid(steep, [-0.18, 0.0, 0.22], [math.sin(math.radians(70)), 0, math.cos(math.radians(70))],
                              [math.cos(math.radians(70)), 0, -math.sin(math.radians(70))], [0, -0.5, 0], turn)
    ras = [
        {"name": "overhang_rivets", "mesh": "overhang", "faces": faces_in(ra_cells_A, (2, 8), (1, 7))},
        {"name": "steep_rivets", "mesh": "steep", "faces": faces_in(ra_cells_B, (2, 8), (1, 7))},
    ]
    loads = [load("avionics_box", 4.0, [0.0, 0.0, 0.30], [0.14, 0.12, 0.08])]
    write_problem(out, "sharp_angles", [("overhang", over), ("steep", steep)], ras, loads,
                  "Rivet planes at sharp angles (paper Fig. 7c): an overhanging web facing 30 deg below horizontal "
                  "and a 70 deg web, turned 25 deg about z; one 4 kg box, no floor")


def boxed_in(out):
    """A box walled in by equipment on five sides; the only way out is a 100 mm tall slot in the front baffle."""
    env, floor, frame = Mesh(), Mesh(), Mesh()
    env.box([-0.20, -0.20, 0.00], [0.12, 0.20, 0.15])   # equipment below (60 mm under the base)
    env.box([-0.20, 0.09, 0.15], [0.12, 0.20, 0.34])    # equipment at +y (30 mm gap)
    env.box([-0.20, -0.20, 0.15], [0.12, -0.09, 0.34])  # equipment at -y
    env.box([-0.20, -0.09, 0.15], [-0.10, 0.09, 0.34])  # equipment behind (-x)
    env.box([-0.20, -0.20, 0.32], [0.12, 0.20, 0.34])   # cover above (30 mm over the box)
    # front baffle at x 0.12..0.13 with a slot y -0.09..0.09, z 0.15..0.25 (the cavity's width, 100 mm tall)
    env.box([0.12, -0.20, 0.15], [0.13, -0.09, 0.34])
    env.box([0.12, 0.09, 0.15], [0.13, 0.20, 0.34])
    env.box([0.12, -0.09, 0.25], [0.13, 0.09, 0.34])
    fcells = floor.grid([0.10, -0.25, 0.0], [0.40, 0, 0], [0, 0.5, 0], 8, 10)       # x 0.10..0.50, z = 0
    rcells = frame.grid([0.45, 0.25, 0.0], [0, -0.5, 0], [0, 0, 0.45], 10, 9)       # x = 0.45, normal -x
    ras = [
        {"name": "floor_rivets", "mesh": "floor", "faces": faces_in(fcells, (1, 6), (2, 8))},   # x 0.15..0.40, y -0.15..0.15
        {"name": "frame_rivets", "mesh": "frame", "faces": faces_in(rcells, (2, 8), (2, 7))},   # y -0.15..0.15, z 0.10..0.35
    ]
    loads = [load("avionics_box", 2.0, [0.0, 0.0, 0.25], [0.14, 0.12, 0.08])]
    write_problem(out, "boxed_in", [("equipment", env), ("floor", floor), ("frame", frame)], ras, loads,
                  "A 2 kg box walled in by equipment (30 mm gaps); the only way out is a 100 mm tall slot "
                  "in the front baffle to a floor and a frame outside")


def bulkhead_hole(out):
    """Rivet areas only behind a bulkhead, reachable through its 160 x 160 mm lightening hole."""
    bulk, floor, frame = Mesh(), Mesh(), Mesh()
    # Bulkhead x = 0.20, y -0.30..0.30, z 0..0.60, 20 mm cells; hole y -0.08..0.08, z 0.16..0.32.
    bulk.grid([0.20, -0.30, 0.0], [0, 0.6, 0], [0, 0, 0.6], 30, 30, hole=lambda i, j: 11 <= i < 19 and 8 <= j < 16)
    fcells = floor.grid([-0.20, -0.30, 0.0], [0.70, 0, 0], [0, 0.6, 0], 14, 12)    # x -0.20..0.50, 50 mm cells
    rcells = frame.grid([0.36, 0.25, 0.0], [0, -0.5, 0], [0, 0, 0.5], 10, 10)      # x = 0.36 facing -x
    ras = [
        {"name": "rear_frame_rivets", "mesh": "rear_frame", "faces": faces_in(rcells, (3, 7), (3, 7))},  # y -0.10..0.10, z 0.15..0.35
        {"name": "rear_floor_rivets", "mesh": "floor", "faces": faces_in(fcells, (9, 11), (3, 9))},      # x 0.25..0.35, y -0.15..0.15
    ]
    loads = [load("avionics_box", 2.0, [0.02, 0.0, 0.28], [0.14, 0.12, 0.08])]
    write_problem(out, "bulkhead_hole", [("bulkhead", bulk), ("floor", floor), ("rear_frame", frame)], ras, loads,
                  "A 2 kg box in front of a bulkhead; the only rivet areas (a frame web and a floor patch) "
                  "are behind it, through a 160 x 160 mm lightening hole")


MAZE_CELL = 0.25      # m, cell length along x
MAZE_HEIGHT = 0.45    # m, side wall height
MAZE_BAFFLE = 0.20    # m, baffle height: below the base tab (z = 0.27 m), so feelers pass over and dive into the cells
MAZE_GAP = 0.16       # m, opening left by each baffle


def maze(out):
    """The ablation scene of Barda et al. 2023, Fig. 13(a), for the discovery
    policies (docs/ablation_discovery.md). A corridor along +x (floor z = 0,
    side walls y = +-0.2 m) divided by four baffles into five cells; each baffle
    leaves a 0.16 m gap at alternating sides, so the path from the load (above
    the first cell's left end) to the far cells winds. Five floor rivet areas
    RA1..RA5, one per cell, at increasing distance from the load: the near ones
    are easy to reach, the far ones need long, bent feelers."""
    floor, sides, baffles = Mesh(), Mesh(), Mesh()
    # floor x in [0, 1.25], y in [-0.2, 0.2], 0.05 m cells (normal +z)
    cells = floor.grid([0, -0.2, 0], [5 * MAZE_CELL, 0, 0], [0, 0.4, 0], 25, 8)
    # side walls facing into the corridor
    sides.grid([0, -0.2, 0], [0, 0, MAZE_HEIGHT], [5 * MAZE_CELL, 0, 0], 5, 5)       # y = -0.2, normal +y
    sides.grid([0, 0.2, 0], [5 * MAZE_CELL, 0, 0], [0, 0, MAZE_HEIGHT], 5, 5)        # y = +0.2, normal -y
    # baffles: thin closed boxes 10 mm thick at x = k * MAZE_CELL, gap alternating at +y / -y
    for k in range(1, 5):
        x = k * MAZE_CELL
        if k % 2 == 1:
            baffles.box([x - 0.005, -0.2, 0.0], [x + 0.005, 0.2 - MAZE_GAP, MAZE_BAFFLE])
        else:
            baffles.box([x - 0.005, -0.2 + MAZE_GAP, 0.0], [x + 0.005, 0.2, MAZE_BAFFLE])
    # RA_i: 0.1 x 0.2 m floor patch in the middle of cell i (grid cells of 0.05 m)
    ras = []
    for i in range(5):
        i0 = 5 * i + 1
        ras.append({"name": "RA%d" % (i + 1), "mesh": "floor", "faces": faces_in(cells, (i0, i0 + 3), (2, 6))})
    loads = [load("avionics_box", 4.0, [0.09, 0.0, 0.30], [0.12, 0.10, 0.06])]
    write_problem(out, "maze", [("floor", floor), ("sides", sides), ("baffles", baffles)], ras, loads,
                  "Maze for the discovery ablation (paper Fig. 13): five floor rivet areas in a row "
                  "behind alternating baffles, away from the load")


BAY_CELL = 0.05  # m, the bay's grid cell


class _Bay:
    """The avionics bay's meshes, and the grid cells its rivet areas are cut from."""

    def __init__(self):
        C = BAY_CELL
        self.floor, self.skin, self.fwd, self.aft, self.mid, self.stringers, self.shelf, self.equip = (Mesh() for _ in range(8))
        self.fc = self.floor.grid([0, -0.55, 0], [1.2, 0, 0], [0, 1.0, 0], 24, 20)         # z = 0, normal +z
        self.skin.grid([0, -0.55, 0], [0, 0, 0.9], [1.2, 0, 0], 6, 5)                       # y = -0.55, normal +y
        self.fwdc = self.fwd.grid([0, 0.45, 0], [0, -1.0, 0], [0, 0, 0.9], 20, 18)         # x = 0, normal +x
        self.aftc = self.aft.grid([1.2, -0.55, 0], [0, 1.0, 0], [0, 0, 0.9], 20, 18)       # x = 1.2, normal -x
        self.midc = self.mid.grid([0.6, -0.30, 0], [0, -0.25, 0], [0, 0, 0.9], 5, 18)      # ring-frame web x = 0.6, y -0.55..-0.30
        # Stringers: hat-like closed profiles on the skin, 50 mm deep x 50 mm tall, one per frame bay;
        # the rivet face is the outer cap at y = -0.50 (facing +y), modelled as a 1-cell-tall grid.
        self.caps = {}
        for k, zc in enumerate([0.25, 0.50, 0.75], start=1):
            for b, (x0, x1) in enumerate([(0.025, 0.575), (0.625, 1.175)]):
                n = int(round((x1 - x0) / C))
                self.caps[(k, b)] = (x0, self.stringers.grid([x0, -0.50, zc - 0.025], [x1 - x0, 0, 0], [0, 0, 0.05], n, 1))
                self.stringers.grid([x0, -0.55, zc + 0.025], [x1 - x0, 0, 0], [0, 0.05, 0], n, 1)   # top
                self.stringers.grid([x0, -0.55, zc - 0.025], [0, 0.05, 0], [x1 - x0, 0, 0], 1, n)   # bottom
        self.shc = self.shelf.grid([0.65, -0.50, 0.45], [0.5, 0, 0], [0, 0.4, 0], 10, 8)   # shelf z = 0.45, x 0.65..1.15, y -0.50..-0.10
        self.equip.box([0.05, 0.10, 0.00], [0.35, 0.40, 0.30])   # ECU rack
        self.equip.box([0.80, 0.15, 0.00], [1.10, 0.40, 0.25])   # junction box
        self.equip.box([0.00, 0.25, 0.70], [1.20, 0.35, 0.80])   # air duct along the bay

    def meshes(self):
        return [("floor", self.floor), ("skin", self.skin), ("fwd_bulkhead", self.fwd), ("aft_bulkhead", self.aft),
                ("ring_frame", self.mid), ("stringers", self.stringers), ("shelf", self.shelf), ("equipment", self.equip)]

    def floor_patch(self, x0, x1, y0, y1):
        C = BAY_CELL
        return faces_in(self.fc, (int(round(x0 / C)), int(round(x1 / C))), (int(round((y0 + 0.55) / C)), int(round((y1 + 0.55) / C))))

    @staticmethod
    def _frame_patch(cells, y_of_i, y0, y1, z0, z1):
        i_lo, i_hi = sorted((y_of_i(y0), y_of_i(y1)))
        return faces_in(cells, (i_lo, i_hi), (int(round(z0 / BAY_CELL)), int(round(z1 / BAY_CELL))))

    def fwd_patch(self, y0, y1, z0, z1):
        """Faces of the forward bulkhead (its grid runs from y = 0.45 down)."""
        return self._frame_patch(self.fwdc, lambda y: int(round((0.45 - y) / BAY_CELL)), y0, y1, z0, z1)

    def aft_patch(self, y0, y1, z0, z1):
        return self._frame_patch(self.aftc, lambda y: int(round((y + 0.55) / BAY_CELL)), y0, y1, z0, z1)

    def cap(self, k, b, x0, x1):
        xs, cells = self.caps[(k, b)]
        return faces_in(cells, (int(round((x0 - xs) / BAY_CELL)), int(round((x1 - xs) / BAY_CELL))), (0, 1))

    def shelf_patch(self, x0, x1, y0, y1):
        C = BAY_CELL
        return faces_in(self.shc, (int(round((x0 - 0.65) / C)), int(round((x1 - 0.65) / C))),
                        (int(round((y0 + 0.50) / C)), int(round((y1 + 0.50) / C))))

    def rivet_areas(self):
        ras = [
            ("floor_battery_s", "floor", self.floor_patch(0.40, 0.70, -0.05, 0.10)),
            ("floor_battery_n", "floor", self.floor_patch(0.40, 0.70, 0.30, 0.45)),
            ("floor_psu_s", "floor", self.floor_patch(0.15, 0.40, -0.45, -0.35)),
            ("floor_psu_n", "floor", self.floor_patch(0.15, 0.40, -0.10, -0.05)),
            ("shelf_outboard", "shelf", self.shelf_patch(0.70, 1.10, -0.50, -0.40)),
            ("shelf_inboard", "shelf", self.shelf_patch(0.70, 1.10, -0.20, -0.10)),
            ("aft_frame_low", "aft_bulkhead", self.aft_patch(-0.45, -0.15, 0.15, 0.40)),
            ("stringer1_aft", "stringers", self.cap(1, 1, 0.775, 1.175)),
            ("fwd_frame_mid", "fwd_bulkhead", self.fwd_patch(-0.45, -0.15, 0.40, 0.65)),
            ("stringer2_fwd", "stringers", self.cap(2, 0, 0.025, 0.425)),
            ("stringer3_fwd", "stringers", self.cap(3, 0, 0.275, 0.575)),
            ("ring_frame_top", "ring_frame", faces_in(self.midc, (0, 5), (13, 17))),           # z 0.65..0.85
            ("fwd_frame_inboard", "fwd_bulkhead", self.fwd_patch(0.05, 0.45, 0.35, 0.60)),
            ("aft_frame_inboard", "aft_bulkhead", self.aft_patch(0.10, 0.45, 0.30, 0.55)),
            ("stringer1_coupler", "stringers", self.cap(1, 1, 0.625, 0.775)),
            ("floor_coupler", "floor", self.floor_patch(0.65, 0.85, -0.35, -0.30)),
            ("ring_frame_low", "ring_frame", faces_in(self.midc, (0, 5), (1, 4))),             # z 0.05..0.20
            ("aft_frame_top", "aft_bulkhead", self.aft_patch(-0.10, 0.10, 0.60, 0.85)),
        ]
        for name, _, faces in ras:
            if not faces:
                raise ValueError(f"avionics_bay: rivet area {name} has no face")
        return [{"name": n, "mesh": m, "faces": f} for n, m, f in ras]


# (name, mass kg, centre m, size m): heaviest first, each next to its own rivet areas.
BAY_BOXES = [
    ("battery", 15.0, [0.55, 0.20, 0.14], [0.26, 0.18, 0.16]),
    ("power_supply", 10.0, [0.30, -0.20, 0.13], [0.24, 0.16, 0.14]),
    ("flight_computer", 8.0, [0.90, -0.30, 0.57], [0.30, 0.16, 0.14]),
    ("inertial_unit", 6.0, [0.20, -0.30, 0.56], [0.20, 0.16, 0.12]),
    ("radio", 5.0, [1.00, -0.28, 0.28], [0.22, 0.14, 0.10]),
    ("data_recorder", 4.0, [0.95, 0.28, 0.42], [0.18, 0.12, 0.12]),
    ("transponder", 3.0, [0.20, 0.25, 0.45], [0.20, 0.12, 0.08]),
    ("data_acquisition", 2.5, [1.05, 0.00, 0.75], [0.16, 0.12, 0.08]),
    ("gps_receiver", 1.5, [0.45, -0.40, 0.80], [0.12, 0.10, 0.06]),
    ("antenna_coupler", 1.0, [0.75, -0.42, 0.12], [0.10, 0.08, 0.05]),
]


def avionics_bay(out):
    """Ten boxes (1-15 kg) in a bay 1.2 m long between two bulkheads (x = 0 and x = 1.2), with the
    fuselage side at y = -0.55 carrying three stringers, a ring frame at x = 0.6, a shelf and
    existing equipment (obstacles). Later loads see earlier parts as obstacles (the solver)."""
    bay = _Bay()
    write_problem(out, "avionics_bay", bay.meshes(), bay.rivet_areas(), [load(*box) for box in BAY_BOXES],
                  "Avionics bay (paper Fig. 10): ten boxes of 1-15 kg between two bulkheads, a ring frame, "
                  "three stringers, a shelf and existing equipment; 18 rivet areas",
                  forward=FORWARD_BAY)


# Every scene, in the library's order of difficulty (docs/scenes.md): name -> writer(out folder).
SCENES = {
    "shelf": shelf,
    "corner": lambda out: corner(out, "corner", with_obstacle=False),
    "wall_standoff": wall_standoff,
    "corner_obstacle": lambda out: corner(out, "corner_obstacle", with_obstacle=True),
    "slanted": slanted,
    "sharp_angles": sharp_angles,
    "boxed_in": boxed_in,
    "bulkhead_hole": bulkhead_hole,
    "maze": maze,
    "avionics_bay": avionics_bay,
}
LIBRARY = list(SCENES)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m sheetgen_tools.scenes", description=__doc__.split("\n\n")[0])
    ap.add_argument("scenes", nargs="*", metavar="SCENE", help="default: all of " + ", ".join(LIBRARY))
    ap.add_argument("--out", default=paths.SAMPLE_SCENES, help="folder to write <scene>/ into (default sample_scenes/)")
    args = ap.parse_args(argv)
    unknown = [s for s in args.scenes if s not in SCENES]
    if unknown:
        ap.error("unknown scene(s): " + ", ".join(unknown))
    for name in args.scenes or LIBRARY:
        SCENES[name](args.out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
