"""A sweep's outcome and columns -> a plain summary dictionary: extremes and the figures
parts are sized by (numbers only; the report words them)."""

from __future__ import annotations

from typing import Any

import numpy as np

from dyade import cycle
from dyade.arrays import plain, resolution
from dyade.linkage.columns import Columns
from dyade.linkage.verdicts import Outcome
from dyade.model.mechanism import Revolute
from dyade.units import RAD_PER_S_TO_RPM


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
    the output has exactly one maximum and one minimum per revolution. One curve of
    ``time_ratios``."""
    ratio = float(time_ratios(angle_deg, np.asarray(output, dtype=np.float64)[None, :])[0])
    return None if np.isnan(ratio) else ratio


def time_ratios(angle_deg: np.ndarray, output: np.ndarray) -> np.ndarray:
    """``time_ratio`` of every row of ``output`` (variants, positions), all at the crank
    angles ``angle_deg``; NaN where there is none."""
    ratio = np.full(output.shape[0], np.nan)
    keep = np.isfinite(output).all(axis=1)
    if not keep.any() or not full_cycle(angle_deg):
        return ratio
    cycle = output[:, :-1] if angle_deg[-1] - angle_deg[0] >= 360.0 - 1e-9 else output
    rises = np.diff(np.concatenate((cycle, cycle[:, :1]), axis=1), axis=1) > 0
    keep &= np.count_nonzero(rises != np.roll(rises, 1, axis=1), axis=1) == 2  # one rise, one fall
    step = float(angle_deg[1] - angle_deg[0])
    top, bottom = _vertices(angle_deg, cycle, step, 1.0), _vertices(angle_deg, cycle, step, -1.0)
    forward = (top - bottom) % 360.0
    short, long = np.minimum(forward, 360.0 - forward), np.maximum(forward, 360.0 - forward)
    keep &= short > 0
    np.divide(long, short, out=ratio, where=keep)
    return ratio


def _vertices(angle_deg: np.ndarray, cycle: np.ndarray, step: float, sign: float
              ) -> np.ndarray:
    """Crank angle [°] of the maximum (sign +1) or minimum (−1) of each row of periodic
    sampled outputs, refined by the parabola through it and its two neighbours (error ∝
    step³ instead of half a step)."""
    rows = np.arange(cycle.shape[0])
    k = np.argmax(sign * np.where(np.isnan(cycle), -sign * np.inf, cycle), axis=1)
    before, here, after = (cycle[rows, k - 1], cycle[rows, k],
                           cycle[rows, (k + 1) % cycle.shape[1]])
    curvature = before - 2.0 * here + after
    shift = np.zeros(rows.size)
    np.divide(0.5 * (before - after), curvature, out=shift, where=curvature != 0.0)
    return angle_deg[k] + shift * step


def least_transmission(mu: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The smallest distance [°] of transmission angles ``mu`` (variants, positions)
    [°] from a dead centre (0° or 180°) per row, and the position where it lies (NaN,
    0 where a row has none)."""
    off = np.minimum(mu, 180.0 - mu)  # the angle to the nearer dead centre
    k = np.argmin(np.where(np.isnan(off), np.inf, off), axis=1)
    return np.take_along_axis(off, k[:, None], axis=1)[:, 0], k


def strokes(travel: np.ndarray) -> np.ndarray:
    """The stroke [m] of each row of slider travels (variants, positions): its range,
    NaN where it does not move (or has no value)."""
    high, low = np.fmax.reduce(travel, axis=1), np.fmin.reduce(travel, axis=1)
    stroke = high - low
    reach = np.maximum(np.fmax.reduce(np.abs(travel), axis=1), 1e-300)
    return np.where(stroke > 1e-12 * reach, stroke, np.nan)


def swings(phi_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The swing [°] of each row of link angles (variants, positions) [°] and the angles
    turned (unwrapped); NaN where the link turns round, does not move or a value is
    missing."""
    turned = np.rad2deg(np.unwrap(np.deg2rad(phi_deg), axis=1))
    swing = turned.max(axis=1) - turned.min(axis=1)
    moves = np.isfinite(phi_deg).all(axis=1) & (swing > 1e-9) & (swing < 359.0)
    return np.where(moves, swing, np.nan), turned


def peaks(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The value of largest magnitude of each row (variants, positions), signed, and its
    position (NaN, 0 where a row has none)."""
    k = np.argmax(np.where(np.isnan(values), -np.inf, np.abs(values)), axis=1)
    return np.take_along_axis(values, k[:, None], axis=1)[:, 0], k


def pivoted(mechanism, link: int) -> bool:
    """The link turns about a frame pivot (a rocker, or a crank that turns round)."""
    return any(isinstance(j, Revolute) and 1 in j.links and link in j.links
               for j in mechanism.joints)


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
        least, k = least_transmission(cols[f"mu_{dyad.number}_deg"][None, :])
        if not np.isnan(least[0]):
            out["transmission"][str(dyad.number)] = {"min_deg": least[0], "at_deg": at[k[0]]}
    for joint in mechanism.joints:
        a, b = joint.name
        if isinstance(joint, Revolute):
            continue
        travel = cols[f"s_{a}_{b}"][None, :]
        stroke = strokes(travel)[0]
        if not np.isnan(stroke):
            ratio = time_ratios(angle, travel)[0]
            out["strokes"][f"{a}_{b}"] = {"stroke": stroke,
                                         "time_ratio": None if np.isnan(ratio) else ratio}
    for link in mechanism.moving_links[1:]:
        if not pivoted(mechanism, link):
            continue
        swing, turned = swings(cols[f"phi_{link}_deg"][None, :])
        if not np.isnan(swing[0]):
            ratio = time_ratios(angle, turned)[0]
            out["swings"][str(link)] = {"swing_deg": swing[0],
                                        "time_ratio": None if np.isnan(ratio) else ratio}
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
        torque = cols["M_drive"][None, :]  # NaN where the forces are not given
        out["drive"] = {"M_max": np.fmax.reduce(torque, axis=1)[0],
                        "M_min": np.fmin.reduce(torque, axis=1)[0],
                        "M_rms": cycle.rmss(radians, torque)[0],
                        "P_mean": cycle.means(radians, cols["P_drive"][None, :])[0]}
        joint_peaks = {}
        for name in joint_force_names(result.mechanism):
            value, k = peaks(cols[name][None, :])
            if not np.isnan(value[0]):
                joint_peaks[name] = {"value": value[0], "at_deg": at[k[0]]}
        out["joint_peaks"] = joint_peaks
    out.update(stage_figures(result, cols))
    return plain(out)


def stage_figures(result: Outcome, cols: Columns) -> dict[str, Any]:
    """The summary's figures of the stages beyond the kinematics and the forces, where
    the sweep ran them: friction (its mean power, iterations, worst residual),
    self-locking (per slider and joint: whether and where), the crank's motion from the
    equation of motion, the clearance check."""
    angle = cols["angle_deg"]
    radians = np.deg2rad(angle)
    out: dict[str, Any] = {}
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
    return out


def joint_force_names(mechanism) -> list[str]:
    """The column of each joint's force: F_a_b of a revolute joint, FN_a_b (the normal
    force) of a prismatic one."""
    return [f"F_{a}_{b}" if isinstance(j, Revolute) else f"FN_{a}_{b}"
            for j in mechanism.joints for a, b in (j.name,)]


def motion_summary(result: Outcome) -> dict[str, Any]:
    """The crank's speed from the equation of motion (over the last revolution of a
    run-up), SI units; angles in degrees."""
    motion = result.drive
    figures = motion.figures
    drive = result.mechanism.drive
    out: dict[str, Any] = {
        "state": motion.state, "motor": drive.motor.describe(),
        "flywheel_inertia": drive.flywheel_inertia,
        "speed_mean": figures["speed_mean"],
        "speed_mean_rpm": figures["speed_mean"] * RAD_PER_S_TO_RPM,
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
