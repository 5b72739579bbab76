"""The cuspidal 3-RPR of Innocenti & Parenti-Castelli (1998) as a mechanism file for the
sweeps' mode tests: its geometry from :mod:`tests.reference.rpr_cusp_loops` (the same
numbers the independent computation uses), its reference configuration the pose ``x`` of
the section rho1 over (rho2, rho3), so that the sweep's swept values are the leg lengths
minus the reference's (P2 = rho2 - rho2_ref)."""

from __future__ import annotations

import numpy as np

from tests.reference import rpr_cusp_loops as ref


def design_yaml(rho1: float, x: np.ndarray) -> tuple[str, np.ndarray]:
    """The file's text and the legs' reference lengths (rho1, rho2, rho3) at pose x."""
    b = ref.pivots(rho1, float(x[0]), float(x[1]))
    A = [ref.A1, ref.A2, ref.A3]
    lengths = np.array([float(np.linalg.norm(b[i] - A[i])) for i in range(3)])

    def v(p: np.ndarray) -> str:
        return f"[{float(p[0])!r}, {float(p[1])!r}, 0]"

    joints = []
    for i in range(3):
        k = i + 1
        joints += [
            f"  - {{name: Rb{k}, type: R, between: [ground, cyl{k}], axis: [0, 0, 1], "
            f"point: {v(A[i])}}}",
            f"  - {{name: P{k}, type: P, between: [cyl{k}, pis{k}], axis: {v(b[i] - A[i])}}}",
            f"  - {{name: Rp{k}, type: R, between: [pis{k}, platform], axis: [0, 0, 1], "
            f"point: {v(b[i])}}}",
        ]
    text = "\n".join(
        [
            "mechanism: cuspidal-3rpr",
            "bodies: [ground, cyl1, pis1, cyl2, pis2, cyl3, pis3, platform]",
            "joints:",
            *joints,
            "inputs: [P1, P2, P3]",
            "output: {body: platform}",
            "configurations:",
            "  reference: {}",
            "  corner: {P1: 0, P2: 0, P3: 0}",
            "",
        ]
    )
    return text, lengths
