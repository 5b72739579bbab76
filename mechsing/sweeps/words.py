"""What a sweep calls a fold it located, and the stop note of a path past one.

A fold of the swept value is where the path's curve turns back: two solutions of the
given values (two assembly modes, or a leg's two postures) meet there, and past it they
are complex.  Where the analysis finds a Type I singularity (``input``: a leg stretched
or folded, the input at the end of its stroke) or the mechanism has one input (every
configuration of the swept input is on the path), that is the input's **limit of
travel**.  Where it finds a Type II singularity alone (``output``) on a mechanism with
more inputs, the swept input goes on (other assembly modes have real configurations
beyond): it is a **fold of the direct kinematics**, where the two assembly modes the path
follows meet and become complex, not a limit of the joint's travel.

Owns :func:`fold_words` and :func:`stop_notes`.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

__all__ = ["fold_words", "stop_notes"]

#: the path engine's stop note past a fold (mechsing.kinematics.paths.arc)
PAST_FOLD = "the rest of the range is beyond the limits of travel"
#: the same where the fold is where two assembly modes meet
PAST_MODES_FOLD = (
    "the rest of the range is past a fold of the direct kinematics (the two assembly "
    "modes followed meet there and are complex beyond it)"
)
#: a located fold's name when it is one of the direct kinematics
MODES_FOLD = "fold of the direct kinematics (two assembly modes meet, complex past it)"


def _modes_meet(mechanism: Any, classes: Iterable[str] | None) -> bool:
    """Is a fold with these ``classes`` one where two assembly modes meet while the
    swept input goes on (Type II alone, a mechanism with more than one input)?"""
    if classes is None or len(mechanism.inputs) < 2:
        return False
    got = set(classes)
    return "output" in got and "input" not in got


def fold_words(mechanism: Any, classes: Iterable[str] | None) -> str:
    """The name of a located fold: ``limit of travel`` or a fold of the direct
    kinematics (see the module)."""
    return MODES_FOLD if _modes_meet(mechanism, classes) else "limit of travel"


def stop_notes(
    mechanism: Any, notes: Iterable[str], folds: Iterable[Iterable[str] | None]
) -> list[str]:
    """``notes`` with the engine's stop note past a fold named as a fold of the direct
    kinematics where every located fold (``folds``: their classes) is one."""
    kinds = [_modes_meet(mechanism, c) for c in folds]
    if not kinds or not all(kinds):
        return list(notes)
    return [n.replace(PAST_FOLD, PAST_MODES_FOLD) for n in notes]
