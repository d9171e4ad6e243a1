"""A disc cam and its follower (``dyade cam``): the cam with its follower at chosen cam
angles, the pressure angle against its limit, the radii of curvature with the roller's
radius and the undercut shaded, and the follower's motion s, s′, s″, s‴ over the turn.
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import math

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from dyade.plot import canvas
from dyade.units import LENGTH_FACTORS


def _turned(points: np.ndarray, theta: float, clockwise: bool) -> np.ndarray:
    """Cam-frame points in the fixed frame at cam angle θ (a clockwise cam turns by −θ)."""
    angle = -theta if clockwise else theta
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


def _spans(ax, x: np.ndarray, mask: np.ndarray, label: str) -> None:
    """Shade the runs of ``mask`` over x [°] (one legend entry)."""
    if not mask.any():
        return
    padded = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    step = float(x[1] - x[0]) if x.size > 1 else 1.0
    for k, (a, b) in enumerate(zip(edges[::2], edges[1::2])):
        ax.axvspan(x[a] - step / 2, x[b - 1] + step / 2, color="0.85", hatch="////",
                   lw=0, label=label if k == 0 else None)


def draw_cam(ax, result, angles_deg, unit: str) -> None:
    """The cam turned to each of ``angles_deg`` with its follower (the first drawn
    solid, the others faint), the base circle and the cam centre."""
    from dyade.cam import checks

    cam = result.cam
    size = 1.0 / LENGTH_FACTORS[unit]
    angles = np.radians(np.asarray(angles_deg, dtype=float))
    geo, _ = checks.curves(cam, angles)
    working = result.geometry.working
    pitch = result.geometry.pitch
    reach = float(np.max(np.hypot(*working.T)))
    for k, theta in enumerate(angles):
        first = k == 0
        colour = canvas.COLOURS[k % len(canvas.COLOURS)]
        alpha = 1.0 if first else 0.55
        shape = _turned(working, float(theta), cam.clockwise) * size
        ax.fill(*np.vstack((shape, shape[:1])).T, color="0.93" if first else "none",
                ec=colour, lw=1.3 if first else 0.8, alpha=alpha,
                label=f"cam at {math.degrees(theta):g}°")
        if first and pitch is not None and cam.closure == "groove":  # the groove's far wall
            from dyade.cam.geometry import outer_wall

            wall = _turned(outer_wall(result.geometry)[0], float(theta), cam.clockwise) * size
            ax.plot(*np.vstack((wall, wall[:1])).T, color=colour, lw=1.3,
                    label="groove's outer flank")
        if first and pitch is not None:
            path = _turned(pitch, float(theta), cam.clockwise) * size
            ax.plot(*np.vstack((path, path[:1])).T, color=canvas.GREY, lw=0.7,
                    linestyle=canvas.DASHES[1], label="pitch curve")
        centre = geo.centre[k] * size
        contact = geo.contact[k] * size
        if cam.follower == "translating-flat":
            half = max(abs(float(result.v.min())), abs(float(result.v.max()))) * size * 1.3
            half = max(half, 0.15 * reach * size)
            ax.plot([centre[0] - half - (centre[0] - contact[0]) * 0, centre[0] + half],
                    [centre[1], centre[1]], color=colour, lw=2.0, alpha=alpha)
            ax.plot([centre[0], centre[0]], [centre[1], centre[1] + 0.5 * reach * size],
                    color=colour, lw=2.5, alpha=alpha, solid_capstyle="butt")
        else:
            ax.add_patch(Circle(centre, cam.roller_radius * size, fill=False, ec=colour,
                                lw=1.1, alpha=alpha))
            if cam.follower == "translating-roller":
                ax.plot([centre[0], centre[0]], [centre[1], centre[1] + 0.5 * reach * size],
                        color=colour, lw=2.5, alpha=alpha, solid_capstyle="butt")
            else:
                pivot = np.array([-cam.pivot_distance if cam.clockwise else cam.pivot_distance,
                                  0.0]) * size
                ax.plot([pivot[0], centre[0]], [pivot[1], centre[1]], color=colour, lw=2.5,
                        alpha=alpha, solid_capstyle="round")
                ax.plot(*pivot, marker="^", color="k", ms=6)
        ax.plot(*contact, marker="o", ms=2.5, color="k")
        if first:  # the line of the contact force (the common normal)
            normal = geo.contact_normal[k]
            ends = np.array([contact - 0.25 * reach * size * normal,
                             contact + 0.25 * reach * size * normal])
            ax.plot(*ends.T, color=canvas.COLOURS[1], lw=0.8, linestyle=canvas.DASHES[2],
                    label="common normal")
    circle = np.linspace(0.0, 2.0 * math.pi, 361)
    ax.plot(cam.base_radius * size * np.cos(circle), cam.base_radius * size * np.sin(circle),
            color=canvas.GREY, lw=0.6, linestyle=canvas.DASHES[2], label="base circle")
    ax.plot(0.0, 0.0, marker="+", color="k", ms=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    ax.set_title(f"{cam.name}: {cam.follower} follower, turning "
                 f"{'clockwise' if cam.clockwise else 'counter-clockwise'}")
    ax.legend(loc="upper left", fontsize=6.5)


def figure(outcome, angles_deg=(0.0,), fig: Figure | None = None) -> Figure:
    """The cam figure of a ``cam`` Outcome.

    Parameters
    ----------
    outcome : Outcome
        Of ``dyade.run("cam", ...)``.
    angles_deg : sequence of float
        Cam angles [°] to draw the cam and its follower at.
    """
    result = outcome.result
    cam = result.cam
    unit = cam.length_unit
    size = 1.0 / LENGTH_FACTORS[unit]
    angle = np.degrees(result.geometry.theta)
    with canvas.style():
        fig = canvas.new(11.0, 7.5, fig)
        grid = fig.add_gridspec(4, 2, width_ratios=(1.15, 1.0))
        draw_cam(fig.add_subplot(grid[:, 0]), result, angles_deg, unit)
        angular = cam.follower == "oscillating-roller"
        q_unit = "°" if angular else unit
        q_size = math.degrees(1.0) if angular else size
        motion = fig.add_subplot(grid[0, 1])
        rates = motion.twinx()
        motion.plot(angle, result.s * q_size, **canvas.line(0), label="s")
        for k, (values, name) in enumerate(((result.v, "s′"), (result.a, "s″"),
                                           (result.j, "s‴")), start=1):
            peak = float(np.max(np.abs(values))) or 1.0
            rates.plot(angle, values / peak, **canvas.line(k), lw=0.9,
                       label=f"{name}/{_number(peak * q_size)} {q_unit}/rad"
                             f"{'' if k == 1 else '²' if k == 2 else '³'}")
        motion.set_ylabel(f"s [{q_unit}]")
        rates.set_ylabel("s′, s″, s‴ scaled [-]")
        rates.grid(False)
        handles = motion.get_legend_handles_labels()[0] + rates.get_legend_handles_labels()[0]
        motion.legend(handles=handles, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncols=4,
                      fontsize=6.5)
        pressure = fig.add_subplot(grid[1, 1], sharex=motion)
        pressure.plot(angle, np.degrees(result.geometry.pressure_angle), **canvas.line(0),
                      label="α")
        limit = math.degrees(cam.limit)
        for sign in (1, -1):
            pressure.axhline(sign * limit, color=canvas.COLOURS[1], lw=0.8,
                             linestyle=canvas.DASHES[1],
                             label=f"limit ±{limit:g}°" if sign == 1 else None)
        if result.jammed is not None:  # guide friction: where the follower jams
            _spans(pressure, angle, result.jammed, "jams in its guide")
        pressure.set_ylabel("pressure angle α [°]")
        canvas.legend_above(pressure)
        curvature = fig.add_subplot(grid[2, 1], sharex=motion)
        geo = result.geometry
        bound = 6.0 * cam.pitch_radius * size
        if cam.follower != "translating-flat":
            curvature.plot(angle, _broken(geo.pitch_curvature_radius * size, bound),
                           **canvas.line(0), label="ρ pitch curve")
            curvature.axhline(cam.roller_radius * size, color=canvas.COLOURS[1], lw=0.8,
                              linestyle=canvas.DASHES[1], label="roller radius")
        curvature.plot(angle, _broken(geo.working_curvature_radius * size, bound),
                       **canvas.line(2), label="ρ working curve")
        curvature.axhline(0.0, color="k", lw=0.5)
        _spans(curvature, angle, geo.undercut, "undercut")
        curvature.set_ylabel(f"radius of curvature [{unit}]")
        shown = np.concatenate([r[np.isfinite(r)] * size for r in (
            geo.pitch_curvature_radius, geo.working_curvature_radius)])
        top = min(bound, 1.1 * float(shown.max())) if shown.size else bound
        bottom = max(-bound, min(-0.05 * top, 1.1 * float(shown.min()))) if shown.size else -bound
        curvature.set_ylim(bottom, top)
        canvas.legend_above(curvature)
        force = fig.add_subplot(grid[3, 1], sharex=motion)
        force.plot(angle, result.contact_force, **canvas.line(0), label="contact force N")
        force.set_ylabel("N [N]")
        torque = force.twinx()
        torque.plot(angle, result.drive_torque, **canvas.line(3), lw=0.9, label="drive torque")
        torque.set_ylabel("drive torque [N·m]")
        torque.grid(False)
        _spans(force, angle, result.lifted, "lifted off")
        handles = force.get_legend_handles_labels()[0] + torque.get_legend_handles_labels()[0]
        force.legend(handles=handles, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncols=3,
                     fontsize=6.5)
        force.set_xlabel("cam angle θ [°]")
        force.set_xlim(0.0, 360.0)
        force.set_xticks(np.arange(0, 361, 60))
    return fig


def _broken(values: np.ndarray, bound: float) -> np.ndarray:
    """A radius of curvature as drawn: a gap where it runs off beyond ±bound (through
    an inflection it passes ±∞), never a vertical line."""
    return np.where(np.abs(values) > bound, np.nan, values)


def _number(value: float) -> str:
    return f"{value:.3g}"
