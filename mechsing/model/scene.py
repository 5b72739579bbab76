"""The scene an analysis works on: the output and inputs a user names outside the file,
and only the part of the mechanism they require.

Owns :class:`SceneChoice` and :func:`choose_scene` (what the command line's
``--output-body``, ``--output-point``, ``--relative-to`` and ``--inputs`` do) and
:func:`relevant_part`.  The choices mean exactly what the file's keys mean:

* ``output_body`` names the output body; it *replaces* the file's output (its
  ``point`` and ``relative_to`` too, which then default as in a file: no point, the
  ground); ``output_point`` (``X,Y,Z`` in the file's length unit, at the reference
  configuration in the ground frame) and ``relative_to`` are the output's ``point`` and
  ``relative_to``; given without ``output_body`` they change the file's output (a file
  without one is refused: name the body);
* ``inputs`` (``A,B,"C1[1]"`` as in the file: a joint name, or ``NAME[i]`` for one
  coordinate) replaces the file's inputs; an empty text means no inputs.

A replaced key is said in the mechanism's notes (``-v``).  With an output named this
way, only what the scene requires is modelled: a joint is kept when some path of joints
from ``relative_to`` to the output body passes through it, or it closes a loop with
such a path (the joints of the blocks, in the graph's biconnected components, between
the two bodies: :func:`relevant_part`); the other branches (another arm, the fingers,
the head) are left out, with their joint values, limits, inputs and couplings, and the
:class:`~mechsing.model.mechanism.Scene` says which.  When the ground itself is left out
(an output relative to a body whose path to the output avoids it), ``relative_to``
becomes the ground: the geometry, given at the reference configuration, is unchanged.
The file's own output prunes nothing: a mechanism file describes what it analyses.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from mechsing.errors import InputRefError, UserError
from mechsing.model.graph import build_graph
from mechsing.model.mechanism import Configuration, InputRef, Joint, Mechanism, Output, Scene

__all__ = ["SceneChoice", "choose_scene", "refuse_left_out", "relevant_part"]


@dataclass(frozen=True)
class SceneChoice:
    """Output and inputs named outside the file (None: the file's), as texts."""

    output_body: str | None = None
    #: ``"X,Y,Z"`` in the file's length unit (numbers or whitelisted expressions)
    output_point: str | None = None
    relative_to: str | None = None
    #: ``"A,B[1]"``: joint names or single coordinates, comma-separated
    inputs: str | None = None

    def names_output(self) -> bool:
        return any(x is not None for x in (self.output_body, self.output_point, self.relative_to))

    def __bool__(self) -> bool:
        return self.names_output() or self.inputs is not None


def choose_scene(mech: Mechanism, choice: SceneChoice) -> Mechanism:
    """``mech`` with the output and inputs of ``choice`` and, when an output is named, only
    the part that output requires (``mech`` itself when ``choice`` names nothing).

    Raises UserError (exit 2) for a body or joint that does not exist, a point that is not
    three numbers, an output relative to itself, an input on a branch left out, or a
    configuration that gives the pose of an output the choice replaces."""
    if not choice:
        return mech
    notes = list(mech.notes)
    output = _output(mech, choice, notes) if choice.names_output() else mech.output
    if choice.names_output():
        assert output is not None
        bodies, joints = relevant_part(mech.bodies, mech.joints, output.relative_to, output.body)
    else:
        bodies, joints = set(mech.bodies), {j.name for j in mech.joints}
    kept = tuple(j for j in mech.joints if j.name in joints)
    kept_bodies = tuple(b for b in mech.bodies if b in bodies)
    left = _branches(mech, bodies, joints)
    scene_notes = []
    if left:
        base = output.relative_to if output is not None else mech.ground
        shown = "; ".join(
            f"joint{'s' if len(js) > 1 else ''} {', '.join(js)}"
            + (f" (bod{'ies' if len(bs) > 1 else 'y'} {', '.join(bs)})" if bs else "")
            for bs, js in left
        )
        scene_notes.append(
            f"left out of the analysis, as they neither lead from {base} to the output "
            f"body {output.body if output else ''} nor close a loop with that path: {shown}"
        )
    ground = mech.ground
    if ground not in bodies:
        assert output is not None
        ground = output.relative_to
        scene_notes.append(
            f"the ground {mech.ground!r} is not on the path from {ground} to the output: "
            f"{ground!r} is the ground of the analysis"
        )
    jmap = {j.name: j for j in kept}
    if choice.inputs is not None:
        inputs = _inputs(mech, choice.inputs, jmap)
        notes.append(_replaced("inputs", ", ".join(map(str, inputs)) or "none", mech.inputs))
    else:
        inputs = tuple(i for i in mech.inputs if i.joint in joints)
        dropped = [str(i) for i in mech.inputs if i.joint not in joints]
        if dropped:
            scene_notes.append(f"inputs left out with their branches: {', '.join(dropped)}")
    # a coupling whose leader is left out goes too: the leader's coordinate is then free,
    # and so is the follower's (q_f = m q_l + c for any q_l); an undefined leader stays, to
    # be refused (mechsing.model.couplings.refuse_orphan_couplings)
    couplings = tuple(
        c
        for c in mech.couplings
        if c.joint in joints and (c.leader in joints or not c.leader_defined)
    )
    dropped_c = tuple(c.joint for c in mech.couplings if c.joint not in joints)
    if dropped_c:
        scene_notes.append(
            f"coupling{'s' if len(dropped_c) > 1 else ''} (mimic) left out with "
            f"{'their' if len(dropped_c) > 1 else 'its'} branch: {', '.join(dropped_c)}"
        )
    freed = tuple(c for c in mech.couplings if c.joint in joints and c not in couplings)
    if freed:
        dropped_c += tuple(c.joint for c in freed)
        scene_notes.append(
            "coupled joint(s) whose leader is left out, now moving freely as their leader "
            "would let them: " + ", ".join(f"{c.joint} (leader {c.leader})" for c in freed)
        )
    configs = _configurations(mech, output, joints)
    return dataclasses.replace(
        mech,
        bodies=kept_bodies,
        ground=ground,
        joints=kept,
        inputs=inputs,
        output=output,
        configurations=configs,
        notes=tuple(notes),
        graph=build_graph(kept_bodies, ground, kept) if left else mech.graph,
        limits={k: v for k, v in mech.limits.items() if k in joints},
        couplings=couplings,
        scene=Scene(
            left_out=tuple(left),
            dropped_couplings=dropped_c,
            notes=tuple(scene_notes),
        ),
    )


def refuse_left_out(mech: Mechanism, names: Sequence[str], option: str) -> None:
    """UserError (exit 2) when an option names a joint of a branch the scene left out
    (``--set r_elbow=1`` with ``--output-body`` on the other arm): it says so, rather
    than that the joint does not exist."""
    if mech.scene is None:
        return
    for name in names:
        for _bodies, joints in mech.scene.left_out:
            if name in joints:
                raise UserError(
                    f"{option} {name}: joint {name!r} is on a branch left out of the analysis "
                    f"(joints {', '.join(joints)}), which neither leads to the output body "
                    f"{mech.output.body if mech.output else ''} nor closes a loop with that "
                    "path; name a joint between the output and the body it is relative to"
                )


def relevant_part(
    bodies: Sequence[str], joints: Sequence[Joint], base: str, body: str
) -> tuple[set[str], set[str]]:
    """The bodies and joint names a relative motion of ``body`` to ``base`` depends on:
    the joints some path of joints from ``base`` to ``body`` passes through, and those
    that close a loop with such a path.  With a virtual joint added between the two
    bodies these are exactly the joints of its biconnected component (an edge lies on a
    simple path between two vertices iff it shares a cycle with the edge joining them),
    in the graph whose nodes are the bodies and the joints (so parallel joints are two
    paths)."""
    import networkx as nx

    g = nx.Graph()
    g.add_nodes_from(("body", b) for b in bodies)
    for j in joints:
        g.add_edge(("body", j.between[0]), ("joint", j.name))
        g.add_edge(("body", j.between[1]), ("joint", j.name))
    virtual = ("virtual", "")
    g.add_edge(virtual, ("body", base))
    g.add_edge(virtual, ("body", body))
    for comp in nx.biconnected_components(g):
        if virtual in comp:
            return (
                {name for kind, name in comp if kind == "body"},
                {name for kind, name in comp if kind == "joint"},
            )
    raise AssertionError("a virtual edge is in a biconnected component")  # pragma: no cover


def _branches(
    mech: Mechanism, bodies: set[str], joints: set[str]
) -> list[tuple[tuple[str, ...], tuple[str, ...]]]:
    """The parts left out, each (bodies, joints) in file order, in the order of their
    first joint in the file: connected through bodies left out."""
    import networkx as nx

    g = nx.Graph()
    for j in mech.joints:
        if j.name in joints:
            continue
        g.add_node(("joint", j.name))
        for b in j.between:
            if b not in bodies:
                g.add_edge(("joint", j.name), ("body", b))
    order = {j.name: i for i, j in enumerate(mech.joints)}
    border = {b: i for i, b in enumerate(mech.bodies)}
    out = []
    for comp in nx.connected_components(g):
        js = sorted((n for k, n in comp if k == "joint"), key=order.__getitem__)
        bs = sorted((n for k, n in comp if k == "body"), key=border.__getitem__)
        out.append((tuple(bs), tuple(js)))
    return sorted(out, key=lambda bj: order[bj[1][0]])


def _output(mech: Mechanism, choice: SceneChoice, notes: list[str]) -> Output:
    where = mech.path or mech.name
    old = mech.output
    if choice.output_body is not None:
        body, rel, point = choice.output_body.strip(), mech.ground, None
    elif old is not None:
        body, rel, point = old.body, old.relative_to, old.point
    else:
        given = "--output-point" if choice.output_point is not None else "--relative-to"
        raise UserError(f"{given}: {where} names no output; name its body with --output-body BODY")
    body = _body(mech, body, "--output-body")
    if choice.relative_to is not None:
        rel = _body(mech, choice.relative_to.strip(), "--relative-to")
    if rel == body:
        given = (
            f"--relative-to {rel}" if choice.relative_to is not None else f"--output-body {body}"
        )
        raise UserError(
            f"{given}: the output body {body!r} is the body it is measured relative to "
            f"({'the ground' if rel == mech.ground else '--relative-to'}); name another body"
        )
    if choice.output_point is not None:
        point = _point(mech, choice.output_point)
    new = Output(body, rel, point, None, False)
    shown = f"{{body: {body}" + (f", relative_to: {rel}" if rel != mech.ground else "")
    shown += f", point: [{', '.join(f'{float(x):.6g}' for x in point)}] m" if point else ""
    shown += "}"
    if old is None:
        notes.append(f"output {shown} from the command line (the file names none)")
    elif (old.body, old.relative_to, old.point) != (body, rel, point):
        line = f" (line {old.line})" if old.line else ""
        notes.append(
            f"output {shown} from the command line replaces the file's output "
            f"{{body: {old.body}}}{line}"
        )
    return new


def _body(mech: Mechanism, name: str, option: str) -> str:
    if name in mech.bodies:
        return name
    shown = ", ".join(mech.bodies[:12]) + (", ..." if len(mech.bodies) > 12 else "")
    raise UserError(
        f"{option} {name}: {mech.path or mech.name} has no body {name!r}; its bodies are "
        f"{shown} (in a URDF or MJCF file, links joined rigidly are one body, named after "
        "the link nearer the root)"
    )


def _point(mech: Mechanism, text: str) -> tuple[Any, Any, Any]:
    from mechsing.errors import ExpressionError
    from mechsing.model.expressions import parse_number

    parts = [t.strip() for t in text.split(",")]
    if len(parts) != 3 or not all(parts):
        raise UserError(
            f"--output-point {text!r}: give three comma-separated coordinates X,Y,Z in the "
            "file's length unit (the point at the reference configuration, ground frame), "
            "e.g. --output-point 1.5,0,0"
        )
    f = mech.units.length_factor
    try:
        x, y, z = (parse_number(t) * f if f != 1 else parse_number(t) for t in parts)
    except ExpressionError as exc:
        raise UserError(f"--output-point {text!r}: {exc}") from None
    return (x, y, z)


def _inputs(mech: Mechanism, text: str, kept: dict[str, Joint]) -> tuple[InputRef, ...]:
    everything = {j.name: j for j in mech.joints}
    out: list[InputRef] = []
    taken: set[tuple[str, int]] = set()
    for part in (t.strip() for t in text.split(",")):
        if not part:
            continue
        try:
            ref = InputRef.parse(part, everything)
        except InputRefError as exc:
            raise UserError(f"--inputs {text!r}: {exc.item}: {exc.problem}") from None
        if ref.joint not in kept:
            raise UserError(
                f"--inputs {text!r}: joint {ref.joint!r} is on a branch left out of the "
                "analysis (it neither leads to the output nor closes a loop with that path); "
                "name joints between the output and the body it is relative to"
            )
        coords = range(kept[ref.joint].dof) if ref.index is None else (ref.index,)
        for c in coords:
            if (ref.joint, c) in taken:
                raise UserError(
                    f"--inputs {text!r}: coordinate {c} of joint {ref.joint!r} is given "
                    "twice; list it once"
                )
            taken.add((ref.joint, c))
        out.append(ref)
    return tuple(out)


def _replaced(key: str, new: str, old: tuple[Any, ...]) -> str:
    was = ", ".join(map(str, old))
    return f"{key} [{new}] from the command line" + (
        f" replace the file's [{was}]" if old else " (the file names none)"
    )


def _configurations(
    mech: Mechanism, output: Output | None, joints: set[str]
) -> dict[str, Configuration]:
    old = mech.output
    changed = output is not old and (
        old is None
        or output is None
        or (old.body, old.relative_to, old.point) != (output.body, output.relative_to, output.point)
    )
    out: dict[str, Configuration] = {}
    for name, cfg in mech.configurations.items():
        if cfg.pose is not None and changed:
            raise UserError(
                f"{mech.path or mech.name}: configuration {name!r} gives the pose of the file's "
                "output, which the output options replace; analyse another configuration, or "
                "give the output in the file"
            )
        if all(k in joints for k in cfg.values):
            out[name] = cfg
            continue
        out[name] = dataclasses.replace(
            cfg,
            values={k: v for k, v in cfg.values.items() if k in joints},
            lines={k: v for k, v in cfg.lines.items() if k in joints},
        )
    return out
