"""``mechsing modes`` against its engine run directly on the same system.

* 3-RPR (examples/planar_3rpr_six.yaml, configuration six): the built-in exact method
  (elimination and certified isolation alone, then the whole command with certification
  and classification) against Bertini 2 on the same three pose equations in (x, y, c, s)
  with c^2 + s^2 = 1.
* Dietmaier's platform (examples/stewart_dietmaier.yaml, the slides set to the published
  leg lengths):
  ``mechsing.assembly.modes`` against ``bertini.solve`` on the same Study-coordinate system
  (recording off in both), with the share of paths that fail or go to infinity.
* UR5 at a generic pose (examples/ur5.yaml with a configuration given by the output's
  pose): ``modes`` against ``bertini.solve`` on the same half-angle system (24 paths).
* The general formulation (Bennett's 4R, the spherical four-bar, a SCARA at a pose):
  ``find`` against ``bertini.solve`` on the same patched system (:func:`general`).
* The leg formulation (a 3-RPS and a Delta, tests/data; Tsai's 3-UPU): ``find`` against
  ``bertini.solve`` on the same Study-coordinate system from its total-degree start
  (:func:`legs`).
* The rod formulation (an RSSR with its crank given, tests/data/rssr.yaml): its closed
  form, refined and certified, tracks no path; against the general formulation, which
  tracked the same loop with Bertini 2 before (:func:`rod`).
* The axis formulation (Bricard's line-symmetric 6R, examples/bricard.yaml at q1-0.4): 24
  paths of the square system with J4 eliminated, every root certified, against the
  general formulation's 120 paths of five random combinations (:func:`axis`).

Times are CPU seconds of this process (the machine is shared).  Run from the repository
root: ``OPENBLAS_NUM_THREADS=1 python benchmarks/modes.py [rpr|dietmaier|ur5|general|legs|rod|axis]``.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import mpmath
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
#: Dietmaier's published leg lengths (ARK 1998)
DIETMAIER_LENGTHS = (1, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071)


def _cpu(f):
    t0 = time.process_time()
    out = f()
    return time.process_time() - t0, out


def _engine(text: str, mptype: str = "adaptive"):
    """``bertini.solve`` on a system's text with recording off (as ``modes`` runs it, in
    the precision model ``mptype``): its CPU seconds and result."""
    import bertini

    was = bertini.recording()
    bertini.recording(False)
    try:
        return _cpu(lambda: bertini.solve(bertini.parse.system(text), seed=34, mptype=mptype))
    finally:
        bertini.recording(was)


def _given(mech, config: str) -> dict:
    """The configuration's given values, read as ``modes`` reads them."""
    from mechsing.assembly.given import read_given
    from mechsing.numeric import parse_precision

    return read_given(mech, config, parse_precision("float"), 50, 1e-9).values


def rpr() -> None:
    import sympy

    from mechsing import load
    from mechsing.assembly import modes
    from mechsing.assembly.engine import system_text
    from mechsing.assembly.exact import eliminate_planar
    from mechsing.assembly.planar import C, S, X, Y, planar_system

    mech = load(ROOT / "examples" / "planar_3rpr_six.yaml")
    system = planar_system(mech, _given(mech, "six"))
    with mpmath.workdps(50):
        t_exact, found = _cpu(lambda: eliminate_planar(system, 50))
    t_all, res = _cpu(lambda: modes(mech, "six", "auto"))
    eqs = [sympy.expand(e) for e in (*system.equations, C**2 + S**2 - 1)]
    t_b, r = _engine(system_text(eqs, [[X, Y, C, S]]))
    real = [z for z in r.solutions if max(abs(complex(v).imag) for v in z) < 1e-8]
    paths = r.solver.num_paths() if callable(r.solver.num_paths) else r.solver.num_paths
    print(
        f"3-RPR six: exact elimination + isolation {t_exact:.2f} s ({len(found.poses)} real, "
        f"proven={found.proven}); modes (certified, classified) {t_all:.2f} s ({res.count}); "
        f"Bertini 2 on the pose system {t_b:.2f} s ({len(r.solutions)} finite of {paths} "
        f"paths, {len(real)} real)"
    )


def dietmaier() -> None:

    from mechsing import load
    from mechsing.adhoc import with_set_values
    from mechsing.assembly import modes
    from mechsing.assembly.engine import system_text
    from mechsing.assembly.spatial import XS, YS, patch_equation, spatial_system

    mech = load(ROOT / "examples" / "stewart_dietmaier.yaml")
    sets = []
    for i, length in enumerate(DIETMAIER_LENGTHS, 1):  # the slides giving the published lengths
        a = np.array(mech.joint(f"U{i}").params["point"], float)
        b = np.array(mech.joint(f"S{i}").params["point"], float)
        u = np.array(mech.joint(f"P{i}").params["axis"], float)
        d = b - a
        sets.append(f"dietmaier:P{i}={float(-d @ u + np.sqrt((d @ u) ** 2 - d @ d + length**2))!r}")
    mech = with_set_values(mech, sets, None, "stewart_dietmaier.yaml")
    system = spatial_system(mech, _given(mech, "dietmaier"))
    text = system_text([*system.equations, patch_equation()], [[*XS, *YS]])
    t_b, r = _engine(text)
    t_m, res = _cpu(lambda: modes(mech, "dietmaier", "float"))
    p = res.paths
    print(
        f"Dietmaier: bertini.solve {t_b:.1f} s ({len(r.solutions)} finite); modes (float "
        f"classification) {t_m:.1f} s: {res.count} real, complete {res.complete}, paths "
        f"{p['tracked']}, {p['finite']} finite, failed or at infinity {p['failed_or_infinite']} "
        f"({100 * p['failed_or_infinite'] / p['tracked']:.0f} %)"
    )


UR5_POSE = "{pose: {position: [-0.3, -0.4, 0.5], axis: [1, 1, 0], angle: 2.1}}"


def ur5() -> None:
    from mechsing import load
    from mechsing.assembly import modes
    from mechsing.assembly.engine import system_text
    from mechsing.assembly.serial import serial_arm, serial_system, serial_target
    from mechsing.kinematics import KinematicModel

    with tempfile.TemporaryDirectory() as tmp:  # the example with one configuration more
        path = Path(tmp) / "ur5.yaml"
        path.write_text((ROOT / "examples" / "ur5.yaml").read_text() + f"  reach: {UR5_POSE}\n")
        mech = load(path)
    with mpmath.workdps(50):
        arm = serial_arm(mech, float(KinematicModel(mech, "float").length_scale))
        system = serial_system(arm, serial_target(mech, "reach", arm)[0])
    t_b, r = _engine(system_text(system.patched, system.groups))
    t_m, res = _cpu(lambda: modes(mech, "reach", "float"))
    p = res.paths
    print(
        f"UR5 at a generic pose: bertini.solve {t_b:.1f} s ({len(r.solutions)} finite); modes "
        f"(float classification) {t_m:.1f} s: {res.count} real, complete {res.complete}, "
        f"paths {p['tracked']}, {p['finite']} finite, {p['extraneous']} extraneous, failed or "
        f"at infinity {p['failed_or_infinite']} ({100 * p['failed_or_infinite'] / p['tracked']:.0f} %)"
    )


#: a SCARA at a target pose (the file tests/test_modes_general.py solves too)
SCARA = ROOT / "tests" / "data" / "scara_at_a_pose.yaml"


def general() -> None:
    """The general formulation (joint displacements in Study coordinates) against
    ``bertini.solve`` on the same patched system in the same precision model: Bennett's 4R
    and the spherical four-bar with their inputs, a SCARA at a pose.  The formulation's
    time holds its second, sliced homotopy (the search for curves of solutions)."""
    from mechsing import load
    from mechsing.assembly import modes
    from mechsing.assembly.engine import system_text
    from mechsing.assembly.general import FORMULATION, MPTYPE, patched_system, problem
    from mechsing.assembly.given import read_given
    from mechsing.assembly.parts import split
    from mechsing.numeric import parse_precision

    cases = [
        ("Bennett 4R, J1 = 1 rad", load(ROOT / "examples" / "bennett.yaml"), "q1-1rad"),
        (
            "spherical four-bar, A = 60 deg",
            load(ROOT / "examples" / "spherical_4r.yaml"),
            "crank-60",
        ),
        ("SCARA at a pose", load(SCARA), "target"),
    ]
    cases.append(("3-RPR at a pose (3 legs apart)", _posed_3rpr(), "target"))
    for label, mech, config in cases:
        with mpmath.workdps(50):
            given = read_given(mech, config, parse_precision("float"), 50, 1e-9)
            prob = problem(given)
            # Bertini on the systems the formulation tracks: each part's (one, unsplit)
            systems = []
            for part in split(prob):
                eqs, groups = patched_system(part)
                randomized = len(part.equations) > part.unknowns
                systems.append((system_text(eqs, groups), MPTYPE if randomized else "adaptive"))
            t_b, r = _engines(systems)
            # the formulation alone: its system built, tracked, refined and certified
            t_f, found = _cpu(lambda g=given: (FORMULATION.applies(g), FORMULATION.find(g))[1])
        t_m, res = _cpu(lambda m=mech, c=config: modes(m, c, "float"))
        print(
            f"{label}: bertini.solve {t_b:.2f} s ({len(r.solutions)} finite); the general "
            f"formulation {t_f:.2f} s ({found.count} real, {found.paths['tracked']} paths, "
            f"ratio {t_f / t_b:.1f}); modes with classification {t_m:.2f} s"
        )
        # the same, warm: what a process that has already loaded both libraries pays per
        # configuration (the first call above also pays the first imports: the analysis's
        # for the closure from the start, Bertini's bindings); the two timed in turn, the
        # certificates' per-system caches cleared before each run of the formulation
        engine, formulation = [], []
        for _ in range(GENERAL_REPEAT):
            with mpmath.workdps(50):
                engine.append(_engines(systems)[0])
                _clear_certificate_caches()
                formulation.append(
                    _cpu(lambda g=given: (FORMULATION.applies(g), FORMULATION.find(g))[1])[0]
                )
        tb, tf = float(np.median(engine)), float(np.median(formulation))
        print(
            f"{label}, warm (medians of {GENERAL_REPEAT}, in turn): bertini.solve {tb:.2f} s, "
            f"the general formulation {tf:.2f} s, ratio {tf / tb:.1f}"
        )


#: the warm rounds of :func:`general`
GENERAL_REPEAT = 5


def _engines(systems: list[tuple[str, str]]) -> tuple[float, Any]:
    """``bertini.solve`` on each system in turn: the summed CPU seconds, and the results
    (their ``solutions`` concatenated)."""
    total, solutions = 0.0, []
    for text, mptype in systems:
        t, r = _engine(text, mptype)
        total += t
        solutions += list(r.solutions)
    return total, SimpleNamespace(solutions=solutions)


def _posed_3rpr() -> Any:
    """The 3-RPR example with a configuration ``target`` that gives the platform's pose
    (its working modes: 8, leg by leg)."""
    from mechsing import load

    text = (ROOT / "examples" / "planar_3rpr.yaml").read_text()
    head = text[: text.index("configurations:")]
    pose = "{position: [1.1, 0.9, 0], rotation_vector: [0, 0, 0.1]}"
    path = Path(tempfile.mkdtemp()) / "planar_3rpr_at_a_pose.yaml"
    path.write_text(f"{head}configurations:\n  reference: {{}}\n  target: {{pose: {pose}}}\n")
    return load(path)


def _clear_certificate_caches() -> None:
    """Forget what the certificates remember per system (a repeated run of one system
    would otherwise reuse its interval functions and term arrays)."""
    from mechsing.assembly import certify

    for name in dir(certify):
        f = getattr(certify, name)
        if callable(f) and hasattr(f, "cache_clear"):
            f.cache_clear()


def legs() -> None:
    """The leg formulation (each leg's constraint on the platform's Study coordinates)
    against ``bertini.solve`` on the same system in the same precision model: the 3-RPS
    and the Delta of tests/data with their inputs."""
    from mechsing import load
    from mechsing.assembly.engine import system_text
    from mechsing.assembly.given import read_given
    from mechsing.assembly.legs import FORMULATION
    from mechsing.assembly.spatial import XS, YS, patch_equation, study_quadric
    from mechsing.numeric import parse_precision

    cases = [
        ("3-RPS, slides 0.3, -0.2, 0.1", ROOT / "tests" / "data" / "three_rps.yaml", "tilted"),
        ("Delta, arms 0.3, -0.2, 0.1 rad", ROOT / "tests" / "data" / "delta.yaml", "driven"),
        ("Tsai's 3-UPU, slides 0.1, -0.05, 0", ROOT / "examples" / "tsai_3upu.yaml", "lateral"),
    ]
    for label, path, config in cases:
        mech = load(path)
        with mpmath.workdps(50):
            given = read_given(mech, config, parse_precision("float"), 50, 1e-9)
            t_f, found = _cpu(lambda g=given: (FORMULATION.applies(g), FORMULATION.find(g))[1])
            pieces = given.cache["legs"]
            eqs = [*(e for p in pieces for e in p.equations), study_quadric(), patch_equation()]
            # the formulation's precision model: double along a U-U piece's quartics
            mptype = "double" if found.formulation["polynomial_degree"] > 2 else "adaptive"
            t_b, r = _engine(system_text(eqs, [[*XS, *YS]]), mptype)  # total-degree start
        paths = r.solver.num_paths() if callable(r.solver.num_paths) else r.solver.num_paths
        print(
            f"{label}: bertini.solve {t_b:.2f} s ({len(r.solutions)} finite of {paths} "
            f"paths); the leg formulation {t_f:.2f} s ({found.count} real, {found.complete}, "
            f"{found.paths['tracked']} paths, {found.paths['solutions']} solutions, "
            f"ratio {t_f / t_b:.1f})"
        )


def rod() -> None:
    """The rod formulation (the rod's length as a quadratic in the other unknown joint,
    no path tracked) against the general formulation's ``find`` on the same RSSR (what
    ``modes`` ran before: Bertini 2 on the loop's Study system, with the coupler's idle
    spin fixed, then Newton and certificates)."""
    from mechsing import load
    from mechsing.assembly import general, rod
    from mechsing.assembly.given import read_given
    from mechsing.numeric import parse_precision

    mech = load(ROOT / "tests" / "data" / "rssr.yaml")
    runs = []
    for form in (rod.FORMULATION, general.FORMULATION):
        with mpmath.workdps(50):
            given = read_given(mech, "crank-30", parse_precision("float"), 50, 1e-9)
            runs.append(_cpu(lambda g=given, f=form: (f.applies(g), f.find(g))[1]))
    (t_r, found), (t_g, old) = runs
    print(
        f"RSSR, crank 30 deg: the rod formulation {t_r:.2f} s ({found.count} real, "
        f"{found.complete}, no path); the general formulation {t_g:.2f} s ({old.count} "
        f"real, {old.complete}, {old.paths['tracked']} paths); ratio {t_r / t_g:.2f}"
    )


def axis() -> None:
    """The axis formulation (one revolute eliminated through its axis: 24 paths, every
    root certified) against the general formulation's ``find`` on Bricard's 6R at J1 =
    0.4 (what ``modes`` ran before)."""
    from mechsing import load
    from mechsing.assembly import axis, general
    from mechsing.assembly.given import read_given
    from mechsing.numeric import parse_precision

    mech = load(ROOT / "examples" / "bricard.yaml")
    runs = []
    for form in (axis.FORMULATION, general.FORMULATION):
        with mpmath.workdps(50):
            given = read_given(mech, "q1-0.4", parse_precision("float"), 50, 1e-9)
            runs.append(_cpu(lambda g=given, f=form: (f.applies(g), f.find(g))[1]))
    (t_a, found), (t_g, old) = runs
    print(
        f"Bricard 6R, J1 = 0.4: the axis formulation {t_a:.2f} s ({found.count} real, "
        f"{found.complete}, {found.paths['tracked']} paths, "
        f"{found.paths['failed_or_infinite']} failed); the general formulation {t_g:.2f} s "
        f"({old.count} real, {old.complete}, {old.paths['tracked']} paths, "
        f"{old.paths['failed_or_infinite']} failed); ratio {t_a / t_g:.2f}"
    )


if __name__ == "__main__":
    import sys

    which = sys.argv[1:] or ["rpr", "dietmaier", "ur5", "general", "legs", "rod", "axis"]
    for name in which:
        globals()[name]()
