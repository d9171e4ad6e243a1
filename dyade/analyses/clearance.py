"""``clearance-peak``, ``clearance-check``, ``clearance-speeds``: the peak force in a
revolute joint with clearance (Dresig & Thümmel, eq. (36)).

Where a joint force reverses its sense, the pin crosses the clearance 2s and strikes the
bearing.

- ``clearance-peak``: standalone, from four numbers (reduced mass, contact stiffness,
  clearance, force slope F0/t0), optionally over a range of crank speeds (the slope grows
  with Ω³, eq. (30)); ``simulate`` integrates the two-mass model beside the closed form.
- ``clearance-check``: over a mechanism (a file, its text or a ``Mechanism``): each
  revolute joint's dominant line of action, whether the force keeps to it, and every
  reversal with its slope, τ, f(τ), peak force and amplification over the rigid force.
- ``clearance-speeds``: the same check at each crank speed of a range.

This module imports no numpy at import time.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field
from typing import Any

from dyade.analyses import inputs
from dyade.analyses.base import Analysis, Budget, Option, Outcome, withheld

SIM_TIME = 1e-4  # [s per case and RK4 step per contact period] a direct simulation
TITLE = "Dresig & Thümmel, eq. (36)"

MASS = Option("mass", float, "kg", multiple=True, positive=True, metavar="KG",
              help="Reduced mass m; give it twice (--mass m11 --mass m22) for the two masses "
                   "of eq. (17). With a file: default from the joint's `clearance.mass` or the "
                   "two links' masses")
STIFFNESS = Option("stiffness", float, "N/m", positive=True,
                   help="Contact stiffness c (typical 1e7…1e9)")
CLEARANCE = Option("clearance", float, "m", positive=True,
                   help="Clearance (radial play) 2s (typical 2e-5…2e-4)")
SLOPE = Option("slope", float, "N/s", positive=True,
               help="Standalone: force slope F0/t0 at the reversal")
SPEED = Option("speed", float, "rpm", positive=True, metavar="RPM", old=("--speed-rpm",),
               help="Standalone: crank speed at which --slope holds (for --speed-range)")
SPEED_RANGE = Option("speed-range", str, "rpm", metavar="START:STOP:STEP",
                     help="Peak force against crank speed; the slope grows with Ω³ (eq. 30)")
SIMULATE = Option("simulate", bool,
                  help="Also integrate the two-mass model directly; report its peak, the cost "
                       "of each method and whether contact holds (rebound)")
SIM_STEPS = Option("sim-steps", int, default=400, metavar="N",
                   help="RK4 steps per contact period for --simulate (at least 10)")
JOINT = Option("joint", str, multiple=True, metavar="I,J",
               help="Revolute joint to check, e.g. --joint 5,6 (repeatable); default: every "
                    "revolute joint")
MAX_WANDER = Option("max-wander", float, "°", default=20.0, metavar="DEG",
                    help="Largest angle (0…90) the force may leave its line of action (forces "
                         "≥ 25 % of the peak) for the model to apply")
JOBS = Option("jobs", int, default=1, metavar="N", study=False,
              help="Check the speeds on N processes at once (0: all cores); the output is that "
                   "of a serial run, in the same order")

UNITS = {"speed_rpm": "rpm", "mass": "kg", "stiffness": "N/m", "clearance": "m",
         "slope": "N/s", "t1": "s", "v1": "m/s", "tau": "-", "f_tau": "-", "F_max": "N",
         "F_clearance": "N", "F_rigid_share": "N", "F_rigid": "N", "amplification": "-",
         "angle_deg": "°", "line_deg": "°", "wander_deg": "°", "reversal": "-", "joint": "",
         "F_sim": "N", "sim_rel_diff": "-", "sim_steps": "-", "sim_time_s": "s",
         "closed_time_s": "s", "separates": "1/0", "rebound_speed": "m/s", "note": ""}
DESCRIPTIONS = {
    "speed_rpm": "crank speed", "mass": "reduced mass m", "stiffness": "contact stiffness c",
    "clearance": "clearance 2s", "slope": "force slope F0/t0 at the reversal",
    "t1": "free flight t1, eq. (15)", "v1": "impact speed v1, eq. (16)",
    "tau": "τ = ω·t1, eq. (23)", "f_tau": "f(τ), eq. (36)",
    "F_max": "peak force F12max = c·s·f(τ)", "F_clearance": "clearance share 6·c·s/τ",
    "F_rigid_share": "rigid force reached by then", "F_rigid": "rigid force at the peak",
    "amplification": "peak over rigid force", "angle_deg": "crank angle φ21 of the reversal",
    "line_deg": "direction of the joint force's line of action",
    "wander_deg": "largest angle of the force off that line", "reversal": "reversal number",
    "joint": "the joint (links I-J)", "F_sim": "simulated peak (RK4)",
    "sim_rel_diff": "relative difference of the simulated peak",
    "sim_steps": "RK4 steps", "sim_time_s": "time of the simulation",
    "closed_time_s": "time of the closed form", "separates": "the masses separate after the peak",
    "rebound_speed": "relative speed at separation", "note": "why a joint gives no row"}
STANDALONE = ["mass", "stiffness", "clearance", "slope", "t1", "v1", "tau", "f_tau", "F_max",
              "F_clearance", "F_rigid_share"]
SIMULATION = ["F_sim", "sim_rel_diff", "sim_steps", "sim_time_s", "closed_time_s", "separates"]
MECHANISM = ["joint", "reversal", "angle_deg", "slope", "t1", "v1", "tau", "f_tau", "F_max",
             "F_clearance", "F_rigid", "amplification", "mass", "stiffness", "clearance",
             "line_deg", "wander_deg"]
MECHANISM_SIMULATION = ["F_sim", "sim_rel_diff", "separates", "rebound_speed"]
ENGINE = {"joints": JOINT.api, "speeds_rpm": SPEED_RANGE.api}
"""the engine's parameters -> the options they come from"""
TEXT = ("joint", "note")
"""the columns of text (the others are numbers, NaN where not given)"""


@dataclass
class Worst:
    """The largest peak of a run, simulated with its history (for the figure)."""

    label: str
    """"standalone", or the joint and reversal "(5,6) #1" """
    peak: Any
    """``dyade.clearance.Peak``"""
    simulation: Any
    """``dyade.clearance.Simulation`` with ``history=True``"""


@dataclass
class Peaks:
    """What ``clearance-peak`` found: the case at the given slope, the cases over speed
    (None: no speed range) and the simulated history of the given case (``simulate``)."""

    peak: Any
    speed_rpm: float | None = None
    over_speed: list[tuple[float, Any]] | None = None
    history: Worst | None = None


@dataclass
class Checked:
    """What ``clearance-check`` and ``clearance-speeds`` found: (speed [rpm] or None,
    the checks) per speed, the mechanism and its operating speed [rpm], and the largest
    peak simulated with its history (``simulate``, the check only)."""

    mechanism: Any
    study: list[tuple[float | None, list]]
    speed_rpm: float
    history: Worst | None = None
    rows: list[dict] = field(default_factory=list)


# -- shared ---------------------------------------------------------------------------
def reduced(masses) -> float | None:
    """One reduced mass [kg] of one or two masses (eq. 17); None for none."""
    from dyade import clearance as engine
    from dyade.errors import InputError

    masses = tuple(masses or ())
    if len(masses) > 2:
        raise InputError.parameter(MASS.api, "takes one reduced mass, or the two masses m11 "
                                             "and m22.", value=masses, unit="kg")
    if len(masses) == 2:
        return engine.reduced_mass(*masses)
    return masses[0] if masses else None


def sim_steps(options: dict[str, Any]) -> int:
    """The RK4 steps per contact period, at least 10."""
    from dyade.errors import InputError

    steps = options[SIM_STEPS.api]
    if steps < 10:
        raise InputError.parameter(SIM_STEPS.api, f"must be at least 10, got {steps}.",
                                   value=steps)
    return steps


def simulated(mass, stiffness, gap, slope, steps, closed) -> dict:
    """The direct simulation of one case, timed, beside its closed-form peak ``closed``."""
    from dyade import clearance as engine

    started = time.perf_counter()
    sim = engine.simulate(mass, stiffness, clearance=gap, slope=slope, steps_per_period=steps)
    elapsed = time.perf_counter() - started
    return {"F_sim": sim.force, "sim_rel_diff": (sim.force - closed) / closed,
            "sim_steps": sim.steps, "sim_time_s": elapsed, "separates": sim.separates,
            "separation_time": sim.separation_time, "rebound_speed": sim.rebound_speed,
            "contact_to_peak": sim.contact_to_peak}


def history(label: str, peak, steps: int) -> Worst:
    """The case ``peak`` simulated with its force history."""
    from dyade import clearance as engine

    return Worst(label, peak, engine.simulate(peak.mass, peak.stiffness, clearance=peak.clearance,
                                              slope=peak.slope, steps_per_period=steps,
                                              history=True))


def columns(outcome: Outcome, rows: list[dict], names: list[str]) -> None:
    """The rows as the Outcome's columns ``names`` (numbers as float arrays, NaN where
    not given; text and flags as they are, None where not given)."""
    import numpy as np

    cols: dict[str, Any] = {}
    for name in names:
        values = [row.get(name) for row in rows]
        if name in TEXT or name == "separates":
            cols[name] = np.array(values, dtype=object)
        else:
            cols[name] = np.array([np.nan if v is None else v for v in values], dtype=float)
    outcome.columns = cols
    outcome.units = {name: UNITS[name] for name in names}
    outcome.descriptions = {name: DESCRIPTIONS[name] for name in names}


def row_notes(row: dict, where: str = "") -> list[str]:
    """A soft impact and what follows the peak (``simulate``), worded."""
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


# -- standalone ---------------------------------------------------------------------------
def run_peak(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``clearance-peak``: the peak force of the four numbers (at each speed of a speed
    range), with the direct simulation beside it where asked."""
    from dyade import clearance as engine
    from dyade.analyses.ranges import values
    from dyade.errors import InputError

    mass = reduced(options[MASS.api])
    given = {MASS.api: mass, STIFFNESS.api: options[STIFFNESS.api],
             CLEARANCE.api: options[CLEARANCE.api], SLOPE.api: options[SLOPE.api]}
    missing = tuple(name for name, value in given.items() if value is None)
    if missing:
        raise InputError.parameter(missing, "must be given: the standalone check needs the "
                                            "reduced mass, the contact stiffness, the clearance "
                                            "and the force slope (or give a mechanism file).")
    stiffness, gap, slope = given[STIFFNESS.api], given[CLEARANCE.api], given[SLOPE.api]
    speed_rpm = options[SPEED.api]
    speeds = None
    if options[SPEED_RANGE.api] is not None:
        speeds = values(options[SPEED_RANGE.api], SPEED_RANGE.api, "rpm", positive_start=True)
        if speed_rpm is None:
            raise InputError.parameter(SPEED.api, "must be given with a speed range: the crank "
                                                  "speed at which the slope holds.")
    simulate = bool(options[SIMULATE.api])
    steps = sim_steps(options)
    cases = ([(None, slope)] if not speeds
             else [(rpm, engine.scaled_slope(slope, speed_rpm, rpm)) for rpm in speeds])
    if simulate:
        budget.time(SIM_TIME * steps * (len(cases) + 1),
                    f"the direct simulation of {len(cases):,} case{'s' * (len(cases) != 1)}")
    rows = []
    for rpm, k in cases:
        started = time.perf_counter()
        peak = engine.peak_force(mass, stiffness, clearance=gap, slope=k)
        closed_time = time.perf_counter() - started
        row = {"speed_rpm": rpm, "mass": mass, "stiffness": stiffness, "clearance": gap,
               "slope": k, "t1": peak.t1, "v1": peak.v1, "tau": peak.tau, "f_tau": peak.f_tau,
               "F_max": peak.force, "F_clearance": peak.clearance_share,
               "F_rigid_share": peak.rigid_share, "soft": peak.soft,
               "closed_time_s": closed_time, "peak": peak}
        if simulate:
            row.update(simulated(mass, stiffness, gap, k, steps, peak.force))
        rows.append(row)
    base = engine.peak_force(mass, stiffness, clearance=gap, slope=slope)
    result = Peaks(base, speed_rpm, [(row["speed_rpm"], row["peak"]) for row in rows]
                   if speeds else None,
                   history("standalone", base, steps) if simulate else None)
    outcome = Outcome("clearance-peak", figures=("clearance",), result=result,
                      meta={"cases": len(rows)})
    columns(outcome, rows, (["speed_rpm"] if speeds else []) + STANDALONE
            + (SIMULATION if simulate else []))
    worst = max(rows, key=lambda row: row["F_max"])
    where = {"speed_rpm": worst["speed_rpm"]} if speeds else None
    outcome.add("F_max", worst["F_max"], "N", where=where,
                description="peak force F12max = c·s·f(τ)" + (" (the largest)" * bool(speeds)))
    outcome.add("tau", worst["tau"], "-", where=where, description="τ = ω·t1 there, eq. (23)")
    if simulate:
        outcome.add("F_sim", worst["F_sim"], "N", where=where,
                    description="simulated peak (RK4) there")
    outcome.notes = [line for row in rows for line in row_notes(row)]
    return outcome


# -- over a mechanism -----------------------------------------------------------------
def joints_of(options: dict[str, Any]) -> list[tuple[int, int]] | None:
    """The ``joint`` option as (a, b) pairs, a < b (None: every revolute joint); each
    given as "5,6" or (5, 6)."""
    from dyade.errors import InputError

    out = []
    for joint in options.get(JOINT.api) or ():
        try:
            a, b = (int(part) for part in (joint.split(",") if isinstance(joint, str)
                                           else joint))
        except (TypeError, ValueError):
            raise InputError.parameter(JOINT.api, f"must be two link numbers like 5,6, got "
                                                  f"{joint!r}.", value=joint) from None
        out.append((a, b) if a < b else (b, a))
    return out or None


def check_options(options: dict[str, Any]) -> dict[str, Any]:
    """The keyword arguments of ``dyade.check_clearance`` from the options."""
    from dyade.errors import InputError

    stiffness, gap = options[STIFFNESS.api], options[CLEARANCE.api]
    if (stiffness is None) != (gap is None):
        raise InputError.parameter((STIFFNESS.api, CLEARANCE.api),
                                   "go together: give both, or neither to use the clearance "
                                   "data of the mechanism file.")
    wander = options[MAX_WANDER.api]
    if not 0.0 <= wander <= 90.0:
        raise InputError.parameter(MAX_WANDER.api, f"must lie in 0…90 °, got {wander:g}.",
                                   value=wander, unit="°")
    return {"joints": joints_of(options), "stiffness": stiffness, "clearance": gap,
            "mass": reduced(options[MASS.api]), "max_wander_deg": wander,
            "allow_partial": bool(options[inputs.ALLOW_PARTIAL.api])}


def flagged(check, reason: str) -> str:
    """A check's reason with its missing inputs named as the options."""
    from dyade.linkage.joint_clearance import MISSING

    if not check.missing:
        return reason
    a, b = check.joint
    return MISSING[check.missing].format(a=a, b=b, stiffness="--stiffness",
                                         clearance="--clearance", mass="--mass")


def mechanism_rows(study, simulate: bool, steps: int) -> tuple[list[dict], list]:
    """One row per reversal of each checked joint at each speed; and the checks of the
    first speed that gave no rows (no reversal, or the model does not apply). Over a
    speed range a joint that gives no reversal rows at a speed gets a row of its own
    with the reason in ``note``, so that no speed is silently missing."""
    import numpy as np

    rows, skipped = [], []
    first = study[0][0]
    for rpm, checks in study:
        for check in checks:
            if rpm is not None and not (check.applies and check.reversals):
                a, b = check.joint
                why = (check.reason if not check.applies
                       else "no reversal: the force keeps one sense over the cycle")
                rows.append({"speed_rpm": rpm, "joint": f"{a}-{b}", "note": f"not checked — "
                             f"{flagged(check, why)}" if not check.applies else why})
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
                       "impacts": len(check.reversals), "mass_source": check.mass_source,
                       "peak": peak}
                if simulate:
                    row.update(simulated(peak.mass, peak.stiffness, peak.clearance,
                                         peak.slope, steps, peak.force))
                rows.append(row)
            if not check.reversals and rpm == first:
                skipped.append(check)
    return rows, skipped


def mechanism_notes(skipped: list, rows: list[dict]) -> list[str]:
    """The joints not checked (and why), soft impacts, rebounds, worded."""
    import numpy as np

    notes = []
    for check in skipped:
        a, b = check.joint
        if check.applies:
            notes.append(f"joint ({a},{b}): the force keeps one sense over the cycle (line of "
                         f"action {np.rad2deg(check.line_angle):.0f}°): no reversal, no "
                         f"clearance impact.")
        else:
            notes.append(f"joint ({a},{b}): not checked — {flagged(check, check.reason)}.")
    if any(row.get("soft") for row in rows):
        notes.append("note: reversals with τ < 2 are soft impacts: their peak comes after the "
                     "first contact half-wave (see `dyade clearance --help`).")
    for row in rows:  # with simulate: what happens after each peak
        if row.get("separates"):
            at = f" at {row['speed_rpm']:g} rpm" if row.get("speed_rpm") is not None else ""
            where = f"joint ({row['joint'].replace('-', ',')}) reversal {row['reversal']}{at}: "
            notes += [line for line in row_notes(row, where) if "separate" in line]
    return notes


def nothing_to_compute(checks, label: str) -> None:
    """An ``InputError`` where no joint has clearance data."""
    from dyade.errors import InputError

    if checks and all(check.missing == "data" for check in checks):
        raise InputError(f"{label}: nothing to compute: no joint has clearance data. Give "
                         f"--stiffness and --clearance, or `clearance = {{ gap = …, stiffness = "
                         f"… }}` in a joint table.", source=label)


def label_of(loaded) -> str:
    """The mechanism's file as messages name it."""
    if loaded.text is None:
        return loaded.mechanism.name
    return loaded.label if loaded.label == "<stdin>" else os.path.basename(loaded.label)


def mechanism_outcome(name: str, loaded, study, arguments: dict[str, Any], simulate: bool,
                      steps: int, speeds: bool) -> Outcome:
    """The Outcome of a check over a mechanism at one speed or several (``study``: (speed
    [rpm] or None, checks) per speed; ``arguments``: those of the check)."""
    from dyade.units import RPM

    mechanism = loaded.mechanism
    rows, skipped = mechanism_rows(study, simulate, steps)
    outcome = Outcome(name, figures=("clearance",))
    columns(outcome, rows, (["speed_rpm"] if speeds else []) + MECHANISM
            + (MECHANISM_SIMULATION if simulate else []) + (["note"] if speeds else []))
    joints = arguments["joints"] or [j.name for j in mechanism.joints if j.kind == "R"]
    outcome.meta = {"name": mechanism.name, "source": None if loaded.text is None
                    else loaded.label, "joints": [f"{a}-{b}" for a, b in joints]}
    peaks = [row for row in rows if "F_max" in row]
    outcome.add("reversals", len(peaks), "-",
                description="reversals checked (impacts per revolution" +
                            (", over every speed)" if speeds else ")"))
    if peaks:
        worst = max(peaks, key=lambda row: row["F_max"])
        where = {"joint": worst["joint"], "angle_deg": worst["angle_deg"]}
        if speeds:
            where = {"speed_rpm": worst["speed_rpm"], **where}
        outcome.add("F_max", worst["F_max"], "N", where=where,
                    description="largest peak force F12max")
        most = max(peaks, key=lambda row: row["amplification"])
        where = {"joint": most["joint"], "angle_deg": most["angle_deg"]}
        if speeds:
            where = {"speed_rpm": most["speed_rpm"], **where}
        outcome.add("amplification_max", most["amplification"], "-", where=where,
                    description="largest amplification over the rigid force")
    outcome.notes = mechanism_notes(skipped, rows)
    outcome.result = Checked(mechanism, study, abs(mechanism.crank.speed) / RPM, None, rows)
    return outcome


def run_check(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``clearance-check``: every reversal of the mechanism's revolute joints (those
    asked) with its peak force; the largest simulated with its history where asked."""
    from dyade.analyses.machine import withholding
    from dyade.errors import InputError
    from dyade.linkage.clearance_study import check
    from dyade.linkage.sweep import analyse

    loaded = inputs.load(source, options)
    arguments = check_options(options)
    simulate, steps = bool(options[SIMULATE.api]), sim_steps(options)
    result = analyse(loaded.mechanism, allow_partial=arguments["allow_partial"])
    try:
        checks = check(loaded.mechanism, result=result, **arguments)
    except InputError as err:
        raise err.naming(ENGINE) from None
    label = label_of(loaded)
    nothing_to_compute(checks, label)
    why = withholding(result.notes)
    withheld(Outcome("clearance-check"), [check.missing != "forces" for check in checks],
             f"{label}: no crank position of the sweep has its joint forces given (every "
             f"position is withheld{f': {why}' if why else ''})")
    if simulate:
        count = sum(len(c.reversals) for c in checks)
        budget.time(SIM_TIME * steps * (count + 1),
                    f"the direct simulation of {count:,} reversal{'s' * (count != 1)}")
    outcome = mechanism_outcome("clearance-check", loaded, [(None, checks)], arguments,
                                simulate, steps, False)
    if simulate:
        cases = [(f"({c.joint[0]},{c.joint[1]}) #{k}", rev.peak)
                 for c in checks for k, rev in enumerate(c.reversals, 1)]
        if cases:
            label_, peak = max(cases, key=lambda case: case[1].force)
            outcome.result.history = history(label_, peak, steps)
    return outcome


def run_speeds(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``clearance-speeds``: the check at each crank speed of a range (the crank keeps
    its sense of rotation), every joint accounted for at every speed."""
    from dyade.analyses.machine import sweep_seconds
    from dyade.analyses.ranges import values
    from dyade.errors import InputError
    from dyade.linkage.clearance_study import speed_study

    loaded = inputs.load(source, options)
    arguments = check_options(options)
    simulate, steps = bool(options[SIMULATE.api]), sim_steps(options)
    if options[SPEED_RANGE.api] is None:
        raise InputError.parameter(SPEED_RANGE.api, "must be given: the crank speeds of the "
                                                    "study, START:STOP:STEP [rpm].")
    speeds = values(options[SPEED_RANGE.api], SPEED_RANGE.api, "rpm", positive_start=True)
    jobs = options[JOBS.api]
    if jobs < 0:
        raise InputError.parameter(JOBS.api, f"must be 0 (all cores) or more, got {jobs}.",
                                   value=jobs)
    workers = jobs if jobs > 0 else (os.cpu_count() or 1)
    mechanism = loaded.mechanism
    budget.time(sweep_seconds(mechanism, mechanism.sweep.count) * len(speeds)
                / min(workers, len(speeds)), f"the clearance check at {len(speeds):,} speeds")
    try:
        study = speed_study(mechanism, speeds, progress=budget.progress, workers=workers,
                            **arguments)
    except InputError as err:
        raise err.naming(ENGINE) from None
    label = label_of(loaded)
    nothing_to_compute([check for _, checks in study for check in checks], label)
    withheld(Outcome("clearance-speeds"), [any(check.missing != "forces" for check in checks) for _, checks in study],
             f"{label}: no crank speed of the study has its joint forces given at any crank "
             f"position (every position is withheld; `dyade analyse` says why)")
    if simulate:
        count = sum(len(c.reversals) for _, checks in study for c in checks)
        budget.time(SIM_TIME * steps * count,
                    f"the direct simulation of {count:,} reversal{'s' * (count != 1)}")
    return mechanism_outcome("clearance-speeds", loaded, study, arguments, simulate, steps, True)


CHECK = (inputs.SET, *inputs.SWEEP, inputs.ALLOW_PARTIAL, JOINT, MASS, STIFFNESS, CLEARANCE,
         MAX_WANDER, SIMULATE, SIM_STEPS)
"""the options of a check over a mechanism"""

ENTRIES = {
    "clearance-peak": Analysis("clearance-peak", "Clearance peak force from four numbers "
                               "(Dresig & Thümmel)", run_peak,
                               (MASS, STIFFNESS, CLEARANCE, SLOPE, SPEED, SPEED_RANGE, SIMULATE,
                                SIM_STEPS), source="", figures=("clearance",),
                               command="dyade clearance --mass --stiffness --clearance --slope"),
    "clearance-check": Analysis("clearance-check", "Clearance peaks of a mechanism's revolute "
                                "joints (Dresig & Thümmel)", run_check, CHECK,
                                figures=("clearance",), command="dyade clearance MECHANISM"),
    "clearance-speeds": Analysis("clearance-speeds", "Clearance peaks of a mechanism's joints "
                                 "against crank speed", run_speeds,
                                 CHECK + (SPEED_RANGE, JOBS), figures=("clearance",),
                                 command="dyade clearance MECHANISM --speed-range"),
}
