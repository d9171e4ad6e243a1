"""What the figures share: the style, crank-angle axes with the result's notes shaded,
and deterministic output (the same data gives the same bytes).

Line styles come with dash patterns and markers as well as colours, so that a figure
reads in grey-scale print; colours are the Okabe–Ito palette (safe for colour-blind
readers). Figures are ``matplotlib.figure.Figure`` objects made here or handed in (a
pyplot figure for a window); nothing touches pyplot's global state but ``window`` and
``show``, which the command line calls for ``--show``.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import math
import os
from contextlib import contextmanager
from typing import Callable, Iterator

import matplotlib
import numpy as np
from matplotlib.figure import Figure

from dyade.errors import InputError

RC = {
    "svg.hashsalt": "dyade",  # clip-path ids from a fixed salt: the same SVG bytes every run
    "svg.fonttype": "path",  # text as paths: no font needed to view the SVG
    "pdf.fonttype": 42,
    "font.size": 8.5,
    "axes.titlesize": 9.0,
    "axes.labelsize": 8.5,
    "legend.fontsize": 7.5,
    "legend.framealpha": 0.9,
    "xtick.labelsize": 7.5,
    "ytick.labelsize": 7.5,
    "axes.grid": True,
    "grid.color": "0.88",
    "grid.linewidth": 0.5,
    "lines.linewidth": 1.3,
    "hatch.linewidth": 0.6,
    "hatch.color": "0.35",
    "figure.dpi": 100,
}
"""matplotlib settings of every dyade figure, applied while it is built and saved"""

COLOURS = ("#000000", "#d55e00", "#0072b2", "#009e73", "#cc79a7", "#e69f00", "#56b4e9")
DASHES = ("-", (0, (5, 2)), (0, (1, 1.5)), (0, (6, 1.5, 1, 1.5)), (0, (3, 1.5)),
          (0, (8, 2, 1, 2, 1, 2)), (0, (2, 3)))
MARKERS = ("o", "s", "^", "D", "v", "P", "X")
GREY = "0.55"

METADATA = {"png": {"Software": None},
            "svg": {"Date": None, "Creator": None},
            "pdf": {"Creator": None, "Producer": None, "CreationDate": None}}
"""format -> metadata that would vary between runs or versions, removed"""
FORMATS = tuple(METADATA)
ANIMATION = "gif"

NOTE_LOOK = {
    "partial": ("does not close", "xxxx", "0.75"),
    "dead_centre": ("near a dead centre", "////", "0.85"),
    "poor_transmission": ("poor transmission", "", "0.90"),
    "implausible": ("implausible values", "oo", "0.80"),
    "forces_invalid": ("forces not given", "\\\\\\\\", "0.80"),
    "near_self_locking": ("near self-locking", "||||", "0.85"),
    "self_locking": ("self-locking", "++", "0.80"),
    "friction_not_converged": ("friction not converged", "..", "0.90"),
    "at_rest": ("at rest: no friction", "--", "0.92"),
    "never_moves": ("never moves: no friction loss", "||", "0.95"),
    "run_up_not_settled": ("run-up not settled", "**", "0.88"),
    "clearance_not_applicable": ("clearance check not applicable", "O", "0.93"),
    "drive_line_soft": ("drive line too soft for the rigid model", "xx", "0.82"),
    "lift_off": ("cam follower lifts off", "\\\\\\", "0.87"),
}
"""note kind -> (label, hatch, face grey) of its shaded crank-angle ranges"""


def line(k: int, marker: bool = False, **extra) -> dict:
    """Style k of the cycle: colour and dash pattern (and a sparse marker)."""
    style = {"color": COLOURS[k % len(COLOURS)], "linestyle": DASHES[k % len(DASHES)]}
    if marker:
        style |= {"marker": MARKERS[k % len(MARKERS)], "markevery": 0.08, "markersize": 3.5,
                  "markerfacecolor": "white"}
    return style | extra


@contextmanager
def style() -> Iterator[None]:
    """dyade's matplotlib settings for the figures built or saved inside."""
    with matplotlib.rc_context(RC):
        yield


class Drawing(Figure):
    """A matplotlib ``Figure`` that shows itself in a notebook: IPython's rich display
    takes its PNG (``_repr_png_``), without pyplot or a ``%matplotlib`` magic, as the
    figures are built with the object API.

    >>> png = Drawing(figsize=(1, 1))._repr_png_()
    >>> png[:4]
    b'\\x89PNG'
    """

    def _repr_png_(self) -> bytes:
        return render(self, "png")


def new(width: float, height: float, fig: Figure | None = None,
        layout: str | None = "constrained") -> Figure:
    """A figure of ``width`` × ``height`` [in], laid out by the constrained engine (or
    by hand: ``layout=None``); ``fig`` (a window's figure) is reused when given."""
    if fig is None:
        return Drawing(figsize=(width, height), layout=layout)
    fig.set_size_inches(width, height)
    fig.set_layout_engine(layout or "none")
    return fig


def legend_above(ax, most: int | None = None, **kwargs):
    """The axes' legend in one row above them (``most`` entries a row, where given),
    right-aligned, off the curves (a legend inside the axes hides whatever runs under
    it); constrained layout makes room."""
    handles, _ = ax.get_legend_handles_labels()
    columns = max(1, len(handles) if most is None else min(most, len(handles)))
    return ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), ncols=columns,
                     frameon=False, borderaxespad=0.2, **kwargs)


def grid(count: int, most: int = 3) -> tuple[int, int]:
    """Rows and columns for ``count`` panels, at most ``most`` side by side."""
    rows = math.ceil(count / most)
    return rows, math.ceil(count / rows)  # 4 panels: 2 × 2, not 3 + 1


# -- crank-angle axes ----------------------------------------------------------------
def on_grid(result, values: np.ndarray) -> np.ndarray:
    """A column of the result (reported positions) on every computed position, NaN at the
    others, so that a line breaks where positions are left out."""
    out = np.full(result.rows.shape + values.shape[1:], np.nan)
    out[result.rows] = values
    return out


def crank_axis(ax, result, label: bool = True) -> None:
    """x axis: the crank angle [°] over the sweep, ticks every 30°, 60° or 90°."""
    from matplotlib.ticker import MultipleLocator

    angle = np.rad2deg(result.crank_angle)
    span = float(angle[-1] - angle[0]) if angle.size > 1 else 1.0
    ax.set_xlim(angle[0], angle[-1] if angle.size > 1 else angle[0] + 1.0)
    ax.xaxis.set_major_locator(MultipleLocator(90 if span > 400 else 60 if span > 200 else 30
                                               if span >= 60 else 10))
    if label:
        ax.set_xlabel("crank angle φ21 [°]")


def shade_notes(ax, result) -> None:
    """Shade the crank-angle ranges of the result's notes, each kind with its hatch, and
    name them in the legend (one entry per note)."""
    half = 0.5 * np.rad2deg(result.mechanism.sweep.step)
    for note in result.notes:
        if not note.ranges or note.kind not in NOTE_LOOK:
            continue
        label, hatch, face = NOTE_LOOK[note.kind]
        name = f"{note.subject}: {label}" if note.subject else label
        for k, (first, last) in enumerate(note.ranges):
            ax.axvspan(np.rad2deg(first) - half, np.rad2deg(last) + half, facecolor=face,
                       edgecolor=GREY, hatch=hatch, linewidth=0.0, alpha=0.6, zorder=0,
                       label=name if k == 0 else None, gid=f"note-{note.kind}")


# -- output ----------------------------------------------------------------------------
def suffix(path: str) -> str:
    """The format named by a file's suffix, lower case without the dot."""
    return os.path.splitext(path)[1].lower().lstrip(".")


def render(fig: Figure, fmt: str, dpi: int = 100) -> bytes:
    """The figure as PNG, SVG or PDF bytes, without the metadata that varies (dates,
    versions): the same figure gives the same bytes."""
    from io import BytesIO

    if fmt not in METADATA:
        raise InputError.parameter("format", f"must be one of {', '.join(FORMATS)}, got "
                                             f"{fmt!r}.", value=fmt)
    buffer = BytesIO()
    with style():
        fig.savefig(buffer, format=fmt, dpi=dpi, metadata=METADATA[fmt])
    return buffer.getvalue()


def save(fig: Figure, path: str, dpi: int = 100) -> None:
    """Write the figure in the format of the path's suffix: to a temporary file beside
    it, renamed when complete. The same figure gives the same bytes (no dates or
    versions in the file).

    Parameters
    ----------
    fig : Figure
        From one of ``dyade.plot``'s ``figure`` functions.
    path : str
        The file: .png, .svg or .pdf.
    dpi : int
        Dots per inch (PNG).

    Examples
    --------
    >>> import tempfile, dyade
    >>> from pathlib import Path
    >>> from dyade.plot import canvas, curves
    >>> fig = curves.figure(dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml")))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "fourbar.svg"
    ...     canvas.save(fig, str(path))
    ...     print("<svg" in path.read_text())
    True
    """
    data = render(fig, suffix(path), dpi)
    with _atomic(path) as temporary:
        with open(temporary, "wb") as handle:
            handle.write(data)


def save_frames(fig: Figure, update: Callable[[int], object], count: int, path: str,
                fps: float = 20.0, dpi: int = 80) -> None:
    """An animated GIF (matplotlib's PillowWriter): ``update(k)`` sets frame k of
    ``count`` on ``fig``, which is then grabbed; written beside ``path`` and renamed."""
    from matplotlib.animation import PillowWriter

    if suffix(path) != ANIMATION:
        raise InputError.parameter("path", f"an animation is written as .gif, got {path!r}.",
                                   value=path)
    if not (math.isfinite(fps) and fps > 0):
        raise InputError.parameter("fps", f"must be a positive number of frames per second, "
                                          f"got {fps:g}.", value=fps)
    writer = PillowWriter(fps=fps)
    with _atomic(path) as temporary, style():
        with writer.saving(fig, temporary, dpi):
            for k in range(count):
                update(k)
                writer.grab_frame()


@contextmanager
def _atomic(path: str) -> Iterator[str]:
    """A temporary file name beside ``path`` (same suffix) renamed to it on success."""
    folder, name = os.path.split(os.fspath(path))
    stem, ext = os.path.splitext(name)
    temporary = os.path.join(folder, f".{stem}.part{ext}")
    try:  # a missing folder is created, as for every output of dyade
        if folder:
            os.makedirs(folder, exist_ok=True)
        with open(temporary, "wb"):
            pass
    except (FileExistsError, NotADirectoryError):
        raise InputError(f"{path}: cannot write the file: a part of its folder {folder} is a "
                         f"file, not a folder.", source=os.fspath(path)) from None
    except OSError as err:
        raise InputError(f"{path}: cannot write the file ({err.strerror}).",
                         source=os.fspath(path)) from None
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


# -- a window ------------------------------------------------------------------------
NON_INTERACTIVE = {"agg", "cairo", "pdf", "pgf", "ps", "svg", "template"}


def window(width: float, height: float) -> Figure:
    """A pyplot figure in a window (for ``--show``); ``InputError`` when matplotlib has
    no interactive backend here (no display, or no GUI toolkit installed)."""
    from matplotlib import pyplot

    if pyplot.get_backend().lower() in NON_INTERACTIVE:
        raise InputError(f"no window can be opened: matplotlib's backend here is "
                         f"{pyplot.get_backend()!r} (no display, or no GUI toolkit such as "
                         f"tkinter). Write the figure to a file instead.")
    return pyplot.figure(figsize=(width, height))


def show() -> None:
    """Show the windows opened by ``window`` until they are closed."""
    from matplotlib import pyplot

    pyplot.show()
