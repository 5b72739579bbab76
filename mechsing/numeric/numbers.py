"""Numbers as people write them, and vectors made unit without overflow.

One syntax for a number written in a file or on a command line, whatever reads it (the
YAML expressions, the URDF and MJCF attributes, ``--set``, ``--vary``): ASCII decimal
digits with an optional sign, point and exponent (``30``, ``-0.25``, ``1.5e-3``).
Python's ``float`` also takes ``1_000``, fullwidth digits (``３０``), ``nan`` and
``inf``; none of them is a number here.  A number is also of a sensible size: at most
:data:`~mechsing.numeric.tolerances.MAX_NUMBER` in magnitude.

:func:`unit_vector` normalises a direction or a quaternion after scaling it by its
largest component, so that ``[1e308, 1e308, 0]`` and ``[1e-200, 1e-200, 0]`` give the
same unit vector as ``[1, 1, 0]`` (the plain norm overflows to infinity or underflows to
zero there).
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from mechsing.numeric.tolerances import MAX_NUMBER

__all__ = [
    "DECIMAL",
    "SIGNED_DECIMAL",
    "decimal_float",
    "is_decimal_text",
    "is_sensible_size",
    "safe_norm",
    "unit_vector",
]

#: an unsigned decimal literal, ASCII digits only
DECIMAL = re.compile(r"^(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?$", re.ASCII)
#: a decimal literal with an optional sign (blanks allowed after the sign)
SIGNED_DECIMAL = re.compile(
    r"^[-+]?[ \t]*(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?$", re.ASCII
)


def is_decimal_text(text: str) -> bool:
    """True for a plain signed decimal number in ASCII (``-1.5e3``), False for anything
    else (``1_000``, ``３０``, ``nan``, ``0x10``, an expression)."""
    return bool(SIGNED_DECIMAL.match(text.strip()))


def is_sensible_size(x: Any) -> bool:
    """True when ``|x|`` is at most :data:`MAX_NUMBER` (a float, or anything that
    compares with one, such as an exact rational)."""
    return bool(abs(x) <= MAX_NUMBER)


def decimal_float(text: str) -> float:
    """The float of a plain decimal number (:func:`is_decimal_text`), finite and of a
    sensible size (:func:`is_sensible_size`); ``ValueError`` saying which otherwise."""
    if not is_decimal_text(text):
        raise ValueError(f"{text.strip()[:40]!r} is not a decimal number (write ASCII digits)")
    x = float(text.strip().replace(" ", "").replace("\t", ""))
    if not math.isfinite(x) or not is_sensible_size(x):
        raise ValueError(
            f"the number {text.strip()[:40]!r} is too large: numbers are at most "
            f"{MAX_NUMBER:g} in magnitude"
        )
    return x


def _scaled(v: Any) -> tuple[np.ndarray, float]:
    a = np.asarray(v, dtype=float).ravel()
    if not np.all(np.isfinite(a)):
        raise ValueError("a direction must have finite components")
    m = float(np.max(np.abs(a))) if a.size else 0.0
    return (a / m if m > 0.0 else a), m


def safe_norm(v: Any) -> float:
    """The Euclidean norm of a finite float vector, computed as ``m |v / m|`` with ``m``
    its largest component in absolute value (no overflow or underflow in the squares); ``inf`` only
    when the norm itself is beyond the float range."""
    u, m = _scaled(v)
    return m * math.sqrt(float(u @ u)) if m > 0.0 else 0.0


def unit_vector(v: Any) -> np.ndarray:
    """``v / |v|`` as floats, computed as ``u / |u|`` with ``u = v / max|v_i|``, which
    neither overflows nor underflows for any finite non-zero ``v``; ``ValueError`` for
    a zero or non-finite vector."""
    u, m = _scaled(v)
    if m == 0.0:
        raise ValueError("a zero vector has no direction")
    return u / math.sqrt(float(u @ u))
