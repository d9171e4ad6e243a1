"""Readable figures: the drawn text labels of a figure neither overlap each other nor leave
the figure (issue 29). Used by tests/plot/test_readable.py on every plot kind and shipped example.
"""

from __future__ import annotations

import numpy as np

PAD = 0.5  # [px] boxes that merely touch do not overlap


def drawn_labels(fig) -> list:
    """Every Text the figure draws (titles, tick and axis labels, legend entries,
    annotations), with its bounding box [px]: recorded while the figure is drawn, so that
    tick labels outside the view and hidden texts, which are not drawn, do not count."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    drawn, original = [], Text.draw

    def draw(self, renderer):
        original(self, renderer)
        if self.get_visible() and self.get_text().strip():
            # the text's own box (an annotation's would include its leader line)
            drawn.append((self, Text.get_window_extent(self, renderer)))

    canvas = FigureCanvasAgg(fig)  # a figure made without pyplot has no renderer of its own
    Text.draw = draw
    try:
        canvas.draw()
    finally:
        Text.draw = original
    return drawn


def clashes(fig) -> list[str]:
    """What is wrong with the figure's labels: pairs that overlap, labels outside the
    figure, after a draw; [] when readable."""
    found = drawn_labels(fig)
    texts, boxes = [t for t, _ in found], [b for _, b in found]
    width, height = fig.bbox.width, fig.bbox.height
    problems = []
    for t, b in zip(texts, boxes):
        if b.x0 < -PAD or b.y0 < -PAD or b.x1 > width + PAD or b.y1 > height + PAD:
            problems.append(f"{t.get_text()!r} leaves the figure ({b.x0:.0f},{b.y0:.0f},"
                            f"{b.x1:.0f},{b.y1:.0f} in {width:.0f}×{height:.0f})")
    if not boxes:
        return problems
    box = np.array([[b.x0, b.y0, b.x1, b.y1] for b in boxes])
    overlap = ((box[:, None, 0] < box[None, :, 2] - PAD) & (box[None, :, 0] < box[:, None, 2] - PAD)
               & (box[:, None, 1] < box[None, :, 3] - PAD)
               & (box[None, :, 1] < box[:, None, 3] - PAD))
    for i, j in zip(*np.nonzero(np.triu(overlap, 1))):
        problems.append(f"{texts[i].get_text()!r} overlaps {texts[j].get_text()!r}")
    return problems


def covered_lines(fig) -> list[str]:
    """The drawn lines a legend inside the axes covers (after a draw): "legend 'drive line,
    rigid drive' covers 'rigid drive'"; [] when every legend is off the curves."""
    from matplotlib.transforms import Bbox

    renderer = fig.canvas.get_renderer()
    problems = []
    for ax in (ax for ax in fig.axes if ax.get_visible()):
        legend = ax.get_legend()
        if legend is None or not legend.get_visible():
            continue
        box = Bbox.intersection(legend.get_window_extent(renderer), ax.get_window_extent())
        if box is None:  # a legend outside its axes covers no curve of them
            continue
        entries = ", ".join(t.get_text() for t in legend.get_texts())
        for line in (line for line in ax.get_lines() if line.get_visible()):
            path = line.get_transform().transform_path(line.get_path())
            vertices = path.vertices[np.isfinite(path.vertices).all(axis=1)]
            if line.get_linestyle() in ("None", "none", "", " "):
                hit = bool(box.count_contains(vertices)) if len(vertices) else False
            else:
                hit = path.intersects_bbox(box, filled=False)
            if hit:
                problems.append(f"legend {entries!r} covers {line.get_label()!r}")
    return problems
