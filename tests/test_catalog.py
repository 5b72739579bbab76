"""The catalog data (catalog/*.toml) and its loader."""

from __future__ import annotations

import ast
import shutil
from pathlib import Path

import numpy as np
import pytest
import sympy

from mechsing import lie
from mechsing.numeric import EXACT, FLOAT
from mechsing.subgroups import CatalogError, Subgroup, identify, in_plane, load_catalog
from tests.mechanisms import ROOT

CATALOG_DIR = ROOT / "catalog"  # the source of truth (the installed copy: tests/test_trust.py)

CAT = load_catalog()
RAT = sympy.Rational


def exact_params(t):
    """Rational parameters of every kind (the direction (2, 3, 6)/7 is a rational unit vector)."""
    vals = {
        "direction": [RAT(2, 7), RAT(3, 7), RAT(6, 7)],
        "normal": [RAT(2, 7), RAT(-3, 7), RAT(6, 7)],
        "point": [RAT(1, 2), RAT(-1, 3), 2],
        "pitch": RAT(3, 5),
    }
    return {n: vals[k] for n, k in t.parameters}


def test_data_files_and_loader_agree():
    files = {p.stem for p in CATALOG_DIR.glob("*.toml")}
    assert files == set(CAT)
    assert files == {"E", "R", "P", "H", "C", "T2", "T3", "S", "G", "Y", "X", "D"}
    assert 5 not in {t.dimension for t in CAT.values()}


def test_readme_documents_format_and_no_dimension_five():
    text = (CATALOG_DIR / "README.md").read_text()
    assert "5-dimensional" in text or "dimension 5" in text
    for word in ("e1(", "x", "*", "nonzero", "coordinates"):
        assert word in text


@pytest.mark.parametrize("sym", list(CAT))
def test_every_type_is_recognised_by_the_code(sym):
    """A type added to the data must be identified as itself; the code names no type."""
    t = CAT[sym]
    sub = Subgroup(t, exact_params(t))
    res = identify(sub.basis(), precision="exact")
    assert res.ok and res.subgroup.symbol == sym
    assert res.subgroup.equals(sub)


def test_code_names_no_type():
    """No string constant of mechsing.subgroups is a type symbol: the data decides."""
    src = Path(__file__).resolve().parents[1] / "mechsing" / "subgroups"
    for f in src.glob("*.py"):
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                assert node.value not in CAT, (f.name, node.value)


def test_added_type_is_accepted_and_bad_files_refused(tmp_path):
    d = tmp_path / "cat"
    shutil.copytree(CATALOG_DIR, d)
    text = (d / "R.toml").read_text().replace('symbol = "R"', 'symbol = "Rbis"')
    (d / "Rbis.toml").write_text(text)
    cat = load_catalog(d)
    assert "Rbis" in cat and cat["Rbis"].dimension == 1
    (d / "Bad.toml").write_text(
        (d / "P.toml")
        .read_text()
        .replace('symbol = "P"', 'symbol = "Bad"')
        .replace('kind = "direction"', 'kind = "colour"')
    )
    with pytest.raises(CatalogError, match="colour"):
        load_catalog(d)
    (d / "Bad.toml").write_text(
        (d / "P.toml")
        .read_text()
        .replace('symbol = "P"', 'symbol = "Bad"')
        .replace('v = "axis"', 'v = "axis x nothing"')
    )
    with pytest.raises(CatalogError, match="nothing"):
        load_catalog(d)
    (d / "Bad.toml").write_text(
        (d / "P.toml")
        .read_text()
        .replace('symbol = "P"', 'symbol = "Bad"')
        .replace("dimension = 1", "dimension = 2")
    )
    with pytest.raises(CatalogError, match="dimension 2"):
        load_catalog(d)


@pytest.mark.parametrize("sym", list(CAT))
def test_basis_dimension_and_exact_closure(sym):
    t = CAT[sym]
    B = Subgroup(t, exact_params(t)).basis("exact")
    assert B.shape == (t.dimension, 6)
    assert all(isinstance(x, sympy.Basic) for x in B.flat)
    M = sympy.Matrix(B.tolist()) if t.dimension else sympy.zeros(0, 6)
    assert M.rank(simplify=True) == t.dimension
    for i in range(t.dimension):
        for j in range(i + 1, t.dimension):
            br = lie.bracket(B[i], B[j])
            N = sympy.Matrix(B.tolist() + [list(br)])
            assert N.rank(simplify=True) == t.dimension, (sym, i, j)
    # structural facts: rotation part of dimension 0, 1 or 3; normal in D iff an ideal
    assert t.rotation_rank in (0, 1, 3)
    if t.dimension:
        ad_all = [lie.bracket(e, b) for e in np.eye(6, dtype=int).astype(object) for b in B]
        N = sympy.Matrix(B.tolist() + [list(x) for x in ad_all])
        assert (N.rank(simplify=True) == t.dimension) == t.normal_in_D


def test_in_plane_rule():
    e1, e2 = in_plane(np.array([0.0, 0.0, 1.0]), FLOAT)
    assert np.allclose(e1, [1, 0, 0]) and np.allclose(e2, [0, 1, 0])
    e1, e2 = in_plane(np.array([1.0, 0.0, 0.0]), FLOAT)  # tie between y and z: y first
    assert np.allclose(e1, [0, 1, 0]) and np.allclose(e2, [0, 0, 1])
    w = np.array([RAT(2, 7), RAT(3, 7), RAT(6, 7)], dtype=object)
    e1, e2 = in_plane(w, EXACT)  # least aligned axis: x
    assert sympy.simplify(e1 @ w) == 0 and sympy.simplify(e1 @ e1 - 1) == 0
    assert sympy.simplify(e1[0]) > 0 and sympy.simplify(e1 @ np.array([0, 0, 1])) != 0
    w_x_e1 = [w[1] * e1[2] - w[2] * e1[1], w[2] * e1[0] - w[0] * e1[2], w[0] * e1[1] - w[1] * e1[0]]
    assert all(sympy.simplify(a - b) == 0 for a, b in zip(e2, w_x_e1, strict=True))


def test_catalog_fields():
    for t in CAT.values():
        assert len(t.coordinates) == t.dimension
        assert t.explanation.strip() and t.name
        assert all(k in ("direction", "normal", "point", "pitch") for _, k in t.parameters)
    assert CAT["H"].nonzero == {"pitch"} and CAT["Y"].nonzero == {"pitch"}
    assert [n for n, _ in CAT["H"].parameters] == ["axis", "point", "pitch"]
    assert CAT["T3"].normal_in_D and CAT["D"].normal_in_D and not CAT["S"].normal_in_D
