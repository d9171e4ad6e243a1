"""Campbell diagram of a gear drive: natural frequencies against the input speed, the
excitation lines and the resonance crossings, each ranked by the API's modal mesh
stiffness (Berczyński, Maćkowiak and Marchelek 1978).

The model has no gyroscopic terms, so the natural frequencies are horizontal lines (the
same at every speed). The excitation lines of ``dyade.campbell`` run through the origin:
each shaft line's speed (grey, dotted), each mesh's tooth-mesh frequency z·n/60 and its
harmonics (one dash pattern per mesh), and the file's excitations (a wide light band
under the line, which often coincides with a mesh line). Every crossing the API reports
is marked where it reports it; its size shows the modal mesh stiffness κ = F²/ω² of the
exciting mesh relative to the largest κ among the crossings (the dynamic mesh force a
transmission error drives at that resonance is κ·e/(2ζ)): filled and larger the more the
mode loads the mesh, open where κ is below ``WEAK`` of the largest (the mode hardly loads
that mesh), open squares for shaft-speed and torque lines, which κ does not rank. The
strongest crossings are labelled with their mode and speed.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import math

import numpy as np
from matplotlib.figure import Figure

from dyade.plot import canvas

WEAK = 1e-4  # [-] κ below this share of the largest: the mode hardly loads the mesh
SIZES = (12.0, 110.0)  # [pt²] marker areas at κ = WEAK·largest and at the largest
LABELLED = 4  # the strongest crossings named on the diagram
MESH_STYLE = ("-", (0, (6, 2)), (0, (6, 1.5, 1, 1.5)), (0, (3, 1.5)))
ZOOM = 600.0  # [Hz] a second panel enlarges the frequencies below this …
ZOOM_ABOVE = 1.5  # [-] … where the diagram reaches this many times higher
"""dash pattern of each mesh's tooth-mesh lines (repeats after four meshes)"""


def importance(diagram) -> np.ndarray:
    """Per crossing (in the diagram's order), κ divided by the largest κ among the
    crossings: NaN where κ does not apply (shaft-speed and torque lines)."""
    kappa = np.array([c.mesh_stiffness for c in diagram.crossings], dtype=float)
    largest = np.nanmax(kappa, initial=0.0) if np.isfinite(kappa).any() else 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        return kappa / largest if largest > 0.0 else np.full(kappa.size, np.nan)


def marker_areas(share: np.ndarray) -> np.ndarray:
    """Marker areas [pt²] of ranked crossings: linear in log10(share) from ``WEAK`` (the
    smallest) to 1 (the largest)."""
    position = np.clip(1.0 + np.log10(np.clip(share, WEAK, 1.0)) / -math.log10(WEAK), 0.0, 1.0)
    return SIZES[0] + (SIZES[1] - SIZES[0]) * position


def figure(diagram, *, fig: Figure | None = None) -> Figure:
    """The Campbell diagram of ``diagram`` (``dyade.campbell(drive, speeds)``).

    Parameters
    ----------
    diagram : Campbell
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Examples
    --------
    >>> import numpy as np, dyade
    >>> from dyade.plot import campbell as plot
    >>> from dyade.vibration.gears.campbell import default_speeds
    >>> drive = dyade.read_gears("mechanisms/gears/two-stage.toml")
    >>> diagram = dyade.campbell(drive, default_speeds(drive.speed.rpm))
    >>> fig = plot.figure(diagram)
    >>> mode = [l for l in fig.axes[0].get_lines() if l.get_gid() == "mode-1"][0]
    >>> bool(np.all(mode.get_ydata() == diagram.modes.frequencies[0]))
    True
    """
    speeds, modes = diagram.speeds_rpm, diagram.modes
    drive = modes.system.drive
    frequencies = modes.frequencies
    lines = diagram.lines
    sloped = np.array([o.slope > 0.0 for o in diagram.orders], dtype=bool)
    tops = [float(np.max(lines[sloped, -1]))] if sloped.any() else []
    tops += [float(o.frequency) for o in diagram.orders if o.slope == 0.0]
    tops += [c.frequency for c in diagram.crossings]
    top = 1.08 * max(tops + [float(np.nanmax(frequencies, initial=0.0))] * (not tops) + [1.0])
    zoom = top > ZOOM_ABOVE * ZOOM
    with canvas.style():
        fig = canvas.new(8.5, 11.0 if zoom else 7.0, fig)
        axes = fig.subplots(2, 1, height_ratios=(2, 3)) if zoom else [fig.subplots()]
        for ax, ceiling, crowd in zip(axes, (top, ZOOM), (1.8 if zoom else 1.0, 1.0)):
            _panel(ax, diagram, ceiling, crowd)
        if zoom:
            axes[1].set_title(f"below {ZOOM:.0f} Hz, enlarged", fontsize=8)
        fig.legend(handles=_legend(axes[0], diagram), loc="outside lower center", ncols=3)
        hidden = int(np.sum(frequencies > top))
        above = f"; {hidden} modes above {top:.0f} Hz not shown" if hidden else ""
        fig.suptitle(f"{drive.name}: Campbell diagram ({len(diagram.crossings)} crossings{above})"
                     f"\nnatural frequencies are horizontal lines: this model has no gyroscopic "
                     f"terms, so they do not depend on speed")
    return fig


def _panel(ax, diagram, top: float, crowd: float = 1.0) -> None:
    """The diagram up to ``top`` [Hz] on one axes; ``crowd``: how many times shorter
    than a full figure's the axes are (labels are merged over that much more)."""
    speeds, modes = diagram.speeds_rpm, diagram.modes
    drive, frequencies = modes.system.drive, modes.frequencies
    low, high = float(speeds[0]), float(speeds[-1])
    shown = np.flatnonzero(np.isfinite(frequencies) & (frequencies <= top))
    for k in shown:
        ax.plot([low, high], [frequencies[k]] * 2, color="0.6", linewidth=0.7, zorder=1,
                gid=f"mode-{k + 1}")
    _mode_labels(ax, frequencies[shown], shown + 1, high, top, crowd)
    _order_lines(ax, diagram, top, crowd)
    _crossings(ax, diagram)
    rpm = drive.speed.rpm if drive.speed is not None else None
    if rpm is not None and low <= rpm <= high:
        ax.axvline(rpm, color="0.25", linestyle=canvas.DASHES[4], linewidth=0.9, zorder=2,
                   gid="operating")
        ax.annotate(f"operating speed {rpm:g} rpm", (rpm, 0.0),  # the lines leave at the top
                    xycoords=("data", "axes fraction"), xytext=(-3, 4),
                    textcoords="offset points", rotation=90, ha="right", va="bottom",
                    fontsize=7)
    ax.set_xlim(low, high)
    ax.set_ylim(0.0, top)
    body = drive.speed.body if drive.speed is not None else "input"
    ax.set_xlabel(f"input speed n ({body}) [rpm]")
    ax.set_ylabel("frequency [Hz]")


def _mode_labels(ax, frequencies: np.ndarray, numbers: np.ndarray, right: float,
                 top: float, crowd: float = 1.0) -> None:
    """Mode numbers at the right edge, modes closer than 1.6 % of the axis (times
    ``crowd``) in one label, labels pushed apart to that spacing."""
    gap = 0.016 * crowd * top
    groups: list[list[int]] = []
    for k, f in enumerate(frequencies):
        if groups and f - frequencies[groups[-1][0]] < gap:
            groups[-1].append(k)
        else:
            groups.append([k])
    below = -np.inf
    for group in groups:
        first, last = numbers[group[0]], numbers[group[-1]]
        text = f"{first}" if first == last else f"{first}–{last}"
        at = max(float(np.mean(frequencies[group])), below + gap)
        below = at
        ax.annotate(text, (right, at), xytext=(3, 0),
                    textcoords="offset points", va="center", fontsize=6, color="0.35",
                    annotation_clip=False)
    ax.annotate("mode", (1.0, 1.0), xycoords="axes fraction", xytext=(3, 3),
                textcoords="offset points", fontsize=6, color="0.35")


def _style(order) -> dict:
    if order.kind == "shaft":
        return {"color": "0.45", "linestyle": canvas.DASHES[2], "linewidth": 1.0}
    if order.kind == "mesh":
        return {"color": canvas.COLOURS[order.mesh % len(canvas.COLOURS)],
                "linestyle": MESH_STYLE[order.mesh % len(MESH_STYLE)], "linewidth": 1.1}
    return {"color": canvas.COLOURS[5], "linestyle": "-", "linewidth": 4.5, "alpha": 0.35,
            "solid_capstyle": "butt"}


def _order_lines(ax, diagram, top: float, crowd: float = 1.0) -> None:
    """Each excitation line, named where it leaves the axes (coinciding lines once)."""
    speeds = diagram.speeds_rpm
    names: dict[tuple[float, float], list[str]] = {}
    for k, order in enumerate(diagram.orders):
        ax.plot(speeds, diagram.lines[k], zorder=2 if order.kind != "excitation" else 1.5,
                gid=f"order-{order.name}", **_style(order))
        key = (round(order.slope, 12), round(order.frequency, 9))
        names.setdefault(key, []).append(order.name)
    ends = []  # (where, label, at the right edge)
    for (slope, fixed), labels in names.items():
        end = slope * speeds[-1] + fixed
        if end <= top:
            ends.append(((float(speeds[-1]), end), [" = ".join(labels)], True))
        elif slope > 0.0:
            ends.append((((top - fixed) / slope, top), [" = ".join(labels)], False))
    right = sorted((e for e in ends if e[2]), key=lambda e: -e[0][1])
    merged: list[tuple[tuple[float, float], list[str], bool]] = []
    for where, labels, edge in right:  # labels closer than 3 % of the axis: one label
        if merged and merged[-1][0][1] - where[1] < 0.03 * crowd * top:
            merged[-1][1].extend(labels)
        else:
            merged.append((where, list(labels), edge))
    for where, labels, edge in merged + [e for e in ends if not e[2]]:
        ax.annotate(", ".join(labels), where, xytext=(-2, 2) if edge else (-2, -2),
                    textcoords="offset points", ha="right", va="bottom" if edge else "top",
                    fontsize=6.5, bbox={"boxstyle": "square,pad=0.1", "facecolor": "white",
                                        "edgecolor": "none", "alpha": 0.8}, zorder=5)


def _crossings(ax, diagram) -> None:
    """The crossings: ranked (filled, sized by κ), weak (open) and unranked (squares)."""
    points = np.array([(c.speed_rpm, c.frequency) for c in diagram.crossings],
                      dtype=float).reshape(-1, 2)
    share = importance(diagram)
    unranked = np.isnan(share)
    weak = ~unranked & (share < WEAK)
    ranked = ~unranked & ~weak
    ax.scatter(points[ranked, 0], points[ranked, 1], s=marker_areas(share[ranked]),
               facecolors="black", edgecolors="white", linewidths=0.5, zorder=4,
               gid="crossings-ranked")
    ax.scatter(points[weak, 0], points[weak, 1], s=SIZES[0], facecolors="white",
               edgecolors="black", linewidths=0.6, zorder=4, gid="crossings-weak")
    ax.scatter(points[unranked, 0], points[unranked, 1], s=16.0, marker="s",
               facecolors="white", edgecolors="0.3", linewidths=0.6, zorder=4,
               gid="crossings-unranked")
    order = np.argsort(-np.where(ranked, share, -1.0), kind="stable")
    named: list[tuple[int, float]] = []
    for i in order[:LABELLED * 3]:
        if not ranked[i] or len(named) == LABELLED:
            break
        c = diagram.crossings[i]
        if any(mode == c.mode and abs(speed - c.speed_rpm) < 1e-6 * (1 + speed)
               for mode, speed in named):
            continue  # the same resonance met by coinciding lines: named once
        named.append((c.mode, c.speed_rpm))
        ax.annotate(f"mode {c.mode}\n{c.speed_rpm:.0f} rpm", (c.speed_rpm, c.frequency),
                    xytext=(-6, 6), textcoords="offset points", ha="right", va="bottom",
                    fontsize=6.5,
                    bbox={"boxstyle": "round,pad=0.2", "facecolor": "white", "edgecolor": "0.5",
                          "linewidth": 0.5, "alpha": 0.9}, zorder=6, gid="crossing-label")


def _legend(ax, diagram) -> list:
    """Legend handles: the line kinds, the marker sizes and what they mean."""
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color="0.6", linewidth=0.7, label="natural frequency (mode)")]
    kinds = {o.kind for o in diagram.orders}
    if "shaft" in kinds:
        handles.append(Line2D([], [], label="shaft speed n/60 × ratio",
                              **_style(next(o for o in diagram.orders if o.kind == "shaft"))))
    for order in diagram.orders:
        if order.kind == "mesh" and order.name.endswith("×1"):
            mesh = diagram.modes.system.drive.meshes[order.mesh].name
            handles.append(Line2D([], [], label=f"{mesh}: z·n/60 and harmonics", **_style(order)))
    if "excitation" in kinds:
        handles.append(Line2D([], [], label="the file's excitations",
                              **_style(next(o for o in diagram.orders
                                            if o.kind == "excitation"))))
    share = importance(diagram)
    kappa = np.array([c.mesh_stiffness for c in diagram.crossings], dtype=float)
    if np.isfinite(share).any():
        largest = float(np.nanmax(kappa))
        for s in (1.0, 1e-2, WEAK):
            handles.append(Line2D([], [], linestyle="none", marker="o", markerfacecolor="black",
                                  markeredgecolor="white",
                                  markersize=math.sqrt(float(marker_areas(np.array([s]))[0])),
                                  label=f"crossing, κ = {s * largest:.3g} N/m"))
        handles.append(Line2D([], [], linestyle="none", marker="o", markerfacecolor="white",
                              markeredgecolor="black", markersize=math.sqrt(SIZES[0]),
                              label=f"κ < {WEAK:g} × largest (mesh hardly loaded)"))
    if np.isnan(share).any():
        handles.append(Line2D([], [], linestyle="none", marker="s", markerfacecolor="white",
                              markeredgecolor="0.3", markersize=4.0,
                              label="crossing of a shaft or torque line (κ n/a)"))
    return handles
