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


def run(args: argparse.Namespace) -> int:
    from mechsing.subgroups import CatalogError, load_catalog

    try:
        cat = load_catalog()
    except CatalogError as exc:
        raise UserError(str(exc)) from None
    if args.type is not None:
        key = args.type.strip()
        match = cat.get(key) or {s.upper(): t for s, t in cat.items()}.get(key.upper())
        if match is None:
            raise UserError(
                f"catalog: unknown subgroup type {args.type!r}; use one of {', '.join(cat)}"
            )
        types = [match]
    else:
        types = list(cat.values())
    if args.format == "json":
        print(json.dumps([t.to_json() for t in types], indent=2, ensure_ascii=False))
        return 0
    if args.type is None:
        width = max(len(t.symbol) for t in types)
        print("Lie subgroup types of D (mechsing catalog S for one of them):")
        for t in types:
            params = ", ".join(n for n, _ in t.parameters) or "-"
            print(f"  {t.symbol:<{width}}  dim {t.dimension}  {t.name}  [{params}]")
        print("There is no 5-dimensional subgroup (theory.md §2.2).")
    else:
        print(_describe(types[0]))
    return 0
