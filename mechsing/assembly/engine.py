"""The continuation engine: Bertini 2 (the ``modes`` extra) on a polynomial system, and
the sorting of its endpoints.

Bertini's records are turned off for the solve (``bertini.recording(False)``): nothing is
written in the user's directory and no path is replayed from an earlier run.  The seed is
fixed, so a run repeats: the same random gamma, start points and patches.

Owns :func:`track`, :func:`real_endpoints`, :func:`system_text` (the system in Bertini's
input language, its variable groups first).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy

from mechsing.assembly.settings import MODE_IMAGINARY_RTOL
from mechsing.errors import UserError
from mechsing.timelimit import interruptible

__all__ = ["SEED", "real_endpoints", "system_text", "track"]

#: the seed of every homotopy (its random gamma, start points and patches): runs repeat
SEED = 34


def system_text(eqs: Sequence[sympy.Expr], groups: Sequence[Sequence[sympy.Symbol]]) -> str:
    """The system in Bertini's input language (coefficients to 17 digits)."""
    lines = ["variable_group " + ",".join(str(v) for v in g) + ";" for g in groups]
    lines.append("function " + ",".join(f"f{i}" for i in range(len(eqs))) + ";")
    for i, e in enumerate(eqs):
        text = sympy.sstr(sympy.N(e, 17), full_prec=False).replace("**", "^")
        lines.append(f"f{i} = {text};")
    return "\n".join(lines) + "\n"


def track(
    eqs: Sequence[sympy.Expr],
    groups: Sequence[Sequence[sympy.Symbol]],
    mptype: str = "adaptive",
) -> tuple[list[np.ndarray], int]:
    """Every finite endpoint (complex, double precision, the groups' variables in order)
    of the system's homotopy, and the number of paths tracked.  Several variable groups
    make Bertini's start system multihomogeneous (one path per multihomogeneous Bezout
    root), one group a total-degree start.  ``mptype``: Bertini's precision model
    (``adaptive``, or ``double`` where the endpoints are refined afterwards anyway and
    adaptive precision would crawl along the many singular paths of an overconstrained
    loop's isotropic components)."""
    try:
        import bertini
    except ImportError:
        raise UserError(
            "this configuration needs homotopy continuation: install the extra with "
            "pip install 'mechsing[modes]' (Bertini 2, GPL-3.0-or-later)"
        ) from None
    was = bertini.recording()
    bertini.recording(False)  # no records directory in the user's cwd, no replayed paths
    try:
        text = system_text(eqs, groups)
        while True:  # a signal stops the tracking; its handler raises once the solve returns
            with interruptible(bertini.request_stop) as stopped:
                result = bertini.solve(bertini.parse.system(text), seed=SEED, mptype=mptype)
            if not stopped():  # (a handler that did not raise: the solve is run again)
                break
    finally:
        bertini.recording(was)
    solver = result.solver
    tracked = int(solver.num_paths()) if callable(solver.num_paths) else int(solver.num_paths)
    return [np.asarray(s, dtype=complex) for s in result.solutions], tracked


def real_endpoints(points: Sequence[np.ndarray]) -> list[np.ndarray]:
    """The endpoints whose imaginary parts are negligible (their real parts)."""
    out = []
    for z in points:
        scale = max(1.0, float(np.max(np.abs(z))))
        if float(np.max(np.abs(z.imag))) <= MODE_IMAGINARY_RTOL * scale:
            out.append(z.real)
    return out
