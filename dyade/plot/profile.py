"""A motion profile over the machine cycle: s, v, a, j in four panels with the segments
marked (their boundaries, their laws); and a motion law alone over its normalised time.

Each segment is drawn from its own law on its own interval, and the curve breaks at a
boundary: a jump (of the jerk at a rest, of the acceleration where a law's class allows
it) shows as a step between two ends, never as a steep line.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import numpy as np
from matplotlib.figure import Figure

from dyade.plot import canvas

PANELS = (("s", "position s"), ("v", "velocity v"), ("a", "acceleration a"),
          ("j", "jerk j"))
SAMPLES = 400  # [-] points per segment (per law)
SHADE = "0.95"


def curves(profile, laws, samples: int = SAMPLES) -> tuple[np.ndarray, list[np.ndarray]]:
    """The master [SI] and s, v, a, j [SI] segment by segment, a NaN between segments."""
    from dyade.motion.profile import physical

    xs, values = [], [[], [], [], []]
    for segment, law in zip(profile.segments, laws):
        z = np.linspace(0.0, 1.0, samples)
        xs.append(segment.start + z * segment.duration)
        xs.append(np.array([np.nan]))
        if law is None:
            parts = (np.full(samples, segment.lift_from), *(np.zeros(samples),) * 3)
        else:
            parts = physical(law, segment, z)
        for target, part in zip(values, parts):
            target.append(np.asarray(part, dtype=float))
            target.append(np.array([np.nan]))
    return np.concatenate(xs), [np.concatenate(v) for v in values]


def figure(outcome, *, fig: Figure | None = None) -> Figure:
    """s, v, a, j of a ``profile`` Outcome over the cycle, in its units, the segments
    marked.

    Parameters
    ----------
    outcome : Outcome
        ``dyade.run("profile", ...)`` (its ``result``: the profile, its laws, the
        motion and the master speed).
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Returns
    -------
    Figure

    Examples
    --------
    >>> import dyade
    >>> from dyade.plot import profile as plot
    >>> fig = plot.figure(dyade.run("profile", "mechanisms/profiles/indexing.toml"))
    >>> len(fig.axes), fig.axes[0].get_ylabel()
    (4, 'position s [mm]')
    """
    from dyade.analyses.profile import MASTER_WORDS
    from dyade.files.profile import MASTER_UNITS, output_factor

    profile, laws, _, omega = outcome.result
    x_size = MASTER_UNITS[profile.master][1]
    s_size = output_factor(profile.unit)
    x_word = MASTER_WORDS[MASTER_UNITS[profile.master][0]]
    x, values = curves(profile, laws)
    if omega is None:
        rate, x_axis, shown = x_size, f"master angle [{x_word}]", x / x_size
        if profile.master == "time":
            x_axis = "time [s]"
    else:
        rate, x_axis, shown = 1.0 / omega, "time [s]", (x - profile.start) / omega
    scaled = [values[k] * rate**k / s_size for k in range(4)]
    bounds = [s.start for s in profile.segments] + [profile.segments[-1].end]
    edges = np.array(bounds) if omega is None else (np.array(bounds) - profile.start) / omega
    edges = edges / (x_size if omega is None else 1.0)
    with canvas.style():
        fig = canvas.new(7.0, 7.2, fig)
        axes = fig.subplots(4, 1, sharex=True)
        for k, (ax, (symbol, label)) in enumerate(zip(axes, PANELS)):
            for n, (left, right) in enumerate(zip(edges[:-1], edges[1:])):
                if n % 2:
                    ax.axvspan(left, right, color=SHADE, zorder=0, linewidth=0)
            for edge in edges:
                ax.axvline(edge, color=canvas.GREY, linewidth=0.6, zorder=1)
            ax.axhline(0.0, color="0.3", linewidth=0.5, zorder=1)
            ax.plot(shown, scaled[k], gid=symbol, **canvas.line(0, linewidth=1.4))
            ax.set_ylabel(f"{label} [{outcome.units[symbol]}]")
            ax.grid(True, axis="y")
            ax.grid(False, axis="x")
        top = axes[0]
        for n, (segment, left, right) in enumerate(zip(profile.segments, edges[:-1],
                                                       edges[1:]), start=1):
            name = laws[n - 1].name if laws[n - 1] is not None else "dwell"
            top.annotate(f"{n} {name}", ((left + right) / 2, 1.0),
                         xycoords=("data", "axes fraction"), xytext=(0, 3 + 9 * (n % 2)),
                         textcoords="offset points", ha="center", va="bottom", fontsize=6.5,
                         gid=f"segment-{n}")
        axes[-1].set_xlabel(x_axis)
        axes[-1].set_xlim(edges[0], edges[-1])
        fig.suptitle(f"Motion profile: {profile.name}")
    return fig


def law_figure(law, *, samples: int = 801, fig: Figure | None = None) -> Figure:
    """A motion law over its normalised time: s, v = s′, a = s″, j = s‴ in four small
    panels, its characteristic values in the titles.

    Parameters
    ----------
    law : Law
        ``dyade.motion.laws.law(name, ...)``.
    samples : int
        Points over the law (each piece drawn on its own, broken at the joins).
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Returns
    -------
    Figure

    >>> from dyade.motion.laws import LAWS
    >>> from dyade.plot import profile as plot
    >>> len(plot.law_figure(LAWS["modified-sine"]).axes)
    4
    """
    z_parts, value_parts = [], [[], [], [], []]
    for piece in law.pieces:                      # broken where a piece's jerk jumps
        z = np.linspace(piece.z0, piece.z1, max(8, int(samples * (piece.z1 - piece.z0))))
        z_parts += [z, np.array([np.nan])]
        for target, part in zip(value_parts, piece(z)):
            target += [np.broadcast_to(np.asarray(part, dtype=float), z.shape),
                       np.array([np.nan])]
    z = np.concatenate(z_parts)
    values = [np.concatenate(v) for v in value_parts]
    titles = ("s", f"s′ (C_v = {law.C_v:.4f})", f"s″ (C_a = {law.C_a:.4f})",
              f"s‴ (C_j = {law.C_j:.4g})")
    with canvas.style():
        fig = canvas.new(6.4, 3.6, fig)
        axes = fig.subplots(2, 2, sharex=True).ravel()
        for k, ax in enumerate(axes):
            ax.axhline(0.0, color="0.3", linewidth=0.5)
            ax.plot(z, values[k], gid=PANELS[k][0], **canvas.line(k))
            ax.set_title(titles[k], loc="left")
            ax.set_xlim(0.0, 1.0)
        for ax in axes[2:]:
            ax.set_xlabel("normalised time z [-]")
        fig.suptitle(f"{law.title}: class {law.boundary}, C_M = {law.C_M:.4g}")
    return fig
