"""Result columns against the crank angle, with the result's notes shaded and named.

Any column of ``Result.columns()`` (the CSV's names) can be drawn; columns of one unit
share a panel, whose axis carries the unit (``dyade.linkage.columns.unit_of``). Ranges
the result warns about (dead centres, forces not given, positions that do not close,
self-locking, friction) are shaded with a hatch per kind and named in the legend, and
values that are not given leave a gap in the line. The drive torque comes with its
cycle mean and the energy surplus between them shaded (what a flywheel must store,
ΔE = max − min of ∫(M_drive − M_mean)dφ), a panel of transmission angles with the
dead-centre band; by default, both.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import numpy as np
from matplotlib.figure import Figure

from dyade import cycle
from dyade.errors import InputError
from dyade.linkage.columns import unit_of
from dyade.linkage.machine_curve import torque_curve
from dyade.machine.flywheel import energy_extremes, machine_curve
from dyade.plot import canvas

WIDTH, PANEL = 8.5, 2.5  # [in] figure width (the legends beside the panels), height of one panel


def energy_surplus(angle: np.ndarray, torque: np.ndarray) -> tuple[float, float | None]:
    """The drive torque's cycle mean [N·m] and, over a whole revolution, the range
    ΔE = max E − min E [J] of the energy E(φ) = ∫(M − M_mean)dφ (else None): the energy a
    flywheel must take up and give back per cycle (``angle`` in [rad]). Both as
    ``dyade flywheel`` and ``analyse`` compute them (``dyade.cycle``,
    ``dyade.machine.flywheel``): each position once, E between the samples too.

    >>> import numpy as np
    >>> phi = np.linspace(0.0, 2 * np.pi, 361)
    >>> mean, delta = energy_surplus(phi, 5.0 + 2.0 * np.sin(phi))
    >>> round(mean, 12), round(delta, 6)      # ∫ 2 sin φ dφ over 0..π
    (5.0, 4.0)
    """
    mean = cycle.mean(angle, torque)
    if not cycle.revolution(angle, torque)[2]:
        return mean, None
    top, _, bottom, _ = energy_extremes(machine_curve(angle, torque, speed=1.0))
    return mean, top - bottom


def default_quantities(result) -> list[str]:
    """The drive torque (with forces) and every dyad's transmission angle."""
    torque = ["M_drive"] if result.forces_valid is not None else []
    return torque + [f"mu_{dyad.number}_deg" for dyad in result.mechanism.dyads]


def figure(result, quantities=None, *, fig: Figure | None = None) -> Figure:
    """Columns of a result against the crank angle, one panel per unit.

    Parameters
    ----------
    result : Result
        From ``dyade.analyse``.
    quantities : iterable of str, optional
        Column names as in the CSV (``M_drive``, ``F_2_3``, ``mu_2_deg`` …); default:
        the drive torque with its mean and energy surplus, and the transmission angles.
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Examples
    --------
    >>> import dyade
    >>> from dyade.plot import curves
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml"))
    >>> [ax.get_ylabel() for ax in curves.figure(result).axes]
    ['M_drive [N·m]', 'transmission angle μ [°]']
    """
    cols = result.columns()
    names = default_quantities(result) if quantities is None else list(quantities)
    _check(names, cols)
    panels: dict[str, list[str]] = {}
    for name in names:
        panels.setdefault(unit_of(name), []).append(name)
    with canvas.style():
        fig = canvas.new(WIDTH, PANEL * len(panels) + 0.4, fig)
        axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False).ravel()
        for ax, (unit, group) in zip(axes, panels.items()):
            for k, name in enumerate(group):
                values = canvas.on_grid(result, cols[name])
                if name == "M_drive":
                    _torque(ax, result, values, k)
                elif name.startswith("mu_"):
                    ax.plot(np.rad2deg(result.crank_angle), values, gid=name,
                            label=f"μ dyad {name.split('_')[1]}", **canvas.line(k, True))
                else:
                    ax.plot(np.rad2deg(result.crank_angle), values, gid=name, label=name,
                            **canvas.line(k, len(group) > 1))
            canvas.shade_notes(ax, result)
            canvas.crank_axis(ax, result, label=ax is axes[-1])
            ax.set_ylabel(f"{group[0]} [{unit}]" if len(group) == 1 else f"[{unit}]"
                          if unit else "[-]")
            if unit == "°" and all(name.startswith("mu_") for name in group):
                _dead_centre_band(ax, result)
                ax.set_ylabel("transmission angle μ [°]")
            # beside the panel, not on it: "best" still hid part of a curve (issue 29)
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                      fontsize="small")
        fig.suptitle(result.mechanism.name)
    return fig


def _check(names: list[str], cols: dict) -> None:
    import difflib

    if not names:
        raise InputError.parameter("quantities", "name no column to draw.")
    for name in names:
        if name not in cols or name == "angle_deg":
            close = difflib.get_close_matches(name, [c for c in cols if c != "angle_deg"], n=3)
            hint = (f" Did you mean {', '.join(close)}?" if close else
                    " The columns are those of `dyade analyse --format csv` "
                    "(`dyade help columns`).")
            raise InputError.parameter("quantities", f"{name!r} is not a column of this "
                                                     f"result.{hint}", value=name)


def _torque(ax, result, torque: np.ndarray, k: int = 0) -> None:
    """The drive torque (style k), its cycle mean, and the energy surplus and deficit
    shaded; at constant speed over a whole revolution the mean and ΔE are those of
    ``dyade flywheel`` (the machine's torque curve at its fine step), else those of the
    plotted samples (``energy_surplus``)."""
    angle = np.rad2deg(result.crank_angle)
    ax.plot(angle, torque, gid="M_drive", label="M_drive", **canvas.line(k))
    given = np.isfinite(torque)
    if not given.all():
        ax.set_title("no cycle mean or ΔE: the torque is not given everywhere", fontsize=7.5)
        return
    mean, delta = energy_surplus(result.crank_angle, torque)
    if delta is not None and result.drive is None:  # at constant speed: as `dyade flywheel`
        curve = torque_curve(result.mechanism)
        top, _, bottom, _ = energy_extremes(curve)
        mean, delta = curve.mean_torque, top - bottom
    ax.axhline(mean, gid="M_mean", label=f"mean {mean:.4g} N·m", **canvas.line(k + 2))
    ax.fill_between(angle, torque, mean, where=torque >= mean, interpolate=True,
                    facecolor="0.85", edgecolor=canvas.GREY, hatch="////", linewidth=0.0,
                    label="above the mean: the flywheel gives", gid="surplus")
    ax.fill_between(angle, torque, mean, where=torque < mean, interpolate=True,
                    facecolor="white", edgecolor=canvas.GREY, hatch="....", linewidth=0.0,
                    label="below: the flywheel takes up", gid="deficit")
    if delta is not None:
        ax.set_title(f"drive torque: ΔE = {delta:.4g} J per cycle (what a flywheel must store)",
                     fontsize=7.5)
    else:
        ax.set_title("drive torque (not a full cycle: no ΔE)", fontsize=7.5)


def _dead_centre_band(ax, result) -> None:
    """The validity policy's bands: around 0° and 180° nothing is given (hatched); below
    the transmission warning results come with a warning (shaded)."""
    band = np.rad2deg(result.mechanism.dead_centre_angle)
    for low, high in ((0.0, band), (180.0 - band, 180.0)):
        ax.axhspan(low, high, facecolor="0.8", edgecolor=canvas.GREY, hatch="xx",
                   linewidth=0.0, zorder=0, gid="dead-centre-band",
                   label=f"dead-centre band ±{band:g}°" if low == 0.0 else None)
    warn = np.rad2deg(result.mechanism.transmission_warning)  # the soft band: a warning
    for low, high in ((band, warn), (180.0 - warn, 180.0 - band)):
        ax.axhspan(low, high, facecolor="0.93", edgecolor="none", linewidth=0.0, zorder=0,
                   gid="warning-band",
                   label=f"warning below {warn:g}°" if low == band else None)
    ax.set_ylim(0.0, 180.0)
    ax.set_yticks([0, 30, 60, 90, 120, 150, 180])
