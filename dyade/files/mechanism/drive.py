"""The [drive] table: the motor's characteristic, a flywheel on the crank and the
settings of the equation of motion, read into ``dyade.model.drive.Drive``."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from dyade.files.schema import UnitReader, fmt, show
from dyade.units import rpm_to_rad_per_s

if TYPE_CHECKING:  # the motor models load only with a [drive] table
    from dyade.model.drive import Drive

MOTOR_KEYS = {"constant": {"torque"},
              "asynchronous": {"rated_torque", "rated_speed_rpm", "synchronous_speed_rpm"},
              "table": {"table"}}
"""[drive] motor kind -> the keys of its characteristic"""
DRIVE_KEYS = {"motor", "flywheel_inertia", "steps", "tol", "max_revolutions"}.union(
    *MOTOR_KEYS.values())


class DriveReader(UnitReader):
    """Reads the [drive] table."""

    def drive(self, table: Any) -> Drive:
        """The [drive] table: motor characteristic, flywheel and integration settings."""
        from dyade.model.drive import Asynchronous, ConstantTorque, Drive, Motor, TorqueSpeedTable

        self.keys(table, "drive", DRIVE_KEYS)
        kind = self.required(table, "motor", "drive")
        if not isinstance(kind, str) or kind not in MOTOR_KEYS:
            raise self.fail("drive.motor", f"must be one of {', '.join(map(show, MOTOR_KEYS))}"
                                           f", got {show(kind)}.", kind)
        for key in table:
            if key in DRIVE_KEYS - {"motor", "flywheel_inertia", "steps", "tol",
                                    "max_revolutions"} - MOTOR_KEYS[kind]:
                raise self.fail(f"drive.{key}", f"does not belong to a {show(kind)} motor "
                                                f"(its keys: {', '.join(sorted(MOTOR_KEYS[kind]))}"
                                                f").")
        motor: Motor
        if kind == "constant":
            torque = (self.number(table["torque"], "drive.torque", "N·m", positive=True)
                      if "torque" in table else None)
            motor = ConstantTorque(torque)
        elif kind == "asynchronous":
            rated = self.number(self.required(table, "rated_torque", "drive"),
                                "drive.rated_torque", "N·m", positive=True)
            speed = self.number(self.required(table, "rated_speed_rpm", "drive"),
                                "drive.rated_speed_rpm", "rpm", positive=True)
            synchronous = self.number(self.required(table, "synchronous_speed_rpm", "drive"),
                                      "drive.synchronous_speed_rpm", "rpm", positive=True)
            if synchronous <= speed:
                raise self.fail("drive.synchronous_speed_rpm", f"must be above the rated speed "
                                                               f"({fmt(speed)} rpm: an "
                                                               f"asynchronous motor slips), got "
                                                               f"{fmt(synchronous)}.",
                                synchronous, "rpm")
            motor = Asynchronous(rated, rpm_to_rad_per_s(speed), rpm_to_rad_per_s(synchronous))
        else:
            rows = self.required(table, "table", "drive")
            if not isinstance(rows, list) or len(rows) < 2:
                raise self.fail("drive.table", f"must list at least two rows [speed [rpm], "
                                               f"torque [N·m]], got {show(rows)}.")
            parsed = []
            for r, row in enumerate(rows, 1):
                if (not isinstance(row, list) or len(row) != 2
                        or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in row)
                        or not all(math.isfinite(v) for v in row)):
                    raise self.fail(f"drive.table.{r}", f"must be [speed [rpm], torque [N·m]], "
                                                        f"got {show(row)}.")
                self.below_top(row[0], f"drive.table.{r}", "speed_rpm", "rpm")
                self.below_top(row[1], f"drive.table.{r}", "torque", "N·m")
                parsed.append([float(v) for v in row])
            arr = np.array(parsed)
            if arr[0, 0] < 0 or np.any(np.diff(arr[:, 0]) <= 0):
                raise self.fail("drive.table", "speeds must rise strictly from 0 rpm or more.")
            motor = TorqueSpeedTable(rpm_to_rad_per_s(arr[:, 0]), arr[:, 1])
        flywheel = self.number(table.get("flywheel_inertia", 0.0), "drive.flywheel_inertia",
                               "kg·m²", non_negative=True)
        steps = None
        if "steps" in table:
            steps = self.integer(table["steps"], "drive.steps")
            if steps < 36:
                raise self.fail("drive.steps", f"must be at least 36 steps per revolution, got "
                                               f"{steps}.", steps)
        tol = self.number(table.get("tol", 1e-10), "drive.tol", "-", positive=True)
        revolutions = self.integer(table.get("max_revolutions", 500), "drive.max_revolutions")
        if revolutions < 2:
            raise self.fail("drive.max_revolutions", f"must be at least 2, got {revolutions}.")
        return Drive(motor, flywheel, steps, tol, revolutions)
