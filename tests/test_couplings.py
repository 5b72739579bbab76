"""The ``couplings`` key (a URDF mimic): read in the file's units, checked, and refused by
the analysis while a coupled joint is in the analysed part."""

from __future__ import annotations

import pytest
import sympy

import mechsing
from mechsing.model import MechanismError, loads

HEAD = """
units: {length: mm, angle: deg}
bodies: [g, a, b, c]
joints:
  - {name: S, type: P, between: [g, a], axis: [1, 0, 0]}
  - {name: B, type: R, between: [a, b], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: T, type: S, between: [b, c], point: [1, 0, 0]}
"""


def test_a_coupling_is_read_in_the_files_units() -> None:
    mech = loads(HEAD + "couplings:\n  - {joint: B, leader: S, multiplier: 2, offset: 10}\n")
    (c,) = mech.couplings
    assert (c.joint, c.leader, c.line) == ("B", "S", 9)
    # B [deg] = 2 S [mm] + 10 deg  <=>  B [rad] = 2 (pi/180) / (1/1000) S [m] + 10 pi/180
    assert sympy.simplify(c.multiplier - 2 * (sympy.pi / 180) * 1000) == 0
    assert sympy.simplify(c.offset - 10 * sympy.pi / 180) == 0


@pytest.mark.parametrize(
    ("entry", "words"),
    [
        ("{joint: B, leader: Q}", "unknown joint 'Q'"),
        ("{joint: B, leader: B}", "coupled to itself"),
        ("{joint: T, leader: B}", "has 3 coordinates"),
        ("{joint: B, leader: S, gain: 2}", "unknown key 'gain'"),
        ("{joint: B}", "missing key 'leader'"),
    ],
)
def test_a_bad_coupling_names_its_line(entry: str, words: str) -> None:
    with pytest.raises(MechanismError) as exc:
        loads(HEAD + f"couplings:\n  - {entry}\n")
    assert words in str(exc.value) and exc.value.line == 9


def test_a_joint_coupled_twice_is_refused() -> None:
    text = HEAD + "couplings:\n  - {joint: B, leader: S}\n  - {joint: B, leader: S}\n"
    with pytest.raises(MechanismError, match="already coupled"):
        loads(text)


def test_the_analysis_refuses_a_coupling_it_does_not_model() -> None:
    mech = loads(HEAD + "couplings:\n  - {joint: B, leader: S, multiplier: 2}\n")
    with pytest.raises(MechanismError) as exc:
        mechsing.analyze(mech, precision="float")
    assert exc.value.line == 9 and "'B' is coupled to joint 'S'" in str(exc.value)
