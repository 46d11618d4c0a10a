"""Reading a problem (sheetgen-problem/1) with its meshes, for the checks and
the pictures (independent of the solver's own reader), and the problem
variants the benchmarks solve."""
import copy
import json
import os

import numpy as np

from .geometry import box_mesh


def read_obj(path):
    """An OBJ file's vertices (#V by 3, m) and triangles (#F by 3, 0-based;
    polygons fanned from their first corner, so a quad gives two faces as the
    solver numbers them)."""
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append([float(x) for x in p[1:4]])
            elif p[0] == "f":
                idx = [int(x.split("/")[0]) for x in p[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    tris.append([idx[0], idx[k], idx[k + 1]])
    return np.array(verts, float), np.array(tris, int)


def load_problem(path):
    """(the problem document, {mesh name: (vertices #V by 3 m, triangles #F by 3)}),
    file meshes read relative to the problem's folder."""
    with open(path) as f:
        prob = json.load(f)
    base = os.path.dirname(path)
    meshes = {}
    for m in prob["environment"]["meshes"]:
        if "file" in m:
            meshes[m["name"]] = read_obj(os.path.join(base, m["file"]))
        else:
            meshes[m["name"]] = (np.array(m["vertices"], float), np.array(m["triangles"], int))
    return prob, meshes


def rivet_area_mesh(prob, ra):
    """The name of the mesh a rivet area lies on (its "mesh" is a name or an index)."""
    return ra["mesh"] if isinstance(ra["mesh"], str) else prob["environment"]["meshes"][ra["mesh"]]["name"]


def problem_of_result(out_dir, result):
    """The absolute path of the problem a result.json was solved from (its
    "problem" is relative to the real output folder)."""
    return os.path.normpath(os.path.join(os.path.realpath(out_dir), result["problem"]))


def with_absolute_files(doc, problem_dir):
    """A copy of a problem document whose file meshes name their files by
    absolute path, so it can be written into any folder."""
    q = copy.deepcopy(doc)
    for m in q["environment"]["meshes"]:
        if "file" in m:
            m["file"] = os.path.join(problem_dir, m["file"])
    return q


def one_load_problem(doc, problem_dir, load, thickness, obstacles, path, base_room=0.0):
    """Writes to `path` the problem `doc` (read from problem_dir) with only
    `load`, the sheet `thickness` (m), the other loads' boxes and `obstacles`
    (inline meshes) added: what sheetgen's own run of the load would avoid
    (every load box and the parts before it). Each other box is lowered by
    `base_room` (m): the room its own base tab needs under it
    (docs/gauge_baseline.md "Reading")."""
    q = with_absolute_files(doc, problem_dir)
    q["environment"]["meshes"] += [box_mesh(other, base_room) for other in doc["loads"] if other["name"] != load["name"]]
    q["environment"]["meshes"] += obstacles
    q["loads"] = [load]
    q.setdefault("material", {})["thickness"] = thickness
    q["description"] = (f"{doc.get('name', '')}: load {load['name']} alone at {thickness * 1e3:.3f} mm sheet, "
                        f"right angles, the other parts as obstacles (bench/gauge_baseline.py)")
    with open(path, "w") as f:
        json.dump(q, f)
