"""The clearance entries' Outcomes (``dyade.analyses.clearance``) -> rich tables: the
standalone peak (one case, or over speed) and the peaks per reversal over a mechanism
(at one speed, or several). Every number through ``dyade.report.format.number``."""

from __future__ import annotations

from typing import Any

from dyade.analyses.clearance import TITLE
from dyade.report.format import number

STANDALONE_LINES = [("reduced mass m", "mass", "kg"), ("contact stiffness c", "stiffness", "N/m"),
                    ("clearance 2s", "clearance", "m"), ("force slope F0/t0", "slope", "N/s"),
                    ("free flight t1, eq. (15)", "t1", "s"),
                    ("impact speed v1, eq. (16)", "v1", "m/s"),
                    ("τ = ω·t1, eq. (23)", "tau", "-"), ("f(τ), eq. (36)", "f_tau", "-"),
                    ("peak force F12max = c·s·f(τ)", "F_max", "N"),
                    ("  clearance share 6·c·s/τ", "F_clearance", "N"),
                    ("  rigid force reached by then", "F_rigid_share", "N")]
SIMULATION_LINES = [("simulated peak (RK4)", "F_sim", "N"),
                    ("  relative difference", "sim_rel_diff", "-"),
                    ("  RK4 steps", "sim_steps", "-"), ("time: closed form", "closed_time_s", "s"),
                    ("time: simulation", "sim_time_s", "s")]


def shown(value: Any) -> str:
    """A value of a clearance table: 5 significant digits (4 from 1e5 up)."""
    if isinstance(value, float) and abs(value) >= 1e5:
        return number(value, spec=".4g")
    return number(value, spec=".5g")


def standalone_table(outcome):
    """A ``clearance-peak`` Outcome: quantity | value | unit for one case, or one row per
    speed of a speed range."""
    from rich.table import Table

    cols = outcome.columns
    simulate = "F_sim" in cols
    table = Table(title=f"Clearance peak force ({TITLE})", title_justify="left")
    if "speed_rpm" not in cols:
        for head in ("quantity", "value", "unit"):
            table.add_column(head, justify="right" if head == "value" else "left")
        for label, key, unit in STANDALONE_LINES + (SIMULATION_LINES if simulate else []):
            table.add_row(label, shown(cols[key][0].item()), unit)
        return table
    show = [("speed_rpm", "speed [rpm]"), ("slope", "F0/t0 [N/s]"), ("tau", "τ [-]"),
            ("F_max", "F12max [N]"), ("F_clearance", "6cs/τ [N]")]
    if simulate:
        show += [("F_sim", "simulated [N]")]
    fill(table, show, [{key: cols[key][k].item() for key, _ in show}
                       for k in range(len(cols["speed_rpm"]))])
    return table


def mechanism_table(outcome):
    """A ``clearance-check`` or ``clearance-speeds`` Outcome: one row per reversal (and,
    over speeds, per joint not checked at a speed, with the reason); the caption gives
    each joint's line of action, wander and reduced mass."""
    from rich.table import Table

    checked = outcome.result
    cols = outcome.columns
    rows = [{name: values[k] for name, values in cols.items()}
            for k in range(len(cols["joint"]))]
    lines = {}
    for row in checked.rows:
        if "line_deg" in row:
            lines.setdefault(row["joint"], (row["line_deg"], row["wander_deg"], row["mass"],
                                            row["mass_source"]))
    caption = "; ".join(f"({j.replace('-', ',')}): line {number(line, spec='.0f')}°, wander "
                        f"{number(wander, spec='.0f')}°, m = {number(mass, spec='.3g')} kg "
                        f"({source})" for j, (line, wander, mass, source) in lines.items())
    if caption:
        caption += ". One impact per row and revolution; sim: the direct simulation."
    table = Table(title=f"{checked.mechanism.name}: clearance peaks per reversal (Dresig & "
                        f"Thümmel)", title_justify="left", caption=caption or None,
                  caption_justify="left")
    speeds = "speed_rpm" in cols
    show = [("speed_rpm", "speed [rpm]")] if speeds else []
    show += [("joint", "joint"), ("angle_deg", "φ21 [°]"),
             ("slope", "F0/t0 [N/s]"), ("tau", "τ [-]"), ("F_max", "F12max [N]"),
             ("F_rigid", "rigid [N]"), ("amplification", "× [-]")]
    if "F_sim" in cols:
        show += [("F_sim", "sim [N]"), ("rebound", "rebound [m/s]")]
        for row in rows:
            if row["separates"] is not None:
                row["rebound"] = (number(row["rebound_speed"], spec=".3g") if row["separates"]
                                  else "none")
    if any(row.get("note") for row in rows):
        show += [("note", "note")]
    fill(table, show, rows)
    return table


def fill(table, show: list[tuple[str, str]], rows: list[dict]) -> None:
    """Right-aligned columns (key, heading) and one table row per result row."""
    for key, head in show:
        table.add_column(head, justify="left" if key in ("note", "rebound") else "right")
    for row in rows:
        table.add_row(*[text(key, row.get(key)) for key, _ in show])


def text(key: str, value: Any) -> str:
    """A cell: a note or a joint as it is (a joint without a note: empty)."""
    if key in ("note", "rebound"):
        return "" if value is None else str(value)
    if key == "joint":
        return str(value)
    return shown(value.item() if hasattr(value, "item") else value)
