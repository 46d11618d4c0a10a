#!/usr/bin/python3
"""Writes a problem whose environment is one finely tessellated floor, for the
memory and time of the environment build on a big mesh (docs/benchmarks.md,
"A 2-million-triangle environment"):

    /usr/bin/python3 bench/big_floor.py /tmp/bigfloor --cells 1000
    /usr/bin/time -v build/native/cli/sheetgen check /tmp/bigfloor/problem.json --env

A 2 m x 2 m floor of cells x cells quads (2 cells^2 triangles, binary PLY), a
rivet strip of 20 x 100 cells beside a 3 kg box at 9 g standing 60 mm above it.
"""
import argparse
import json
import os
import struct


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="folder to write problem.json and floor.ply into")
    ap.add_argument("--cells", type=int, default=1000, help="quads per side (default 1000: 2 000 000 triangles)")
    a = ap.parse_args()
    n, size = a.cells, 2.0
    if n < 10:
        raise SystemExit("big_floor.py: --cells must be at least 10")
    os.makedirs(a.out, exist_ok=True)
    h = size / n
    with open(os.path.join(a.out, "floor.ply"), "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                 "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % ((n + 1) ** 2, 2 * n * n)).encode())
        for j in range(n + 1):
            f.write(b"".join(struct.pack("<fff", -1.0 + i * h, -1.0 + j * h, 0.0) for i in range(n + 1)))
        for j in range(n):
            row = []
            for i in range(n):
                v = j * (n + 1) + i
                row.append(struct.pack("<Biii", 3, v, v + 1, v + n + 2))
                row.append(struct.pack("<Biii", 3, v, v + n + 2, v + n + 1))
            f.write(b"".join(row))
    # Rivet strip: cells with x in [0.15, 0.15 + 20 h) and y in [-50 h, 50 h).
    i0, j0 = int(round((1.0 + 0.15) / h)), n // 2 - 50
    faces = [2 * (j * n + i) + k for j in range(j0, j0 + 100) for i in range(i0, i0 + 20) for k in (0, 1)]
    problem = {
        "format": "sheetgen-problem/1",
        "name": "big_floor_%d" % n,
        "description": "benchmark: a %d x %d-quad floor (%d triangles)" % (n, n, 2 * n * n),
        "units": "m",
        "environment": {"meshes": [{"name": "floor", "file": "floor.ply"}]},
        "rivet_areas": [{"name": "strip", "mesh": "floor", "faces": faces}],
        "loads": [{"name": "box", "center": [0.0, 0.0, 0.11], "size": [0.16, 0.2, 0.1], "rotation": [1, 0, 0, 0],
                   "force": [0.0, 0.0, -264.9], "moment": [0, 0, 0]}],
        "requirements": {"max_deflection": 0.001, "min_margin_of_safety": 0.0},
        "search": {"chains": 10, "iterations": 1000, "beam_width": 8, "seed": 1},
    }
    with open(os.path.join(a.out, "problem.json"), "w") as f:
        json.dump(problem, f, indent=1)
    print("wrote %s (%d triangles, %d rivet-area faces)" % (a.out, 2 * n * n, len(faces)))


if __name__ == "__main__":
    main()
