"""Result -> a plain summary dictionary: extremes and the figures parts are sized by."""

from __future__ import annotations

from typing import Any

import numpy as np

from dyade.linkage.sweep import Result
from dyade.linkage.model import Revolute
from dyade.linkage.columns import Columns


def cycle_mean(angle: np.ndarray, values: np.ndarray) -> float:
    """Mean over the crank angle (trapezoid rule), finite values only."""
    keep = np.isfinite(values)
    a, v = angle[keep], values[keep]
    if a.size < 2:
        return float(v.mean()) if v.size else float("nan")
    return float(np.sum((v[1:] + v[:-1]) * np.diff(a)) / (2.0 * (a[-1] - a[0])))



def _extreme(angle, values) -> dict[str, Any]:
    finite = np.isfinite(values)
    if not finite.any():
        return {"min": None, "min_at_deg": None, "max": None, "max_at_deg": None}
    masked = np.where(finite, values, np.nan)
    lo, hi = int(np.nanargmin(masked)), int(np.nanargmax(masked))
    return {"min": values[lo], "min_at_deg": angle[lo], "max": values[hi], "max_at_deg": angle[hi]}


def summary(result: Result, cols: Columns) -> dict[str, Any]:
    """Per column min/max and where; drive, friction, self-locking, clearance figures."""
    angle = cols["angle_deg"]
    out: dict[str, Any] = {"mechanism": result.mechanism.name, "positions": int(angle.size),
                           "effects": result.plan.effects(),
                           "columns": {name: _extreme(angle, values)
                                       for name, values in cols.items() if name != "angle_deg"}}
    if result.forces is not None:
        torque = cols["M_drive"]
        out["drive"] = {"M_max": np.nanmax(torque), "M_min": np.nanmin(torque),
                        "M_rms": float(np.sqrt(cycle_mean(angle, torque ** 2))),
                        "P_mean": cycle_mean(angle, cols["P_drive"])}
        peaks = {}
        for joint in result.mechanism.joints:
            a, b = joint.name
            name = f"F_{a}_{b}" if isinstance(joint, Revolute) else f"FN_{a}_{b}"
            values = np.abs(cols[name])
            if np.isfinite(values).any():
                k = int(np.nanargmax(values))
                peaks[name] = {"value": cols[name][k], "at_deg": angle[k]}
        out["joint_peaks"] = peaks
    if result.friction is not None:
        rows = result.rows & result.forces.valid
        out["friction"] = {"P_mean": cycle_mean(angle, cols["P_friction"]),
                           "iterations_min": float(np.min(cols["friction_iterations"])),
                           "iterations_max": float(np.max(cols["friction_iterations"])),
                           "worst_residual": float(np.max(result.friction.residual[rows], initial=0.0))}
    if result.locking:
        out["self_locking"] = {f"{a}_{b}": {"locks": bool(lock.locks[result.rows].any()),
                                            "locking_angles_deg": np.rad2deg(
                                                result.crank_angle[lock.locks & result.rows])}
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


def motion_summary(result: Result) -> dict[str, Any]:
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
