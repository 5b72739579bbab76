"""Independent reference for a grid's aspects: a breadth-first flood fill over the
samples, one sample at a time (imports nothing from mechsing).

``regular`` (rows by columns) marks the regular samples; ``right[j][i]`` cuts sample
(j, i) from (j, i + 1), ``up[j][i]`` cuts (j, i) from (j + 1, i).  Two neighbouring
samples are in one region when both are regular and no cut lies between them.
"""

from __future__ import annotations

from collections import deque


def regions(
    regular: list[list[bool]],
    right: list[list[bool]],
    up: list[list[bool]],
    xs: list[float],
    ys: list[float],
) -> list[tuple[int, tuple[tuple[float, float], tuple[float, float]], list[list[bool]]]]:
    """Each region as (samples, ((x_min, x_max), (y_min, y_max)), mask), largest first,
    ties by the first sample row by row."""
    rows, cols = len(regular), len(regular[0])
    seen = [[False] * cols for _ in range(rows)]
    found = []
    for j0 in range(rows):
        for i0 in range(cols):
            if not regular[j0][i0] or seen[j0][i0]:
                continue
            seen[j0][i0] = True
            queue = deque([(j0, i0)])
            members = []
            while queue:
                j, i = queue.popleft()
                members.append((j, i))
                steps = []
                if i + 1 < cols and not right[j][i]:
                    steps.append((j, i + 1))
                if i > 0 and not right[j][i - 1]:
                    steps.append((j, i - 1))
                if j + 1 < rows and not up[j][i]:
                    steps.append((j + 1, i))
                if j > 0 and not up[j - 1][i]:
                    steps.append((j - 1, i))
                for jj, ii in steps:
                    if regular[jj][ii] and not seen[jj][ii]:
                        seen[jj][ii] = True
                        queue.append((jj, ii))
            mask = [[False] * cols for _ in range(rows)]
            for j, i in members:
                mask[j][i] = True
            x = [xs[i] for _, i in members]
            y = [ys[j] for j, _ in members]
            found.append(((j0, i0), len(members), ((min(x), max(x)), (min(y), max(y))), mask))
    found.sort(key=lambda r: (-r[1], r[0]))
    return [(n, box, mask) for _, n, box, mask in found]
