"""Exact mode's time limit and its configuration-by-configuration report (issue: every valid
file, every mode: right answer or clear message, never a traceback).

Two mechanisms written here with exact data (angles such as ``17`` degrees are exactly
17 pi / 180, lengths rational), on which sympy works for many minutes:

* a Stanford arm (R R P R R R with a spherical wrist: the axes of J4, J5, J6 meet at the wrist
  centre W; J4 and J6 are both along the arm when J5 = 0, which is its wrist singularity);
* a 5R five-bar (planar, mobility 5 - 3 = 2), whose configurations are built from rational
  points on circles (link lengths 3 and 5/2), its joint values differences of ``atan2`` of
  rationals, so they close exactly.

What is checked comes from the problem statement and the geometry: a configuration that exact
mode cannot finish within ``--time-limit`` gets an ``error`` entry that says what could not be
done and which precision to use, the others are reported, the exit status is 3, and the whole
run takes about the limit per configuration (before the limit: 22 minutes for the arm's wrist
configuration, 15 for the five-bar).  The verdicts of the fast configurations are the
mathematical ones: the arm at J5 = 0 is wrist-singular with a null joint-rate vector on J4 and
J6 (the two coaxial joints) only; the five-bar's closure system has rank 3 in G and nullity 2.
"""

from __future__ import annotations

import json
import signal
import threading
import time
from pathlib import Path

import pytest

import mechsing
from mechsing.timelimit import TimeLimit, TimeLimitExceeded, activity
from tests.cli import run_cli, run_cli_subprocess
from tests.mechanisms import ROOT, by_name, finding, write

STANFORD = """mechanism: stanford-arm
units: {{angle: deg}}
bodies: [base, l1, l2, l3, l4, l5, hand]
joints:
  - {{name: J1, type: R, between: [base, l1], axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: J2, type: R, between: [l1, l2], axis: [0, 1, 0], point: [0, 0, "1/2"]}}
  - {{name: J3, type: P, between: [l2, l3], axis: [1, 0, 0]}}
  - {{name: J4, type: R, between: [l3, l4], axis: [1, 0, 0], point: [1, "3/20", "1/2"]}}
  - {{name: J5, type: R, between: [l4, l5], axis: [0, 1, 0], point: [1, "3/20", "1/2"]}}
  - {{name: J6, type: R, between: [l5, hand], axis: [1, 0, 0], point: [1, "3/20", "1/2"]}}
inputs: [J1, J2, J3, J4, J5, J6]
output: {{body: hand}}
configurations:
  reference: {{}}
  wrist: {{J1: 17, J2: 60, J3: "1/4", J4: 11, J5: 0, J6: 0}}
{extra}"""

#: 5R five-bar: ground A1 (0, 0), A2 (4, 0); at the reference B1 (0, 3), C (2, 9/2), B2 (4, 3)
#: (proximal links 3, distal links 5/2).  Each configuration moves B1, C, B2 to rational points
#: with the same link lengths; a body's angle is atan2(cross, dot) of its link direction at the
#: reference and now, and a joint's value the difference of the angles of its two bodies.
FIVEBAR_POINTS = {
    "one": ((45, 17, 24, 17), (79, 17, 99, 34), (11, 5, 12, 5)),
    "two": ((60, 29, -63, 29), (10, 29, -21, 58), (8, 5, 9, 5)),
    "three": ((63, 29, 60, 29), (121, 29, 33, 58), (137, 41, 120, 41)),
    "four": ((-36, 37, 105, 37), (103, 74, 135, 37), (16, 13, 15, 13)),
}


def fivebar_text() -> str:
    from fractions import Fraction as F

    def txt(x: F) -> str:
        return str(x.numerator) if x.denominator == 1 else f"{x.numerator}/{x.denominator}"

    def angle(r: tuple[F, F], n: tuple[F, F]) -> str:
        return f"atan2({txt(r[0] * n[1] - r[1] * n[0])}, {txt(r[0] * n[0] + r[1] * n[1])})"

    def sub(a: tuple[F, F], b: tuple[F, F]) -> tuple[F, F]:
        return (a[0] - b[0], a[1] - b[1])

    A1, A2 = (F(0), F(0)), (F(4), F(0))
    B1r, Cr, B2r = (F(0), F(3)), (F(2), F(9, 2)), (F(4), F(3))
    lines = [
        "mechanism: five-bar-5R",
        "bodies: [ground, p1, d1, d2, p2]",
        "joints:",
        "  - {name: A1, type: R, between: [ground, p1], axis: [0, 0, 1], point: [0, 0, 0]}",
        "  - {name: B1, type: R, between: [p1, d1], axis: [0, 0, 1], point: [0, 3, 0]}",
        '  - {name: C, type: R, between: [d1, d2], axis: [0, 0, 1], point: [2, "9/2", 0]}',
        "  - {name: B2, type: R, between: [d2, p2], axis: [0, 0, 1], point: [4, 3, 0]}",
        "  - {name: A2, type: R, between: [p2, ground], axis: [0, 0, 1], point: [4, 0, 0]}",
        "inputs: [A1, A2]",
        'output: {body: d1, point: [2, "9/2", 0]}',
        "configurations:",
        "  reference: {}",
    ]
    for name, pts in FIVEBAR_POINTS.items():
        B1, C, B2 = ((F(a, b), F(c, d)) for a, b, c, d in pts)
        # the link lengths hold exactly: these points are a configuration of the five-bar
        assert sub(B1, A1)[0] ** 2 + sub(B1, A1)[1] ** 2 == 9
        assert sub(B2, A2)[0] ** 2 + sub(B2, A2)[1] ** 2 == 9
        assert sub(C, B1)[0] ** 2 + sub(C, B1)[1] ** 2 == F(25, 4)
        assert sub(C, B2)[0] ** 2 + sub(C, B2)[1] ** 2 == F(25, 4)
        p1 = angle(sub(B1r, A1), sub(B1, A1))
        d1 = angle(sub(Cr, B1r), sub(C, B1))
        d2 = angle(sub(B2r, Cr), sub(B2, C))
        p2 = angle(sub(B2r, A2), sub(B2, A2))
        q = {"A1": p1, "B1": f"{d1} - {p1}", "C": f"{d2} - {d1}", "B2": f"{p2} - {d2}"}
        q["A2"] = f"-{p2}"
        lines.append(f"  {name}: {{" + ", ".join(f'{k}: "{v}"' for k, v in q.items()) + "}")
    return "\n".join(lines) + "\n"


def analyze_cli(path: Path, *args: str, timeout: float = 300) -> tuple[int, dict, str, float]:
    """``python -m mechsing analyze PATH --format json ARGS`` in a child process (the command
    as users run it: main thread, SIGALRM free); (status, JSON, stderr, seconds)."""
    t0 = time.monotonic()
    r = run_cli_subprocess(["analyze", path, "--format", "json", *args], timeout=timeout)
    dt = time.monotonic() - t0
    assert "Traceback" not in r.err, r.err
    return r.status, json.loads(r.out) if r.out else {}, r.err, dt


def assert_wrist_singular(c: dict) -> None:
    """J5 = 0: the axes of J4 and J6 coincide (both along the arm through W), so q4' = -q6'
    moves nothing: a serial finding whose null joint rates have support {J4, J6}."""
    assert c["precision"] == "exact" and c["singular"] is True, c
    f = finding(c, "serial")
    assert f["joints"] == ["J4", "J6"], f
    rates = f["null_joint_rates"]
    assert rates[3] == pytest.approx(-rates[5]) and rates[3] != 0
    assert [rates[i] for i in (0, 1, 2, 4)] == [0, 0, 0, 0]


def assert_stopped(c: dict, limit: float) -> None:
    """The error entry of a configuration stopped by the time limit: what, and what to do."""
    err = c["error"]
    assert c["singular"] is None and c["singularities"] == []
    assert f"configuration {c['name']!r}" in err and f"after {limit:g} s" in err, err
    assert "time limit" in err and "while " in err, err
    assert "--precision mp:50" in err and "--time-limit" in err, err


# ============================================================================ the time limit


def test_stanford_wrist_is_stopped_at_the_limit_and_the_reference_is_reported(
    tmp_path: Path,
) -> None:
    """The wrist configuration (17, 60, 11 degrees) ran 22 minutes: with --time-limit 2 it is
    stopped with an error entry, the reference (J5 = 0 too) is analysed, status 3."""
    path = write(tmp_path, "stanford", STANFORD.format(extra=""))
    rc, out, err, dt = analyze_cli(path, "--precision", "exact", "--time-limit", "2")
    assert rc == 3, err
    c = by_name(out)
    assert_wrist_singular(c["reference"])
    assert "error" not in c["reference"]
    assert_stopped(c["wrist"], 2)
    # progress: stderr says which configuration exact mode is working on, then how it ended
    assert "mechsing: exact: working on configuration 'wrist' (2 of 2)" in err, err
    assert "configuration 'wrist': stopped after" in err, err
    # the error is also on stderr, as for a configuration that does not close
    assert f"mechsing: {path}: configuration 'wrist': exact mode stopped after 2 s" in err
    # start-up, the reference and 2 s for the wrist: far below the 22 minutes it used to take
    assert dt < 60, dt


def test_five_bar_each_configuration_within_the_limit(tmp_path: Path) -> None:
    """The five-bar's four configurations took over 15 minutes; with --time-limit 1 each is
    either analysed (closure rank 3 in G, nullity 2: 5 joints, planar loop) or stopped with an
    error entry, and the whole file takes about the limit per configuration."""
    path = write(tmp_path, "fivebar", fivebar_text())
    rc, out, err, dt = analyze_cli(path, "--precision", "exact", "--time-limit", "1")
    configs = by_name(out)
    assert list(configs) == ["reference", *FIVEBAR_POINTS]
    stopped = [n for n, c in configs.items() if "error" in c]
    for name, c in configs.items():
        if name in stopped:
            assert_stopped(c, 1)
        else:
            assert c["closure_residual"] == 0
            assert (c["closure_rank"]["rank"], c["closure_rank"]["nullity"]) == (3, 2)
            assert c["loops"][0]["subgroup"]["type"] == "G"
    assert "reference" not in stopped
    assert rc == (3 if stopped else 0), err
    assert dt < 60, dt


def test_fast_exact_configurations_are_unaffected(tmp_path: Path) -> None:
    """A configuration that exact mode finishes at once gives the same report under a short
    limit as under the default one."""
    path = write(tmp_path, "stanford", STANFORD.format(extra=""))
    rc1, short, _err, _dt = analyze_cli(
        path, "--precision", "exact", "--time-limit", "2", "--config", "reference"
    )
    rc2, default, _err, _dt = analyze_cli(path, "--precision", "exact", "--config", "reference")
    assert rc1 == rc2 == 0
    assert short == default
    assert_wrist_singular(by_name(short)["reference"])


def test_the_api_stops_a_configuration_in_any_thread(tmp_path: Path) -> None:
    """``mechsing.analyze(..., time_limit=S)`` from a thread that is not the main one (no
    signals there): the wrist configuration is stopped all the same; the result is failed
    and the reference analysed."""
    path = write(tmp_path, "stanford", STANFORD.format(extra=""))
    box: dict = {}

    def work() -> None:
        t0 = time.monotonic()
        box["result"] = mechsing.analyze(path, precision="exact", time_limit=1)
        box["seconds"] = time.monotonic() - t0

    th = threading.Thread(target=work)
    th.start()
    th.join(timeout=120)
    assert not th.is_alive(), "exact mode ignored the time limit in a thread"
    res = box["result"]
    assert res.failed
    c = by_name(res.to_json())
    assert_stopped(c["wrist"], 1)
    assert_wrist_singular(c["reference"])
    assert box["seconds"] < 60


def test_the_main_thread_alarm_is_put_back(tmp_path: Path) -> None:
    """In the main thread the limit uses SIGALRM: afterwards the caller's handler is back and
    an interval timer the caller had set is still running (postponed, not lost)."""
    if not hasattr(signal, "SIGALRM") or threading.current_thread() is not threading.main_thread():
        pytest.skip("SIGALRM in the main thread only")
    path = write(tmp_path, "stanford", STANFORD.format(extra=""))
    fired: list[int] = []

    def mine(signum: int, frame: object) -> None:
        fired.append(signum)

    before = signal.signal(signal.SIGALRM, mine)
    try:
        signal.setitimer(signal.ITIMER_REAL, 300)
        res = mechsing.analyze(path, precision="exact", time_limit=1)
        assert signal.getsignal(signal.SIGALRM) is mine
        left, _interval = signal.getitimer(signal.ITIMER_REAL)
        assert 0 < left < 300
        assert not fired
        assert by_name(res.to_json())["wrist"]["error"]
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, before)


def _busy(seconds: float, swallow: bool) -> int:
    """Pure Python work for ``seconds``; with ``swallow`` every Exception is caught, as sympy
    does in places."""
    n = 0
    t_end = time.monotonic() + seconds
    while time.monotonic() < t_end:
        try:
            n += sum(range(1000))
        except Exception:  # noqa: BLE001 -- the point of the test
            if swallow:
                continue
            raise
    return n


@pytest.mark.parametrize("in_thread", [False, True])
def test_time_limit_interrupts_code_that_catches_exceptions(in_thread: bool) -> None:
    """TimeLimitExceeded is not an Exception: ``except Exception`` does not keep the code
    running past the limit, in the main thread (SIGALRM) or another (watchdog)."""
    box: dict = {}

    def work() -> None:
        lim = TimeLimit(0.3)
        t0 = time.monotonic()
        try:
            with lim, activity("counting"):
                _busy(30, swallow=True)
        except TimeLimitExceeded as exc:
            box["activity"] = exc.activity
        box["seconds"] = time.monotonic() - t0
        box["exceeded"] = lim.exceeded

    if in_thread:
        th = threading.Thread(target=work)
        th.start()
        th.join(timeout=60)
    else:
        work()
    assert box["activity"] == "counting"
    assert box["exceeded"] is True
    assert box["seconds"] < 10


def test_time_limit_does_not_fire_after_the_block() -> None:
    """A block that ends before its limit leaves nothing behind: no late interruption."""
    lim = TimeLimit(0.2)
    with lim:
        _busy(0.05, swallow=False)
    assert not lim.exceeded
    _busy(0.6, swallow=False)  # would be interrupted if the alarm were still armed


# ============================================================================ per-configuration errors


def test_a_joint_value_that_is_not_exact_data_is_that_configuration_s_error(tmp_path: Path) -> None:
    """180/pi degrees is 1 rad: sin 1 is transcendental, not exact data.  That configuration
    gets an error entry naming the joint; the others are reported; status 3 (not 2)."""
    extra = '  one-radian: {J1: "180/pi", J2: 0, J3: 0, J4: 0, J5: 90, J6: 0}\n'
    path = write(tmp_path, "stanford", STANFORD.format(extra=extra))
    rc, out, err = run_cli(
        ["analyze", str(path), "--precision", "exact", "--format", "json"]
        + ["--config", "reference", "--config", "one-radian"]
    )
    assert rc == 3, err
    c = by_name(json.loads(out))
    assert "not exact data" in c["one-radian"]["error"]
    assert "'J1'" in c["one-radian"]["error"] and "--precision" in c["one-radian"]["error"]
    assert_wrist_singular(c["reference"])


def test_a_configuration_not_given_exactly_is_that_configuration_s_error() -> None:
    """examples/fourbar.yaml: crank-30 gives only the crank angle (the rest would be solved
    numerically), crank-200 starts from it.  Exact mode reports the reference (rank 3 in G,
    mobility 1) and gives each of the others an error naming itself; status 3."""
    rc, out, err = run_cli(
        ["analyze", str(ROOT / "examples" / "fourbar.yaml"), "--precision", "exact"]
        + ["--format", "json"]
    )
    assert rc == 3, err
    c = by_name(json.loads(out))
    assert (c["reference"]["closure_rank"]["rank"], c["reference"]["mobility"]["finite"]) == (3, 1)
    for name in ("crank-30", "crank-200"):
        assert c[name]["error"].startswith(f"configuration {name!r}"), c[name]["error"]
        assert "every joint value" in c[name]["error"]


def test_geometry_that_is_not_exact_data_refuses_the_file(tmp_path: Path) -> None:
    """An axis (cos 1, sin 1, 0) is not exact data: exact mode refuses the whole file with
    status 2, naming the file, line and joint; float takes it."""
    text = STANFORD.format(extra="").replace(
        "{name: J1, type: R, between: [base, l1], axis: [0, 0, 1]",
        '{name: J1, type: R, between: [base, l1], axis: ["cos(1)", "sin(1)", 0]',
    )
    path = write(tmp_path, "stanford", text)
    rc, out, err = run_cli(["analyze", str(path), "--precision", "exact", "--config", "reference"])
    assert rc == 2 and out == ""
    assert f"{path}:5: joint 'J1': axis" in err and "not exact data" in err, err
    rc, _out, err = run_cli(["analyze", str(path), "--precision", "float", "--config", "reference"])
    assert rc == 0, err


@pytest.mark.parametrize("value", ["0", "-1", "abc", "inf", "nan"])
def test_time_limit_option_must_be_positive_seconds(tmp_path: Path, value: str) -> None:
    path = write(tmp_path, "stanford", STANFORD.format(extra=""))
    with pytest.raises(SystemExit) as exc:
        run_cli(["analyze", str(path), "--precision", "exact", "--time-limit", value])
    assert exc.value.code == 2


@pytest.mark.parametrize("value", [0, -1.0, float("inf"), "60"])
def test_time_limit_argument_must_be_positive_seconds(value: object) -> None:
    with pytest.raises(ValueError, match="time_limit"):
        mechsing.analyze(ROOT / "examples" / "fourbar.yaml", precision="exact", time_limit=value)
