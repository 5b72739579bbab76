"""The catalog of Lie subgroup types of D, read from the package data ``mechsing.catalog``.

The data files are the repository's ``catalog/*.toml``; the build maps that
folder into the package as ``mechsing.catalog``, so an editable install and an
installed wheel read the same files through :mod:`importlib.resources`.

The code knows no type by name: every type (symbol, parameters, basis,
coordinates ...) comes from the data files, validated here.  The basis is
written as data in a small vocabulary of vector expressions, documented in
``catalog/README.md`` and compiled by :func:`compile_vector`:

* ``0`` the zero vector; ``ex``, ``ey``, ``ez`` the coordinate axes;
* a parameter name of kind ``direction``, ``normal`` or ``point``;
* ``e1(NAME)``, ``e2(NAME)`` the in-plane directions of a direction/normal
  parameter (by the conventions: ``e1 = normalise(a - (a.w) w)`` with ``a`` the
  coordinate axis least aligned with ``w``, first in x, y, z order on a tie,
  and ``e2 = w x e1``);
* ``A x B`` the cross product of two of the above;
* ``s * A`` a pitch parameter ``s`` times one of the above;
* terms joined by ``+``.
"""

from __future__ import annotations

import functools
import importlib.resources
import re
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from importlib.resources.abc import Traversable
from pathlib import Path
from typing import Any

import numpy as np

from mechsing.errors import CatalogError
from mechsing.lie import ANGULAR
from mechsing.numeric import FLOAT, Backend
from mechsing.numeric.scaling import cross3

__all__ = [
    "CATALOG_PACKAGE",
    "PARAMETER_KINDS",
    "CatalogError",
    "SubgroupType",
    "catalog_dir",
    "compile_vector",
    "in_plane",
    "load_catalog",
]

#: the package whose data files are the catalog (the repository's ``catalog/``, mapped by the build)
CATALOG_PACKAGE = "mechsing.catalog"

#: the parameter kinds a catalog file may use; ``pitch`` is a scalar, the others 3-vectors
PARAMETER_KINDS = ("direction", "normal", "point", "pitch")
#: the units a canonical coordinate may have
COORDINATE_UNITS = ("rad", "m")

_REQUIRED = {
    "symbol": str,
    "name": str,
    "dimension": int,
    "normal_in_D": bool,
    "invariants": list,
    "joints": list,
    "explanation": str,
    "parameters": list,
    "basis": list,
    "coordinates": list,
}


# ---------------------------------------------------------------------------
# Vector expressions of the catalog
# ---------------------------------------------------------------------------

_VectorFn = Callable[[Mapping[str, np.ndarray], Backend], np.ndarray]


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    if (
        type(a) is np.ndarray
        and type(b) is np.ndarray
        and a.dtype == b.dtype == np.float64
        and a.shape == b.shape == (3,)
    ):
        return cross3(a, b)  # the same products and differences, in Python floats
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]],
        dtype=np.result_type(a, b),
    )


def in_plane(w: np.ndarray, bk: Backend) -> tuple[np.ndarray, np.ndarray]:
    """In-plane directions ``(e1, e2)`` of a unit vector ``w`` (catalog/README.md).

    ``e1 = normalise(a - (a.w) w)`` with ``a`` the coordinate axis least aligned
    with ``w`` (smallest ``|w_i|``, first in x, y, z order on a tie) and
    ``e2 = w x e1``.  Works on every backend.
    """
    mags = [abs(w[i]) for i in range(3)]
    i = 0
    for j in (1, 2):
        if mags[j] < mags[i]:
            i = j
    a = bk.zeros(3)
    a[i] = bk.convert(1)
    e = a - w * w[i]
    n = bk.sqrt(np.asarray(e @ e))[()]
    e1 = e / n
    if bk.name == "exact":
        e1 = np.array([_simplify(x) for x in e1], dtype=object)
    e2 = _cross(w, e1)
    if bk.name == "exact":
        e2 = np.array([_simplify(x) for x in e2], dtype=object)
    return e1, e2


def _simplify(x: Any) -> Any:
    import sympy

    return sympy.radsimp(sympy.nsimplify(x) if isinstance(x, float) else sympy.simplify(x))


_ATOM = re.compile(r"^(?:(e[12])\((\w+)\)|(\w+))$")


def compile_vector(text: str, kinds: Mapping[str, str], where: str = "") -> _VectorFn:
    """Compile a catalog vector expression into ``f(params, backend) -> (3,) array``.

    ``kinds`` maps the type's parameter names to their kinds; a name of the
    wrong kind, an unknown name or a bad shape raises :class:`CatalogError`.
    """

    def bad(msg: str) -> CatalogError:
        return CatalogError(f"{where}: basis expression {text!r}: {msg}")

    def atom(tok: str) -> _VectorFn:
        tok = tok.strip()
        m = _ATOM.match(tok)
        if not m:
            raise bad(f"cannot read {tok!r} (expected 0, ex, ey, ez, a parameter, e1(P) or e2(P))")
        if m.group(1):
            which, pname = m.group(1), m.group(2)
            if kinds.get(pname) not in ("direction", "normal"):
                raise bad(f"{which}({pname}) needs a direction or normal parameter {pname!r}")
            idx = 0 if which == "e1" else 1
            return lambda p, bk: in_plane(p[pname], bk)[idx]
        name = m.group(3)
        if name == "0":
            return lambda p, bk: bk.zeros(3)
        if name in ("ex", "ey", "ez"):
            k = "xyz".index(name[1])

            def unit(p: Mapping[str, np.ndarray], bk: Backend, k: int = k) -> np.ndarray:
                out = bk.zeros(3)
                out[k] = bk.convert(1)
                return out

            return unit
        if kinds.get(name) in ("direction", "normal", "point"):
            return lambda p, bk: p[name]
        if name in kinds:
            raise bad(f"{name!r} is a {kinds[name]}, not a vector")
        raise bad(f"unknown name {name!r}")

    def term(tok: str) -> _VectorFn:
        if "*" in tok:
            s, _, rest = tok.partition("*")
            s = s.strip()
            if kinds.get(s) != "pitch":
                raise bad(f"{s!r} before '*' must be a pitch parameter")
            f = term(rest)
            return lambda p, bk: f(p, bk) * p[s]
        parts = re.split(r"\s+x\s+", tok.strip())
        if len(parts) == 1:
            return atom(parts[0])
        if len(parts) == 2:
            fa, fb = atom(parts[0]), atom(parts[1])
            return lambda p, bk: _cross(fa(p, bk), fb(p, bk))
        raise bad("at most one cross product ' x ' per term")

    if not text.strip():
        raise bad("empty")
    terms = [term(t) for t in text.split("+")]

    def value(p: Mapping[str, np.ndarray], bk: Backend) -> np.ndarray:
        out = terms[0](p, bk)
        for f in terms[1:]:
            out = out + f(p, bk)
        return np.asarray(out, dtype=bk.dtype)

    return value


# ---------------------------------------------------------------------------
# Subgroup types
# ---------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class SubgroupType:
    """One connected Lie subgroup type of D, as the catalog describes it.

    Attributes
    ----------
    symbol, name : str
        Hervé's symbol (``"R"``, ``"T2"`` ...) and a readable name.
    dimension : int
    parameters : tuple of (str, str)
        ``(name, kind)`` pairs in file order; the names are the mechanism-file keys.
    nonzero : frozenset of str
        Pitch parameters that may not be zero (H, Y).
    normal_in_D : bool
    invariants, joints : tuple of str
    explanation : str
    basis_text : tuple of (omega, v) expression strings
    coordinates : tuple of (str, str)
        ``(name, unit)`` pairs: the canonical (first-kind exponential) coordinates of the
        joint value.
    source : Path
    """

    symbol: str
    name: str
    dimension: int
    parameters: tuple[tuple[str, str], ...]
    nonzero: frozenset[str]
    normal_in_D: bool
    invariants: tuple[str, ...]
    joints: tuple[str, ...]
    explanation: str
    basis_text: tuple[tuple[str, str], ...]
    coordinates: tuple[tuple[str, str], ...]
    source: Path
    _basis_fns: tuple[tuple[_VectorFn, _VectorFn], ...] = field(repr=False, default=())

    @property
    def parameter_names(self) -> tuple[str, ...]:
        return tuple(n for n, _ in self.parameters)

    @property
    def parameter_kinds(self) -> dict[str, str]:
        return dict(self.parameters)

    @property
    def length_columns(self) -> np.ndarray:
        """Boolean mask of the coordinates that are lengths (the commensurate scaling)."""
        return np.array([u == "m" for _, u in self.coordinates], dtype=bool)

    @property
    def pitched(self) -> bool:
        """True when the type carries a pitch that may not be zero (H, Y)."""
        return bool(self.nonzero)

    def basis(self, params: Mapping[str, Any], backend: Backend = FLOAT) -> np.ndarray:
        """The subalgebra basis ``(dimension, 6)`` for already-normalised parameters.

        ``params`` maps each parameter name to a backend array (3-vectors) or
        scalar (pitch); directions must be unit vectors.
        """
        out = backend.zeros((self.dimension, 6))
        for i, (fw, fv) in enumerate(self._basis_fns):
            out[i, 0:3] = fw(params, backend)
            out[i, 3:6] = fv(params, backend)
        return out

    @functools.cached_property
    def rotation_rank(self) -> int:
        """Dimension of the rotation part (projection of the algebra to so(3))."""
        return int(np.linalg.matrix_rank(self.basis(_sample_params(self))[:, ANGULAR]))


def _sample_params(t: SubgroupType) -> dict[str, Any]:
    """Generic float parameters (used to compute structural facts of a type)."""
    d = np.array([1.0, 2.0, 2.0]) / 3.0
    out: dict[str, Any] = {}
    for name, kind in t.parameters:
        out[name] = {"direction": d, "normal": d, "point": np.array([0.5, -1.0, 2.0])}.get(
            kind, 0.5
        )
    return out


def _parse_type(path: Traversable) -> SubgroupType:
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise CatalogError(f"{path}: cannot read the catalog file ({exc})") from exc
    where = str(path)
    stem = path.name.removesuffix(".toml")
    for key, typ in _REQUIRED.items():
        if key not in data:
            raise CatalogError(f"{where}: missing key {key!r}")
        if not isinstance(data[key], typ) or (typ is int and isinstance(data[key], bool)):
            raise CatalogError(f"{where}: {key!r} must be a {typ.__name__}")
    unknown = set(data) - set(_REQUIRED)
    if unknown:
        raise CatalogError(f"{where}: unknown keys {sorted(unknown)}")
    symbol = data["symbol"]
    if symbol != stem:
        raise CatalogError(f"{where}: symbol {symbol!r} must equal the file name {stem!r}")
    params: list[tuple[str, str]] = []
    nonzero: set[str] = set()
    for p in data["parameters"]:
        if not isinstance(p, dict) or set(p) - {"name", "kind", "nonzero"} or "name" not in p:
            raise CatalogError(
                f"{where}: each parameter needs 'name' and 'kind' (and optional 'nonzero')"
            )
        if p.get("kind") not in PARAMETER_KINDS:
            raise CatalogError(
                f"{where}: parameter {p['name']!r} has kind {p.get('kind')!r}; use one of {PARAMETER_KINDS}"
            )
        if p.get("nonzero") and p["kind"] != "pitch":
            raise CatalogError(f"{where}: only a pitch parameter may be 'nonzero'")
        params.append((p["name"], p["kind"]))
        if p.get("nonzero"):
            nonzero.add(p["name"])
    kinds = dict(params)
    if len(kinds) != len(params):
        raise CatalogError(f"{where}: duplicate parameter names")
    fns = []
    texts = []
    for b in data["basis"]:
        if not isinstance(b, dict) or set(b) != {"omega", "v"}:
            raise CatalogError(f"{where}: each basis entry needs exactly 'omega' and 'v'")
        fns.append((compile_vector(b["omega"], kinds, where), compile_vector(b["v"], kinds, where)))
        texts.append((b["omega"], b["v"]))
    coords = []
    for c in data["coordinates"]:
        if (
            not isinstance(c, dict)
            or set(c) != {"name", "unit"}
            or c["unit"] not in COORDINATE_UNITS
        ):
            raise CatalogError(
                f"{where}: each coordinate needs 'name' and 'unit' in {COORDINATE_UNITS}"
            )
        coords.append((c["name"], c["unit"]))
    dim = data["dimension"]
    if not (len(fns) == len(coords) == dim):
        raise CatalogError(
            f"{where}: dimension {dim} but {len(fns)} basis screws and {len(coords)} coordinates"
        )
    t = SubgroupType(
        symbol=symbol,
        name=data["name"],
        dimension=dim,
        parameters=tuple(params),
        nonzero=frozenset(nonzero),
        normal_in_D=data["normal_in_D"],
        invariants=tuple(str(x) for x in data["invariants"]),
        joints=tuple(str(x) for x in data["joints"]),
        explanation=data["explanation"],
        basis_text=tuple(texts),
        coordinates=tuple(coords),
        source=path,
        _basis_fns=tuple(fns),
    )
    B = t.basis(_sample_params(t))
    if dim and np.linalg.matrix_rank(B) != dim:
        raise CatalogError(f"{where}: the basis screws are not independent")
    if t.rotation_rank not in (0, 1, 3):
        raise CatalogError(f"{where}: rotation part of dimension {t.rotation_rank} is impossible")
    return t


def _checkout_catalog() -> Path | None:
    """The ``catalog/`` folder of the source checkout this package is imported from (the
    folder beside ``mechsing/``, under a ``pyproject.toml``), or None when the package is not
    run from a checkout: ``python -m mechsing`` in a checkout that was never installed."""
    root = Path(__file__).resolve().parents[2]
    folder = root / "catalog"
    if (root / "pyproject.toml").is_file() and any(folder.glob("*.toml")):
        return folder
    return None


def catalog_dir() -> Traversable:
    """The catalog: the installed package data, or else the ``catalog/`` folder of the source
    checkout the package runs from; a clear error when neither is there."""
    try:
        root = importlib.resources.files(CATALOG_PACKAGE)
    except ModuleNotFoundError:
        root = _checkout_catalog()
    if root is None or not any(f.name.endswith(".toml") for f in root.iterdir()):
        raise CatalogError(
            f"the subgroup catalog (package data {CATALOG_PACKAGE}) is missing from this "
            "installation of mechsing; reinstall it (pip install mechsing, or pip install . "
            "from its source)"
        )
    return root


def _toml_files(directory: Traversable) -> list[Traversable]:
    return sorted(
        (f for f in directory.iterdir() if f.name.endswith(".toml")), key=lambda f: f.name
    )


def _parse_all(files: list[Traversable], where: object) -> dict[str, SubgroupType]:
    if not files:
        raise CatalogError(f"{where}: no catalog files (*.toml)")
    types = [_parse_type(f) for f in files]
    types.sort(key=lambda t: (t.dimension, t.rotation_rank, t.pitched, t.symbol))
    return {t.symbol: t for t in types}


@functools.cache
def _installed() -> dict[str, SubgroupType]:
    root = catalog_dir()
    return _parse_all(_toml_files(root), root)


@functools.cache
def _load(directory: Path, stamp: tuple[tuple[str, int, int], ...]) -> dict[str, SubgroupType]:
    return _parse_all(_toml_files(directory), directory)


def load_catalog(directory: str | Path | None = None) -> dict[str, SubgroupType]:
    """All subgroup types, ``symbol -> SubgroupType``, ordered by dimension.

    Parameters
    ----------
    directory : path, optional
        Another catalog directory (tests; re-read when a file changes); default:
        the installed catalog (package data ``mechsing.catalog``).

    Raises
    ------
    CatalogError
        When the directory or a file is missing or malformed.
    """
    if directory is None:
        return dict(_installed())
    d = Path(directory).resolve()
    if not d.is_dir():
        raise CatalogError(f"{d}: the catalog directory does not exist")
    stamp = tuple(
        (f.name, f.stat().st_mtime_ns, f.stat().st_size) for f in sorted(d.glob("*.toml"))
    )
    return dict(_load(d, stamp))
