"""A synthesis's designs against its target: the target and what each design traces
(its coupler path, its output angle, its poses), and the designs drawn at one position
(links as bars and plates between their joints, frame pivots as triangles, the coupler
point marked).
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

import numpy as np
from matplotlib.figure import Figure

from dyade.plot import canvas

MOST = 3
"""designs drawn"""


def joints(data: dict, crank: float) -> tuple[dict[int, np.ndarray], list[complex], complex]:
    """Each moving link's joint positions (complex [m]) at crank angle ``crank`` [rad],
    the frame pivots, and the coupler point P, through dyade's positions-only stage."""
    from dyade.files.mechanism import build
    from dyade.linkage.kinematics import joint_anchor
    from dyade.linkage.positions import positions
    from dyade.model.mechanism import FRAME, Revolute

    mechanism = build(data)
    asked, owners, frame = [], [], []
    for joint in mechanism.joints:
        if not isinstance(joint, Revolute):
            asked.append((joint.slider, joint.slider_point))
            owners.append((joint.slider,))
            continue
        asked.append(joint_anchor(joint))
        owners.append(joint.links)
        if FRAME in joint.links:
            frame.append(len(asked) - 1)
    carrier = next((k for k, body in sorted(mechanism.links.items()) if "P" in body.points),
                   None)  # the coupler point's link (3; a six-bar's 5)
    if carrier is not None:
        asked.append((carrier, mechanism.links[carrier].points["P"]))
        owners.append((carrier,))
    found = positions(mechanism, np.array([crank]), asked)
    z = found.points[0, :, 0] + 1j * found.points[0, :, 1]
    links: dict[int, list] = {}
    for where, owner in zip(z, owners):
        for link in owner:
            if link != FRAME:
                links.setdefault(link, []).append(where)
    p = z[-1] if carrier is not None else complex(np.nan, np.nan)
    return {k: np.array(v) for k, v in links.items()}, [z[k] for k in frame], p


def figure(result, *, fig: Figure | None = None) -> Figure:
    """The target against the designs (left) and the designs drawn (right).

    Parameters
    ----------
    result : dyade.synthesis.Result
    fig : Figure, optional
    """
    designs = result.designs[:MOST]
    target = result.problem.target
    fig = canvas.new(11.0, 4.8, fig)
    left, right = fig.subplots(1, 2)
    colours = [canvas.line(k)["color"] for k in range(MOST)]
    if target.kind == "function" and result.problem.topology == "slider-crank":
        _slider(left, result.function, colours)
    elif target.kind == "function":
        made = result.function
        left.plot(np.rad2deg(made.crank), np.rad2deg(made.target), "o", ms=3, color="0.3",
                  label="target")
        from dyade.synthesis.function import traced

        if hasattr(made, "dense"):  # a six-bar: link 6's angle through dyade
            dense, psi = made.dense
            label = "six-bar, link 6 (dyade)"
        else:
            dense = np.linspace(made.crank[0], made.crank[-1], 241)
            psi, label = traced(made.linkage, dense), "four-bar (dyade)"
        left.plot(np.rad2deg(dense), np.rad2deg(np.unwrap(psi)), "-", color=colours[0],
                  label=label)
        if made.precision.size:
            left.plot(np.rad2deg(made.precision), np.rad2deg(np.interp(
                made.precision, made.crank, np.unwrap(made.target))), "s", mfc="none",
                color=colours[0], label="precision points")
        twin = left.twinx()
        twin.plot(np.rad2deg(made.crank), np.rad2deg(made.error), ":", color=colours[1])
        twin.set_ylabel("structural error [°]", color=colours[1])
        left.set_xlabel("crank angle φ [°]")
        left.set_ylabel("output angle ψ [°]")
        left.set_title("Function: target and " + ("six-bar" if hasattr(made, "dense")
                                                    else "four-bar"))
    else:
        if target.kind == "poses":
            z = target.poses[:, 0] + 1j * target.poses[:, 1]
            size = np.ptp(np.concatenate([z.real, z.imag])) or 1.0
            for x, y, theta in target.poses:  # each pose's angle, its tip within the limits
                tip = (x + 0.15 * size * np.cos(theta), y + 0.15 * size * np.sin(theta))
                left.annotate("", tip, (x, y), arrowprops={"arrowstyle": "->", "color": "0.3"},
                              annotation_clip=False)
                left.update_datalim([tip])
            left.plot(z.real, z.imag, "o", color="0.3", label="poses")
        elif target.points is not None:
            left.plot(target.points.real, target.points.imag, "o", ms=3, color="0.3",
                      label="target")
        for k, design in enumerate(designs):
            path = design.traced
            stretch = getattr(design, "stretch", None)
            left.plot(path.real, path.imag, "-", lw=1.0, color=colours[k],
                      label=f"{design.name}: error {design.error:.3g}")
            if stretch is not None:
                part = _stretch(design.data, stretch)[1]
                left.plot(part.real, part.imag, "-", lw=4.0, color=colours[k], alpha=0.4)
        left.set_aspect("equal", adjustable="datalim")
        left.set_xlabel("x [m]")
        left.set_ylabel("y [m]")
        left.set_title({"poses": "Poses and the coupler point's path",
                        "line": "Straight-line stretch", "arc": "Circular-arc stretch"}.get(
            target.kind, "Target path and traced coupler curves"))
    left.legend(fontsize=7, loc="best")
    for k, design in enumerate(designs):
        sweep = design.data["sweep"]
        crank = np.deg2rad(0.5 * (sweep["start"] + sweep["stop"])) if target.kind in (
            "function", "poses") else float(design.crank[0])
        bodies, frame, p = joints(design.data, crank)
        for link, where in bodies.items():
            ring = np.append(where, where[0]) if where.size > 2 else where
            right.plot(ring.real, ring.imag, "-o", ms=3, lw=2.0 if k == 0 else 1.2,
                       color=colours[k], alpha=1.0 if k == 0 else 0.6,
                       label=design.name if link == 2 else None)
        for pivot in frame:
            right.plot(pivot.real, pivot.imag, "^", ms=9, color="0.2")
        if np.isfinite(p):
            right.plot(p.real, p.imag, "*", ms=9, color=colours[k])
    if designs:  # the best design and the target set the view (a far pivot may be cut)
        bodies, frame, p = joints(designs[0].data, float(designs[0].crank[0]) if target.kind
                                  not in ("function", "poses") else np.deg2rad(0.5 * (
                                      designs[0].data["sweep"]["start"]
                                      + designs[0].data["sweep"]["stop"])))
        seen = np.concatenate([*bodies.values(), np.array(frame, dtype=complex),
                               designs[0].traced if target.kind != "function" else []])
        seen = seen[np.isfinite(seen)]
        if seen.size:
            pad = 0.15 * max(np.ptp(seen.real), np.ptp(seen.imag), 1e-9)
            right.set_xlim(seen.real.min() - pad, seen.real.max() + pad)
            right.set_ylim(seen.imag.min() - pad, seen.imag.max() + pad)
        if target.kind != "function":
            right.plot(designs[0].traced.real, designs[0].traced.imag, ":", lw=0.8,
                       color=colours[0])
    right.set_aspect("equal", adjustable="box")
    right.set_xlabel("x [m]")
    right.set_ylabel("y [m]")
    right.set_title("Designs (▲ frame pivots, ★ coupler point)")
    right.legend(fontsize=7, loc="best")
    return fig


def _slider(axes, made, colours) -> None:
    """A slider's position: the target, the slider-crank's (through dyade), the
    precision points, the structural error on a second axis [mm]."""
    from dyade.synthesis.slider import traced
    from dyade.units import LENGTH_FACTORS

    MM = LENGTH_FACTORS["mm"]

    axes.plot(np.rad2deg(made.crank), made.target / MM, "o", ms=3, color="0.3",
              label="target")
    dense = np.linspace(made.crank[0], made.crank[-1], 241)
    axes.plot(np.rad2deg(dense), traced(made.linkage, dense) / MM, "-", color=colours[0],
              label="slider-crank (dyade)")
    if made.precision.size:
        axes.plot(np.rad2deg(made.precision), traced(made.linkage, made.precision) / MM, "s",
                  mfc="none", color=colours[0], label="precision points")
    twin = axes.twinx()
    twin.plot(np.rad2deg(made.crank), made.error / MM, ":", color=colours[1])
    twin.set_ylabel("structural error [mm]", color=colours[1])
    axes.set_xlabel("crank angle φ [°]")
    axes.set_ylabel("slider position s [mm]")
    axes.set_title("Function: target and slider-crank")


def _stretch(data: dict, stretch: tuple[float, float]):
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions

    mechanism = build(data)
    crank = np.linspace(stretch[0], stretch[1], 121)
    carrier = next(k for k, body in sorted(mechanism.links.items()) if "P" in body.points)
    found = positions(mechanism, crank, [(carrier, mechanism.links[carrier].points["P"])])
    return crank, found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
