"""List the Lie subgroup types of D (the catalog), or describe one of them.

Every type comes from the data files in catalog/: symbol, name, dimension,
geometric parameters (the mechanism-file keys), the subalgebra basis written
in terms of those parameters, the canonical coordinates of a joint value,
and a short explanation.
"""

from __future__ import annotations

import argparse
import json

from mechsing.cli import UserError

NAME = "catalog"
HELP = "list the subgroup types of D (joints and loop subgroups), or describe one"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("type", nargs="?", metavar="TYPE", help="a type symbol, e.g. S or T2")
    parser.add_argument("--format", choices=("text", "json"), default="text", help="output format")


def _describe(t) -> str:  # noqa: ANN001 - SubgroupType
    lines = [f"{t.symbol}: {t.name} (dimension {t.dimension})"]
    params = ", ".join(f"{n} ({k})" for n, k in t.parameters) or "none"
    lines.append(f"  parameters: {params}")
    lines.append("  basis (omega; v):")
    for w, v in t.basis_text:
        lines.append(f"    ({w}; {v})")
    coords = ", ".join(f"{n} [{u}]" for n, u in t.coordinates) or "none"
    lines.append(f"  joint value coordinates: {coords}")
    lines.append(f"  normal in D: {'yes' if t.normal_in_D else 'no'}")
    if t.invariants:
        lines.append("  invariants: " + "; ".join(t.invariants))
    lines.append("  realised by: " + "; ".join(t.joints))
    lines.append("  " + " ".join(t.explanation.split()))
    return "\n".join(lines)


#: the universal joint is not a subgroup: a composite joint the mechanism file accepts
UNIVERSAL_JOINT = {
    "symbol": "U",
    "name": "universal joint (Hooke's joint)",
    "composite": True,
    "of": ["R", "R"],
    "dimension": 2,
    "parameters": [["axes", "two directions"], ["point", "point"]],
    "explanation": (
        "U is not a subgroup of D: its motions (two rotations about axes that meet at a point, "
        "the second axis carried by the first rotation) do not form a group. It is a composite "
        "joint, two R joints in series through a hidden cross body named <joint>.cross. Write it "
        "as {type: U, axes: [a1, a2], point: c}: a1 is fixed in the first body of between, a2 in "
        "the second, the axes meet at c and are not parallel; its value is [q1, q2], with "
        "g_b = g_a exp(q1 R(a1, c)) exp(q2 R(a2, c)). Each loop through it is analysed with its two "
        "revolutes (see 'mechsing catalog R')."
    ),
}


def _universal_joint(fmt: str) -> int:
    if fmt == "json":
        print(json.dumps([UNIVERSAL_JOINT], indent=2, ensure_ascii=False))
        return 0
    u = UNIVERSAL_JOINT
    print(f"U: {u['name']}: a composite joint, not a subgroup of D (two R joints)")
    print("  parameters: axes (two directions), point (point)")
    print("  joint value coordinates: q1 [rad], q2 [rad]")
    print("  " + u["explanation"])
    return 0


def run(args: argparse.Namespace) -> int:
    from mechsing.analysis.contract import to_json
    from mechsing.subgroups import load_catalog

    cat = load_catalog()
    if args.type is not None:
        key = args.type.strip()
        match = cat.get(key) or {s.upper(): t for s, t in cat.items()}.get(key.upper())
        if match is None and key.upper() == "U":
            return _universal_joint(args.format)
        if match is None:
            raise UserError(
                f"catalog: unknown subgroup type {args.type!r}; use one of {', '.join(cat)}"
            )
        types = [match]
    else:
        types = list(cat.values())
    if args.format == "json":
        print(json.dumps([to_json(t) for t in types], indent=2, ensure_ascii=False))
        return 0
    if args.type is None:
        width = max(len(t.symbol) for t in types)
        print("Lie subgroup types of D (mechsing catalog S for one of them):")
        for t in types:
            params = ", ".join(n for n, _ in t.parameters) or "-"
            print(f"  {t.symbol:<{width}}  dim {t.dimension}  {t.name}  [{params}]")
        print("There is no 5-dimensional subgroup of D (Herve's classification).")
        print("The universal joint U is composite (two R joints), not a type: mechsing catalog U.")
    else:
        print(_describe(types[0]))
    return 0
