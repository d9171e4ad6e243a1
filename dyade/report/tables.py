"""A ``sweep`` Outcome (``dyade.analyses.sweep``) -> rich tables: the key results, the
crank's motion, the extremes of every column, the forces, the clearance peaks, the
values at single positions; and what a plan does not simulate (``skipped``).

Every number through ``dyade.report.format.number`` (a value not given: —, flags yes
or no); lengths in the mechanism file's length unit unless SI is asked for, said in the
title.
"""

from __future__ import annotations

import re

import numpy as np
from rich.table import Table

from dyade.analyses.base import MISSING
from dyade.linkage.columns import unit_of
from dyade.model.mechanism import Revolute
from dyade.linkage.plan import Plan
from dyade.report.format import FLAG, display, flag, number
from dyade.roundoff import ROUNDOFF, is_roundoff
from dyade.units import RAD_PER_S_TO_RPM


def at(angle) -> str:
    """Where a figure occurs, in a table's "at φ21 [°]" column: one decimal."""
    return "" if angle is None else f"{angle:.1f}"


def where_of(figure) -> str:
    """The crank angle of a figure's ``where``, for the "at φ21 [°]" column."""
    return at((figure.where or {}).get("angle_deg"))


def lengths(outcome, length_unit: str | None) -> str:
    """The table length unit: ``length_unit``, else the mechanism file's."""
    return length_unit or outcome.result.mechanism.units[0]


def heading(outcome, length_unit: str) -> str:
    """"NAME: n crank positions a°–b°", the positions of a sweep or the single ones."""
    angle = np.asarray(outcome.columns["angle_deg"])
    name = outcome.result.mechanism.name
    if "at_deg" in outcome.options:
        return f"{name}: {angle.size} crank position{'s' if angle.size != 1 else ''}"
    first, last = (angle[0], angle[-1]) if angle.size else (np.nan, np.nan)
    return f"{name}: {angle.size} crank positions {first:.1f}°–{last:.1f}°"


def sweep_tables(outcome, length_unit: str | None = None, everything: bool = False,
                 chosen: bool = False) -> list:
    """The tables of ``dyade analyse``: the key results and the crank's motion; with
    ``everything`` (--all) the extremes of every column, the forces, the motion and the
    clearance peaks; for ``chosen`` columns (--columns) their extremes; at single
    positions (--at) their values."""
    unit = lengths(outcome, length_unit)
    if "at_deg" in outcome.options:
        return [positions_table(outcome, unit)]
    if chosen:
        return [sweep_summary(outcome, unit)]
    if everything:
        return [sweep_summary(outcome, unit), force_summary(outcome),
                motion_table(outcome), clearance_summary(outcome)]
    return [key_results(outcome, unit), motion_table(outcome)]


def unit_scales(cols) -> dict[str, float]:
    """The largest magnitude of all columns of each unit: the scale against which a
    value is round-off (a force of 1e-14 N in a joint of a machine with 300 N forces)."""
    out: dict[str, float] = {}
    for name in cols:
        values = np.asarray(cols[name])
        finite = values[np.isfinite(values)]
        if finite.size:
            unit = unit_of(name)
            out[unit] = max(out.get(unit, 0.0), float(np.max(np.abs(finite))))
    return out


def sweep_summary(outcome, length_unit: str = "m") -> Table:
    """Per column: min and max over the sweep and the crank angle of each (the summary's
    ``<column>_min`` and ``<column>_max``); constant columns (frame joints, the crank's
    speed) are left out and named in the caption, round-off noise is shown as 0."""
    cols, summary = outcome.columns, outcome.summary
    title = heading(outcome, length_unit) + (f" (lengths in {length_unit})"
                                             if length_unit != "m" else "")
    table = Table(title=title, title_justify="left")
    table.add_column("quantity")
    table.add_column("unit")
    for head in ("min", "at φ21 [°]", "max", "at φ21 [°]"):
        table.add_column(head, justify="right")
    constant = []
    scales = unit_scales(cols)
    for name in cols:
        if name == "angle_deg":
            continue
        factor, unit = display(unit_of(name), length_unit)
        low, high = summary[f"{name}_min"], summary[f"{name}_max"]
        if low.value is None:
            table.add_row(name, "" if unit == FLAG else unit, MISSING, "", MISSING, "")
            continue
        if unit == FLAG:
            unit, shown = "", lambda value, scale: flag(value)
        else:
            shown = number
        scale = scales[unit_of(name)] * factor
        lo, hi = low.value * factor, high.value * factor
        if hi - lo <= ROUNDOFF * scale and np.isfinite(cols[name]).all():
            constant.append(f"{name} = {shown(lo, scale)}{f' {unit}' if unit else ''}")
            continue
        table.add_row(name, unit, shown(lo, scale), where_of(low), shown(hi, scale),
                      where_of(high))
    if constant:
        table.caption = "constant over the sweep: " + ", ".join(constant)
        table.caption_justify = "left"
    return table


def scale(summary, name: str) -> float:
    """The largest magnitude of a column from the summary's extremes (0 if not there)."""
    values = [summary[f"{name}_{which}"].value for which in ("min", "max")
              if f"{name}_{which}" in summary]
    return max((abs(v) for v in values if v is not None), default=0.0)


def key_results(outcome, length_unit: str = "m") -> Table:
    """The results that matter first: drive torque and power, the shaking force, each
    joint's peak force, the smallest transmission angle of each dyad, strokes, swings
    and time ratios, self-locking and clearance peaks (the summary's figures)."""
    summary = outcome.summary
    value = {name: figure.value for name, figure in summary.items()}
    mechanism = outcome.result.mechanism
    rpm = abs(mechanism.crank.speed) * RAD_PER_S_TO_RPM
    speed = f"at {number(rpm, spec='g')} rpm"
    if "motion_state" in value:  # the equation of motion sets the speed, not the file's rpm
        speed = (f"at a mean {number(value['speed_mean_rpm'], spec='.4g')} rpm (equation of "
                 f"motion)" if value["motion_state"] == "steady" else "in a run-up from rest")
    table = Table(title=f"{heading(outcome, length_unit)} {speed} — key results"
                        + (f", lengths in {length_unit}" if length_unit != "m" else ""),
                  title_justify="left", caption="--all: min and max of every column; "
                  "--columns PATTERN to choose columns", caption_justify="left")
    for head, justify in (("quantity", "left"), ("value", "right"), ("unit", "left"),
                          ("at φ21 [°]", "right")):
        table.add_column(head, justify=justify)

    def row(name: str, shown: str | None = None, unit: str | None = None,
            label: str | None = None) -> None:
        figure = summary[name]
        table.add_row(label or figure.description, number(figure.value) if shown is None
                      else shown, figure.unit if unit is None else unit, where_of(figure))

    if "M_drive_max" in value:
        torque = max(abs(value[n]) for n in ("M_drive_max", "M_drive_min")
                     if value[n] is not None) if value["M_drive_max"] is not None else 0.0
        for name in ("M_drive_max", "M_drive_min"):
            if value[name] is not None:
                row(name, number(value[name], torque))
        if "M_drive_rms" in value:
            row("M_drive_rms", number(value["M_drive_rms"], torque))
            row("P_drive_mean", number(value["P_drive_mean"], scale(summary, "P_drive")))
        if "P_friction_mean" in value:
            row("P_friction_mean", number(value["P_friction_mean"],
                                          scale(summary, "P_friction")))
        for name in ("F_shake_max", "F_shake_rms", "M_shake_abs_max", "F_cam_min",
                     "F_cam_max"):
            if name in value:
                row(name)
        peaks = [name for name in summary if name.endswith("_peak")]
        largest = max((abs(value[n]) for n in peaks), default=0.0)
        for name in peaks:
            row(name, number(abs(value[name]), largest), label=f"peak force {name[:-5]}")
    for name, figure in summary.items():
        if name.startswith("mu_") and name.endswith("_min_deg"):
            row(name)
        elif name.startswith("stroke_"):
            factor, unit = display("m", length_unit)
            row(name, number(None if figure.value is None else figure.value * factor), unit)
        elif name.startswith("swing_") or (name.startswith("time_ratio_")
                                           and figure.value is not None):
            row(name)
    for name, figure in summary.items():
        if name.startswith("locks_"):
            tag = name[len("locks_"):]
            start, stop = value[f"lock_start_{tag}_deg"], value[f"lock_stop_{tag}_deg"]
            table.add_row(f"self-locking, slider ({tag.replace('_', ',')})",
                          f"{value[f'lock_positions_{tag}']} positions" if figure.value
                          else "none", "",
                          f"{at(start)}–{at(stop)}" if figure.value else "")
        elif re.fullmatch(r"F_clearance_\d+_\d+_r\d+", name):
            tag, _, k = name[len("F_clearance_"):].rpartition("_r")
            row(name, label=f"clearance peak ({tag.replace('_', ',')}), τ = "
                            f"{number(value[f'tau_{tag}_r{k}'], spec='.3g')}")
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


def force_summary(outcome) -> Table | None:
    """Per joint: the largest force and where; the drive: max/min/RMS torque, mean power;
    friction's passes and residual; the least self-locking margin of each slider."""
    result, cols, summary = outcome.result, outcome.columns, outcome.summary
    if result.forces_valid is None:
        return None
    value = {name: figure.value for name, figure in summary.items()}
    angle = np.asarray(cols["angle_deg"])
    rubbing = result.rubbing
    kind = "with Coulomb friction" if rubbing is not None else "frictionless"
    table = Table(title=f"Joint forces and drive (rigid, {kind})", title_justify="left")
    table.add_column("quantity")
    table.add_column("unit")
    table.add_column("largest |value|", justify="right")
    table.add_column("at φ21 [°]", justify="right")
    scales = unit_scales({name: cols[name] for name in cols if unit_of(name) in ("N", "N·m")})
    for joint in result.mechanism.joints:
        a, b = joint.name
        names = ([f"F_{a}_{b}"] if isinstance(joint, Revolute) else [f"FN_{a}_{b}", f"M_{a}_{b}"])
        for name in names:
            values = np.abs(cols[name])
            if not np.isfinite(values).any():
                table.add_row(name, unit_of(name), MISSING, "")
                continue
            k = int(np.nanargmax(values))
            if is_roundoff(values[k], scales[unit_of(name)]):
                table.add_row(name, unit_of(name), "0", "")  # round-off everywhere
                continue
            table.add_row(name, unit_of(name), number(cols[name][k]), at(angle[k]))
    if value.get("M_drive_max") is not None:
        torque = max(abs(value["M_drive_max"]), abs(value["M_drive_min"]))
        table.add_row("M_drive max", "N·m", number(value["M_drive_max"], torque),
                      where_of(summary["M_drive_max"]))
        table.add_row("M_drive min", "N·m", number(value["M_drive_min"], torque),
                      where_of(summary["M_drive_min"]))
        table.add_row("M_drive RMS", "N·m", number(value["M_drive_rms"], torque), "")
        table.add_row("P_drive mean", "W", number(value["P_drive_mean"]), "")
    if rubbing is not None:
        table.add_row("P_friction mean", "W", number(value["P_friction_mean"]), "")
        table.add_row("friction passes", "-", f"{number(value['friction_iterations_min'], spec='.0f')}"
                                              f"–{number(value['friction_iterations_max'], spec='.0f')}",
                      "")
        table.add_row("worst final residual", "-",
                      number(value["friction_residual_max"], spec=".2g"), "")
    for name, lock in (result.locking or {}).items():
        a, b = name
        locks = lock.locks[result.rows]
        verdict = f"locks over {int(locks.sum())} positions" if locks.any() else "no lock"
        if lock.margin is None:
            table.add_row(f"joint ({a},{b}) ({verdict})", "", "", "")
            continue
        margin = summary.get(f"lock_margin_{a}_{b}_min")
        if margin is not None and margin.value is not None:
            table.add_row(f"lock_margin_{a}_{b} min ({verdict})", "-", number(margin.value),
                          where_of(margin))
    return table


def clearance_summary(outcome) -> Table | None:
    """One row per reversal of each checked joint: angle, τ, peak, amplification."""
    result = outcome.result
    if not result.clearance:
        return None
    table = Table(title="Clearance peaks (Dresig & Thümmel)", title_justify="left")
    for head in ("joint", "impacts [1/rev]", "φ21 [°]", "τ [-]", "F12max [N]", "rigid [N]",
                 "× [-]"):
        table.add_column(head, justify="right")
    for check in result.clearance:
        a, b = check.joint
        if not check.applies:
            table.add_row(f"({a},{b})", MISSING, "model does not apply", "", "", "", "")
            continue
        if not check.reversals:
            table.add_row(f"({a},{b})", "0", "no reversal", "", "", "", "")
        for rev in check.reversals:
            table.add_row(f"({a},{b})", str(len(check.reversals)),
                          at(np.rad2deg(rev.crank_angle)), number(rev.peak.tau, spec=".4g"),
                          number(rev.peak.force, spec=".5g"),
                          number(rev.rigid_force, spec=".5g"),
                          number(rev.amplification, spec=".3g"))
    return table


def motion_table(outcome) -> Table | None:
    """The crank's speed from the equation of motion: mean, extremes, fluctuation; for a
    run-up its duration and work balance (the summary's figures)."""
    summary = outcome.summary
    if "motion_state" not in summary:
        return None
    value = {name: figure.value for name, figure in summary.items()}
    steady = value["motion_state"] == "steady"
    state = "steady state" if steady else "run-up from rest"
    scope = "; speeds over the last revolution" if not steady else ""
    title = f"Crank speed from the equation of motion ({state}{scope})\nmotor: {value['motor']}"
    table = Table(title=title, title_justify="left",
                  min_width=max(len(line) for line in title.splitlines()))
    for head, justify in (("quantity", "left"), ("unit", "left"), ("value", "right"),
                          ("at φ21 [°]", "right")):
        table.add_column(head, justify=justify)

    def row(name: str, label: str | None = None, shown: str | None = None) -> None:
        figure = summary[name]
        table.add_row(label or figure.description, figure.unit,
                      number(figure.value) if shown is None else shown, where_of(figure))

    row("J_F", "flywheel J_F")
    row("J_red_mean")
    row("speed_mean_rpm")
    row("speed_min_rpm")
    row("speed_max_rpm")
    table.add_row("speed fluctuation δ", "%", number(100 * value["fluctuation"], spec=".4g"), "")
    row("period")
    row("M_motor_mean")
    if not steady:
        table.add_row("revolutions to repeat" if value["settled"] else
                      "revolutions (not yet periodic)", "-", f"{value['revolutions']}", "")
        row("duration")
        row("W_motor")
        row("E_kinetic", "= kinetic energy")
        row("W_load", "+ work on the loads")
        row("W_friction", "+ friction work")
    return table


def positions_table(outcome, length_unit: str = "m") -> Table:
    """The values at single crank positions (--at): one row per column, one column per
    position, each with its unit (lengths in ``length_unit``)."""
    cols = outcome.columns
    angle = np.asarray(cols["angle_deg"])
    table = Table(title=heading(outcome, length_unit) + (f" (lengths in {length_unit})"
                                                         if length_unit != "m" else ""),
                  title_justify="left")
    table.add_column("quantity")
    table.add_column("unit")
    for value in angle:
        table.add_column(f"φ21 = {number(value)}°", justify="right")
    scales = unit_scales(cols)
    for name in cols:
        if name == "angle_deg":
            continue
        factor, unit = display(unit_of(name), length_unit)
        values = np.asarray(cols[name]) * factor
        if unit == FLAG:
            table.add_row(name, "", *[MISSING if np.isnan(v) else flag(v) for v in values])
            continue
        scale_ = scales.get(unit_of(name), 0.0) * factor
        table.add_row(name, unit, *[number(float(v), scale_) for v in values])
    return table
