"""One variant: the mechanism file with the study's overrides, swept by
``dyade.analyse``, its summary flattened to named key results (``key_results``).

A variant that cannot be built (the reader refuses a value), does not close over the
sweep (``AssemblyError``) or fails otherwise is a row with its status and reason and no
outputs; a variant that self-locks is a row with its outputs and the status "locks".
"""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np

UNITS = {"M_drive_max": "N·m", "M_drive_min": "N·m", "M_drive_rms": "N·m", "P_drive_mean": "W",
         "P_friction_mean": "W", "F_shake_max": "N", "F_shake_rms": "N", "M_shake_max": "N·m",
         "flywheel_inertia": "kg·m²", "speed_mean_rpm": "rpm", "fluctuation": "-"}
"""units of the outputs with fixed names; the others by their prefix (``unit``)"""

OK, LOCKS, OPEN, REFUSED, FAILED = "ok", "locks", "does not close", "refused", "failed"
STATUSES = (OK, LOCKS, OPEN, REFUSED, FAILED)


def unit(name: str) -> str:
    """The unit of an output column (SI; angles in degrees)."""
    if name in UNITS:
        return UNITS[name]
    if name.endswith("_deg"):
        return "deg"
    if name.startswith(("F_", "FN_")):
        return "N"
    if name.startswith("stroke_"):
        return "m"
    if name.startswith(("time_ratio_", "locks_", "lock_margin_", "amplification_")):
        return "-"
    return ""


def key_results(result, extras: tuple[str, ...] = (), fluctuation: float = 0.02
                ) -> dict[str, float]:
    """The key results of a sweep (a ``dyade.Result``) as named numbers: what ``analyse``'s
    summary gives (drive torque and power, joint peaks, smallest transmission angles,
    strokes, swings and time ratios, friction power, self-locking), the shaking force and
    moment, and ``extras`` (``flywheel``: the inertia for ``fluctuation``;
    ``clearance``: the peak force and amplification per clearance joint). NaN where the
    summary gives no value (a time ratio of an output that does not swing once)."""
    from dyade import cycle
    from dyade.linkage.summary import summary

    cols = result.columns()
    s = summary(result, cols, extremes=False)
    out: dict[str, float] = {}
    for dyad, figures in s["transmission"].items():
        out[f"mu_{dyad}_min_deg"] = figures["min_deg"]
    for joint, figures in s["strokes"].items():
        out[f"stroke_{joint}"] = figures["stroke"]
        out[f"time_ratio_{joint}"] = figures["time_ratio"]
    for link, figures in s["swings"].items():
        out[f"swing_{link}_deg"] = figures["swing_deg"]
        out[f"time_ratio_{link}"] = figures["time_ratio"]
    if "drive" in s:
        drive = s["drive"]
        out.update(M_drive_max=drive["M_max"], M_drive_min=drive["M_min"],
                   M_drive_rms=drive["M_rms"], P_drive_mean=drive["P_mean"])
        for name, peak in s["joint_peaks"].items():
            out[f"{name}_peak"] = peak["value"]
        angle = cols["angle_deg"]
        force = np.hypot(cols["Fx_shake"], cols["Fy_shake"])
        out["F_shake_max"] = float(np.nanmax(force)) if np.isfinite(force).any() else math.nan
        out["F_shake_rms"] = cycle.rms(np.deg2rad(angle), force)
        moment = np.abs(cols["M_shake"])
        out["M_shake_max"] = float(np.nanmax(moment)) if np.isfinite(moment).any() else math.nan
    if "friction" in s:
        out["P_friction_mean"] = s["friction"]["P_mean"]
    for joint, lock in s.get("self_locking", {}).items():
        out[f"locks_{joint}"] = 1.0 if lock["locks"] else 0.0
        angles = lock["locking_angles_deg"]
        out[f"lock_start_{joint}_deg"] = float(angles[0]) if len(angles) else math.nan
        out[f"lock_stop_{joint}_deg"] = float(angles[-1]) if len(angles) else math.nan
        margin = cols.get(f"lock_margin_{joint}")
        if margin is not None:
            out[f"lock_margin_{joint}_min"] = (float(np.nanmin(margin))
                                               if np.isfinite(margin).any() else math.nan)
    if "motion" in s:
        out["speed_mean_rpm"] = s["motion"]["speed_mean_rpm"]
        out["fluctuation"] = s["motion"]["fluctuation"]
    if "flywheel" in extras and "drive" in s:
        from dyade.linkage.machine_curve import torque_curve
        from dyade.machine.flywheel import size_flywheel

        out["flywheel_inertia"] = size_flywheel(torque_curve(result.mechanism),
                                                fluctuation).flywheel
    if "clearance" in extras:
        for check in s.get("clearance", []):
            joint = check["joint"]
            peaks = [r["F_max"] for r in check["reversals"]]
            gains = [r["amplification"] for r in check["reversals"]]
            out[f"F_clearance_{joint}_max"] = max(peaks) if peaks else math.nan
            out[f"amplification_{joint}_max"] = max(gains) if gains else math.nan
    return {name: math.nan if value is None else float(value) for name, value in out.items()}


def status_of(values: dict[str, float]) -> str:
    """"locks" where any joint self-locks, else "ok"."""
    return LOCKS if any(v == 1.0 for k, v in values.items() if k.startswith("locks_")) else OK


class Evaluator:
    """The study's variants, evaluated one after another: ``evaluator(block)`` for a
    block of (variant number, values) gives one row per variant (a class, not a closure:
    it pickles for the processes of any executor)."""

    def __init__(self, path: str, data: dict[str, Any], keys: tuple[str, ...],
                 extras: tuple[str, ...] = (), fluctuation: float = 0.02) -> None:
        self.path, self.data, self.keys = path, data, keys
        self.extras, self.fluctuation = extras, fluctuation
        self.calls = 0
        """variants evaluated by this object (in this process)"""

    def mechanism(self, values) -> Any:
        """The variant's mechanism: the file's data (with the study's fixed overrides)
        and ``values`` at the parameters' key paths, read as ``--set`` would."""
        from dyade.files.mechanism import NUMBERING, build, set_dotted

        data = copy.deepcopy(self.data)
        label = self.path.rsplit("/", 1)[-1]
        for key, value in zip(self.keys, values):
            value = float(value)
            set_dotted(data, key, int(value) if value.is_integer() and _whole(key) else value,
                       label, "parameter", NUMBERING)
        return build(data, self.path)

    def one(self, values) -> tuple[str, str, dict[str, float]]:
        """(status, reason, outputs) of one variant."""
        from dyade.errors import AssemblyError, DyadeError, InputError
        from dyade.linkage.sweep import analyse

        self.calls += 1
        try:
            mechanism = self.mechanism(values)
        except InputError as err:
            return REFUSED, str(err), {}
        try:
            result = analyse(mechanism)
        except AssemblyError as err:
            return OPEN, str(err), {}
        except DyadeError as err:
            return FAILED, str(err), {}
        out = key_results(result, self.extras, self.fluctuation)
        status = status_of(out)
        reason = ""
        if status == LOCKS:
            reason = "self-locks at " + ", ".join(
                f"joint ({k[6:].replace('_', ',')})" for k, v in out.items()
                if k.startswith("locks_") and v == 1.0)
        return status, reason, out

    def __call__(self, block: tuple[int, np.ndarray]) -> list[tuple[int, str, str, dict]]:
        first, values = block
        return [(first + i, *self.one(row)) for i, row in enumerate(values)]


def _whole(key: str) -> bool:
    """Keys that take whole numbers (a variant, a link number)."""
    return key.rsplit(".", 1)[-1] in ("variant", "link")
