"""Labels that neither overlap each other nor sit on the curves they name.

A figure's labels (crank-angle marks and reversal numbers of a polar diagram, link numbers
and point names of a mechanism drawing) are placed once the axes have their final place
on the figure: each label tries offsets around its anchor, nearest first, and takes the
first whose box stays inside the axes, clear of the labels placed before it and of the
drawn lines and markers (the obstacles, sampled points in display coordinates); when no
offset is clear it takes the one that covers the fewest obstacle points, with a thin
leader line back to its anchor. Nothing is dropped: a label that cannot be placed clear is
still drawn (``tests/readable.py`` checks the result on every shipped example).

Anchors that fall on one spot (several crank-angle marks where the force stays at zero)
are merged into one label by the caller (``merge``), which abbreviates, not deletes:
"0°–150°" for a run of marks, "180°/240°" for a few.
"""

from __future__ import annotations

import numpy as np
from matplotlib.font_manager import FontProperties
from matplotlib.textpath import text_to_path

DIRECTIONS = 16  # candidate directions around an anchor
RADII = (4.0, 8.0, 13.0, 19.0, 26.0, 34.0, 44.0, 56.0)  # [pt] candidate distances
PAD = 1.0  # [pt] space kept around a label's box
LEADER = 11.0  # [pt] labels placed farther than this get a leader line


def extent(text: str, size: float, weight: str = "normal") -> tuple[float, float]:
    """Width and height [pt] of ``text`` in dyade's font at ``size`` [pt]."""
    width, _, _ = text_to_path.get_text_width_height_descent(
        text, FontProperties(size=size, weight=weight), ismath=False)
    return float(width), 1.25 * size


class Placer:
    """Free places for labels on one axes (after the figure's layout is final)."""

    def __init__(self, ax, obstacles: np.ndarray | None = None) -> None:
        ax.apply_aspect()
        self.ax = ax
        self.scale = ax.figure.dpi / 72.0  # [px/pt]
        self.frame = ax.bbox.extents  # x0, y0, x1, y1 [px]
        self.boxes: list[np.ndarray] = []
        self.points = np.empty((0, 2))
        if obstacles is not None:
            self.avoid(obstacles)

    def display(self, xy: np.ndarray) -> np.ndarray:
        """Data coordinates (m, 2) -> display [px], NaN rows kept."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        out = np.full_like(xy, np.nan)
        given = np.isfinite(xy).all(axis=1)
        if given.any():
            out[given] = self.ax.transData.transform(xy[given])
        return out

    def avoid(self, xy: np.ndarray, step: float = 2.0) -> None:
        """Keep labels off a polyline (data coordinates, NaN breaks it): its vertices and
        points every ``step`` [px] between them."""
        at = self.display(xy)
        pieces = [at]
        if len(at) > 1:
            a, b = at[:-1], at[1:]
            length = np.hypot(*(b - a).T)
            count = np.where(np.isfinite(length), np.ceil(np.nan_to_num(length) / step), 0)
            count = np.minimum(count, 400).astype(int)
            if count.sum():
                which = np.repeat(np.arange(len(a)), count)
                share = (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)) \
                    / np.repeat(np.maximum(count, 1), count)
                pieces.append(a[which] + share[:, None] * (b[which] - a[which]))
        points = np.concatenate(pieces)
        self.points = np.concatenate([self.points, points[np.isfinite(points).all(axis=1)]])

    def place(self, anchor, text: str, size: float, weight: str = "normal",
              first: float = 0.0, pad: float = PAD) -> tuple[float, float]:
        """The offset [pt] of the centre of ``text`` from ``anchor`` (data coordinates)
        where it is clear; its box (grown by ``pad`` [pt]) is taken. ``first`` [rad]: the
        direction tried first."""
        width, height = extent(text, size, weight)
        half = 0.5 * np.array([width, height]) * self.scale + pad * self.scale
        centre = self.display(anchor)[0]
        turns = first + 2 * np.pi * np.arange(DIRECTIONS) / DIRECTIONS
        unit = np.stack([np.cos(turns), np.sin(turns)], axis=1)
        reach = np.abs(unit) @ half  # the box's edge (not its centre) at the distance
        radii = np.array(RADII) * self.scale
        offsets = (unit[None] * (radii[:, None] + reach[None])[..., None]).reshape(-1, 2)
        boxes = np.concatenate([centre + offsets - half, centre + offsets + half], axis=1)
        cost = self._cost(boxes)
        best = int(np.argmin(cost))  # the first of the cheapest: nearest, first direction
        self.boxes.append(boxes[best])
        return float(offsets[best, 0] / self.scale), float(offsets[best, 1] / self.scale)

    def _cost(self, boxes: np.ndarray) -> np.ndarray:
        """Per candidate box (c, 4): inf outside the axes, 1e9 on a placed label, else
        the obstacle points it covers."""
        x0, y0, x1, y1 = self.frame
        outside = (boxes[:, 0] < x0) | (boxes[:, 1] < y0) | (boxes[:, 2] > x1) | (boxes[:, 3] > y1)
        cost = np.zeros(len(boxes))
        if self.boxes:
            taken = np.array(self.boxes)
            hit = ((boxes[:, None, 0] < taken[None, :, 2]) & (taken[None, :, 0] < boxes[:, None, 2])
                   & (boxes[:, None, 1] < taken[None, :, 3])
                   & (taken[None, :, 1] < boxes[:, None, 3]))
            cost += 1e9 * hit.any(axis=1)
        p = self.points
        if len(p):
            inside = ((p[None, :, 0] > boxes[:, None, 0]) & (p[None, :, 0] < boxes[:, None, 2])
                      & (p[None, :, 1] > boxes[:, None, 1]) & (p[None, :, 1] < boxes[:, None, 3]))
            cost += inside.sum(axis=1)
        cost[outside] = np.inf
        return cost


def leader(offset: tuple[float, float], colour: str = "0.45") -> dict | None:
    """``arrowprops`` of a thin leader line for a label placed far from its anchor."""
    if np.hypot(*offset) <= LEADER:
        return None
    return {"arrowstyle": "-", "color": colour, "linewidth": 0.5, "shrinkA": 1, "shrinkB": 1}


def merge(values: list[float], step: float) -> str:
    """Crank angles [°] that share one spot as one label: "0°–150°" for a run (each
    ``step`` [°] after the one before), "180°/240°" otherwise."""
    values = sorted(values)
    runs: list[list[float]] = [[values[0]]]
    for v in values[1:]:
        if abs(v - runs[-1][-1] - step) < 1e-6:
            runs[-1].append(v)
        else:
            runs.append([v])
    parts = [f"{r[0] % 360:.0f}°–{r[-1] % 360:.0f}°" if len(r) > 2 else
             "/".join(f"{v % 360:.0f}°" for v in r) for r in runs]
    return "/".join(parts)
