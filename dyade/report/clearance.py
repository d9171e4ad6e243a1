"""Clearance results -> rows (CSV/JSON records), notes and rich tables.

Standalone (from four numbers, optionally over a speed range) and over a mechanism
(one row per reversal of each checked joint, per speed).
"""

from __future__ import annotations

import time

import numpy as np

from dyade import clearance as engine
from dyade.linkage.joint_clearance import MISSING

STANDALONE_COLUMNS = ["mass", "stiffness", "clearance", "slope", "t1", "v1", "tau", "f_tau",
                      "F_max"]
SIMULATION_COLUMNS = ["F_sim", "sim_rel_diff", "sim_steps", "sim_time_s", "closed_time_s",
                      "separates"]
MECHANISM_COLUMNS = ["joint", "reversal", "angle_deg", "slope", "t1", "v1", "tau", "f_tau",
                     "F_max", "F_clearance", "F_rigid", "amplification", "mass", "stiffness",
                     "clearance", "line_deg", "wander_deg"]
TITLE = "Dresig & Thümmel, eq. (36)"
UNITS = {"speed_rpm": "rpm", "mass": "kg", "stiffness": "N/m", "clearance": "m",
         "slope": "N/s", "t1": "s", "v1": "m/s", "tau": "-", "f_tau": "-", "F_max": "N",
         "F_clearance": "N", "F_rigid": "N", "amplification": "-", "angle_deg": "°",
         "line_deg": "°", "wander_deg": "°", "reversal": "-", "joint": "",
         "F_sim": "N", "sim_rel_diff": "-", "sim_steps": "-", "sim_time_s": "s",
         "closed_time_s": "s", "separates": "1/0"}


def standalone_rows(mass: float, stiffness: float, gap: float,
                    cases: list[tuple[float | None, float]], simulate: bool, sim_steps: int
                    ) -> list[dict]:
    """One row per (speed [rpm] or None, slope [N/s]): the closed form, timed, and with
    ``simulate`` the direct simulation next to it."""
    rows = []
    for rpm, k in cases:
        started = time.perf_counter()
        peak = engine.peak_force(mass, stiffness, clearance=gap, slope=k)
        closed_time = time.perf_counter() - started
        row = {"speed_rpm": rpm, "mass": mass, "stiffness": stiffness, "clearance": gap,
               "slope": k, "t1": peak.t1, "v1": peak.v1, "tau": peak.tau, "f_tau": peak.f_tau,
               "F_max": peak.force, "F_clearance": peak.clearance_share,
               "F_rigid_share": peak.rigid_share, "soft": peak.soft,
               "closed_time_s": closed_time}
        if simulate:
            row.update(simulated(mass, stiffness, gap, k, sim_steps, peak.force))
        rows.append(row)
    return rows


def standalone_names(speeds: bool, simulate: bool) -> list[str]:
    return (["speed_rpm"] if speeds else []) + STANDALONE_COLUMNS + (SIMULATION_COLUMNS if simulate else [])


def standalone_table(rows: list[dict], speeds: bool, simulate: bool):
    from rich.table import Table

    table = Table(title=f"Clearance peak force ({TITLE})", title_justify="left")
    if not speeds:
        row = rows[0]
        for head in ("quantity", "value", "unit"):
            table.add_column(head, justify="right" if head == "value" else "left")
        lines = [("reduced mass m", "mass", "kg"), ("contact stiffness c", "stiffness", "N/m"),
                 ("clearance 2s", "clearance", "m"), ("force slope F0/t0", "slope", "N/s"),
                 ("free flight t1, eq. (15)", "t1", "s"), ("impact speed v1, eq. (16)", "v1", "m/s"),
                 ("τ = ω·t1, eq. (23)", "tau", "-"), ("f(τ), eq. (36)", "f_tau", "-"),
                 ("peak force F12max = c·s·f(τ)", "F_max", "N"),
                 ("  clearance share 6·c·s/τ", "F_clearance", "N"),
                 ("  rigid force reached by then", "F_rigid_share", "N")]
        if simulate:
            lines += [("simulated peak (RK4)", "F_sim", "N"),
                      ("  relative difference", "sim_rel_diff", "-"),
                      ("  RK4 steps", "sim_steps", ""), ("time: closed form", "closed_time_s", "s"),
                      ("time: simulation", "sim_time_s", "s")]
        for label, key, unit in lines:
            table.add_row(label, cell_pretty(row[key]), unit)
    else:
        show_cols = [("speed_rpm", "speed [rpm]"), ("slope", "F0/t0 [N/s]"), ("tau", "τ [-]"),
                     ("F_max", "F12max [N]"), ("F_clearance", "6cs/τ [N]")]
        if simulate:
            show_cols += [("F_sim", "simulated [N]")]
        fill(table, show_cols, rows)
    return table


def simulated(mass, stiffness, gap, slope, steps, closed) -> dict:
    started = time.perf_counter()
    sim = engine.simulate(mass, stiffness, clearance=gap, slope=slope, steps_per_period=steps)
    elapsed = time.perf_counter() - started
    return {"F_sim": sim.force, "sim_rel_diff": (sim.force - closed) / closed,
            "sim_steps": sim.steps, "sim_time_s": elapsed, "separates": sim.separates,
            "separation_time": sim.separation_time, "rebound_speed": sim.rebound_speed,
            "contact_to_peak": sim.contact_to_peak}


def notes(row: dict, where: str = "") -> list[str]:
    out = []
    if row.get("soft"):
        out.append(f"note: {where}τ = {row['tau']:.3g} < 2: a soft impact. The first maximum of "
                   f"eq. (26) comes after the first contact half-wave, where the paper's eq. (36) "
                   f"(principal arccos) does not apply; dyade gives that true first maximum. For "
                   f"τ ≪ 2 it is only a small ripple on the rising rigid force: there is no knock.")
    if row.get("separates"):
        out.append(f"note: {where}after the peak the masses separate at t = "
                   f"{row['separation_time']:.4g} s (rebound at {row['rebound_speed']:.3g} m/s): "
                   f"a second impact follows.")
    elif "separates" in row:
        out.append(f"note: {where}the masses stay in contact through the first contact period "
                   f"(the closed form's assumption holds).")
    return out




def mechanism_rows(study: list[tuple[float | None, list]], simulate: bool, sim_steps: int
                   ) -> tuple[list[dict], list]:
    """One row per reversal of each checked joint at each speed; and the checks of the
    first speed that gave no rows (no reversal, or the model does not apply). Over a
    speed range a joint that gives no reversal rows at a speed gets a row of its own
    with the reason in ``note``, so that no speed is silently missing."""
    rows, skipped = [], []
    first = study[0][0]
    for rpm, checks in study:
        for check in checks:
            if rpm is not None and not (check.applies and check.reversals):
                a, b = check.joint
                why = (check.reason if not check.applies
                       else "no reversal: the force keeps one sense over the cycle")
                rows.append({"speed_rpm": rpm, "joint": f"{a}-{b}", "note": f"not checked — "
                             f"{_flagged(check, why)}" if not check.applies else why})
            if not check.applies:
                if rpm == first:
                    skipped.append(check)
                continue
            for number, rev in enumerate(check.reversals, 1):
                peak = rev.peak
                row = {"speed_rpm": rpm, "joint": f"{check.joint[0]}-{check.joint[1]}",
                       "reversal": number, "angle_deg": float(np.rad2deg(rev.crank_angle)),
                       "slope": peak.slope, "t1": peak.t1, "v1": peak.v1, "tau": peak.tau,
                       "f_tau": peak.f_tau, "F_max": peak.force,
                       "F_clearance": peak.clearance_share, "F_rigid": rev.rigid_force,
                       "amplification": rev.amplification, "mass": peak.mass,
                       "stiffness": peak.stiffness, "clearance": peak.clearance,
                       "line_deg": float(np.rad2deg(check.line_angle)),
                       "wander_deg": float(np.rad2deg(check.wander)), "soft": peak.soft,
                       "impacts": len(check.reversals), "mass_source": check.mass_source}
                if simulate:
                    row.update(simulated(peak.mass, peak.stiffness, peak.clearance,
                                         peak.slope, sim_steps, peak.force))
                    row["rebound"] = (f"{row['rebound_speed']:.3g}" if row["separates"]
                                      else "none")
                rows.append(row)
            if not check.reversals and rpm == first:
                skipped.append(check)
    return rows, skipped


def mechanism_names(speeds: bool, simulate: bool) -> list[str]:
    return ((["speed_rpm"] if speeds else []) + MECHANISM_COLUMNS
            + (["F_sim", "sim_rel_diff", "separates", "rebound_speed"] if simulate else [])
            + (["note"] if speeds else []))


def mechanism_warnings(skipped: list, rows: list[dict]) -> list[str]:
    warnings = []
    for check in skipped:
        a, b = check.joint
        if check.applies:
            warnings.append(f"joint ({a},{b}): the force keeps one sense over the cycle (line of "
                            f"action {np.rad2deg(check.line_angle):.0f}°): no reversal, no "
                            f"clearance impact.")
        else:
            warnings.append(f"joint ({a},{b}): not checked — {_flagged(check, check.reason)}.")
    if any(row.get("soft") for row in rows):
        warnings.append("note: reversals with τ < 2 are soft impacts: their peak comes after the "
                        "first contact half-wave (see `dyade clearance --help`).")
    for row in rows:  # with --simulate: what happens after each peak
        if row.get("separates"):
            at = f" at {row['speed_rpm']:g} rpm" if row.get("speed_rpm") is not None else ""
            where = f"joint ({row['joint'].replace('-', ',')}) reversal {row['reversal']}{at}: "
            warnings += [line for line in notes(row, where) if "separate" in line]
    return warnings


def _flagged(check, reason: str) -> str:
    """A check's reason with the missing inputs named as the command's flags."""
    if not check.missing:
        return reason
    a, b = check.joint
    return MISSING[check.missing].format(a=a, b=b, stiffness="--stiffness",
                                         clearance="--clearance", mass="--mass")


def mechanism_table(name, rows, speeds, simulate):
    from rich.table import Table

    lines = {}
    for row in rows:
        if "line_deg" in row:
            lines.setdefault(row["joint"], (row["line_deg"], row["wander_deg"], row["mass"],
                                            row["mass_source"]))
    caption = "; ".join(f"({j.replace('-', ',')}): line {line:.0f}°, wander {wander:.0f}°, "
                        f"m = {mass:.3g} kg ({source})"
                        for j, (line, wander, mass, source) in lines.items())
    if caption:
        caption += ". One impact per row and revolution; sim: the direct simulation."
    table = Table(title=f"{name}: clearance peaks per reversal (Dresig & Thümmel)", title_justify="left",
                  caption=caption or None, caption_justify="left")
    show = [("speed_rpm", "speed [rpm]")] if speeds else []
    show += [("joint", "joint"), ("angle_deg", "φ21 [°]"),
             ("slope", "F0/t0 [N/s]"), ("tau", "τ [-]"), ("F_max", "F12max [N]"),
             ("F_rigid", "rigid [N]"), ("amplification", "× [-]")]
    if simulate:
        show += [("F_sim", "sim [N]"), ("rebound", "rebound [m/s]")]
    if any("note" in row for row in rows):
        show += [("note", "note")]
    fill(table, show, rows)
    return table


def fill(table, show: list[tuple[str, str]], rows: list[dict]) -> None:
    """Right-aligned columns (key, heading) and one table row per result row."""
    for key, head in show:
        table.add_column(head, justify="left" if key in ("note", "rebound") else "right")
    for row in rows:
        table.add_row(*[cell_pretty(row.get(key)) for key, _ in show])


def cell_pretty(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.5g}" if abs(value) < 1e5 else f"{value:.4g}"
    return str(value)

