"""The record of one direction of a followed path (:class:`PathTrace`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mechsing.kinematics.paths.folds import Fold

__all__ = ["PathTrace"]


@dataclass
class PathTrace:
    """The closed configurations of one direction of a path: ``Z`` (K, n), NaN rows at
    samples not reached; its folds; ``stopped``: why the path ended early (None: it
    reached every sample it could); ``newton``: batched Newton iterations per sample."""

    Z: np.ndarray
    folds: list[Fold]
    stopped: str | None = None
    newton: np.ndarray | None = None
    #: node pairs whose samples in between are still to be closed (``follow(...,
    #: fine=False)``: :func:`close_segments` closes them, several traces together)
    segments: list[tuple[int, int]] = field(default_factory=list)
    values: np.ndarray | None = None
