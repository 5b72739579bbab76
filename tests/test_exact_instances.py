"""The random exact instances of the exact-mode benchmark (benchmarks/_exact_instances.py).

Each generator's instance is checked independently of mechsing: a Bennett linkage's loop
closes exactly at every configuration it writes (the product of exponentials from the
file's axes and points, which the generator derived from the Denavit-Hartenberg product);
a Bricard linkage satisfies its symmetry conditions exactly (invariants of consecutive
lines); a 6-UPS platform's P axes point from its U to its S points and its field has the
degree asked for.  Then mechsing's float analysis gives the published mobilities (Bennett 1
with closure rank 3, Bricard 1 with closure rank 5, the 6-UPS platform 6 with closure
rank 30 and no singularity at a generic pose), and exact mode agrees with float on a small
instance of each family.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

import mechsing
from mechsing.model import loads
from tests.reference.benchmarks import benchmark_module

ei = benchmark_module("_exact_instances")


def _write(tmp_path: Path, inst: object) -> Path:
    path = tmp_path / f"{inst.name}.yaml"  # type: ignore[attr-defined]
    path.write_text(inst.text)  # type: ignore[attr-defined]
    return path


def test_field_degree_of_known_fields():
    s2, s3, s5 = sp.sqrt(2), sp.sqrt(3), sp.sqrt(5)
    assert ei.field_degree([sp.Rational(3, 5), 7]) == 1
    assert ei.field_degree([3 * s2 / 5, 1 - s2]) == 2
    assert ei.field_degree([s2, s3 / 2, s2 * s3]) == 4
    assert ei.field_degree([s2, s3, s5]) == 8
    assert ei.field_degree([sp.sqrt(8), sp.sqrt(18)]) == 2  # both in QQ(sqrt 2)


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("degree", [1, 2])
def test_bennett_closes_exactly_at_every_configuration(seed, degree):
    inst = ei.bennett(seed, degree)
    assert inst.degree == degree
    assert set(inst.configs) == {"reference", "moved1", "moved2"}
    for config in inst.configs:
        assert ei.closes(inst, config), config
    # the check can fail: the first joint turned alone does not close the loop
    inst.configs["broken"] = {"J1": 2 * sp.atan(sp.Rational(1, 3))}
    assert not ei.closes(inst, "broken")
    # a Bennett linkage's opposite links are equal: consecutive axes' distances repeat
    lines = [(sp.Matrix(w), sp.Matrix(p)) for w, p in inst.joints.values()]
    link = [ei._line_pair(lines[i], lines[(i + 1) % 4]) for i in range(4)]
    assert all(ei.is_zero(x - y) for x, y in zip(link[0], link[2], strict=True))
    assert all(ei.is_zero(x - y) for x, y in zip(link[1], link[3], strict=True))


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("degree", [1, 2])
@pytest.mark.parametrize("make", ["bricard", "bricard_plane"])
def test_bricard_is_symmetric_exactly(seed, degree, make):
    inst = getattr(ei, make)(seed, degree)
    assert inst.degree == degree
    assert ei.symmetric(inst)
    # the check can fail: joint 5 moved along its own axis breaks the symmetry
    w, p = inst.joints["J5"]
    moved = dict(inst.joints)
    moved["J5"] = (w, tuple(sp.Matrix(p) + sp.Matrix([0, 0, sp.Rational(1, 7)])))
    assert not ei.symmetric(type(inst)(inst.family, inst.name, inst.text, degree, moved))


@pytest.mark.parametrize("degree", [1, 2, 4])
def test_stewart_legs_and_field(degree):
    inst = ei.stewart(0, degree)
    assert inst.degree == degree
    mech = loads(inst.text)
    joints = {j.name: j for j in mech.joints}
    squares = []
    for k in range(1, 7):
        base = sp.Matrix(joints[f"U{k}"].params["point"])
        top = sp.Matrix(joints[f"S{k}"].params["point"])
        axis = sp.Matrix(joints[f"P{k}"].params["axis"])
        leg = top - base
        assert ei.is_zero(base[2])  # the U joints stand on the base plane
        # the P axis is the leg's unit direction
        assert all(ei.is_zero(x) for x in leg.cross(axis))
        assert ei.is_zero(axis.dot(leg) ** 2 - leg.dot(leg))
        squares.append(leg.dot(leg))
    # the squared leg lengths are rational; their square roots generate the field
    assert all(s.is_Rational for s in squares)
    assert ei.field_degree([sp.sqrt(s) for s in squares]) == degree


def _published(res: object, inst: object) -> None:
    for conf in res.to_json()["configurations"]:  # type: ignore[attr-defined]
        assert conf.get("error") is None, conf.get("error")
        assert conf["mobility"]["finite"] == inst.published["finite"], conf["name"]  # type: ignore[attr-defined]
        assert conf["closure_rank"]["rank"] == inst.published["closure_rank"], conf["name"]  # type: ignore[attr-defined]
        assert conf["singularities"] == [], conf["name"]


@pytest.mark.parametrize(
    "make",
    [
        lambda: ei.bennett(0, 1),
        lambda: ei.bennett(1, 2),
        lambda: ei.bricard(0),
        lambda: ei.bricard_plane(0),
        lambda: ei.bricard(1, 2),
        lambda: ei.bricard_plane(1, 2),
        lambda: ei.stewart(0, 4),
    ],
    ids=[
        "bennett-d1",
        "bennett-d2",
        "bricard",
        "bricard-plane",
        "bricard-d2",
        "bricard-plane-d2",
        "stewart-d4",
    ],
)
def test_float_gives_the_published_mobility(tmp_path, make):
    inst = make()
    _published(mechsing.analyze(_write(tmp_path, inst), precision="float"), inst)


@pytest.mark.parametrize(
    ("make", "config"),
    [
        (lambda: ei.bennett(0, 1), "moved1"),
        (lambda: ei.bennett(0, 2), "reference"),
        (lambda: ei.bricard(0), "reference"),
        (lambda: ei.bricard_plane(0), "reference"),
        (lambda: ei.stewart(0, 1), "reference"),
    ],
    ids=["bennett", "bennett-sqrt", "bricard", "bricard-plane", "stewart"],
)
def test_exact_agrees_with_float(tmp_path, make, config):
    verdict = benchmark_module("_scale_exact").verdict
    inst = make()
    path = _write(tmp_path, inst)
    exact = mechsing.analyze(path, configs=[config], precision="exact", time_limit=120)
    flt = mechsing.analyze(path, configs=[config], precision="float")
    _published(exact, inst)
    e, f = exact.to_json()["configurations"][0], flt.to_json()["configurations"][0]
    assert e["precision"] == "exact"
    assert verdict(e) == verdict(f)
