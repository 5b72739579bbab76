"""A limit of travel's class and the path's stop note do not depend on the sample step
(issue 27, item 6).

The mechanism is tests/data/planar_3rrr.yaml, a symmetric planar 3-RRR whose platform is
turned about its reference point (``--vary pose.rz``).  The expected limit comes from the
file's joint points read by the reference reader (tests/reference) and plane geometry
alone: a leg A-B-C with the platform pivot C given reaches it while |AC| lies between
|AB| - |BC| and |AB| + |BC|, and a turn by rz about the platform's reference point p moves
C to p + R(rz)(C0 - p), so |AC|^2 = |d|^2 + |r|^2 + 2 rho cos(rz + phi) (d = p - A,
r = C0 - p, rho cos phi = d.r, rho sin phi = (d x r)_z): the limit is the first rz below 0
where some leg's |AC| reaches its bound.  There the leg is stretched (or folded): the
input joint's rate is redundant (input), the platform cannot move along the leg
(impossible-output) and the leg's three parallel axes lie in one plane (serial).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tests.cli import run_cli
from tests.reference.files import MechanismFile

DATA = Path(__file__).resolve().parent / "data" / "planar_3rrr.yaml"
LEGS = ("1", "2", "3")


def expected_limit() -> float:
    """The first platform turn below 0 at which some leg reaches its reach's bound."""
    f = MechanismFile(DATA)
    pt = {j.name: np.asarray(j.prm["point"], dtype=float)[:2] for j in f.joints}
    p = np.mean([pt[f"C{k}"] for k in LEGS], axis=0)  # the platform's reference point
    best = -math.inf
    for k in LEGS:
        A, B, C = pt[f"A{k}"], pt[f"B{k}"], pt[f"C{k}"]
        l1, l2 = np.linalg.norm(B - A), np.linalg.norm(C - B)
        d, r = p - A, C - p
        rho = math.hypot(d @ r, d[0] * r[1] - d[1] * r[0])
        phi = math.atan2(d[0] * r[1] - d[1] * r[0], d @ r)
        for bound in (l1 + l2, abs(l1 - l2)):
            c = (bound**2 - d @ d - r @ r) / (2 * rho)
            if abs(c) > 1:
                continue
            for s in (1, -1):
                for turn in (-2, -1, 0):
                    rz = -phi + s * math.acos(c) + 2 * math.pi * turn
                    if rz < 0:
                        best = max(best, rz)
    return best


@pytest.fixture(scope="module")
def sweeps() -> dict[str, dict]:
    out = {}
    # 0.7 and 0.4 left the fold "not resolved" when it was placed along the swept value
    for step in ("0.7", "0.5", "0.4", "0.1", "0.001"):
        r = run_cli(
            ["sweep", DATA, "--vary", f"pose.rz=0:-3:{step}", "--format", "json", "--quiet"]
        )
        assert r.status == 0, r.err
        out[step] = json.loads(r.out)
    return out


def test_the_limit_of_travel_is_located_and_classed_the_same_at_every_step(sweeps):
    limit = expected_limit()
    assert limit == pytest.approx(-math.acos(1 / 8), abs=1e-14)  # the file's comment
    found = {}
    for step, d in sweeps.items():
        folds = [p for p in d["located"] if p["kind"] == "fold"]
        assert len(folds) == 1, (step, folds)
        (p,) = folds
        assert p["values"][0] == pytest.approx(limit, abs=1e-10), step
        assert p["unresolved"] is None, (step, p["unresolved"])
        # placed on its augmented system, float decides the fold at some steps (the
        # smallest singular value at rounding level), mp:50 at the others (undecided)
        assert p["precision"] in ("float", "mp:50"), step
        found[step] = set(p["classes"])
    assert all(c == {"input", "impossible-output", "serial"} for c in found.values()), found


def test_the_stop_note_is_the_same_at_every_step(sweeps):
    reasons = set()
    for step, d in sweeps.items():
        stops = [n for n in d["notes"] if "stopped after" in n]
        assert len(stops) == 1, (step, d["notes"])
        reasons.add(stops[0].split(": ", 2)[-1])
    assert reasons == {"the rest of the range is beyond the limits of travel"}, reasons


def test_a_limit_of_travel_not_placed_again_is_not_resolved_never_regular(monkeypatch):
    """When the fold cannot be placed again at the analysis's digits, the float point is
    regular at 50 digits: the sweep says the limit was not resolved, and why."""
    from mechsing.sweeps.locate import Locator
    from mechsing.sweeps.relocate import Relocator

    # the fold left where the path placed it (not on its augmented system), and not
    # placed again at 50 digits
    monkeypatch.setattr(Locator, "_fold_again", lambda self, f: f.z)
    monkeypatch.setattr(Relocator, "_fold", lambda self, z: None)
    r = run_cli(["sweep", DATA, "--vary", "pose.rz=0:-3:0.5", "--quiet"])
    assert r.status == 0, r.err
    line = next(ln for ln in r.out.splitlines() if "limit of travel" in ln)
    assert "not resolved" in line and "no singularity" not in line, line
    assert "kept its float values" in line, line
    assert any("was not resolved" in ln for ln in r.out.splitlines() if "note:" in ln), r.out


def test_a_passive_joints_limit_of_travel_is_regular_and_says_why():
    """The crank-rocker four-bar swept in its passive joint C (between coupler and rocker):
    C is extreme where the crank lies along the ground line (A = 0, the drawing, and A = pi),
    a regular configuration; the turn of C between them is the change of the interior
    angle at C, acos(-3/sqrt(10)) - acos(1/sqrt(10)) = pi/2 by the law of cosines (BC =
    2 sqrt(2), CD = sqrt(5), BD = 3 at A = 0 and 5 at A = pi).  Placed again at 50 digits,
    both are regular, and the text says that a passive joint is at its extreme."""
    four = Path(__file__).resolve().parents[1] / "examples" / "fourbar.yaml"
    turn = math.acos(-3 / math.sqrt(10)) - math.acos(1 / math.sqrt(10))
    argv = ["sweep", four, "--vary", "C=-180:180:20", "--precision", "mp:50", "--quiet"]
    r = run_cli([*argv, "--format", "json"])
    assert r.status == 0, r.err
    folds = [p for p in json.loads(r.out)["located"] if p["kind"] == "fold"]
    np.testing.assert_allclose(sorted(abs(p["values"][0]) for p in folds), [0, turn], atol=1e-10)
    assert all(p["classes"] == [] and p["unresolved"] is None for p in folds), folds
    lines = [ln for ln in run_cli(argv).out.splitlines() if "limit of travel" in ln]
    assert len(lines) == 2 and all("passive joint at its extreme" in ln for ln in lines), lines
