"""The machine in motion: the flywheel and the counterweights as rows and tables."""

from __future__ import annotations

import math
from typing import Any

from rich.table import Table

from dyade.roundoff import clean
from dyade.units import RAD_PER_S_TO_RPM

FLYWHEEL_COLUMNS = ["speed_rpm", "P_mean", "M_mean", "delta_E", "J_machine", "J_flywheel",
                    "fluctuation", "angle_max_speed_deg", "angle_min_speed_deg"]
"""the keys of ``dyade flywheel`` (CSV columns, JSON keys)"""
FLYWHEEL_UNITS = {"speed_rpm": "rpm", "P_mean": "W", "M_mean": "N·m", "delta_E": "J",
                  "J_machine": "kg·m²", "J_flywheel": "kg·m²", "fluctuation": "-",
                  "angle_max_speed_deg": "°", "angle_min_speed_deg": "°"}
FLYWHEEL_LABELS = {"speed_rpm": "mean speed Ω", "P_mean": "mean power", "M_mean":
                   "mean drive torque", "delta_E": "energy fluctuation ΔE", "J_machine":
                   "machine's mean reduced inertia", "J_flywheel": "flywheel inertia J_F",
                   "fluctuation": "speed fluctuation δ", "angle_max_speed_deg":
                   "highest speed at φ21", "angle_min_speed_deg": "lowest speed at φ21"}
COUNTERWEIGHT_COLUMNS = ["link", "first_moment", "angle_deg", "radius", "mass"]
COUNTERWEIGHT_UNITS = {"link": "", "first_moment": "kg·m", "angle_deg": "°", "radius": "m",
                       "mass": "kg"}


def flywheel_row(result) -> dict[str, Any]:
    """A ``Flywheel`` as the command's keys (SI, speed in rpm, angles in degrees)."""
    return {"speed_rpm": result.speed * RAD_PER_S_TO_RPM, "P_mean": result.power,
            "M_mean": result.mean_torque, "delta_E": result.delta_energy,
            "J_machine": result.machine_inertia, "J_flywheel": result.flywheel,
            "fluctuation": result.fluctuation,
            "angle_max_speed_deg": math.degrees(result.angle_max_speed),
            "angle_min_speed_deg": math.degrees(result.angle_min_speed)}


def flywheel_table(row: dict[str, Any], source: str, asked: str) -> Table:
    """One row per key: what, unit, value; the asked quantity marked."""
    table = Table(title=f"Flywheel for {source} (δ ≈ ΔE/(J·Ω²))", title_justify="left")
    table.add_column("quantity")
    table.add_column("key")
    table.add_column("unit")
    table.add_column("value", justify="right")
    for key in FLYWHEEL_COLUMNS:
        label = FLYWHEEL_LABELS[key] + (" (given)" if key == asked else "")
        table.add_row(label, key, FLYWHEEL_UNITS[key], f"{row[key] + 0.0:.7g}")
    return table


def counterweight_rows(result) -> list[dict[str, Any]]:
    return [{"link": weight.link, "first_moment": weight.first_moment,
             "angle_deg": math.degrees(weight.angle), "radius": weight.radius,
             "mass": weight.mass} for weight in result.counterweights]


def balance_tables(name: str, rows: list[dict[str, Any]], changes: dict[str, Any]
                   ) -> list[Table]:
    """The counterweights, and what they change (before, after)."""
    weights = Table(title=f"Counterweights for {name} (least-squares shaking-force balance)",
                    title_justify="left")
    for head in ("link", "m·r [kg·m]", "angle in link frame [°]", "radius [m]", "mass [kg]"):
        weights.add_column(head, justify="right")
    for row in rows:
        weights.add_row(str(row["link"]), f"{row['first_moment']:.6g}",
                        f"{row['angle_deg']:.2f}", f"{row['radius']:.6g}",
                        f"{row['mass']:.6g}")
    effect = Table(title="Before and after (constant crank speed)", title_justify="left")
    for head in ("quantity", "unit", "before", "after", "after/before"):
        effect.add_column(head, justify="left" if head in ("quantity", "unit") else "right")

    def add(label, unit, before, after, scale=None):
        """A row; round-off of ``scale`` (default: the larger of before and after) is 0."""
        if before is None or after is None:
            effect.add_row(label, unit, "—", "—", "")
            return
        scale = max(abs(before), abs(after)) if scale is None else scale
        before, after = clean(before, scale), clean(after, scale)
        ratio = f"{after / before + 0.0:.3g}" if before else ""
        effect.add_row(label, unit, f"{before:.6g}", f"{after:.6g}", ratio)

    shaking = changes["shaking_force"]
    add("shaking force, largest", "N", shaking["before_max"], shaking["after_max"])
    add("shaking force, RMS", "N", shaking["before_rms"], shaking["after_rms"])
    for key, label, unit in (("shaking_moment", "shaking moment M_shake", "N·m"),
                             ("drive_torque", "drive torque M_drive", "N·m")):
        entry = changes[key]
        add(f"{label}, largest", unit, entry["before_max"], entry["after_max"])
        add(f"{label}, RMS", unit, entry["before_rms"], entry["after_rms"])
    forces = changes["joint_forces"]
    largest = max((abs(value) for entry in forces.values() for value in entry.values()
                   if value is not None), default=0.0)  # the machine's joint-force scale
    for name_, entry in forces.items():
        add(f"{name_} largest", "N", entry["before"], entry["after"], largest)
    return [weights, effect]
