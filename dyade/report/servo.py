"""A ``servo`` Outcome (``dyade.analyses.servo``) -> rich tables, and the profile's table
for a motion controller (CSV)."""

from __future__ import annotations

from typing import TextIO

import numpy as np

from dyade.report.format import cell, number
from dyade.report.outcome import summary_table
from dyade.units import RAD_PER_S_TO_RPM


def fmt(value, digits: int = 5) -> str:
    return number(value, spec=f".{digits}g")


def tables(outcome) -> list:
    """The summary, the gear ratios of a range (the optimum marked) and the catalogue's
    motors with their margins."""
    from rich.table import Table

    run = outcome.result
    name = outcome.meta.get("name") or "mechanism"
    parts = [summary_table(outcome, f"Servo-driven crank of {name}: the cycle and the motor")]
    sizing = run.sizing
    if sizing.ratio.size > 1:
        table = Table(title="Gear ratios (* the RMS optimum)", title_justify="left")
        for head in ("i [-]", "peak [N·m]", "RMS [N·m]", "top speed [rpm]", "λ [-]",
                     "fed back [J]"):
            table.add_column(head, justify="right")
        for k in range(sizing.ratio.size):
            mark = " *" if run.optimum is not None and sizing.ratio[k] == run.optimum else ""
            table.add_row(fmt(sizing.ratio[k]) + mark, fmt(sizing.peak_torque[k]),
                          fmt(sizing.rms_torque[k]), fmt(sizing.top_speed[k] * RAD_PER_S_TO_RPM),
                          fmt(sizing.inertia_ratio[k], 4), fmt(sizing.regenerated[k]))
        parts.append(table)
    if run.checks:
        table = Table(title="Motor catalogue (margin = 1 − used/available; ≥ 0 passes; → the "
                            "smallest that passes)", title_justify="left")
        for head in ("motor", "M_N [N·m]", "M_max [N·m]", "n_max [rpm]", "J_M [kg·m²]", "i [-]",
                     "RMS [N·m]", "peak [N·m]", "thermal", "peak", "speed", "inertia",
                     "passes"):
            table.add_column(head, justify="left" if head == "motor" else "right")
        for check in run.checks:
            row = check.best
            if row is None:  # the ratio where it comes closest
                least = np.minimum(np.minimum(check.thermal, check.peak),
                                   np.minimum(check.speed, check.inertia))
                row = int(np.argmax(least))
            motor = check.motor
            arrow = "→ " if check is run.chosen else ""
            table.add_row(arrow + motor.name, fmt(motor.rated_torque), fmt(motor.peak_torque),
                          fmt(motor.top_speed * RAD_PER_S_TO_RPM), fmt(motor.rotor_inertia, 4),
                          fmt(check.sizing.ratio[row], 4), fmt(check.sizing.rms_torque[row], 4),
                          fmt(check.sizing.peak_torque[row], 4), fmt(check.thermal[row], 3),
                          fmt(check.peak[row], 3), fmt(check.speed[row], 3),
                          fmt(check.inertia[row], 3), "yes" if check.best is not None else
                          "no: " + ", ".join(check.failed(row)))
        parts.append(table)
    return parts


CONTROLLER = ("t", "position_deg", "velocity_deg_s", "acceleration_deg_s2")
"""the columns of the table for a motion controller: time [s] and the crank's (the load
axis's) position [°], velocity [°/s] and acceleration [°/s²]"""


def write_controller(outcome, handle: TextIO) -> None:
    """The crank's motion over the cycle as a motion controller's cam table (CSV, one
    row per instant, the columns ``CONTROLLER``; the motor axis is i times the crank)."""
    run = outcome.result
    motion = run.motion
    rows = np.column_stack((motion.time, np.degrees(motion.angle), np.degrees(motion.speed),
                            np.degrees(motion.acceleration)))
    handle.write(",".join(CONTROLLER) + "\n")
    for row in rows.tolist():
        handle.write(",".join(cell(value) for value in row) + "\n")
