"""Configurations given on the command line: ``--set [NAME:]JOINT=VALUE``.

Each value is one joint's, in the file's units (a joint of several coordinates takes a
comma-separated list, ``S1=0.1,0,0.2``; exact expressions such as ``pi/4`` are read as in a
mechanism file, and a decimal written with digits to spare has the written resolution a
file's has, which the verdicts are checked against).  Values with the same ``NAME`` form
one configuration of that name; without ``NAME`` the configuration is ``cli``.  Each is solved by closure from ``reference`` or from
the configuration ``start`` names.  A name the file already uses is refused (exit 2), and so
is a joint given twice in one configuration.  A joint whose own name holds a colon is read
as a joint (``a:b=1`` sets joint ``a:b`` when the file has one).

Owns :data:`SET_CONFIG`, :func:`with_set_values` and :func:`set_start`.  It sits above the
model, which it imports only inside its functions, so that the command line's parser can
name :data:`SET_CONFIG` without loading the model (``mechsing --version`` stays fast).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from mechsing.errors import UserError

__all__ = ["SET_CONFIG", "set_names", "set_start", "with_set_values"]

#: the name of the configuration that values given without a name form
SET_CONFIG = "cli"


def _split(mech: Any, text: str) -> tuple[str, str, str]:
    """(configuration name, joint, value text) of ``[NAME:]JOINT=VALUE``."""
    left, eq, raw = text.partition("=")
    left = left.strip()
    config, joint = SET_CONFIG, left
    if left not in mech.joint_names and ":" in left:
        config, _, joint = (s.strip() for s in left.partition(":"))
    if not eq or not joint or not raw.strip() or not config:
        raise UserError(
            f"--set {text!r}: expected JOINT=VALUE or NAME:JOINT=VALUE, e.g. --set J2=30 or "
            "--set wrist:J5=0"
        )
    return config, joint, raw


def set_names(mech: Any, sets: list[str] | None) -> list[str]:
    """The configurations ``sets`` give, in the order they first appear."""
    return list(dict.fromkeys(_split(mech, t)[0] for t in sets or ()))


def set_start(mech: Any, sets: list[str] | None, command: str) -> str | None:
    """The one configuration ``sets`` give, where a command starts (a sweep, a report's
    sweep, solve): None without ``sets``; several names are refused."""
    names = set_names(mech, sets)
    if len(names) > 1:
        raise UserError(
            f"{command} starts from one configuration, and --set gives {len(names)} "
            f"({', '.join(names)}); give the values of one (or use 'mechsing analyze')"
        )
    return names[0] if names else None


def with_set_values(mech: Any, sets: list[str] | None, start: str | None, path: str) -> Any:
    """``mech`` with the configurations the ``--set`` values give (``mech`` itself when
    there is none); ``start``: the configuration each is solved from (None: reference);
    ``path`` names the file in messages."""
    from mechsing.model.expressions import ExpressionError, parse_number, written_digits
    from mechsing.model.mechanism import Configuration
    from mechsing.numeric import data_resolution
    from mechsing.numeric.pirational import evalf_float

    if not sets:
        if start is not None:
            raise UserError(
                f"--from {start}: names the configuration --set values are solved from; give "
                "--set JOINT=VALUE too (or --config to analyse a configuration of the file)"
            )
        return mech
    start = start or "reference"
    if start not in mech.configurations:
        raise UserError(
            f"{path}: --from {start!r}: no such configuration; the file has: "
            f"{', '.join(mech.configurations)}"
        )
    units = mech.units
    values: dict[str, dict[str, tuple[Any, ...]]] = {}
    # each value's written resolution, as a file's (half a unit in its last digit)
    resolutions: dict[str, dict[str, tuple[tuple[float, int], ...]]] = {}
    for text in sets:
        config, name, raw = _split(mech, text)
        if config in mech.configurations:
            raise UserError(
                f"{path}: the file already has a configuration named {config!r}, the name "
                f"--set {text!r} gives its values; choose another name (or use --config "
                f"{config} without --set)"
            )
        if name not in mech.joint_names:
            shown = ", ".join(mech.joint_names[:12]) + (", ..." if len(mech.joints) > 12 else "")
            raise UserError(f"--set {text!r}: {path} has no joint {name!r}; its joints are {shown}")
        given = values.setdefault(config, {})
        if name in given:
            where = "" if config == SET_CONFIG else f" for {config}"
            raise UserError(f"--set {name} is given twice{where}; give each joint once")
        j = mech.joint(name)
        parts = [t.strip() for t in raw.split(",")]
        if j.dof == 0:
            raise UserError(f"--set {text!r}: joint {name!r} ({j.type}) has no coordinates")
        if len(parts) != j.dof:
            raise UserError(
                f"--set {text!r}: joint {name!r} ({j.type}) has {j.dof} coordinate"
                f"{'s' if j.dof > 1 else ''}; give {j.dof} comma-separated value"
                f"{'s' if j.dof > 1 else ''} in the file's units"
            )
        coords = []
        written = []
        for t, unit in zip(parts, j.units, strict=True):
            try:
                x = parse_number(t)
            except ExpressionError as exc:
                raise UserError(f"--set {text!r}: {exc}") from None
            factor = units.angle_factor if unit == "rad" else units.length_factor
            coords.append(x * factor if factor != 1 else x)
            form = written_digits(t)
            res = 0.0 if form is None else data_resolution(*form, evalf_float(factor, 17))
            written.append((res, form[0] if form is not None and res else 0))
        given[name] = tuple(coords)
        if any(res for res, _ in written):
            resolutions.setdefault(config, {})[name] = tuple(written)
    added = {
        c: Configuration(c, v, start, None, {}, None, resolution=resolutions.get(c, {}))
        for c, v in values.items()
    }
    return dataclasses.replace(mech, configurations={**mech.configurations, **added})
