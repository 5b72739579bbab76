"""The general formulation's system split into parts that share no unknown, each solved
alone, and their modes combined: a mode is one solution of each part.

A parallel mechanism given the output's pose is the plain case: each serial leg reaches
the pose alone, so its three (or six) closure equations hold its own joints only, and
the system is a product.  Solved whole, its multihomogeneous start system has the
product of the legs' path counts (216 for a 3-RPR's three legs of 6), nearly all ending
extraneous; solved part by part, their sum (18).

Owns :func:`split` and :func:`combined`.  The modes combined are counted once the
parts are solved: more than :data:`MAX_MODES` (each would be analysed) is refused with
each part's count.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from typing import Any

import mpmath

from mechsing.errors import TooManyModes
from mechsing.model import Mechanism

__all__ = ["MAX_MODES", "combined", "split"]

#: the most modes the parts' solutions may combine into (each mode is analysed): a
#: Gough-Stewart platform's six U-P-S legs at a pose reach it in four postures each,
#: 4,096 working modes, refused with the counts
MAX_MODES = 4000


def split(prob: Any) -> list[Any]:
    """The parts of ``prob`` (a :class:`~mechsing.assembly.general.Problem`): the
    connected components of its closures, two closures joined where they share an
    unknown (an idle rod's spin equation goes with its joint).  One part: ``[prob]``.
    Each part is a Problem of its own unknowns, with ``others``: the unknown joints of
    the other parts, held at 0 in its rows (only its own joints are read)."""
    import networkx as nx

    owner = {g: k for k, grp in enumerate(prob.groups) for g in grp.gens}
    items = [("closure", c, c.equations) for c in prob.closures]
    items += [("spin", k, (e,)) for k, e in enumerate(prob.spin_equations)]
    used = [{owner[s] for e in es for s in e.free_symbols if s in owner} for _, _, es in items]
    if not all(used) or set().union(*used) != set(range(len(prob.groups))):
        return [prob]  # an unknown in no equation: not a finite set, said of the whole
    graph = nx.Graph()
    graph.add_nodes_from(range(len(prob.groups)))
    for ks in used:
        graph.add_edges_from(itertools.pairwise(sorted(ks)))
    components = sorted((sorted(c) for c in nx.connected_components(graph)), key=min)
    if len(components) < 2:
        return [prob]
    parts = []
    for keep in components:
        index = {k: i for i, k in enumerate(keep)}
        mine = {prob.groups[k].joint for k in keep}
        here = [(kind, x) for (kind, x, _), ks in zip(items, used, strict=True) if min(ks) in index]
        spins = [x for kind, x in here if kind == "spin"]
        parts.append(
            dataclasses.replace(
                prob,
                groups=tuple(prob.groups[k] for k in keep),
                joints={
                    n: tuple(index[k] for k in ks) for n, ks in prob.joints.items() if n in mine
                },
                closures=tuple(x for kind, x in here if kind == "closure"),
                spins=tuple(prob.spins[k] for k in spins),
                spin_equations=tuple(prob.spin_equations[k] for k in spins),
                others=frozenset(set(prob.joints) - mine),
            )
        )
    return parts


def combined(mech: Mechanism, parts: list[Any], found: list[Any]) -> Any:
    """One :class:`~mechsing.assembly.chains.Found` from each part's (``found``, in the
    order of ``parts``): every choice of one mode per part, certified where each is, the
    count proven where every part's is; none where a part has none (proven where that
    part's count is); else, where some parts' solutions are not finitely many,
    ``infinite`` with the sum of their dimensions."""
    from mechsing.assembly.chains import Found

    formulation = dict(found[0].formulation)
    formulation["unknowns"] = [u for f in found for u in f.formulation["unknowns"]]
    formulation["closures"] = [c for f in found for c in f.formulation["closures"]]
    formulation["randomized"] = any(f.formulation["randomized"] for f in found)
    formulation["parts"] = [
        {
            "joints": sorted(p.joints, key=[n for n, _ in mech.coordinates()].index),
            "bezout": f.formulation.get("bezout"),
            "count": f.count,
            "complete": f.complete,
        }
        for p, f in zip(parts, found, strict=True)
    ]
    formulation["bezout"] = sum(f.formulation.get("bezout") or 0 for f in found)
    names = "; ".join(", ".join(part["joints"]) for part in formulation["parts"])
    notes = [
        f"the closure equations fall into {len(parts)} systems that share no unknown "
        f"(joints {names}), each solved alone: a mode is one solution of each"
    ]
    for part, f in zip(formulation["parts"], found, strict=True):
        notes += [f"joints {', '.join(part['joints'])}: {n}" for n in f.notes]
    paths: dict[str, Any] | None = None
    if all(f.paths is not None for f in found):
        paths = {k: sum(f.paths[k] for f in found) for k in found[0].paths}
    empty = [f for f in found if f.count == 0]
    if empty:
        # a part without a real solution: no mode at all, whatever the others have (proven
        # where that part's count is)
        complete = "proven" if any(f.complete == "proven" for f in empty) else "not proven"
        none = [
            ", ".join(part["joints"])
            for part, f in zip(formulation["parts"], found, strict=True)
            if f.count == 0
        ]
        legs = "that leg's" if len(none) == 1 else "those legs'"
        notes.append(
            f"no mode: no real solution for joints {'; '.join(none)}"
            + (
                f" (the output's pose is out of {legs} reach)"
                if found[0].formulation.get("working_modes")
                else ""
            )
        )
        return Found(formulation, [], 0, complete, paths, tuple(notes), 1, found[0].closure)
    infinite = [f for f in found if f.complete == "infinite"]
    if infinite:
        # a product of sets: their dimensions add (a finite part adds none)
        formulation["dimension"] = sum(f.formulation.get("dimension") or 0 for f in infinite)
        return Found(formulation, [], None, "infinite", paths, tuple(notes), 1, found[0].closure)
    sizes = [len(f.rows) for f in found]
    if math.prod(sizes) > MAX_MODES:
        each = "; ".join(
            f"{', '.join(part['joints'])}: {n}"
            for part, n in zip(formulation["parts"], sizes, strict=True)
        )
        raise TooManyModes(
            f"the closure equations fall into {len(parts)} systems solved apart, with "
            f"{' x '.join(map(str, sizes))} real solutions ({each}): they combine into "
            f"{math.prod(sizes)} modes, more than the {MAX_MODES} analysed at most; give "
            "some of these joints' values in the configuration to choose their postures"
        )
    coords = mech.coordinates()
    rows = []
    for choice in itertools.product(*(f.rows for f in found)):
        q = list(choice[0][0])
        for p, (row, _) in zip(parts[1:], choice[1:], strict=True):
            for i, (name, _) in enumerate(coords):
                if name in p.joints:
                    q[i] = row[i]
        rows.append((q, all(ok for _, ok in choice)))
    rows.sort(key=lambda r: [float(mpmath.mpf(x)) for x in r[0]])
    counts = [f.count for f in found]
    count = None if None in counts else len(rows)
    complete = "proven" if all(f.complete == "proven" for f in found) else "not proven"
    equivalent = 1
    for f in found:
        equivalent *= f.equivalent
    return Found(
        formulation, rows, count, complete, paths, tuple(notes), equivalent, found[0].closure
    )
