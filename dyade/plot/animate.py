"""The linkage in motion: one frame per reported position of the sweep, the named points'
paths traced underneath (the drawing of ``dyade.plot.mechanism``), saved as an animated
GIF through matplotlib's PillowWriter (``dyade.plot.canvas.save_frames``).
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from dyade.plot import canvas
from dyade.plot.mechanism import PANEL, Scene, geometry, panel_height

FPS = 20.0  # [1/s] frames per second of the GIF
DPI = 72  # [1/in] small frames keep a GIF small


@dataclass(slots=True, eq=False)
class Animation:
    """A figure and how to set it to each frame."""

    figure: Figure
    scene: Scene
    count: int
    """frames: one per reported position of the sweep"""

    def update(self, k: int) -> list:
        """Set the figure to frame k (position k of the sweep); returns the moved artists."""
        moved = self.scene.update(k)
        angle = np.rad2deg(self.scene.geo.crank_angle[k])
        self.title.set_text(f"φ21 = {angle:6.1f}°")
        return moved + [self.title]

    @property
    def title(self):
        return self.figure.axes[0].title


def animation(result, *, fig: Figure | None = None) -> Animation:
    """The mechanism of ``result`` ready to be animated over its reported positions.

    Parameters
    ----------
    result : Result
        A sweep (``dyade.analyse``): one frame per reported position.
    fig : Figure, optional
        A figure to draw on (a window's; default: a new one).

    Returns
    -------
    Animation
        ``count`` frames; ``update(k)`` draws frame k; ``save`` writes a GIF.

    Examples
    --------
    >>> import dyade
    >>> from dyade.plot.animate import animation
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/slotted-lever.toml"), step_deg=30)
    >>> motion = animation(result)
    >>> motion.count, [artist.get_gid() for artist in motion.update(3)][:2]
    (13, ['link-2', None])
    """
    geo = geometry(result)
    width, height = PANEL + 0.4, panel_height(geo) + 0.9
    with canvas.style():  # margins by hand: no layout engine to rerun for every frame
        fig = canvas.new(width, height, fig, layout=None)
        fig.subplots_adjust(left=0.75 / width, right=1 - 0.15 / width, bottom=0.5 / height,
                            top=1 - 0.6 / height)
        scene = Scene(fig.subplots(), geo)
        fig.suptitle(result.mechanism.name)
        motion = Animation(fig, scene, int(geo.crank_angle.size))
        motion.update(0)
    return motion


def save(motion: Animation, path: str, fps: float = FPS, dpi: int = DPI) -> None:
    """Write the animation as a GIF.

    Parameters
    ----------
    motion : Animation
        From ``animation``.
    path : str
        The file, ending in .gif (written beside and renamed when complete).
    fps : float
        Frames per second.
    dpi : int
        Dots per inch of the frames.

    Examples
    --------
    >>> import tempfile, dyade
    >>> from pathlib import Path
    >>> from dyade.plot import animate
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/scotch-yoke.toml"), step_deg=90)
    >>> path = Path(tempfile.mkdtemp()) / "yoke.gif"
    >>> animate.save(animate.animation(result), str(path), fps=4, dpi=30)
    >>> path.read_bytes()[:6]
    b'GIF89a'
    """
    canvas.save_frames(motion.figure, motion.update, motion.count, path, fps, dpi)


def play(motion: Animation, fps: float = FPS):
    """Run the animation in its window (a figure from ``canvas.window``); returns the
    matplotlib animation, which must be kept while it runs."""
    from matplotlib.animation import FuncAnimation

    return FuncAnimation(motion.figure, motion.update, frames=motion.count,
                         interval=1000.0 / fps)
