#!/usr/bin/env python3
"""Writes the scene library in sample_scenes/ (problem JSON + OBJ meshes), issue 8.

Run from anywhere: python3 scripts/make_scene_library.py. Pure standard library.
The library, by increasing difficulty (docs/scenes.md says what each one is and
where every number comes from):

  shelf           a box held 60 mm above a shelf, two rivet strips on the shelf   (new)
  corner          wall + floor corner                                  (make_sample_scenes.py)
  wall_standoff   light box near a wall, far from the floor: paper Fig. 9  (new)
  corner_obstacle corner with a pipe housing in the way                (make_sample_scenes.py)
  slanted         rivet plane at 45 degrees                            (make_sample_scenes.py)
  sharp_angles    an overhanging plane (60 deg, facing down) and a 70 deg plane, turned 25 deg about z (new)
  boxed_in        box walled in by equipment, one 100 mm tall slot out       (new)
  bulkhead_hole   rivet areas only behind a lightening hole in a bulkhead    (new)
  maze            five rivet areas in a row behind baffles             (make_maze_scene.py)
  avionics_bay    ten boxes between frames, stringers, a shelf and equipment (new)

This script writes only the new scenes; the four existing ones are left alone.
Every mesh is a grid of quads split in two triangles (rivet areas are exact
face subsets of one plane) or a closed box (obstacles). Geometry in metres.

Loads: mass m under a 9 g design load factor, F = m * 9 * 9.81 m/s^2, downward
(the single load case the solver takes; docs/scenes.md), deflection limit 1 mm
at the load (requirements.max_deflection: C_max = |F| * 1 mm), MS >= 0 at
safety factor 1.5, Al 2024-T3 1.6 mm sheet (the defaults).
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_sample_scenes import Mesh, faces_in, OUT  # noqa: E402

G = 9.81
LOAD_FACTOR = 9.0
DEFLECTION_LIMIT = 1.0e-3  # m


def force_down(mass_kg):
    return [0.0, 0.0, -round(mass_kg * LOAD_FACTOR * G, 3)]


def load(name, mass_kg, center, size, description=None):
    entry = {"name": name, "center": [round(c, 6) for c in center], "size": list(size),
             "rotation": [1, 0, 0, 0], "force": force_down(mass_kg), "moment": [0, 0, 0]}
    return entry


def grid_with_hole(mesh, origin, u, v, nu, nv, hole):
    """Like Mesh.grid, but cells (i, j) for which hole(i, j) is true get no faces."""
    base = len(mesh.v)
    for j in range(nv + 1):
        for i in range(nu + 1):
            mesh.v.append([origin[k] + u[k] * i / nu + v[k] * j / nv for k in range(3)])
    cells = {}
    for j in range(nv):
        for i in range(nu):
            if hole(i, j):
                continue
            a = base + j * (nu + 1) + i
            b, c, d = a + 1, a + nu + 2, a + nu + 1
            cells[(i, j)] = [len(mesh.f), len(mesh.f) + 1]
            mesh.f.append([a, b, c])
            mesh.f.append([a, c, d])
    return cells


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
        "requirements": {"max_deflection": DEFLECTION_LIMIT, "min_margin_of_safety": 0.0},
        "search": {"chains": 10, "iterations": 1000, "beam_width": 8, "seed": 1},
    }
    with open(os.path.join(folder, "problem.json"), "w") as out:
        json.dump(problem, out, indent=2)
        out.write("\n")
    print("wrote", folder)


def rot_z(p, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]


# --------------------------------------------------------------------------- scenes

def shelf():
    """A 5 kg box held 60 mm above a shelf; rivet strips left and right of it; a back wall."""
    shelf_m, wall = Mesh(), Mesh()
    cells = shelf_m.grid([-0.25, -0.20, 0.0], [0.5, 0, 0], [0, 0.4, 0], 10, 8)     # z = 0, normal +z
    wall.grid([-0.25, 0.22, 0.0], [0, 0, 0.35], [0.5, 0, 0], 5, 4)                  # y = 0.22, normal -y
    ras = [
        {"name": "shelf_left", "mesh": "shelf", "faces": faces_in(cells, (1, 3), (1, 7))},   # x -0.20..-0.10, y -0.15..0.15
        {"name": "shelf_right", "mesh": "shelf", "faces": faces_in(cells, (7, 9), (1, 7))},  # x 0.10..0.20
    ]
    loads = [load("avionics_box", 5.0, [0.0, 0.0, 0.06 + 0.05], [0.16, 0.20, 0.10])]
    write_problem("shelf", [("shelf", shelf_m), ("wall", wall)], ras, loads,
                  "A 5 kg box at 9 g held 60 mm above a shelf; two rivet strips on the shelf beside it, a back wall")


def wall_standoff():
    """Paper Fig. 9: a light box close to a wall but far above the floor."""
    wall, floor = Mesh(), Mesh()
    wcells = wall.grid([0, -0.3, 0], [0, 0.6, 0], [0, 0, 0.8], 12, 16)   # x = 0, normal +x
    fcells = floor.grid([0, -0.3, 0], [0.6, 0, 0], [0, 0.6, 0], 12, 12)  # z = 0, normal +z
    ras = [
        {"name": "wall_rivets", "mesh": "wall", "faces": faces_in(wcells, (3, 9), (9, 14))},    # y -0.15..0.15, z 0.45..0.70
        {"name": "floor_rivets", "mesh": "floor", "faces": faces_in(fcells, (2, 8), (3, 9))},  # x 0.10..0.40, y -0.15..0.15
    ]
    loads = [load("sensor_box", 1.5, [0.12, 0.0, 0.60], [0.12, 0.10, 0.06])]
    write_problem("wall_standoff", [("wall", wall), ("floor", floor)], ras, loads,
                  "Paper Fig. 9: a 1.5 kg box at 9 g 60 mm from a wall and 0.57 m above the floor")


def sharp_angles():
    """Two rivet planes at sharp angles, neither aligned with the box: an overhanging web whose
    face looks 30 degrees below the horizontal (60 degrees from horizontal, leaning over the box),
    and a 70 degree web on the other side; the whole frame is turned 25 degrees about z."""
    turn = 25.0
    over, steep = Mesh(), Mesh()
    # Overhanging plane A through (0.20, 0, 0.30): normal (-cos30, 0, -sin30), slope direction s (down, +x).
    nA = [-math.cos(math.radians(30)), 0, -math.sin(math.radians(30))]
    sA = [math.sin(math.radians(30)), 0, -math.cos(math.radians(30))]
    cA = [0.20, 0.0, 0.30]
    # grid: u along y (width 0.5), v along -s (up the slope, 0.4); normal u x v must equal nA
    u = [0, 0.5, 0]
    v = [-0.4 * sA[k] for k in range(3)]
    origin = [cA[k] + 0.2 * sA[k] - 0.5 * u[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    if sum(n[k] * nA[k] for k in range(3)) < 0:  # make the face normal look at the box
        origin = [origin[k] + u[k] for k in range(3)]
        u = [-x for x in u]
    ra_cells_A = over.grid(rot_z(origin, turn), rot_z(u, turn), rot_z(v, turn), 10, 8)
    # Steep plane B through (-0.18, 0, 0.20): 70 degrees from horizontal, facing +x and up.
    nB = [math.sin(math.radians(70)), 0, math.cos(math.radians(70))]
    sB = [math.cos(math.radians(70)), 0, -math.sin(math.radians(70))]  # down the slope (towards +x, down)
    cB = [-0.18, 0.0, 0.22]
    u = [0, -0.5, 0]
    v = [-0.4 * sB[k] for k in range(3)]
    origin = [cB[k] + 0.2 * sB[k] - 0.5 * u[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    if sum(n[k] * nB[k] for k in range(3)) < 0:
        origin = [origin[k] + u[k] for k in range(3)]
        u = [-x for x in u]
    ra_cells_B = steep.grid(rot_z(origin, turn), rot_z(u, turn), rot_z(v, turn), 10, 8)
    ras = [
        {"name": "overhang_rivets", "mesh": "overhang", "faces": faces_in(ra_cells_A, (2, 8), (1, 7))},
        {"name": "steep_rivets", "mesh": "steep", "faces": faces_in(ra_cells_B, (2, 8), (1, 7))},
    ]
    loads = [load("avionics_box", 4.0, [0.0, 0.0, 0.30], [0.14, 0.12, 0.08])]
    write_problem("sharp_angles", [("overhang", over), ("steep", steep)], ras, loads,
                  "Rivet planes at sharp angles (paper Fig. 7c): an overhanging web facing 30 deg below horizontal "
                  "and a 70 deg web, turned 25 deg about z; one 4 kg box at 9 g, no floor")


def boxed_in():
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
    write_problem("boxed_in", [("equipment", env), ("floor", floor), ("frame", frame)], ras, loads,
                  "A 2 kg box at 9 g walled in by equipment (30 mm gaps); the only way out is a 100 mm tall slot "
                  "in the front baffle to a floor and a frame outside")


def bulkhead_hole():
    """Rivet areas only behind a bulkhead, reachable through its 160 x 160 mm lightening hole."""
    bulk, floor, frame = Mesh(), Mesh(), Mesh()
    # Bulkhead x = 0.20, y -0.30..0.30, z 0..0.60, 20 mm cells; hole y -0.08..0.08, z 0.16..0.32.
    grid_with_hole(bulk, [0.20, -0.30, 0.0], [0, 0.6, 0], [0, 0, 0.6], 30, 30,
                   lambda i, j: 11 <= i < 19 and 8 <= j < 16)
    fcells = floor.grid([-0.20, -0.30, 0.0], [0.70, 0, 0], [0, 0.6, 0], 14, 12)    # x -0.20..0.50, 50 mm cells
    rcells = frame.grid([0.36, 0.25, 0.0], [0, -0.5, 0], [0, 0, 0.5], 10, 10)      # x = 0.36 facing -x
    ras = [
        {"name": "rear_frame_rivets", "mesh": "rear_frame", "faces": faces_in(rcells, (3, 7), (3, 7))},  # y -0.10..0.10, z 0.15..0.35
        {"name": "rear_floor_rivets", "mesh": "floor", "faces": faces_in(fcells, (9, 11), (3, 9))},      # x 0.25..0.35, y -0.15..0.15
    ]
    loads = [load("avionics_box", 2.0, [0.02, 0.0, 0.28], [0.14, 0.12, 0.08])]
    write_problem("bulkhead_hole", [("bulkhead", bulk), ("floor", floor), ("rear_frame", frame)], ras, loads,
                  "A 2 kg box at 9 g in front of a bulkhead; the only rivet areas (a frame web and a floor patch) "
                  "are behind it, through a 160 x 160 mm lightening hole")


def avionics_bay():
    """Ten boxes (1-15 kg) in a bay 1.2 m long between two bulkheads (x = 0 and x = 1.2), with the
    fuselage side at y = -0.55 carrying three stringers, a ring frame at x = 0.6, a shelf and
    existing equipment (obstacles). Later loads see earlier parts as obstacles (the solver)."""
    C = 0.05  # grid cell, m
    floor, skin, fwd, aft, mid, stringers, shelf_m, equip = (Mesh() for _ in range(8))
    fc = floor.grid([0, -0.55, 0], [1.2, 0, 0], [0, 1.0, 0], 24, 20)                 # z = 0, normal +z
    skin.grid([0, -0.55, 0], [0, 0, 0.9], [1.2, 0, 0], 6, 5)                         # y = -0.55, normal +y
    fwdc = fwd.grid([0, 0.45, 0], [0, -1.0, 0], [0, 0, 0.9], 20, 18)                 # x = 0, normal +x
    aftc = aft.grid([1.2, -0.55, 0], [0, 1.0, 0], [0, 0, 0.9], 20, 18)               # x = 1.2, normal -x
    midc = mid.grid([0.6, -0.30, 0], [0, -0.25, 0], [0, 0, 0.9], 5, 18)              # ring-frame web x = 0.6, y -0.55..-0.30
    # Stringers: hat-like closed profiles on the skin, 50 mm deep x 50 mm tall, one per frame bay;
    # the rivet face is the outer cap at y = -0.50 (facing +y), modelled as a 1-cell-tall grid.
    caps = {}
    for k, zc in enumerate([0.25, 0.50, 0.75], start=1):
        for b, (x0, x1) in enumerate([(0.025, 0.575), (0.625, 1.175)]):
            n = int(round((x1 - x0) / C))
            caps[(k, b)] = (x0, stringers.grid([x0, -0.50, zc - 0.025], [x1 - x0, 0, 0], [0, 0, 0.05], n, 1))
            stringers.grid([x0, -0.55, zc + 0.025], [x1 - x0, 0, 0], [0, 0.05, 0], n, 1)   # top
            stringers.grid([x0, -0.55, zc - 0.025], [0, 0.05, 0], [x1 - x0, 0, 0], 1, n)   # bottom
    shc = shelf_m.grid([0.65, -0.50, 0.45], [0.5, 0, 0], [0, 0.4, 0], 10, 8)        # shelf z = 0.45, x 0.65..1.15, y -0.50..-0.10
    equip.box([0.05, 0.10, 0.00], [0.35, 0.40, 0.30])   # ECU rack
    equip.box([0.80, 0.15, 0.00], [1.10, 0.40, 0.25])   # junction box
    equip.box([0.00, 0.25, 0.70], [1.20, 0.35, 0.80])   # air duct along the bay

    def floor_patch(x0, x1, y0, y1):
        return faces_in(fc, (int(round(x0 / C)), int(round(x1 / C))), (int(round((y0 + 0.55) / C)), int(round((y1 + 0.55) / C))))

    def frame_patch(cells, y_of_i, y0, y1, z0, z1):
        i_lo, i_hi = sorted((y_of_i(y0), y_of_i(y1)))
        return faces_in(cells, (i_lo, i_hi), (int(round(z0 / C)), int(round(z1 / C))))

    fwd_i = lambda y: int(round((0.45 - y) / C))   # noqa: E731  (fwd grid runs from y = 0.45 down)
    aft_i = lambda y: int(round((y + 0.55) / C))   # noqa: E731

    def cap(k, b, x0, x1):
        xs, cells = caps[(k, b)]
        return faces_in(cells, (int(round((x0 - xs) / C)), int(round((x1 - xs) / C))), (0, 1))

    def shelf_patch(x0, x1, y0, y1):
        return faces_in(shc, (int(round((x0 - 0.65) / C)), int(round((x1 - 0.65) / C))),
                        (int(round((y0 + 0.50) / C)), int(round((y1 + 0.50) / C))))

    ras = [
        ("floor_battery_s", "floor", floor_patch(0.40, 0.70, -0.05, 0.10)),
        ("floor_battery_n", "floor", floor_patch(0.40, 0.70, 0.30, 0.45)),
        ("floor_psu_s", "floor", floor_patch(0.15, 0.40, -0.45, -0.35)),
        ("floor_psu_n", "floor", floor_patch(0.15, 0.40, -0.10, -0.05)),
        ("shelf_outboard", "shelf", shelf_patch(0.70, 1.10, -0.50, -0.40)),
        ("shelf_inboard", "shelf", shelf_patch(0.70, 1.10, -0.20, -0.10)),
        ("aft_frame_low", "aft_bulkhead", frame_patch(aftc, aft_i, -0.45, -0.15, 0.15, 0.40)),
        ("stringer1_aft", "stringers", cap(1, 1, 0.775, 1.175)),
        ("fwd_frame_mid", "fwd_bulkhead", frame_patch(fwdc, fwd_i, -0.45, -0.15, 0.40, 0.65)),
        ("stringer2_fwd", "stringers", cap(2, 0, 0.025, 0.425)),
        ("stringer3_fwd", "stringers", cap(3, 0, 0.275, 0.575)),
        ("ring_frame_top", "ring_frame", faces_in(midc, (0, 5), (13, 17))),           # z 0.65..0.85
        ("fwd_frame_inboard", "fwd_bulkhead", frame_patch(fwdc, fwd_i, 0.05, 0.45, 0.35, 0.60)),
        ("aft_frame_inboard", "aft_bulkhead", frame_patch(aftc, aft_i, 0.10, 0.45, 0.30, 0.55)),
        ("stringer1_coupler", "stringers", cap(1, 1, 0.625, 0.775)),
        ("floor_coupler", "floor", floor_patch(0.65, 0.85, -0.35, -0.30)),
        ("ring_frame_low", "ring_frame", faces_in(midc, (0, 5), (1, 4))),             # z 0.05..0.20
        ("aft_frame_top", "aft_bulkhead", frame_patch(aftc, aft_i, -0.10, 0.10, 0.60, 0.85)),
    ]
    rivet_areas = [{"name": n, "mesh": m, "faces": f} for n, m, f in ras]
    for r in rivet_areas:
        assert r["faces"], r["name"]
    # (name, mass kg, centre, size): heaviest first, each next to its own rivet areas.
    boxes = [
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
    loads = [load(n, m, c, s) for n, m, c, s in boxes]
    meshes = [("floor", floor), ("skin", skin), ("fwd_bulkhead", fwd), ("aft_bulkhead", aft),
              ("ring_frame", mid), ("stringers", stringers), ("shelf", shelf_m), ("equipment", equip)]
    write_problem("avionics_bay", meshes, rivet_areas, loads,
                  "Avionics bay (paper Fig. 10): ten boxes of 1-15 kg at 9 g between two bulkheads, a ring frame, "
                  "three stringers, a shelf and existing equipment; 18 rivet areas")


SCENES = {
    "shelf": shelf,
    "wall_standoff": wall_standoff,
    "sharp_angles": sharp_angles,
    "boxed_in": boxed_in,
    "bulkhead_hole": bulkhead_hole,
    "avionics_bay": avionics_bay,
}

if __name__ == "__main__":
    for name in sys.argv[1:] or SCENES:
        SCENES[name]()
