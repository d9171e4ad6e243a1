"""``accuracy``: what each accuracy knob buys and costs, for the user's mechanism
(``dyade.linkage.accuracy``).

The crank step always (5° … 0.05°), the friction tolerance with friction, the closed
form against the direct simulation with clearance data, the drive line's steps with a
``[drive_line]``: each setting timed (best of ``repeats``) and its peaks compared with
the finest setting. The summary gives, per study, the coarsest setting whose every peak
lies within ``RTOL`` of the finest one's (and every finer setting's too).
"""

from __future__ import annotations

import math
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome
from dyade.analyses.inputs import MECHANISM, load

OPTIONS = (
    *MECHANISM,
    Option("repeats", int, default=3, positive=True, metavar="N", study=False,
           help="Runs per setting; the best time counts"),
)

COLUMNS = {  # column -> (unit, description): one row per (study, setting, quantity)
    "study": ("", "crank step, friction tol, clearance or drive line steps"),
    "setting": ("", "the setting of the knob (5°, 1e-06, RK4 400/period, 200 steps)"),
    "time_ms": ("ms", "engine time of the setting, best of the repeats"),
    "quantity": ("", "the peak compared"),
    "value": ("", "the peak, in the row's unit"),
    "unit": ("", "the unit of the row's value"),
    "rel_error": ("-", "relative difference from the finest setting (empty for it)"),
    "note": ("", "positions, friction passes, simulation steps, Newton iterations"),
}

RTOL = 1e-3
"""[-] a peak within this of the finest setting's has stopped moving"""

STUDIES = {"crank step": ("crank_step_deg", "°"), "friction tol": ("friction_tol", "-"),
           "drive line steps": ("drive_line_steps", "-")}
"""study -> (its summary figure: the coarsest setting within RTOL, unit)"""


def unit_of(quantity: str) -> str:
    """The unit of a compared quantity (``dyade.linkage.accuracy``'s names)."""
    if quantity.startswith(("|M_drive|", "|shaft torque|")):
        return "N·m"
    if quantity.startswith(("F_", "FN_", "clearance F12max", "F12max")):
        return "N"
    if quantity.startswith("|alpha_"):
        return "rad/s²"
    if quantity == "twist amplitude":
        return "rad"
    return "-"  # speed fluctuation, largest |mu|


def setting_value(study: str, setting: str) -> float:
    """The number of a setting's label: 5° -> 5, 1e-06 -> 1e-06, 200 steps -> 200."""
    return float(setting.split()[0].rstrip("°"))


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    import numpy as np

    from dyade.analyses.machine import none_given, sweep_seconds
    from dyade.errors import InputError
    from dyade.linkage import accuracy as engine
    from dyade.linkage.options import check_size
    from dyade.linkage.plan import plan
    from dyade.linkage.sweep import analyse_si

    mechanism = load(source, options).mechanism
    repeats = options["repeats"]
    finest = int(round(360 / engine.STEPS_DEG[-1])) + 1
    try:  # the largest sweep of the studies, before any
        check_size(mechanism, max(finest, mechanism.sweep.count), budget.max_memory)
    except InputError as err:
        raise err.naming({"max_memory": "max_memory_mb"}) from None
    # the first setting, run once before the studies: what is given, and the time
    coarse = engine.STEPS_DEG[0]
    angles = mechanism.sweep.start + np.deg2rad(coarse) * np.arange(int(round(360 / coarse)) + 1)
    probe = analyse_si(mechanism, crank_angle=angles)
    cols = probe.columns()
    given = cols["kinematics_valid"] == 1.0
    if "forces_valid" in cols:
        given &= cols["forces_valid"] == 1.0
    if not given.any():
        none_given(mechanism.name, "no crank position of one revolution has its "
                                   f"{'forces' if 'forces_valid' in cols else 'kinematics'} "
                                   "given", probe.notes)
    the_plan = plan(mechanism)
    positions = sum(int(round(360 / step)) + 1 for step in engine.STEPS_DEG)
    seconds = repeats * sweep_seconds(mechanism, positions)
    if the_plan.friction:
        seconds += repeats * len(engine.FRICTION_TOLS) * sweep_seconds(
            mechanism, mechanism.sweep.count)
    if the_plan.drive_line:
        seconds += len(engine.DRIVE_LINE_FACTORS) * DRIVE_LINE_SECONDS
    budget.time(seconds, f"{mechanism.name}: the accuracy studies")
    rows = engine.studies(mechanism, repeats=repeats, progress=budget.progress)
    records = [{"study": r.study, "setting": r.setting, "time_ms": r.time * 1e3,
                "quantity": r.quantity, "value": r.value, "unit": unit_of(r.quantity),
                "rel_error": r.error, "note": r.extra} for r in rows]
    columns = {name: np.array([r[name] for r in records],
                              dtype=np.float64 if name in ("time_ms", "value", "rel_error")
                              else object) for name in COLUMNS}
    outcome = Outcome("accuracy", columns=columns,
                      units={k: unit for k, (unit, _) in COLUMNS.items()},
                      descriptions={k: text for k, (_, text) in COLUMNS.items()},
                      result=records, meta={"name": mechanism.name, "repeats": repeats})
    for study, (name, unit) in STUDIES.items():
        mine = [r for r in records if r["study"] == study]
        if mine:
            setting = converged(mine)
            outcome.add(name, None if setting is None else setting_value(study, setting), unit,
                        description=f"coarsest {study} with every peak within {RTOL:g} of "
                                    f"the finest")
    clearance = [r for r in records if r["study"] == "clearance" and r["setting"] != "closed form"]
    if clearance:
        finest = clearance[-1]["setting"]
        worst = max(r["rel_error"] for r in clearance if r["setting"] == finest)
        outcome.add("clearance_error", worst, "-",
                    description=f"clearance: largest error of the simulation ({finest}) "
                                f"against the closed form")
    if not given.all():
        from dyade.analyses.machine import withholding

        outcome.notes.append(f"the peaks are over the positions where the "
                             f"{'forces are' if 'forces_valid' in cols else 'kinematics is'} "
                             f"given ({withholding(probe.notes) or 'the others withheld'}).")
    return outcome


DRIVE_LINE_SECONDS = 0.5
"""[s] about one steady state of the drive line (the estimate of ``--max-time``)"""


def converged(records: list[dict]) -> str | None:
    """The coarsest setting of one study (its records in the order of its settings, the
    finest last) from which on every peak lies within ``RTOL`` of the finest setting's;
    None where only the finest does."""
    settings = list(dict.fromkeys(r["setting"] for r in records))
    worst = {s: max((r["rel_error"] for r in records if r["setting"] == s
                     and not math.isnan(r["rel_error"])), default=0.0) for s in settings}
    chosen = None
    for setting in reversed(settings[:-1]):
        if not worst[setting] <= RTOL:
            break
        chosen = setting
    return chosen


ENTRIES = {"accuracy": Analysis("accuracy", "What accuracy costs in time, for a mechanism",
                                run, OPTIONS, command="dyade accuracy")}
