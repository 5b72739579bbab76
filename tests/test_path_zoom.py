"""A path sweep's figure zooms to the swept values reached (and the located points) when
they are a small part of the requested range, and says what was not reached; a sweep
reached over its whole range keeps the whole range."""

from __future__ import annotations

import matplotlib
import numpy as np

matplotlib.use("Agg")

from mechsing.reports.figures import path_figure  # noqa: E402

X = np.linspace(0.0, 360.0, 181)


def _texts(fig) -> list[str]:
    return [t.get_text() for t in fig.axes[0].texts]


def test_zooms_to_the_reached_part() -> None:
    y = np.where(X <= 40.0, 0.5, np.nan)
    fig = path_figure("A (deg)", [("input", X, y)], (1e-12, 1e-9), [(20.0, 1e-16, "input")])
    lo, hi = fig.axes[0].get_xlim()
    assert lo == 0.0 and 40.0 < hi < 45.0
    assert any(t.startswith("not reached: ") and t.endswith(" to 360") for t in _texts(fig))


def test_keeps_the_whole_range_when_reached() -> None:
    y = np.full_like(X, 0.5)
    fig = path_figure("A (deg)", [("input", X, y)], (1e-12, 1e-9), [])
    assert fig.axes[0].get_xlim() == (0.0, 360.0)
    assert not any(t.startswith("not reached") for t in _texts(fig))
