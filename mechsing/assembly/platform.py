"""Six-leg platforms as a registered problem: U-P-S or S-P-S legs with their slides given,
the platform's pose in Study coordinates by homotopy continuation (:mod:`.spatial`).

Owns :data:`FORMULATION`.
"""

from __future__ import annotations

from typing import Any

import mpmath

from mechsing.assembly.chains import Found
from mechsing.assembly.given import NO_INPUTS, Formulation, Given
from mechsing.assembly.settings import MODE_CERTIFY_RADIUS
from mechsing.errors import ConfigurationError, FormulationError
from mechsing.numeric import MODE_MATCH_DISTANCE

__all__ = ["FORMULATION"]


def _applies(given: Given) -> str | None:
    from mechsing.assembly.spatial import spatial_system

    if given.values is None:
        return NO_INPUTS
    try:
        given.cache["platform"] = spatial_system(given.mech, given.values)
    except FormulationError as reason:
        return str(reason)
    return None


def _find(given: Given) -> Found:
    mech, dps = given.mech, given.dps
    system = given.cache["platform"]
    from mechsing.assembly.certify import every_solution, krawczyk
    from mechsing.assembly.reach import far_out_of_reach
    from mechsing.assembly.serial import unproven
    from mechsing.assembly.spatial import (
        GENERIC_COUNT,
        XS,
        YS,
        joint_values_spatial,
        out_of_reach,
        patch_equation,
        pose_of,
        solve_study,
    )

    formulation = {
        "name": "Study coordinates",
        "method": "homotopy continuation (Bertini 2), Newton refinement",
        "platform": system.platform,
        "unknowns": [str(v) for v in (*XS, *YS)],
        "legs": [{"kind": "distance", "joints": list(n)} for n, *_ in system.legs],
        "polynomial_degree": 2,
        "bezout": 2**7,
        "generic_count": GENERIC_COUNT,
    }
    reason = out_of_reach(system) or far_out_of_reach(system.legs)
    if reason is not None:  # proved without tracking: no real (or complex) pose
        formulation["proven_without_tracking"] = reason
        return Found(formulation, [], 0, "proven", None, (reason,))
    try:
        studies, paths, solutions = solve_study(system, dps)
    except ConfigurationError as exc:
        raise ConfigurationError(f"{mech.path or mech.name}: {exc}", exc.configuration) from None
    # one mode per platform pose (the Study coordinates' sign is fixed by the patch)
    kept: list[list[Any]] = []
    for z in studies:
        R, t = pose_of(z)
        if all(
            mpmath.norm(R - pose_of(k)[0]) + mpmath.norm(t - pose_of(k)[1]) > MODE_MATCH_DISTANCE
            for k in kept
        ):
            kept.append(z)
    eqs = [*system.equations, patch_equation()]
    rows = []
    for z in kept:
        ok = krawczyk(eqs, [*XS, *YS], z, mpmath.mpf(MODE_CERTIFY_RADIUS))
        rows.append((joint_values_spatial(mech, system, given.values, z), ok))
    paths["duplicates"] = len(studies) - len(kept)
    distinct = all(ok for _, ok in rows)
    complete, notes = "not proven", []
    if len(rows) == GENERIC_COUNT and distinct:
        complete = "maximal"
    elif (
        distinct
        and len(solutions) == GENERIC_COUNT
        and every_solution(eqs, [*XS, *YS], solutions, dps, len(rows))
    ):
        complete = "maximal"
        notes.append(
            f"all {GENERIC_COUNT} solutions (real and complex), the most a platform on six "
            "distance legs has (Raghavan 1993), found and each certified in its own box: no "
            f"mode is missing ({len(rows)} are real)"
        )
    else:
        notes.append(
            f"continuation found {len(solutions)} solution{'' if len(solutions) == 1 else 's'} "
            f"(real and complex, off the exceptional quadric |X|^2 = 0) on "
            f"{paths['tracked']} paths, of the {GENERIC_COUNT} a platform on six distance "
            f"legs can have: {unproven(paths)}"
        )
    lost = paths["real"] - paths["refined"]
    if lost:
        # (a singular pose's double root, once the data are rounded: two real roots closer
        # than double precision tells apart, or a complex pair; 25-digit octahedral legs
        # turned 90 degrees)
        notes.append(
            f"{lost} real endpoint{'' if lost == 1 else 's'} of continuation could not be "
            f"refined by Newton's method at {dps} digits (a multiple root, or roots closer "
            "together than double precision tells apart, as at a singular pose): not "
            "counted, so a mode may be missing there"
        )
    equivalent = 2 ** sum(1 for n, *_ in system.legs if mech.joint(n[0]).type == "U")
    return Found(formulation, rows, len(rows), complete, paths, tuple(notes), equivalent)


FORMULATION = Formulation("Study coordinates of a six-leg platform", _applies, _find)
