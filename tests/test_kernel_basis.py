"""Deterministic findings: a kernel of dimension 2 or more is reported whole, in one
canonical basis (reduced row echelon form), with the moving joints its support: the
same numbers whichever basis an SVD picked, fast paths on or off."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from mechsing.screws.readable import reduced_echelon

ROOT = Path(__file__).resolve().parents[1]

#: the five-bar grid of the sweep snapshot (benchmarks/json_snapshot.py), coarser
FIVE_BAR = [
    str(ROOT / "examples" / "five_bar.yaml"),
    "--vary",
    "A1=-0.4:0.42:0.08",
    "--vary",
    "A2=-0.4:0.42:0.08",
]

#: values below this are rounding (a margin's dropped singular value, a residual)
ROUNDING = 1e-12


def _json(args: list[str], fast: bool) -> dict:
    """The JSON of ``python -m mechsing *args --format json`` in a fresh process, with
    the fast paths on or off (MECHSING_FAST is read at import)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MECHSING_FAST": "1" if fast else "0"}
    run = subprocess.run(
        [sys.executable, "-m", "mechsing", *args, "--format", "json"],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )
    assert run.returncode in (0, 1), run.stderr
    return json.loads(run.stdout)


def _same_fast_on_and_off(args: list[str]) -> dict:
    """The JSON of ``mechsing *args``, after checking it is the same with MECHSING_FAST=0
    (to rounding-level values)."""
    on, off = _json(args, True), _json(args, False)
    diffs: list[str] = []
    _differences(on, off, "", diffs)
    assert not diffs, "\n".join(diffs[:20])
    return on


def _differences(a, b, path, out):
    """Every difference between two JSON values but those of rounding level."""
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            out.append(f"{path}: keys {sorted(set(a) ^ set(b))}")
        for k in set(a) & set(b):
            _differences(a[k], b[k], f"{path}.{k}", out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: length {len(a)} -> {len(b)}")
        for i, (x, y) in enumerate(zip(a, b, strict=False)):
            _differences(x, y, f"{path}[{i}]", out)
    elif isinstance(a, float) and isinstance(b, float):
        if max(abs(a), abs(b)) > ROUNDING and abs(a - b) > 1e-9 * max(abs(a), abs(b)):
            out.append(f"{path}: {a!r} -> {b!r}")
    elif a != b:
        out.append(f"{path}: {a!r} -> {b!r}")


def test_reduced_echelon_of_a_span_does_not_depend_on_its_basis():
    """The span of (1, 0, a), (0, 1, b) in R^3 given by any rotated orthonormal basis
    has that echelon form (its closed form), to rounding."""
    rng = np.random.default_rng(7)
    a, b = 0.37, -1.6
    R = np.array([[1.0, 0.0, a], [0.0, 1.0, b]])
    for _ in range(20):
        Q, _ = np.linalg.qr(R.T)  # an orthonormal basis of the span
        turn, _ = np.linalg.qr(rng.normal(size=(2, 2)))
        rows, pivots = reduced_echelon((Q @ turn).T)
        assert pivots == [0, 1]
        np.testing.assert_allclose(rows, R, atol=1e-14)


def test_five_bar_sweep_is_the_same_with_the_fast_paths_off():
    """At the five-bar's leg 2 stretched, its leg chain's kernel has dimension 2: the
    whole kernel is reported (its canonical basis), the moving joints are its support,
    and the sweep's JSON is the same with MECHSING_FAST=0 (to rounding-level values)."""
    on = _same_fast_on_and_off(["sweep", *FIVE_BAR, "--quiet"])
    wide = [
        s
        for p in on["located"]
        for s in (p.get("configuration") or {}).get("singularities", [])
        if s.get("class") == "serial" and len(s.get("null_joint_rate_basis", [])) >= 2
    ]
    assert wide, "no serial finding with a kernel of dimension 2 on the five-bar grid"
    for s in wide:
        basis = np.array(s["null_joint_rate_basis"])
        assert s["null_joint_rates"] == basis[0].tolist()
        # the moving joints: as many as the kernel's columns with a non-zero entry
        assert len(s["joints"]) == int(np.count_nonzero(np.any(basis != 0, axis=0)))
        # echelon form: each row's first non-zero entry after the row above's
        firsts = [int(np.flatnonzero(row)[0]) for row in basis]
        assert firsts == sorted(set(firsts))


def _five_bar_both_legs_stretched(tmp_path: Path) -> Path:
    """The example five-bar with a configuration where both legs are stretched: P on the
    base's axis of symmetry at distance 2 + 5/2 = 9/2 from both base pivots (+-3/2, 0),
    P = (0, 3 sqrt 2), each proximal link turned by asin(1/3) from the vertical."""
    text = (ROOT / "examples" / "five_bar.yaml").read_text()
    text = text[: text.index("configurations:")]
    text += (
        "configurations:\n"
        '  both: {A1: "-asin(1/3)", B1: "2*atan(1/3)", P: "2*asin(1/3) - 2*atan(3/4)",'
        ' B2: "-2*atan(1/3)", A2: "asin(1/3)"}\n'
    )
    path = tmp_path / "five_bar_both.yaml"
    path.write_text(text)
    return path


def test_closed_chain_motion_space_is_reported_whole_in_its_canonical_basis(tmp_path):
    """Both legs of the five-bar stretched: with the output point P held, each leg turns
    about its base pivot alone (a stretched 2R leg of links l1 = 2, l2 = 5/2 with its tip
    held: A rate w, B rate -w (l1 + l2)/l2, the distal link held by P's rate w l1/l2), so
    the input motion space has dimension 2 and is spanned by
    leg 1: (A1, B1, P, B2, A2) = (l2, -(l1 + l2), l1, 0, 0) and
    leg 2: (0, 0, l1, l1 + l2, -l2) (P joins the two distal links, turning the other way).
    Its reduced echelon form (pivots A1, P), each row scaled to largest entry 1, first
    entry positive, is the closed form below; the moving joints are all five; the same
    with MECHSING_FAST=0.  Before, one vector (the SVD's pick) was reported and ``joints``
    was its support (P missing)."""
    l1, l2 = 2.0, 2.5
    leg1 = np.array([l2, -(l1 + l2), l1, 0.0, 0.0])
    leg2 = np.array([0.0, 0.0, l1, l1 + l2, -l2])
    # echelon by hand: row 1 from leg 1 with its P entry eliminated by leg 2
    row1 = leg1 / l2 - (l1 / l2) * (leg2 / l1)
    row2 = leg2 / l1
    expected = [r / np.max(np.abs(r)) for r in (row1, row2)]
    expected = [r if r[np.flatnonzero(r)[0]] > 0 else -r for r in expected]
    path = _five_bar_both_legs_stretched(tmp_path)
    on = _same_fast_on_and_off(["analyze", str(path)])
    (config,) = on["configurations"]
    assert config["closure_residual"] < 1e-12
    (found,) = [s for s in config["singularities"] if s["class"] == "input"]
    assert found["dimension"] == 2
    assert found["joints"] == ["A1", "B1", "P", "B2", "A2"]
    np.testing.assert_allclose(found["joint_rate_basis"], expected, atol=1e-12)
    # a symmetric pair: no one motion moves the inputs most, joint_rates is the first row
    np.testing.assert_allclose(found["joint_rates"], expected[0], atol=1e-12)
