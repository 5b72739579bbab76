"""Input/output and constraint singularities: Zlatanov-Fenton-Benhabib's classes from
the complete velocity equation, and the legs' constraint wrenches.

Complete velocity equation.  With ``N`` an orthonormal basis of the solution
space K of the closure equations (commensurate joint rates), the output twist
is ``t = T u`` (the output body relative to ``relative_to``, through a tree
path; or the velocity of the output point) and the inputs ``u_a = E u``.  On
one basis of K (Zlatanov, Fenton, Benhabib 1995):

* ``input`` (RI): dim E(K cap ker T) -- input rates with the output still;
* ``output`` (RO): dim T(K cap ker E) -- output motion with the inputs locked;
* ``passive-motion`` (RPM): dim (K cap ker E cap ker T);
* ``impossible-input`` (II): rank E N below its generic value;
* ``impossible-output`` (IO): rank T N below its generic value.

Each is measured against its value at regular configurations of the branch
(the nearby samples), so what holds everywhere (an idle spin, redundancy)
is a property, not a singularity.

Every test whose ingredients the file has is run (:func:`tests_run`): with inputs and no
output, ``impossible-input`` (an input loses its independent rate, as at a toggle of
the driving joint: rank E N alone); with an output and no inputs, ``impossible-output``
(rank T N alone).  :func:`tests_not_run` says which were not, and why, in the words
every output format shows.

The tests themselves (their matrices, references and decisions) are defined once in
:mod:`mechsing.singularity.criteria.motion`; this module assembles them at one
configuration of the analysis (the output rows shared per closure system, the exact
products ``(T Z) C``) and owns which tests run and the words for those that did not.
The constraint test is :class:`mechsing.singularity.criteria.ConstraintTest`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechsing.numeric import Precision, RankDecision
from mechsing.numeric.field import field_product
from mechsing.singularity.criteria.motion import (
    IO_TESTS,
    NEED_INPUTS,
    NEED_OUTPUT,
    IOQuantities,
    MotionTest,
    tests_run,
)

__all__ = [
    "io_quantities",
    "not_run_sentences",
    "output_chain",
    "output_rows",
    "tests_not_run",
]


def tests_not_run(mech: Any) -> tuple[tuple[tuple[str, ...], str], ...]:
    """The tests a closed chain could not run for want of inputs or an output, with the
    reason: ((tests, reason), ...), empty when the file has both (or no loop: an open
    chain's only test is its output chain's rank).  The one place these words live."""
    if not mech.loops:
        return ()
    has_in, has_out = bool(mech.inputs), mech.output is not None
    if has_in and has_out:
        return ()
    if not has_in and not has_out:
        return (
            (
                (*IO_TESTS, "constraint"),
                "no inputs and no output: the input and output tests were not run",
            ),
        )
    if not has_out:
        return ((NEED_OUTPUT, "no output: the output tests were not run"),)
    return ((NEED_INPUTS, "no inputs: the input tests were not run"),)


def not_run_sentences(mech: Any) -> list[str]:
    """:func:`tests_not_run` as the sentences every text format shows: ``no output: the
    output tests were not run (input, output, ...)``."""
    return [f"{why} ({', '.join(tests)})" for tests, why in tests_not_run(mech)]


_FLOAT = Precision("float")


def output_rows(
    mech: Any, model: Any, q: np.ndarray, S: np.ndarray, poses: dict[str, np.ndarray]
) -> np.ndarray | None:
    """Commensurate output map T (6 x n twists, or 3 x n point velocities / L), in
    the model's numbers (the same L and centroid as its closure rows)."""
    if mech.output is None:
        return None
    test = MotionTest.of(mech, model)
    return test.output_rows(S, test.output_point(poses))


def output_chain(mech: Any, model: Any, q: np.ndarray, cs: Any, point: bool) -> tuple[Any, Any]:
    """The output chain's commensurate rows at the closed configuration ``q`` from its
    closure system ``cs`` (in the model's numbers): its twists, or with ``point`` the
    output point's velocities (:func:`output_rows`), and that point's position (None
    without ``point``).  Built once per closure system: the input/output test and the
    output motion both ask for them."""
    key = ("output chain", point)
    got = cs.shared.get(key)
    if got is None:
        test = MotionTest.of(mech, model)
        with model.precision.context():
            poses = model.poses(q) if point or cs.screws is None else None
            S = cs.screws if cs.screws is not None else model.current_screws(q, poses)
            x = test.output_point(poses) if point else None
            got = cs.shared[key] = (test.output_rows(S, x), x)
    return got


def io_quantities(
    mech: Any,
    model: Any,
    q: np.ndarray,
    N: np.ndarray,
    prec: Precision = _FLOAT,
    screws: np.ndarray | None = None,
    kernel: RankDecision | None = None,
    cs: Any = None,
) -> IOQuantities | None:
    """ZFB quantities at q, computed and decided at ``prec`` (float or mp:N).

    ``N``: commensurate kernel basis of the closure system (n x m) in the numbers
    of ``prec``; ``screws``: the current screws at q when already known (the
    closure system's); the output map is built in the model's numbers (exact
    ones included) and then converted, so that it shares L and the centroid
    with the closure rows N was computed from.  ``kernel``: N's decision; when it
    was taken from an exact one (``N = Z C``, Z exact), the products ``T N`` and
    ``E N`` are formed as ``(T Z) C`` with ``T Z`` exact in the data's number field, so
    that what vanishes exactly is exactly zero.  ``cs``: the closure system at q whose
    screws ``screws`` are (the output rows are then shared, :func:`output_chain`).
    """
    run = tests_run(mech)
    if not run:
        return None
    if mech.output is None:
        T = None
    elif cs is not None and screws is cs.screws:
        T = output_chain(mech, model, q, cs, mech.output.point is not None)[0]
    else:
        with model.precision.context():
            poses = model.poses(q) if screws is None or mech.output.point is not None else {}
            S = model.current_screws(q, poses) if screws is None else screws
            T = output_rows(mech, model, q, S, poses)
    test = MotionTest.of(mech, model)
    E = test.E
    # a missing side enters as no rows: its rank is 0 and only the other side's
    # test is read (:attr:`IOQuantities.run`)
    if T is None:
        T = np.zeros((0, model.n))
    if E is None:
        E = np.zeros((0, model.n))
    products = None
    if T.shape[0] and E.shape[0] and kernel is not None and kernel.kernel_coefficients is not None:
        Z, C = kernel.exact_null_space, kernel.kernel_coefficients
        TZ = field_product(T, Z)
        EZ = field_product(E.astype(int).astype(object), Z)
        if TZ is not None and EZ is not None:
            with prec.context():
                products = (prec.asarray(TZ) @ C, prec.asarray(EZ) @ C)
    with prec.context():
        T = prec.asarray(T) if T.shape[0] else prec.backend.zeros((0, model.n))
        return test.decide(T, E, N, prec, products)
