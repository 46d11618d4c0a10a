"""A CalculiX deck of `sheetgen export-ccx` and its .dat, read independently of
sheetgen's own reader (native/sheetgen/fem/ccx_results.cpp does the same in C++).

* deck_steps(): the steps in order (*BUCKLE, *FREQUENCY, *STATIC), each with
  the concentrated loads in effect and the case name of its `** ...` comment.
  ccx keeps a step's *CLOAD in the next one unless `OP=NEW`; a perturbation
  step (*BUCKLE, *FREQUENCY) starts from none (docs/fem.md "CalculiX export").
* rigid_bodies(), point_masses(): the *RIGID BODY sets (RIGIDi are the model's
  links, MASSk the six-point stand-ins of a box's mass) and the MASS elements.
* read_dat(): every displacement block with its set, every stress block, the
  buckling factors of each *BUCKLE step and the frequencies (Hz) of each
  *FREQUENCY step.
* with_buckle_steps(): the deck with one *BUCKLE step per load direction of its
  static cases, each with the case's loads scaled (see buckling_factors()).
* independent_cases() and superpose(): the static cases of a deck as
  combinations of a few of them, so a costly model solves only those.
"""
import dataclasses
import math
import re

import numpy as np

PERTURBATION_STEPS = ("BUCKLE", "FREQUENCY")
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


@dataclasses.dataclass
class Step:
    kind: str                         # "STATIC", "BUCKLE", "FREQUENCY", ...
    name: str                         # the case named in the comment before *STEP ('...'), "" when none
    loads: dict                       # {(node id, dof 1-6): value} in effect: N on 1-3, N m on a ROT node's 1-3
    factors: int = 0                  # *BUCKLE / *FREQUENCY: how many factors or modes the step asks for


def _keyword(line):
    """The upper-case keyword of a `*KEYWORD, PARAM=...` line."""
    return line[1:].split(",")[0].strip().upper()


def deck_steps(text):
    """The deck's steps in order (Step)."""
    steps, comment, step, in_cload, loads = [], "", None, False, {}
    previous = {}
    lines = text.splitlines()
    for k, line in enumerate(lines):
        if line.startswith("**"):
            comment = line
            continue
        if line.startswith("*"):
            key = _keyword(line)
            in_cload = False
            if key == "STEP":
                name = re.search(r"'(.*)'", comment)
                step = Step(kind="", name=name.group(1) if name else "", loads={})
                loads = {}
            elif step is not None and not step.kind and key != "END STEP":
                step.kind = key
                if key in PERTURBATION_STEPS:
                    nxt = lines[k + 1] if k + 1 < len(lines) else ""
                    step.factors = int(nxt.split(",")[0]) if re.match(r"\s*\d", nxt) else 1
                else:
                    loads = dict(previous)
            elif key == "CLOAD" and step is not None:
                in_cload = True
                if re.search(r"OP\s*=\s*NEW", line, re.I):
                    loads = {}
            elif key == "END STEP" and step is not None:
                step.loads = loads
                steps.append(step)
                previous = {} if step.kind in PERTURBATION_STEPS else loads
                step = None
            comment = ""
            continue
        if in_cload and line.strip():
            node, dof, value = (p.strip() for p in line.split(",")[:3])
            loads[(int(node), int(dof))] = float(value)
        if line.strip():
            comment = ""
    return steps


def static_steps(text):
    return [s for s in deck_steps(text) if s.kind == "STATIC"]


def section_lines(text, keyword, **params):
    """Data lines of every section opened by the keyword line `*KEYWORD` (e.g.
    "NODE"; not *NODE PRINT) whose parameters include `params` (e.g. NSET="RIGID1"),
    each up to the next keyword line."""
    out, inside = [], False
    for line in text.splitlines():
        if line.startswith("*"):
            inside = not line.startswith("**") and _keyword(line) == keyword.upper() and all(
                re.search(r",\s*" + k + r"\s*=\s*" + re.escape(str(v)) + r"\s*(,|$)", line, re.I)
                for k, v in params.items())
            continue
        if inside and line.strip():
            out.append(line)
    return out


def nodes(text):
    """{node id: (3,) m} of every *NODE section."""
    out = {}
    for line in section_lines(text, "NODE"):
        p = line.split(",")
        if len(p) >= 4:
            out[int(p[0])] = np.array([float(v) for v in p[1:4]])
    return out


def rigid_bodies(text):
    """[(set name, REF node, ROT node, [node ids])] of the *RIGID BODY cards."""
    bodies = []
    for m in re.finditer(r"^\*RIGID BODY,\s*NSET=(\w+),\s*REF NODE=(\d+),\s*ROT NODE=(\d+)", text, re.M | re.I):
        members = [int(v) for line in section_lines(text, "NSET", NSET=m.group(1)) for v in line.split(",") if v.strip()]
        bodies.append((m.group(1), int(m.group(2)), int(m.group(3)), members))
    return bodies


def links(text):
    """The rigid bodies of the model's links (RIGIDi), without the mass stand-ins (MASSk)."""
    return [b for b in rigid_bodies(text) if not b[0].upper().startswith("MASS")]


def point_masses(text):
    """[(node id, kg)] of the MASS elements (*ELEMENT, TYPE=MASS with their *MASS, ELSET=...)."""
    values = {}
    for m in re.finditer(r"^\*MASS,\s*ELSET=(\w+)\s*\n\s*(" + _NUMBER + ")", text, re.M | re.I):
        values[m.group(1)] = float(m.group(2))
    out = []
    for m in re.finditer(r"^\*ELEMENT,\s*TYPE=MASS,\s*ELSET=(\w+)\s*$", text, re.M | re.I):
        body = text[m.end() + 1:].split("\n*")[0]
        for line in body.splitlines():
            p = line.split(",")
            if len(p) >= 2 and p[1].strip():
                out.append((int(p[1]), values[m.group(1)]))
    return out


def load_resultant(loads, node_xyz, bodies, point):
    """(force N (3,), moment N m (3,) about `point`) of a step's loads: forces
    on nodes, and moments on the ROT nodes of `bodies` (their dofs 1-3)."""
    rot_nodes = {b[2] for b in bodies}
    F, M = np.zeros(3), np.zeros(3)
    for (node, dof), value in loads.items():
        if node in rot_nodes:
            M[dof - 1] += value
        else:
            f = np.zeros(3)
            f[dof - 1] = value
            F += f
            M += np.cross(node_xyz[node] - point, f)
    return F, M


def loaded_ref_node(loads, bodies):
    """The REF node of the body whose REF or ROT node carries the loads, else
    the first loaded node (its |u| is the case's deflection)."""
    loaded = {node for node, _ in loads}
    for _, ref, rot, _ in bodies:
        if ref in loaded or rot in loaded:
            return ref
    return min(loaded) if loaded else None


# --- the .dat

_BLOCKS = {"displacements (vx,vy,vz)": "u", "stresses (elem, integ.pnt.": "s",
           "B U C K L I N G   F A C T O R   O U T P U T": "buckle", "E I G E N V A L U E   O U T P U T": "freq"}


@dataclasses.dataclass
class DatResults:
    displacements: list               # [(set name, {node: (3,) m})], in print order
    stresses: list                    # [{element: [[6 Pa] per integration point]}], in print order
    buckling_factors: list            # per *BUCKLE step, its factors (-) as printed (ascending)
    frequencies_hz: list              # per *FREQUENCY step, its frequencies (Hz, ascending)

    def static_displacements(self, set_name="NALL"):
        """The displacement blocks of `set_name` (each static step prints one)."""
        return [u for s, u in self.displacements if s.upper() == set_name]


def read_dat(text):
    """Every block of a ccx .dat (DatResults). A block's rows follow its header;
    a non-blank line that is not a row ends it."""
    r = DatResults([], [], [], [])
    kind, rows = None, 0
    for line in text.splitlines():
        opened = next((v for k, v in _BLOCKS.items() if k in line), None)
        if opened:
            kind, rows = opened, 0
            if kind == "u":
                set_name = re.search(r"for set (\S+)", line)
                r.displacements.append((set_name.group(1) if set_name else "", {}))
            elif kind == "s":
                r.stresses.append({})
            elif kind == "buckle":
                r.buckling_factors.append([])
            else:
                r.frequencies_hz.append([])
            continue
        p = line.split()
        if kind is None or not p:
            continue
        # Rows: an id, then numbers (a stress row ends in its section's name, e.g. _shell_0000000001).
        count = {"u": 3, "s": 7, "buckle": 1, "freq": 4}[kind]
        row = p[0].isdigit() and len(p) >= count + 1 and all(re.fullmatch(_NUMBER, v) for v in p[1:count + 1])
        if not row:
            if rows:
                kind = None
            continue
        rows += 1
        if kind == "u":
            r.displacements[-1][1][int(p[0])] = np.array([float(v) for v in p[1:4]])
        elif kind == "s":
            r.stresses[-1].setdefault(int(p[0]), {})[int(p[1])] = [float(v) for v in p[2:8]]
        elif kind == "buckle":
            r.buckling_factors[-1].append(float(p[1]))
        else:
            r.frequencies_hz[-1].append(float(p[3]))  # eigenvalue, omega (rad/time), f (cycles/time), imaginary
    return r


def compliance(loads, u):
    """f^T u (J) of a step's loads with its displacements {node: (3,)} (a ROT
    node's "translations" are the rotations its moments work on)."""
    return float(sum(value * u[node][dof - 1] for (node, dof), value in loads.items()))


# --- buckling steps

def _vector(loads, keys):
    return np.array([loads.get(k, 0.0) for k in keys])


def parallel_ratio(a, b, rtol=1e-9):
    """s > 0 with loads a = s b (dicts {(node, dof): value}), else None."""
    keys = sorted(set(a) | set(b))
    va, vb = _vector(a, keys), _vector(b, keys)
    nb = np.linalg.norm(vb)
    if nb == 0 or np.linalg.norm(va) == 0:
        return None
    s = float(va @ vb) / (nb * nb)
    return s if s > 0 and np.linalg.norm(va - s * vb) <= rtol * np.linalg.norm(va) else None


def buckle_step(name, loads, scale, card="3"):
    """A *BUCKLE step (text) of `loads` times `scale`; `card` is its data line
    (factors wanted, accuracy, Lanczos vectors, iterations)."""
    lines = [f"** Linear buckling of load case '{name}', its loads times {scale:.6g} (sheetgen_tools.ccx_check)",
             "*STEP", "*BUCKLE", card, "*CLOAD"]
    lines += [f"{node}, {dof}, {value * scale:.13g}" for (node, dof), value in sorted(loads.items())]
    return "\n".join(lines + ["*END STEP"]) + "\n"


def split_steps(text):
    """(the model section, [each step's text with the comment lines before it])."""
    lines = text.splitlines(keepends=True)
    starts = [k for k, line in enumerate(lines) if line.strip().upper() == "*STEP"]
    if not starts:
        return text, []
    cuts = []
    for k in starts:
        while k > 0 and lines[k - 1].startswith("**"):
            k -= 1
        cuts.append(k)
    model = "".join(lines[:cuts[0]])
    steps = ["".join(lines[a:b]) for a, b in zip(cuts, cuts[1:] + [len(lines)])]
    return model, steps


def step_kind(step_text):
    """The procedure keyword of one step's text (STATIC, BUCKLE, FREQUENCY)."""
    return deck_steps(step_text)[0].kind


def with_buckle_steps(text, scale, card="3"):
    """The deck with a *BUCKLE step per direction of its static cases' loads
    (cases whose loads are positive multiples of an earlier one share its step),
    placed before its first step; each step's loads are the case's times `scale`."""
    firsts = []
    for s in static_steps(text):
        if s.loads and not any(parallel_ratio(s.loads, f.loads) for f in firsts):
            firsts.append(s)
    model, steps = split_steps(text)
    return model + "".join(buckle_step(s.name, s.loads, scale, card) for s in firsts) + "".join(steps)


def with_static_steps_only(text, keep=None, extra="", perturbations=False):
    """The deck with, of its static steps, only the indices in `keep` (all when
    None), and its perturbation steps (*BUCKLE, *FREQUENCY, which carry their
    own loads or none) dropped unless `perturbations`; `extra` (output
    requests) is added to each kept static step. Every step after ccx's first
    writes *CLOAD, OP=NEW, so dropping one leaves the others' loads as they were."""
    model, steps = split_steps(text)
    kept, k = [], 0
    for s in steps:
        if step_kind(s) != "STATIC":
            if perturbations:
                kept.append(s)
            continue
        if keep is None or k in keep:
            kept.append(s.replace("*END STEP", extra + "*END STEP") if extra else s)
        k += 1
    return model + "".join(kept)


def buckling_factors(steps, dat):
    """{static case index: (lowest factor, the step's own lowest factor, index
    of the *BUCKLE step)}: each *BUCKLE step's lowest positive factor (dat:
    DatResults) turned into a factor of every static case whose loads are a
    positive multiple of the step's. A step with no positive factor (a case
    that compresses nothing: ccx then reports a negative one, buckling under
    the reversed load) gives math.inf.

    ccx 2.20 (arpackbu.c) solves with a fixed shift of 1 and reports the factors
    nearest it: with the step's load above the lowest buckling load (factors < 1)
    lower ones can be missed (a clamped strip under 100 x its Euler load: 1.295
    reported, the second mode, where 0.144 is the first). Factors above 1 come
    first, so a step's lowest factor is the true one whenever that exceeds 1,
    and at most one below about half the step's load can be missed: the check
    applies a fraction of each case's load (with_buckle_steps)."""
    buckles = [s for s in steps if s.kind == "BUCKLE"]
    statics = [s for s in steps if s.kind == "STATIC"]
    if len(buckles) != len(dat.buckling_factors):
        raise ValueError(f"the deck has {len(buckles)} *BUCKLE steps and the .dat {len(dat.buckling_factors)} "
                         "buckling factor blocks")
    out = {}
    for b, (step, factors) in enumerate(zip(buckles, dat.buckling_factors)):
        positive = [f for f in factors if f > 0]
        own = min(positive) if positive else math.inf
        for k, case in enumerate(statics):
            ratio = parallel_ratio(step.loads, case.loads)
            if ratio is not None and (k not in out or own * ratio < out[k][0]):
                out[k] = (own * ratio, own, b)
    return out


# --- superposition over the static cases

def independent_cases(load_sets, rtol=1e-9):
    """Indices of a maximal linearly independent subset of the cases' loads
    (dicts {(node, dof): value}), earliest first, and the coefficients that give
    every case from them: (basis indices, A #cases by #basis) with loads_k = sum_j A[k, j] loads_basis[j]."""
    keys = sorted(set().union(*load_sets)) if load_sets else []
    V = np.array([_vector(s, keys) for s in load_sets]).reshape(len(load_sets), len(keys))
    basis = []
    for k in range(len(V)):
        trial = basis + [k]
        if np.linalg.matrix_rank(V[trial], tol=rtol * max(1.0, np.abs(V).max())) == len(trial):
            basis = trial
    if not basis:
        return [], np.zeros((len(V), 0))
    A = np.linalg.lstsq(V[basis].T, V.T, rcond=None)[0].T
    return basis, A


def superpose(coefficients, solutions):
    """{node: (3,)} = sum_j coefficients[j] solutions[j] over the nodes of solutions[0]."""
    return {n: sum(a * s[n] for a, s in zip(coefficients, solutions)) for n in solutions[0]}
