"""The design review's section "Assembly modes": every assembly mode of one
configuration (:func:`mechsing.modes`), each with a sketch, its verdict, its certificate
and whether continuation reaches it.

Owns :func:`modes_blocks`.
"""

from __future__ import annotations

from mechsing.assembly import ModesResult
from mechsing.assembly.render import modes_heading
from mechsing.model import Mechanism
from mechsing.reports import document as doc
from mechsing.reports.figures import svg
from mechsing.reports.sketch import choose_view, sketch_figure

__all__ = ["modes_blocks"]


def modes_blocks(mech: Mechanism, res: ModesResult, length_scale: float) -> list[doc.Block]:
    """The section's blocks: a heading, what the count claims, and per mode a sketch
    with a list of its facts."""
    out: list[doc.Block] = [
        doc.Heading(2, "Assembly modes"),
        doc.Paragraph(modes_heading(res) + "."),
    ]
    view = choose_view(mech)
    for k, m in enumerate(res.modes, 1):
        q = [x for name, _i in mech.coordinates() for x in m.joints[name][_i : _i + 1]]
        fig = sketch_figure(mech, q, view, [], length_scale, f"mode {k}: {view.name}")
        out.append(doc.Heading(3, f"Mode {k}"))
        out.append(
            doc.Figure(
                f"mode-{doc.slug(res.configuration)}-{k}",
                svg(fig),
                f"sketch of {mech.name}, assembly mode {k} of {res.configuration}",
                "Links as segments between their joints, ground hatched.",
            )
        )
        classes = sorted({s["class"] for s in m.analysis.get("singularities", [])})
        facts = [
            "singular: " + ", ".join(classes) if m.analysis.get("singular") else "regular",
            f"certified within {m.radius:.0e}" if m.certified else "not certified",
        ]
        if m.reached_by_continuation:
            facts.append("the mode continuation from the configuration's start reaches")
        if m.outside_limits:
            facts.append("outside the limits of " + ", ".join(m.outside_limits))
        facts.append(
            "joint values (m, rad): "
            + ", ".join(
                f"{n} {', '.join(f'{v:.6g}' for v in vals)}" for n, vals in m.joints.items()
            )
        )
        out.append(doc.Bullets(tuple(facts)))
    return out
