"""A part re-checked by CalculiX (`ccx`) over every case of its load, with the
loads, masses and limits rebuilt from the problem file (problem.py), never
taken from result.json's numbers (those are only shown beside, and compared).

* Every static case (its own *STATIC step of the deck `sheetgen export-ccx`
  writes): the compliance f^T u of that step's *CLOAD set with that step's
  displacements, on the reference model, against the case's limit from the
  problem and against ours, within CCX_TOLERANCE; S6 and S4 are shown beside
  it. The reference:
  - the solid model of the part (solid_reference.py: the tabs as t-thick
    plates fused and meshed in C3D10 by gmsh, with the supports, box link and
    loads of the deck). Why not CalculiX's shells: they are meshed from our own
    triangles, and their 20-node expansion (S8R) is 3-10 % softer than the
    solid on parts whose load passes a fold end (docs/fem.md "A solid reference").
  - for a self-riveted part, a bracket (BRACKET). The solid fuses the riveted
    sheets over their whole contact, a bonded lap, stiffer than the rivets the
    part has: on slanted's envelope part, whose one self-rivet joins two
    coplanar tabs over 6.6 cm², the solid is 9-10 % stiffer than ours and S6,
    and with the riveted tab taken off all three agree within 1 % (docs/fem.md
    "Which CalculiX reference"). The S6 deck ties the rivets' footprints as
    ours does. The part lies between the two: ours may be neither below the
    bonded solid nor above the softer of the solid and S6 by more than
    CCX_TOLERANCE, and that softer one is held against the limit. Where S6 is
    the stiffer (the bay's battery, forward 9 g: S6 1.7 % below the bonded
    solid, which no riveted part can be) this is the solid's own rule.
    Sheets too far apart to touch in the solid give no solid, and S6 alone.
  The solid and S6 solve only a linearly independent few of the cases (the
  FAR 25.561 six are three directions) and superpose the others, exactly.
  S8R is not run: soft at fold ends, it is no reference, and it cost the most
  ccx CPU of the four models (551 s of 1688 s on the corner part of
  docs/testing.md "Cost per part").
* The deck's loads are the problem's: each static step's resultant force and
  moment about the centre of mass equal its case's, and the MASS points of the
  *FREQUENCY step have the load's mass, centre of mass and inertia.
* The margin of safety of every case from CalculiX's stresses on the S4 deck
  (ccx_stress.py: surface von Mises per element by the stress rule of
  docs/fem.md applied to CalculiX's own mesh), MS = Fty / (SF sigma) - 1 with
  the problem's Fty and SF: sigma may exceed the stress at which MS equals the
  requirement by at most STRESS_TOLERANCE.
* Where the problem asks for the eigen checks (problem.eigen_requirements, the
  rule of the C++ reader): the lowest linear buckling factor over the cases
  from ccx *BUCKLE steps on the S6 deck, one per load direction of the cases
  (BUCKLE_LOAD_SHARE says at which load), and the first natural frequency from
  its *FREQUENCY step (the sheet's density and the box's mass). A part fails
  when the factor is below min_buckling_factor or f1 below min_frequency_hz at
  all: these floors are requirements an engineer signs against, with no
  tolerance; the solver keeps its own reserve above them for the difference
  between its model and this one (docs/fem.md "Model reserve on the eigen
  checks"). Why S6 and not
  the S4 deck of the stresses: S4 on our split triangles scatters in buckling
  (29 % below S6 on the bay's battery part, 44 % on the shelf's forward case),
  S6 meets the closed forms of docs/fem.md to 0.2 %.

measure_calculix() runs CalculiX and returns the numbers (CalculixMeasure);
judge_calculix() holds them against a problem's requirements; check_calculix()
does both. docs/testing.md "The independent check" gives the cost per part.
"""
import dataclasses
import math
import os
import resource
import subprocess
import tempfile
import time
from typing import Optional

import numpy as np

from . import ccx_deck, problem, solid_reference
from .ccx_stress import max_von_mises_per_block

CCX_TOLERANCE = 0.05  # the check's acceptance bound on compliance (see the module docstring)
STRESS_TOLERANCE = 0.05  # CalculiX's maximum stress may exceed the allowed one by this share
# The *BUCKLE steps carry each case's loads times this share of the buckling
# floor. ccx 2.20 factors with a fixed shift of 1 and reports the factors
# nearest it, so a factor below about half the step's load can be missed
# (ccx_deck.buckling_factors); at a tenth of the floor every factor above a
# tenth of the floor is found, and a passing part's come out near 10, where
# they were found to 1e-6 (docs/testing.md "The independent check").
BUCKLE_LOAD_SHARE = 0.1
# The *BUCKLE steps' card: 2 factors to an accuracy of 1e-4. On the corner part at
# 0.15 x the forward 9 g load, 1 factor at ccx's default accuracy (0.01) came out
# 0.7 % high (11.39 for 11.3098); 2 at 1e-4, 1 at 1e-5 and 3 at 0.01 all gave
# 11.30981, in 22, 26 and 27 s of ccx CPU.
BUCKLE_CARD = "2, 1e-4"
FREQUENCY_MODES = 3  # natural frequencies the *FREQUENCY step asks for
DEFAULT_YIELD = 345e6  # Pa, material.yield_strength's default (Al 2024-T3)
BRACKET = "max(solid, S6)"  # a self-riveted part's reference: the softer of the bonded solid and S6


# --- running CalculiX

@dataclasses.dataclass
class CaseMeasure:
    """One static case by CalculiX."""
    name: str                         # the problem's case
    s4: float                         # J, f^T u on the S4 deck
    s6: float                         # J, on the S6 deck
    reference: float                  # J, on the reference model (the module docstring)
    deflection: float                 # m, |u| of the load's REF node on the reference model
    sigma_max: float                  # Pa, the stress rule on the S4 deck
    buckling_factor: Optional[float] = None  # -, lowest, from the *BUCKLE step of its direction (None: not asked)
    bonded_solid: Optional[float] = None     # J, a self-riveted part's solid (its laps bonded): the stiff bound


@dataclasses.dataclass
class CalculixMeasure:
    """What CalculiX found for one part (measure_calculix)."""
    load: str
    cases: list                       # CaseMeasure per case of the problem, in its order
    reference: str                    # the compliance reference: "solid C3D10", "S6" or BRACKET (the module docstring)
    frequencies_hz: list              # ascending; empty when not asked
    eigen_checked: bool               # the S6 deck had the *BUCKLE and *FREQUENCY steps
    buckle_load_share: float          # the *BUCKLE steps' loads over the cases'
    buckle_steps: int                 # how many *BUCKLE steps (load directions)
    buckling_suspect: list            # cases whose step reported a factor <= 1 (lower ones may be missed)
    n_singular: int                   # singular points of the stress rule
    n_corners: int                    # re-entrant corners among them
    mismatches: list                  # where the deck's loads or masses are not the problem's (failures)
    notes: list                       # the models' sizes and the solid's fallback, one line each
    failures: list                    # models that could not be built or solved
    seconds: dict                     # per model ("S4", "S6", "solid"): (wall s, ccx CPU s)


def _export(sheetgen, out_dir, load, deck, element_type, modes):
    subprocess.run([sheetgen, "export-ccx", os.path.join(out_dir, "result.json"), "--load", load, "--out", deck,
                    "--element-type", element_type, "--buckle", "none", "--modes", str(modes)],
                   check=True, stdout=subprocess.DEVNULL)
    with open(deck) as f:
        return f.read()


def _children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _run_ccx(tmp, job, text):
    """Writes tmp/job.inp, runs ccx (single-threaded unless OMP_NUM_THREADS says
    otherwise): (ccx_deck.DatResults, (wall s, ccx's CPU s))."""
    with open(os.path.join(tmp, job + ".inp"), "w") as f:
        f.write(text)
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "1"))
    t0, cpu0 = time.monotonic(), _children_cpu()
    run = subprocess.run(["ccx", "-i", job], cwd=tmp, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seconds = (time.monotonic() - t0, _children_cpu() - cpu0)
    if run.returncode != 0 or "*ERROR" in run.stdout:
        first = run.stdout[run.stdout.find("*ERROR"):][:300] if "*ERROR" in run.stdout else run.stdout[-300:]
        raise RuntimeError(f"ccx -i {job} failed (status {run.returncode}): {' '.join(first.split())}")
    with open(os.path.join(tmp, job + ".dat")) as f:
        return ccx_deck.read_dat(f.read()), seconds


def deck_mismatches(text, prob, load, cases):
    """Where the deck's static steps and point masses are not the problem's
    `cases` of `load` and its mass properties, one sentence each."""
    statics = ccx_deck.static_steps(text)
    if len(statics) != len(cases):
        return [f"the deck has {len(statics)} static cases, the problem {len(cases)}"]
    xyz, bodies = ccx_deck.nodes(text), ccx_deck.links(text)
    centre = np.asarray(load.get("center_of_mass", load["center"]), float)
    span = float(np.linalg.norm(load["size"]))
    out = []
    for step, case in zip(statics, cases):
        if step.name and step.name != case["name"]:
            out.append(f"static step '{step.name}' stands where the problem has case '{case['name']}'")
        F, M = ccx_deck.load_resultant(step.loads, xyz, bodies, centre)
        scale = np.linalg.norm(case["force"]) * span + np.linalg.norm(case["moment"])
        if np.linalg.norm(F - case["force"]) * span + np.linalg.norm(M - case["moment"]) > 1e-6 * scale:
            out.append(f"case '{case['name']}': the deck applies F {np.round(F, 4).tolist()} N, "
                       f"M {np.round(M, 4).tolist()} N m about the centre of mass; the problem "
                       f"{np.round(case['force'], 4).tolist()} N, {np.round(case['moment'], 4).tolist()} N m")
    return out + mass_mismatches(text, load)


def mass_mismatches(text, load):
    """Where a deck with a *FREQUENCY step does not carry the load's mass
    properties, one sentence each ([] for a deck without that step)."""
    if not any(s.kind == "FREQUENCY" for s in ccx_deck.deck_steps(text)):
        return []
    return _mass_mismatches(ccx_deck.point_masses(text), ccx_deck.nodes(text), load)


def _mass_mismatches(points, xyz, load):
    """The deck's MASS points against the load's mass, centre of mass and
    inertia (problem.load_mass_properties): the same to 1e-6."""
    if "mass" not in load:
        return [f"the deck has {len(points)} MASS points and the load no mass"] if points else []
    m, c, J = problem.load_mass_properties(load)
    if not points:
        return [f"the load has {m:.6g} kg and the deck no MASS point"]
    w = np.array([v for _, v in points])
    X = np.array([xyz[n] for n, _ in points])
    mass = w.sum()
    centre = (w[:, None] * X).sum(axis=0) / mass
    R = X - centre
    S = (w[:, None, None] * R[:, :, None] * R[:, None, :]).sum(axis=0)
    inertia = np.trace(S) * np.eye(3) - S  # J = tr(S) I - S (docs/fem.md "Rigid masses in CalculiX")
    out = []
    if abs(mass - m) > 1e-6 * m:
        out.append(f"the deck's MASS points weigh {mass:.9g} kg, the load {m:.9g} kg")
    if np.linalg.norm(centre - c) > 1e-6 * np.linalg.norm(load["size"]):
        out.append(f"the deck's mass centre {np.round(centre, 6).tolist()} m is not the load's {np.round(c, 6).tolist()} m")
    if np.linalg.norm(inertia - J) > 1e-6 * np.linalg.norm(J):
        out.append(f"the deck's MASS points have the inertia {np.round(inertia, 6).tolist()} kg m^2, "
                   f"the load {np.round(J, 6).tolist()} kg m^2")
    return out


def _s4_run(sheetgen, out_dir, part, tmp, t, bend_radius):
    """The S4 deck with every static case, stresses printed: (deck text, per
    case (C J, REF node |u| m, sigma Pa), (n_singular, n_corners), seconds)."""
    text = _export(sheetgen, out_dir, part["load"], os.path.join(tmp, "export4.inp"), "S4", 0)
    text = ccx_deck.with_static_steps_only(text, extra="*EL PRINT, ELSET=EALL\nS\n")
    dat, seconds = _run_ccx(tmp, "part", text)
    statics = ccx_deck.static_steps(text)
    blocks = dat.static_displacements()
    if len(blocks) != len(statics) or len(dat.stresses) != len(statics):
        raise RuntimeError(f"the S4 .dat has {len(blocks)} displacement and {len(dat.stresses)} stress blocks "
                           f"for {len(statics)} static steps")
    sigmas, n_singular, n_corners = max_von_mises_per_block(text, dat.stresses, t, bend_radius)
    bodies = ccx_deck.links(text)
    solved = [(ccx_deck.compliance(s.loads, u), float(np.linalg.norm(u[ccx_deck.loaded_ref_node(s.loads, bodies)])),
               sigma) for s, u, sigma in zip(statics, blocks, sigmas)]
    return text, solved, (n_singular, n_corners), seconds


@dataclasses.dataclass
class _S6:
    """What the S6 deck gave."""
    text: str              # the deck as exported (every static step), *BUCKLE steps added where asked
    cases: list            # per static case (C J, REF node |u| m)
    factors: dict          # ccx_deck.buckling_factors: {static case index: (factor, step's own, step)}; {} unasked
    steps: int             # *BUCKLE steps run
    suspects: list         # cases whose step reported a factor <= 1 (lower ones may be missed)
    frequencies_hz: list   # ascending; [] unasked
    seconds: tuple         # (wall s, ccx CPU s)


def _s6_run(sheetgen, out_dir, part, tmp, eigen):
    """The S6 deck: its static cases (a linearly independent few solved, the
    rest superposed) and, where the eigen checks apply, a *BUCKLE step per
    load direction and the *FREQUENCY step (_S6)."""
    modes = FREQUENCY_MODES if eigen.checked else 0
    text = _export(sheetgen, out_dir, part["load"], os.path.join(tmp, "export6.inp"), "S6", modes)
    if eigen.checked:
        text = ccx_deck.with_buckle_steps(text, BUCKLE_LOAD_SHARE * eigen.min_buckling_factor, BUCKLE_CARD)
    statics = ccx_deck.static_steps(text)
    basis, A = ccx_deck.independent_cases([s.loads for s in statics])
    dat, seconds = _run_ccx(tmp, "part6", ccx_deck.with_static_steps_only(text, keep=set(basis), perturbations=True))
    blocks = dat.static_displacements()
    if len(blocks) != len(basis):
        raise RuntimeError(f"the S6 .dat has {len(blocks)} displacement blocks for {len(basis)} static steps")
    bodies = ccx_deck.links(text)
    cases = []
    for k, s in enumerate(statics):
        u = ccx_deck.superpose(A[k], blocks)
        cases.append((ccx_deck.compliance(s.loads, u), float(np.linalg.norm(u[ccx_deck.loaded_ref_node(s.loads, bodies)]))))
    factors = ccx_deck.buckling_factors(ccx_deck.deck_steps(text), dat) if eigen.checked else {}
    suspects = sorted({statics[k].name or f"case {k + 1}" for k, (_, reported, _) in factors.items() if reported <= 1.0})
    return _S6(text=text, cases=cases, factors=factors, steps=len(dat.buckling_factors), suspects=suspects,
               frequencies_hz=dat.frequencies_hz[0] if dat.frequencies_hz else [], seconds=seconds)


def _solid_run(part, deck, tmp, notes, failures):
    """Per static case (C J, |u| m) on the solid model, or None (the reason in notes or failures)."""
    name = part["load"]
    try:
        solid = solid_reference.solid_compliance(part, deck, tmp)
    except solid_reference.SolidNotApplicable as e:
        notes.append(f"{name}: no solid model ({e}); compliance checked against S6")
        return None
    except Exception as e:  # gmsh or ccx failed on this part: a failed check, not a crash
        failures.append(f"{name}: the solid model could not be built or solved ({type(e).__name__}: {e})")
        return None
    notes.append(f"{name}: solid model h = {solid['h'] * 1e3:.2f} mm, {solid['nodes']} nodes, {solid['elements']} "
                 f"C3D10, {solid['fixed']} fixed, {solid['rigid']} in the box link; {solid['solved']} of "
                 f"{len(solid['cases'])} cases solved, the others superposed")
    return [(c["C"], c["deflection"]) for c in solid["cases"]]


def measure_calculix(out_dir, prob, part, sheetgen):
    """Every number CalculiX gives for one part of out_dir/result.json (CalculixMeasure)."""
    t = prob.get("material", {}).get("thickness", 1.6e-3)
    bend_radius = prob.get("manufacturing", {}).get("bend_radius", 4 * t)
    load = next(ld for ld in prob["loads"] if ld["name"] == part["load"])
    cases = problem.load_cases(prob, load)
    eigen = problem.eigen_requirements(prob)
    notes, failures, seconds = [], [], {}
    with tempfile.TemporaryDirectory() as tmp:
        text, s4, (n_singular, n_corners), seconds["S4"] = _s4_run(sheetgen, out_dir, part, tmp, t, bend_radius)
        s6 = _s6_run(sheetgen, out_dir, part, tmp, eigen)
        seconds["S6"] = s6.seconds
        mismatches = deck_mismatches(text, prob, load, cases) + mass_mismatches(s6.text, load)
        t0, cpu0 = time.monotonic(), _children_cpu()
        solid = _solid_run(part, text, tmp, notes, failures)
        seconds["solid"] = (time.monotonic() - t0, _children_cpu() - cpu0)  # CPU: ccx's, not gmsh's (in this process)
    bonded = solid if solid and part.get("self_rivets") else None
    if bonded:
        notes.append(f"{part['load']}: self-riveted: the solid bonds each lap whole, a stiffer joint than the "
                     "rivets; ours is checked between it and the softer of it and S6")
        reference = [max(a, b) for a, b in zip(solid, s6.cases)]  # (C, |u|) of the softer, per case
    else:
        reference = solid or s6.cases
    measured = [CaseMeasure(name=c["name"], s4=s4[k][0], s6=s6.cases[k][0],
                            reference=reference[k][0], deflection=reference[k][1], sigma_max=s4[k][2],
                            buckling_factor=s6.factors[k][0] if k in s6.factors else None,
                            bonded_solid=bonded[k][0] if bonded else None)
                for k, c in enumerate(cases[:len(s4)])]
    return CalculixMeasure(load=part["load"], cases=measured,
                           reference=BRACKET if bonded else "solid C3D10" if solid else "S6",
                           frequencies_hz=s6.frequencies_hz, eigen_checked=eigen.checked,
                           buckle_load_share=BUCKLE_LOAD_SHARE * eigen.min_buckling_factor,
                           buckle_steps=s6.steps, buckling_suspect=s6.suspects,
                           n_singular=n_singular, n_corners=n_corners, mismatches=mismatches, notes=notes,
                           failures=failures, seconds=seconds)


# --- holding the numbers against the requirements

def ours_of(part):
    """Our numbers in result.json, to show beside CalculiX's and compare:
    ({case name: that case's dict} from parts[i].envelope.cases, the envelope's
    buckling_factor (math.inf where it is null after an eigen check: nothing
    buckles; None where result.json has none), its frequencies_hz or [])."""
    env = part.get("envelope") or {}
    cases = {c["name"]: c for c in env.get("cases") or [] if isinstance(c, dict) and "name" in c}
    factor = env.get("buckling_factor")
    if factor is None and env.get("eigen_checked"):
        factor = math.inf
    return cases, factor, list(env.get("frequencies_hz") or [])


def _ours_case(part, case_name, k):
    """Our numbers of case k (named case_name) where result.json says them: the
    envelope's case of that name, else (a result without an envelope) the
    part's own fields for the first case; {} when unknown. Keys as in result.json
    (compliance, deflection_m, max_von_mises_pa, margin_of_safety)."""
    by_name, _, _ = ours_of(part)
    if by_name:
        return by_name.get(case_name, {})
    return part if k == 0 and not part.get("envelope") else {}


def _percent(a, b):
    return f"{(a / b - 1) * 100:+.2f} %"


@dataclasses.dataclass
class _CaseVerdict:
    name: str
    ratio: float                      # C / C_max, the reference model's
    ms: float                         # MS from CalculiX's stress
    limit: float                      # J
    ours: dict                        # _ours_case


def _check_agreement(name, case_name, C, c, reference, findings):
    """Ours (C, J) against CalculiX's case c: within CCX_TOLERANCE of the
    reference, or for a self-riveted part inside the bracket from the bonded
    solid to the reference (the softer of it and S6), each end widened by it."""
    low = c.bonded_solid if c.bonded_solid is not None else c.reference
    if C < (1 - CCX_TOLERANCE) * low or C > (1 + CCX_TOLERANCE) * c.reference:
        off = C / low - 1 if C < low else C / c.reference - 1
        what = "the solid with its laps bonded" if c.bonded_solid is not None and C < low else f"CalculiX ({reference})"
        findings.fail(f"{name}: case '{case_name}': compliance differs from {what} by {off * 100:.1f} %")


def _judge_case(prob, part, m, k, case, findings):
    """Compliance and MS of one case (_CaseVerdict)."""
    name, c = part["load"], m.cases[k]
    req = prob.get("requirements", {})
    limit = problem.compliance_limit(prob, case)
    fty = prob.get("material", {}).get("yield_strength", DEFAULT_YIELD)
    sf = req.get("safety_factor", problem.DEFAULT_SAFETY_FACTOR)
    ms_required = req.get("min_margin_of_safety", 0.0)
    ms = fty / (sf * c.sigma_max) - 1 if c.sigma_max > 0 else math.inf
    line = (f"{name}: case '{case['name']}': compliance CalculiX {m.reference} {c.reference:.5g} J, "
            + (f"S6 {c.s6:.5g} J, " if m.reference != "S6" else "")
            + f"S4 {c.s4:.5g} J; limit {limit:.4g} J (C/C_max {c.reference / limit:.3f}); "
            f"deflection {c.deflection * 1e3:.4f} mm; max von Mises {c.sigma_max * 1e-6:.2f} MPa, MS {ms:.3f}")
    ours = _ours_case(part, case["name"], k)
    if ours.get("compliance") is not None:
        line += f"; ours C {ours['compliance']:.5g} J ({_percent(ours['compliance'], c.reference)})"
        _check_agreement(name, case["name"], ours["compliance"], c, m.reference, findings)
    if c.bonded_solid is not None:
        line += f"; bonded solid {c.bonded_solid:.5g} J (the bracket's stiff end)"
    findings.note(line)
    if c.reference > (1 + CCX_TOLERANCE) * limit:
        findings.fail(f"{name}: case '{case['name']}': CalculiX ({m.reference}) compliance {c.reference:.4g} J "
                      f"exceeds the limit {limit:.4g} J")
    allowed = fty / (sf * (1 + ms_required))  # Pa, the stress at which MS = required
    if c.sigma_max > (1 + STRESS_TOLERANCE) * allowed:
        findings.fail(f"{name}: case '{case['name']}': CalculiX stress {c.sigma_max * 1e-6:.1f} MPa gives MS "
                      f"{ms:.3f} below the required {ms_required:.3g} by more than "
                      f"{STRESS_TOLERANCE * 100:.0f} % of the stress")
    return _CaseVerdict(case["name"], c.reference / limit, ms, limit, ours)


def _governing_lines(prob, part, m, verdicts, findings):
    """The worst C/C_max case's compliance and the lowest MS case's stress in
    the one-line forms of the one-case check (scripts/make_report.py reads
    them), where result.json has our numbers for those cases."""
    name = part["load"]
    k = max(range(len(verdicts)), key=lambda i: verdicts[i].ratio)
    v, c = verdicts[k], m.cases[k]
    if v.ours.get("compliance") is not None:
        C = v.ours["compliance"]
        deflection = v.ours.get("deflection_m")
        findings.note(f"{name}: compliance ours {C:.5g} J, CalculiX {m.reference} {c.reference:.5g} J "
                      f"({_percent(C, c.reference)}), "
                      + (f"S6 {c.s6:.5g} J ({_percent(C, c.s6)}), " if m.reference != "S6" else "")
                      + f"S4 {c.s4:.5g} J "
                      f"({_percent(C, c.s4)}); deflection ours "
                      f"{'%.4f mm' % (deflection * 1e3) if deflection is not None else 'not in result.json'}, "
                      f"CalculiX {c.deflection * 1e3:.4f} mm; limit {v.limit:.4g} J (case '{v.name}', the worst C/C_max)")
    k = min(range(len(verdicts)), key=lambda i: verdicts[i].ms)
    v, c = verdicts[k], m.cases[k]
    s_ours, ms_ours = v.ours.get("max_von_mises_pa"), v.ours.get("margin_of_safety")
    if s_ours is not None and ms_ours is not None:
        required = prob.get("requirements", {}).get("min_margin_of_safety", 0.0)
        findings.note(f"{name}: max von Mises ours {s_ours * 1e-6:.2f} MPa, CalculiX {c.sigma_max * 1e-6:.2f} MPa "
                      f"({_percent(s_ours, c.sigma_max)}; {m.n_singular} singular points, {m.n_corners} re-entrant "
                      f"corners); MS ours {ms_ours:.3f}, CalculiX {v.ms:.3f}, required {required:.3g} "
                      f"(case '{v.name}', the lowest MS)")


def _judge_eigen(prob, part, m, findings):
    """The lowest buckling factor and the first frequency against the floors;
    returns (factor, its case, f1 Hz) (None where not measured)."""
    name = part["load"]
    eigen = problem.eigen_requirements(prob)
    buckled = [c for c in m.cases if c.buckling_factor is not None]
    lowest = min(buckled, key=lambda c: c.buckling_factor) if buckled else None
    f1 = m.frequencies_hz[0] if m.frequencies_hz else None
    if not eigen.checked:
        return None, None, None
    if not m.eigen_checked:
        findings.fail(f"{name}: the problem asks for the buckling and frequency checks and CalculiX ran neither")
        return None, None, None
    missing = [c.name for c in m.cases if c.buckling_factor is None]
    if missing:
        findings.fail(f"{name}: no CalculiX buckling factor for the cases {missing}")
    if m.buckling_suspect:
        findings.note(f"{name}: the *BUCKLE step of {m.buckling_suspect} reported a factor at or below its "
                      "load: ccx 2.20 may have missed lower ones")
    if lowest is not None and math.isinf(lowest.buckling_factor):
        findings.note(f"{name}: no positive CalculiX buckling factor in any case ({m.buckle_steps} *BUCKLE steps): "
                      "no case compresses the sheet")
    elif lowest is not None:
        findings.note(f"{name}: buckling factor CalculiX S6 {lowest.buckling_factor:.4g} ('{lowest.name}'; "
                      f"{m.buckle_steps} *BUCKLE steps at {m.buckle_load_share:.3g} x the loads), "
                      f"required {eigen.min_buckling_factor:.3g}")
        if lowest.buckling_factor < eigen.min_buckling_factor:
            findings.fail(f"{name}: CalculiX buckling factor {lowest.buckling_factor:.4g} ('{lowest.name}') is below "
                          f"the required {eigen.min_buckling_factor:.3g}")
    if f1 is not None:
        floor = eigen.min_frequency_hz
        findings.note(f"{name}: natural frequencies CalculiX S6 {', '.join(f'{f:.4g}' for f in m.frequencies_hz)} Hz; "
                      + (f"required f1 >= {floor:.4g} Hz" if floor is not None else "no floor on f1"))
        if floor is not None and f1 < floor:
            findings.fail(f"{name}: CalculiX first frequency {f1:.4g} Hz is below the required {floor:.4g} Hz")
    return (lowest.buckling_factor if lowest else None), (lowest.name if lowest else None), f1


def judge_calculix(prob, part, m, findings):
    """Holds a CalculixMeasure against the requirements of `prob` (which may
    differ from the one it was measured for in its requirements only) and
    notes one summary line: worst C/C_max, lowest MS, buckling factor and f1,
    CalculiX's and ours."""
    name = part["load"]
    for line in m.notes:
        findings.note(line)
    for line in m.failures:
        findings.fail(line)
    for line in m.mismatches:
        findings.fail(f"{name}: the deck's loads are not the problem's: {line}")
    load = next(ld for ld in prob["loads"] if ld["name"] == name)
    cases = problem.load_cases(prob, load)
    findings.note(f"{name}: stress rule on the S4 deck: {m.n_singular} singular points, {m.n_corners} re-entrant corners")
    verdicts = [_judge_case(prob, part, m, k, case, findings) for k, case in enumerate(cases[:len(m.cases)])]
    _governing_lines(prob, part, m, verdicts, findings)
    factor, factor_case, f1 = _judge_eigen(prob, part, m, findings)
    worst = max(verdicts, key=lambda v: v.ratio)
    weakest = min(verdicts, key=lambda v: v.ms)
    _, ours_factor, ours_f = ours_of(part)
    summary = (f"{name}: envelope by CalculiX: worst C/C_max {worst.ratio:.3f} ('{worst.name}'), "
               f"lowest MS {weakest.ms:.3f} ('{weakest.name}')")
    if factor is not None:
        summary += f", buckling factor {factor:.4g} ('{factor_case}')"
        summary += f" / ours {ours_factor:.4g}" if ours_factor is not None else " / ours not in result.json"
    if f1 is not None:
        summary += f", f1 {f1:.4g} Hz"
        summary += f" / ours {ours_f[0]:.4g} Hz" if ours_f else " / ours not in result.json"
    findings.note(summary)
    findings.note(f"{name}: CalculiX time, wall (ccx CPU): " +
                  ", ".join(f"{k} {wall:.0f} s ({cpu:.0f} s)" for k, (wall, cpu) in m.seconds.items()))


def check_calculix(out_dir, prob, part, sheetgen, findings):
    """measure_calculix and judge_calculix of one part of out_dir/result.json;
    a model that cannot be run is a failure of this part, not a crash."""
    try:
        m = measure_calculix(out_dir, prob, part, sheetgen)
    except (subprocess.CalledProcessError, RuntimeError, ValueError, KeyError) as e:
        findings.fail(f"{part['load']}: the CalculiX check could not run ({type(e).__name__}: {e})")
        return None
    judge_calculix(prob, part, m, findings)
    return m
