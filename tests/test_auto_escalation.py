"""``auto`` re-decides at mp:50 a float rank drop that float itself can see is not rounding.

Four generated families (tests/families.py, the near-singular families of
benchmarks/speed_accuracy.py), each at distances 10^-k from a known singular configuration:

* a Grashof change-point four-bar turned by 10^-k from its fold (closure rank);
* a UR5 with J5 = atan(10^-k) next to its wrist singularity (output chain rank);
* a 3-RPR turned by 10^-k from a pose with concurrent legs (impossible-input rank);
* a 3-UPU translated by 10^-k from a pose with coplanar constraint couples (constraint rank).

At every finite k the configuration is regular (the singular sets are where the fold angle, sin J5,
the concurrency determinant or the couples' determinant vanish, and each is non-zero 10^-k off).
At k = 12 ... 14 the deciding singular value relative to the largest is 10^-13 ... 10^-15: below
float's tau_lo = 1e-12, so float decides a rank drop, but well above float's rounding of that
matrix (eps |M|_F, about 2e-16), so float can see that what it dropped is not noise.  mp:50
decides these configurations regular; ``auto`` must give that verdict.  At the singular
configurations themselves (k = infinity, exact data) ``auto`` stays singular with the class of
the family, and far from them (k = 1 ... 3) it keeps float's verdict without re-deciding.
"""

from __future__ import annotations

from pathlib import Path

import mpmath
import numpy as np
import pytest

import mechsing
from mechsing.analysis.contract import to_json
from mechsing.numeric import FLOAT_ROUNDING_FACTOR, Margin, decide_rank, float_drop_is_real
from tests import families as fam
from tests.cli import cli_json
from tests.mechanisms import EXAMPLES, by_name, classes, write

NEAR = (12, 13, 14)
FAR = (1, 2, 3)


def _families(ks: tuple[int, ...]) -> dict[str, tuple[str, str, str]]:
    """name -> (deciding test, class at the singular configuration, YAML with the singular
    configuration ``singular`` and one configuration ``k<k>`` per k).  The instances of
    benchmarks/speed_accuracy.py (same generator, same seed): their deciding singular value
    is a fifth to a half of 10^-k times the largest, which float resolves to k = 14; an
    instance whose constant is 100 times smaller puts it at float's rounding from k = 13,
    where no float computation can tell it from zero."""
    rng = np.random.default_rng(2026)
    mpmath.mp.dps = 60
    out = {}
    fb = fam.changepoint_fourbar(rng, 0)
    configs = {"singular": {j: "0" for j in "ABCD"}}  # the fold: the reference itself
    configs |= {f"k{k}": fb.pushed_config(mpmath.mpf(10) ** -k, 1) for k in ks}
    out["four-bar change point"] = ("closure", "bifurcation", fb.yaml(configs))

    head = (EXAMPLES / "ur5.yaml").read_text().split("configurations:")[0]
    lines = [head + "configurations:"]
    lines.append('  singular: {J1: 0, J2: "-pi/4", J3: "pi/2", J4: "-pi/4", J5: 0, J6: 0}')
    for k in ks:
        lines.append(
            f'  k{k}: {{J1: 0, J2: "-pi/4", J3: "pi/2", J4: "-pi/4", J5: "atan(1/10**{k})", J6: 0}}'
        )
    out["UR5 wrist"] = ("output chain", "serial", "\n".join(lines) + "\n")

    rpr = fam.rpr_concurrent(rng)
    configs = {"singular": rpr.moved(mpmath.mpf(0), (0, 0))}
    configs |= {f"k{k}": rpr.moved(mpmath.mpf(10) ** -k, (0, 0)) for k in ks}
    out["3-RPR concurrent legs"] = ("impossible-input", "output", rpr.yaml(configs))

    ts = fam.tsai_coplanar(rng)
    m = [mpmath.mpf(x.numerator) / x.denominator for x in ts.m]
    nm = mpmath.sqrt(sum(x * x for x in m))
    configs = {"singular": ts.translated([0, 0, 0])}
    configs |= {f"k{k}": ts.translated([x / nm * mpmath.mpf(10) ** -k for x in m]) for k in ks}
    out["3-UPU coplanar couples"] = ("constraint", "constraint", ts.yaml(configs))
    return out


def _analyze(path: Path, precision: str) -> dict[str, dict]:
    return by_name(cli_json(["analyze", path, "--precision", precision, "--format", "json"]))


def _decision(c: dict, test: str) -> dict:
    (d,) = [d for d in c["decisions"] if d["test"] == test]
    return d


def _regular(c: dict) -> bool:
    return c["singular"] is False and "undecided" not in classes(c)


@pytest.mark.parametrize(
    "family",
    ["four-bar change point", "UR5 wrist", "3-RPR concurrent legs", "3-UPU coplanar couples"],
)
def test_auto_gives_the_regular_verdict_of_mp50_near_a_singularity(
    family: str, tmp_path: Path
) -> None:
    test, singular_class, text = _families(NEAR + FAR)[family]
    path = write(tmp_path, "family", text)
    mp50 = _analyze(path, "mp:50")
    auto = _analyze(path, "auto")
    flt = _analyze(path, "float")
    for k in NEAR:
        name = f"k{k}"
        # the truth (regular at 10^-k), which mp:50 decides
        assert _regular(mp50[name]), (family, name, mp50[name]["singularities"])
        # float decided a drop (its thresholds are not changed) ...
        d = _decision(flt[name], test)
        m = d["margin"]
        assert d["precision"] == "float" and d["rank"] is not None
        assert m["dropped"] <= m["tau_lo"] * m["sigma_max"]
        assert flt[name]["singular"] is True
        # ... of a singular value far above its own rounding: auto re-decides at mp:50
        assert m["dropped"] > FLOAT_ROUNDING_FACTOR * m["rounding"], (family, name, m)
        assert auto[name]["precision"] == "mp:50", (family, name)
        assert _regular(auto[name]), (family, name, auto[name]["singularities"])
        assert _decision(auto[name], test)["rank"] == _decision(mp50[name], test)["rank"]
    # exactly singular data: auto says singular, with the family's class
    ref = auto["singular"]
    assert ref["singular"] is True and singular_class in classes(ref), (family, classes(ref))
    # far from the singularity float decides alone
    for k in FAR:
        c = auto[f"k{k}"]
        assert c["precision"] == "float" and _regular(c), (family, k, c["singularities"])


def test_rounding_bound_of_a_float_decision() -> None:
    """decide_rank in float: the margin's rounding is eps |M|_F; a dropped singular value far
    above it is real, one at its level is not, and a configuration closed only to a residual
    r (relative to L) moves the screws by about r |M|, which raises the bound."""
    Q1, _ = np.linalg.qr(np.random.default_rng(1).normal(size=(6, 6)))
    Q2, _ = np.linalg.qr(np.random.default_rng(2).normal(size=(6, 6)))

    def with_sigma(last: float) -> np.ndarray:
        return Q1 @ np.diag([3.0, 2.0, 1.5, 1.0, 0.5, last]) @ Q2

    eps = float(np.finfo(float).eps)
    real = decide_rank(with_sigma(1e-14), "float")
    assert real.rank == 5  # float's two thresholds: 1e-14 / 3 is below tau_lo
    assert real.margin.rounding == pytest.approx(eps * np.linalg.norm(with_sigma(1e-14)))
    assert float_drop_is_real(real.margin)
    # the JSON record says the same: its margin carries what the test reads
    assert float_drop_is_real(Margin(**to_json(real.margin)))
    assert not float_drop_is_real(real.margin, data_error=1e-14)
    noise = decide_rank(with_sigma(0.0), "float")
    assert noise.rank == 5 and not float_drop_is_real(noise.margin)
    # nothing dropped, or not float: nothing to re-decide
    assert not float_drop_is_real(decide_rank(with_sigma(0.5), "float").margin)
    assert not float_drop_is_real(decide_rank(with_sigma(1e-14), "mp:50").margin)


def test_float_precision_keeps_its_verdict(tmp_path: Path) -> None:
    """--precision float is unchanged: at 10^-14 from the change point it still decides the rank
    drop its thresholds give (auto is where the drop is re-decided)."""
    _test, _cls, text = _families((14,))["four-bar change point"]
    path = write(tmp_path, "family", text)
    res = mechsing.analyze(path, configs=["k14"], precision="float")
    (c,) = res.configurations
    assert c.precision == "float" and c.singular is True
    assert c.closure_rank is not None and c.closure_rank.rank == 2
