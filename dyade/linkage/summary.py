"""A sweep's outcome and columns -> a plain summary dictionary: extremes and the figures
parts are sized by (numbers only; the report words them)."""

from __future__ import annotations

from typing import Any

import numpy as np

from dyade import cycle
from dyade.arrays import plain, resolution
from dyade.linkage.columns import Columns
from dyade.linkage.model import Revolute
from dyade.linkage.verdicts import Outcome


def full_cycle(angle_deg: np.ndarray) -> bool:
    """The positions cover one whole crank revolution (to within a step)."""
    if angle_deg.size < 3:
        return False
    step = float(np.min(np.diff(angle_deg)))
    return float(angle_deg[-1] - angle_deg[0]) >= 360.0 - 1.5 * step


def time_ratio(angle_deg: np.ndarray, output: np.ndarray) -> float | None:
    """Time ratio of a quick-return output over one crank revolution at constant speed:
    the longer of the two crank-angle spans between its extreme positions over the
    shorter (1 for a symmetric drive). None unless the positions cover a revolution and
    the output has exactly one maximum and one minimum per revolution."""
    keep = np.isfinite(output)
    if not keep.all() or not full_cycle(angle_deg):
        return None
    cycle = output[:-1] if angle_deg[-1] - angle_deg[0] >= 360.0 - 1e-9 else output
    rises = np.diff(np.append(cycle, cycle[0])) > 0
    if np.count_nonzero(rises != np.roll(rises, 1)) != 2:  # one rise, one fall
        return None
    step = float(angle_deg[1] - angle_deg[0])
    top, bottom = _vertex(angle_deg, cycle, step, 1.0), _vertex(angle_deg, cycle, step, -1.0)
    forward = (top - bottom) % 360.0
    spans = sorted((forward, 360.0 - forward))
    return spans[1] / spans[0] if spans[0] > 0 else None


def _vertex(angle_deg: np.ndarray, cycle: np.ndarray, step: float, sign: float) -> float:
    """Crank angle [°] of the maximum (sign +1) or minimum (−1) of a periodic sampled
    output, refined by the parabola through it and its two neighbours (error ∝ step³
    instead of half a step)."""
    k = int(np.argmax(sign * cycle))
    before, here, after = cycle[k - 1], cycle[k], cycle[(k + 1) % cycle.size]
    curvature = before - 2.0 * here + after
    shift = 0.5 * (before - after) / curvature if curvature != 0.0 else 0.0
    return float(angle_deg[k] + shift * step)


def motion_figures(result: Outcome, cols: Columns, at=None) -> dict[str, Any]:
    """What a designer reads off the kinematics: the smallest transmission angle of each
    dyad (its distance from a dead centre) and where, the stroke of every slider and the
    swing of every rocker (a link turning about a frame pivot without turning round),
    each with its time ratio. ``at``: the crank angles [°] to say where (default: the
    column ``angle_deg``)."""
    angle = cols["angle_deg"]
    at = angle if at is None else at
    mechanism = result.mechanism
    out: dict[str, Any] = {"transmission": {}, "strokes": {}, "swings": {}}
    for dyad in mechanism.dyads:
        mu = cols[f"mu_{dyad.number}_deg"]
        if not np.isfinite(mu).any():
            continue
        off = np.minimum(mu, 180.0 - mu)  # the angle to the nearer dead centre
        k = int(np.nanargmin(off))
        out["transmission"][str(dyad.number)] = {"min_deg": off[k], "at_deg": at[k]}
    for joint in mechanism.joints:
        a, b = joint.name
        if isinstance(joint, Revolute):
            continue
        travel = cols[f"s_{a}_{b}"]
        stroke = float(np.nanmax(travel) - np.nanmin(travel))
        if stroke > 1e-12 * max(float(np.nanmax(np.abs(travel))), 1e-300):
            out["strokes"][f"{a}_{b}"] = {"stroke": stroke,
                                         "time_ratio": time_ratio(angle, travel)}
    for link in mechanism.moving_links[1:]:
        pivoted = any(isinstance(j, Revolute) and 1 in j.links and link in j.links
                      for j in mechanism.joints)
        phi = cols[f"phi_{link}_deg"]
        if not pivoted or not np.isfinite(phi).all():
            continue
        turned = np.rad2deg(np.unwrap(np.deg2rad(phi)))
        swing = float(turned.max() - turned.min())
        if 1e-9 < swing < 359.0:
            out["swings"][str(link)] = {"swing_deg": swing, "time_ratio": time_ratio(angle, turned)}
    return out


def _extreme(angle, values) -> dict[str, Any]:
    finite = np.isfinite(values)
    if not finite.any():
        return {"min": None, "min_at_deg": None, "max": None, "max_at_deg": None}
    masked = np.where(finite, values, np.nan)
    lo, hi = int(np.nanargmin(masked)), int(np.nanargmax(masked))
    return {"min": values[lo], "min_at_deg": angle[lo], "max": values[hi], "max_at_deg": angle[hi]}


def summary(result: Outcome, cols: Columns, extremes: bool = True) -> dict[str, Any]:
    """Per column min/max and where (unless not ``extremes``); drive, friction,
    self-locking, clearance figures: plain Python numbers (``arrays.plain``), the crank
    angles where an extreme lies rounded to the sweep's resolution
    (``arrays.resolution``: 359.5, not 359.50000000000006)."""
    angle = cols["angle_deg"]
    radians = np.deg2rad(angle)
    at = np.round(angle, resolution(angle))  # where: a position of the sweep
    out: dict[str, Any] = {"mechanism": result.mechanism.name, "positions": int(angle.size),
                           **motion_figures(result, cols, at)}
    if extremes:
        out["columns"] = {name: _extreme(at, values)
                          for name, values in cols.items() if name != "angle_deg"}
    if result.forces_valid is not None:
        torque = cols["M_drive"]
        given = torque[np.isfinite(torque)]  # none where the forces are nowhere given
        out["drive"] = {"M_max": given.max() if given.size else np.nan,
                        "M_min": given.min() if given.size else np.nan,
                        "M_rms": cycle.rms(radians, torque),
                        "P_mean": cycle.mean(radians, cols["P_drive"])}
        peaks = {}
        for joint in result.mechanism.joints:
            a, b = joint.name
            name = f"F_{a}_{b}" if isinstance(joint, Revolute) else f"FN_{a}_{b}"
            values = np.abs(cols[name])
            if np.isfinite(values).any():
                k = int(np.nanargmax(values))
                peaks[name] = {"value": cols[name][k], "at_deg": at[k]}
        out["joint_peaks"] = peaks
    if result.rubbing is not None:
        rows = result.rows & result.forces_valid
        out["friction"] = {"P_mean": cycle.mean(radians, cols["P_friction"]),
                           "iterations_min": float(np.min(cols["friction_iterations"])),
                           "iterations_max": float(np.max(cols["friction_iterations"])),
                           "worst_residual": float(np.max(result.rubbing.residual[rows], initial=0.0))}
    if result.locking:
        out["self_locking"] = {f"{a}_{b}": {"locks": bool(lock.locks[result.rows].any()),
                                            "locking_angles_deg": np.round(np.rad2deg(
                                                result.crank_angle[lock.locks & result.rows]),
                                                resolution(angle))}
                               for (a, b), lock in result.locking.items()}
    if result.drive is not None:
        out["motion"] = motion_summary(result)
    if result.clearance:
        out["clearance"] = [{"joint": f"{c.joint[0]}_{c.joint[1]}", "applies": c.applies,
                             "reason": c.reason,
                             "reversals": [{"angle_deg": np.rad2deg(r.crank_angle),
                                            "tau": r.peak.tau, "F_max": r.peak.force,
                                            "F_rigid": r.rigid_force,
                                            "amplification": r.amplification}
                                           for r in c.reversals]}
                            for c in result.clearance]
    return plain(out)


def motion_summary(result: Outcome) -> dict[str, Any]:
    """The crank's speed from the equation of motion (over the last revolution of a
    run-up), SI units; angles in degrees."""
    motion = result.drive
    figures = motion.figures
    drive = result.mechanism.drive
    out: dict[str, Any] = {
        "state": motion.state, "motor": drive.motor.describe(),
        "flywheel_inertia": drive.flywheel_inertia,
        "speed_mean": figures["speed_mean"], "speed_mean_rpm": figures["speed_mean"] * 30 / np.pi,
        "speed_min": figures["speed_min"], "speed_min_at_deg": np.rad2deg(figures["angle_min"]),
        "speed_max": figures["speed_max"], "speed_max_at_deg": np.rad2deg(figures["angle_max"]),
        "fluctuation": figures["fluctuation"], "period": figures["period"],
        "motor_torque_mean": figures["motor_torque_mean"],
        "inertia_mean": figures["inertia_mean"],
        "steps_per_revolution": figures["steps_per_revolution"],
        "friction_passes": figures["passes"]}
    if "motor_torque" in figures:
        out["motor_torque"] = figures["motor_torque"]
    if motion.state == "run-up":
        for key in ("revolutions", "settled", "duration", "work_motor", "work_load",
                    "work_friction", "kinetic_energy"):
            out[key] = figures[key]
    else:
        out["shooting_iterations"] = figures["iterations"]
    return out
