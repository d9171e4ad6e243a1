"""Result -> rich renderables: the sweep summary and the mechanism description."""

from __future__ import annotations

import numpy as np
from rich.table import Table

from dyade.linkage.plan import Plan
from dyade.linkage.verdicts import Outcome as Result
from dyade.linkage.columns import Columns, unit_of
from dyade import cycle
from dyade.model.mechanism import FRAME, Mechanism, Prismatic, Revolute
from dyade.roundoff import ROUNDOFF, is_roundoff
from dyade.units import LENGTH_FACTORS, RAD_PER_S_TO_RPM

FLAG = "1/0"  # the CSV/JSON unit of a flag column; tables say yes or no


def display(unit: str, length_unit: str) -> tuple[float, str]:
    """Factor and unit to show a value of ``unit`` with lengths in ``length_unit``."""
    if length_unit == "m" or unit not in ("m", "m/s", "m/s²"):
        return 1.0, unit
    return 1.0 / LENGTH_FACTORS[length_unit], length_unit + unit[1:]


def number(value: float, scale: float = 0.0, spec: str = ".6g") -> str:
    """A value to 6 significant digits (``spec``); round-off of ``scale`` as 0
    (``dyade.roundoff``)."""
    if not np.isfinite(value):
        return "—"
    if is_roundoff(value, scale):
        return "0"
    return f"{value + 0.0:{spec}}"


def flag(value: float) -> str:
    """A flag column's value in a table: yes (1) or no (0)."""
    return "yes" if value else "no"


def scale_of(values: np.ndarray) -> float:
    """The largest finite magnitude of ``values`` (0 if none): a quantity's scale."""
    finite = np.abs(values[np.isfinite(values)])
    return float(finite.max()) if finite.size else 0.0


def select(cols: Columns, patterns: list[str]) -> Columns:
    """The columns whose names match any of the glob ``patterns`` (angle_deg always)."""
    from fnmatch import fnmatchcase

    return {name: values for name, values in cols.items()
            if name == "angle_deg" or any(fnmatchcase(name, p) for p in patterns)}


def unit_scales(cols: Columns) -> dict[str, float]:
    """The largest magnitude of all columns of each unit: the scale against which a
    value is round-off (a force of 1e-14 N in a joint of a machine with 300 N forces)."""
    out: dict[str, float] = {}
    for name, values in cols.items():
        finite = values[np.isfinite(values)]
        if finite.size:
            unit = unit_of(name)
            out[unit] = max(out.get(unit, 0.0), float(np.max(np.abs(finite))))
    return out


def sweep_summary(result: Result, cols: Columns, length_unit: str = "m") -> Table:
    """Per column: min and max over the sweep and the crank angle of each; constant
    columns (frame joints, the crank's speed) are left out and named in the caption,
    round-off noise is shown as 0."""
    angle = cols["angle_deg"]
    table = Table(title=f"{result.mechanism.name}: {angle.size} crank positions "
                        f"{angle[0]:.1f}°–{angle[-1]:.1f}°", title_justify="left")
    table.add_column("quantity")
    table.add_column("unit")
    for head in ("min", "at φ21 [°]", "max", "at φ21 [°]"):
        table.add_column(head, justify="right")
    constant = []
    scales = unit_scales(cols)
    for name, values in cols.items():
        if name == "angle_deg":
            continue
        factor, unit = display(unit_of(name), length_unit)
        shown = number
        if unit == FLAG:
            unit, shown = "", lambda value, scale: flag(value)
        finite = np.isfinite(values)
        if not finite.any():
            table.add_row(name, unit, "—", "", "—", "")
            continue
        masked = np.where(finite, values, np.nan) * factor
        lo, hi = int(np.nanargmin(masked)), int(np.nanargmax(masked))
        scale = scales[unit_of(name)] * factor
        if masked[hi] - masked[lo] <= ROUNDOFF * scale and finite.all():
            constant.append(f"{name} = {shown(masked[lo], scale)}{f' {unit}' if unit else ''}")
            continue
        table.add_row(name, unit, shown(masked[lo], scale), f"{angle[lo]:.1f}",
                      shown(masked[hi], scale), f"{angle[hi]:.1f}")
    if constant:
        table.caption = "constant over the sweep: " + ", ".join(constant)
        table.caption_justify = "left"
    return table


def key_results(result: Result, cols: Columns, summary: dict, length_unit: str = "m"
                ) -> Table:
    """The results that matter first: drive torque and power, each joint's peak force,
    the smallest transmission angle of each dyad, strokes, swings and time ratios,
    self-locking and clearance peaks."""
    angle = cols["angle_deg"]
    mechanism = result.mechanism
    rpm = abs(mechanism.crank.speed) * RAD_PER_S_TO_RPM
    speed = f"at {rpm:g} rpm"
    motion = summary.get("motion")
    if motion is not None:  # the equation of motion sets the speed, not the file's rpm
        speed = (f"at a mean {motion['speed_mean'] * RAD_PER_S_TO_RPM:.4g} rpm (equation of "
                 f"motion)" if motion["state"] == "steady" else "in a run-up from rest")
    table = Table(title=f"{mechanism.name}: {angle.size} crank positions "
                        f"{angle[0]:.1f}°–{angle[-1]:.1f}° {speed} — key results",
                  title_justify="left", caption="--all: min and max of every column; "
                  "--columns PATTERN to choose columns", caption_justify="left")
    for head, justify in (("quantity", "left"), ("value", "right"), ("unit", "left"),
                          ("at φ21 [°]", "right")):
        table.add_column(head, justify=justify)
    drive = summary.get("drive")
    if drive:
        torque = cols["M_drive"]
        torque_scale = scale_of(torque)
        for label, pick in (("drive torque max", np.nanargmax), ("drive torque min", np.nanargmin)):
            if np.isfinite(torque).any():
                k = int(pick(torque))
                table.add_row(label, number(torque[k], torque_scale), "N·m", f"{angle[k]:.1f}")
        table.add_row("drive torque RMS", number(drive["M_rms"], torque_scale), "N·m", "")
        table.add_row("mean drive power", number(drive["P_mean"], scale_of(cols["P_drive"])), "W",
                      "")
        if "friction" in summary:
            table.add_row("mean friction power", number(summary["friction"]["P_mean"],
                                                        scale_of(cols["P_friction"])), "W", "")
        peaks = summary.get("joint_peaks", {})
        largest = max((abs(p["value"]) for p in peaks.values()), default=0.0)
        for name, peak in peaks.items():
            table.add_row(f"peak force {name}", number(abs(peak["value"]), largest), "N",
                          f"{peak['at_deg']:.1f}")
    for number_, figure in summary["transmission"].items():
        table.add_row(f"smallest transmission angle, dyad {number_}", number(figure["min_deg"]),
                      "°", f"{figure['at_deg']:.1f}")
    for name, figure in summary["strokes"].items():
        factor, unit = display("m", length_unit)
        joint = name.replace("_", ",")
        table.add_row(f"stroke of slider ({joint})", number(figure["stroke"] * factor), unit, "")
        if figure["time_ratio"] is not None:
            table.add_row(f"  time ratio ({joint})", number(figure["time_ratio"]), "-", "")
    for link, figure in summary["swings"].items():
        table.add_row(f"swing of link {link}", number(figure["swing_deg"]), "°", "")
        if figure["time_ratio"] is not None:
            table.add_row(f"  time ratio (link {link})", number(figure["time_ratio"]), "-", "")
    for name, lock in (summary.get("self_locking") or {}).items():
        joint = name.replace("_", ",")
        where = lock["locking_angles_deg"]
        table.add_row(f"self-locking, slider ({joint})",
                      f"{len(where)} positions" if lock["locks"] else "none", "",
                      f"{where[0]:.1f}–{where[-1]:.1f}" if lock["locks"] else "")
    for check in summary.get("clearance") or []:
        joint = check["joint"].replace("_", ",")
        for rev in check["reversals"]:
            table.add_row(f"clearance peak ({joint}), τ = {rev['tau']:.3g}", number(rev["F_max"]),
                          "N", f"{rev['angle_deg']:.1f}")
    return table


def skipped(the_plan: Plan) -> list[str]:
    """Effects the file does not call for, and what would turn them on."""
    out = []
    if not the_plan.kinetostatics:
        out.append("kinetostatics: no masses, loads or springs in the file")
    if not the_plan.friction:
        out.append("friction: no joint has a friction coefficient μ > 0")
    if not the_plan.self_locking:
        out.append("self-locking: no slider (prismatic joint) with friction")
    if not the_plan.clearance:
        out.append("clearance peaks: no joint has clearance data "
                   "(or run `dyade clearance FILE --stiffness … --clearance …`)")
    return out


def force_summary(result: Result, cols: Columns) -> Table | None:
    """Per joint: the largest force and where; the drive: max/min/RMS torque, mean power."""
    if result.forces_valid is None:
        return None
    angle = cols["angle_deg"]
    rubbing = result.rubbing
    kind = "with Coulomb friction" if rubbing is not None else "frictionless"
    table = Table(title=f"Joint forces and drive (rigid, {kind})", title_justify="left")
    table.add_column("quantity")
    table.add_column("unit")
    table.add_column("largest |value|", justify="right")
    table.add_column("at φ21 [°]", justify="right")
    scales = unit_scales(cols)
    for joint in result.mechanism.joints:
        a, b = joint.name
        names = ([f"F_{a}_{b}"] if isinstance(joint, Revolute) else [f"FN_{a}_{b}", f"M_{a}_{b}"])
        for name in names:
            values = np.abs(cols[name])
            if not np.isfinite(values).any():
                table.add_row(name, unit_of(name), "—", "")
                continue
            k = int(np.nanargmax(values))
            if is_roundoff(values[k], scales[unit_of(name)]):
                table.add_row(name, unit_of(name), "0", "")  # round-off everywhere
                continue
            table.add_row(name, unit_of(name), number(cols[name][k]), f"{angle[k]:.1f}")
    torque = cols["M_drive"]
    finite = np.isfinite(torque)
    radians = np.deg2rad(angle)
    if finite.any():
        lo, hi = int(np.nanargmin(torque)), int(np.nanargmax(torque))
        scale = scale_of(torque)
        table.add_row("M_drive max", "N·m", number(torque[hi], scale), f"{angle[hi]:.1f}")
        table.add_row("M_drive min", "N·m", number(torque[lo], scale), f"{angle[lo]:.1f}")
        table.add_row("M_drive RMS", "N·m", number(cycle.rms(radians, torque), scale), "")
        table.add_row("P_drive mean", "W", number(cycle.mean(radians, cols["P_drive"])), "")
    if rubbing is not None:
        table.add_row("P_friction mean", "W", number(cycle.mean(radians, cols["P_friction"])), "")
        its = cols["friction_iterations"]
        rows = result.rows & result.forces_valid
        worst = float(np.max(rubbing.residual[rows], initial=0.0))
        table.add_row("friction passes", "-", f"{its.min():.0f}–{its.max():.0f}", "")
        table.add_row("worst final residual", "-", f"{worst:.2g}", "")
    for name, lock in (result.locking or {}).items():
        a, b = name
        locks = lock.locks[result.rows]
        verdict = f"locks over {int(locks.sum())} positions" if locks.any() else "no lock"
        if lock.margin is None:
            table.add_row(f"joint ({a},{b}) ({verdict})", "", "", "")
            continue
        margin = cols[f"lock_margin_{a}_{b}"]
        if np.isfinite(margin).any():
            k = int(np.nanargmin(margin))
            table.add_row(f"lock_margin_{a}_{b} min ({verdict})", "-", f"{margin[k]:.6g}",
                          f"{angle[k]:.1f}")
    return table


def clearance_summary(result: Result) -> Table | None:
    """One row per reversal of each checked joint: angle, τ, peak, amplification."""
    if not result.clearance:
        return None
    table = Table(title="Clearance peaks (Dresig & Thümmel)", title_justify="left")
    for head in ("joint", "impacts [1/rev]", "φ21 [°]", "τ [-]", "F12max [N]", "rigid [N]",
                 "× [-]"):
        table.add_column(head, justify="right")
    for check in result.clearance:
        a, b = check.joint
        if not check.applies:
            table.add_row(f"({a},{b})", "—", "model does not apply", "", "", "", "")
            continue
        if not check.reversals:
            table.add_row(f"({a},{b})", "0", "no reversal", "", "", "", "")
        for rev in check.reversals:
            table.add_row(f"({a},{b})", str(len(check.reversals)),
                          f"{np.rad2deg(rev.crank_angle):.1f}", f"{rev.peak.tau:.4g}",
                          f"{rev.peak.force:.5g}", f"{rev.rigid_force:.5g}",
                          f"{rev.amplification:.3g}")
    return table


def motion_table(result: Result, summary: dict) -> Table | None:
    """The crank's speed from the equation of motion: mean, extremes, fluctuation; for a
    run-up its duration and work balance."""
    motion = summary.get("motion")
    if motion is None:
        return None
    rpm = RAD_PER_S_TO_RPM
    state = "steady state" if motion["state"] == "steady" else "run-up from rest"
    scope = "; speeds over the last revolution" if motion["state"] != "steady" else ""
    title = f"Crank speed from the equation of motion ({state}{scope})\nmotor: {motion['motor']}"
    table = Table(title=title, title_justify="left",
                  min_width=max(len(line) for line in title.splitlines()))
    for head, justify in (("quantity", "left"), ("unit", "left"), ("value", "right"),
                          ("at φ21 [°]", "right")):
        table.add_column(head, justify=justify)
    table.add_row("flywheel J_F", "kg·m²", f"{motion['flywheel_inertia']:.6g}", "")
    table.add_row("mean reduced inertia", "kg·m²", f"{motion['inertia_mean']:.6g}", "")
    table.add_row("mean speed 2π/T", "rpm", f"{motion['speed_mean'] * rpm:.6g}", "")
    table.add_row("lowest speed", "rpm", f"{motion['speed_min'] * rpm:.6g}",
                  f"{motion['speed_min_at_deg']:.1f}")
    table.add_row("highest speed", "rpm", f"{motion['speed_max'] * rpm:.6g}",
                  f"{motion['speed_max_at_deg']:.1f}")
    table.add_row("speed fluctuation δ", "%", f"{100 * motion['fluctuation']:.4g}", "")
    table.add_row("period T", "s", f"{motion['period']:.6g}", "")
    table.add_row("mean motor torque", "N·m", f"{motion['motor_torque_mean']:.6g}", "")
    if motion["state"] != "steady":
        table.add_row("revolutions to repeat" if motion["settled"] else
                      "revolutions (not yet periodic)", "-", f"{motion['revolutions']}", "")
        table.add_row("run-up time", "s", f"{motion['duration']:.6g}", "")
        table.add_row("motor work", "J", f"{motion['work_motor']:.6g}", "")
        table.add_row("= kinetic energy", "J", f"{motion['kinetic_energy']:.6g}", "")
        table.add_row("+ work on the loads", "J", f"{motion['work_load']:.6g}", "")
        table.add_row("+ friction work", "J", f"{motion['work_friction']:.6g}", "")
    return table
