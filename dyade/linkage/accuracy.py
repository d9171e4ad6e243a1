"""What accuracy costs: crank step, friction tolerance, clearance simulation and drive line
studies.

Each study reruns the user's mechanism with one knob changed, times the engine (best of
a few runs) and compares the quantities a designer sizes parts by (peak drive torque,
peak joint forces, clearance peaks) with the finest setting.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from dyade.linkage.components import magnitude
from dyade.linkage.plan import plan
from dyade.linkage.sweep import Result, analyse, analyse_si
from dyade.model.mechanism import Mechanism, Revolute
from dyade.roundoff import clean

STEPS_DEG = (5.0, 2.0, 1.0, 0.5, 0.1, 0.05)  # [°] crank steps, the last one is the reference
FRICTION_TOLS = (1e-3, 1e-6, 1e-9, 1e-12)  # [-], the last one is the reference
SIM_STEPS = (25, 100, 400, 1600)  # RK4 steps per contact period


@dataclass(frozen=True, slots=True)
class Row:
    study: str
    """'crank step', 'friction tol' or 'clearance'"""
    setting: str
    time: float
    """engine time [s] (best of the repeats)"""
    quantity: str
    value: float
    error: float
    """relative difference from the reference setting (NaN for the reference itself)"""
    extra: str = ""


def _timed(run, repeats: int):
    best, result = np.inf, None
    for _ in range(repeats):
        started = time.perf_counter()
        result = run()
        best = min(best, time.perf_counter() - started)
    return best, result


def _peaks(mechanism: Mechanism, forces, rows, clearance=None) -> dict[str, float]:
    """Peak |M_drive|, peak joint forces and clearance peaks of one run: its ``forces``
    (``kinetostatics.Forces`` or None), the positions reported (``rows``), its clearance
    check."""
    out: dict[str, float] = {}
    if forces is None:
        return out
    valid = forces.valid & rows
    out["|M_drive| max"] = float(np.max(np.abs(forces.drive_torque[valid]), initial=0.0))
    for joint in mechanism.joints:
        a, b = joint.name
        if isinstance(joint, Revolute):
            size = magnitude(*forces.revolute[joint.name][valid].T)
            out[f"F_{a}_{b} max"] = float(np.max(size, initial=0.0))
        else:
            out[f"FN_{a}_{b} max"] = float(np.max(np.abs(forces.normal[joint.name][valid]),
                                                  initial=0.0))
    largest = max((v for k, v in out.items() if k != "|M_drive| max"), default=0.0)
    for key, value in out.items():  # a joint that carries nothing: round-off is no peak
        if key != "|M_drive| max":
            out[key] = clean(value, largest)
    for check in clearance or []:
        if check.reversals:
            a, b = check.joint
            out[f"clearance F12max {a}_{b}"] = max(r.peak.force for r in check.reversals)
    return out


def _compare(study: str, runs: list[tuple[str, float, dict[str, float], str]]) -> list[Row]:
    reference = runs[-1][2]
    rows = []
    for setting, seconds, peaks, extra in runs:
        for quantity, value in peaks.items():
            ref = reference.get(quantity, np.nan)
            error = np.nan if setting == runs[-1][0] else abs(value - ref) / abs(ref) if ref else np.nan
            rows.append(Row(study, setting, seconds, quantity, value, error, extra))
    return rows


def crank_step(mechanism: Mechanism, steps=STEPS_DEG, repeats: int = 3, tick=None) -> list[Row]:
    """Peaks against the crank step, over one revolution from the file's start angle;
    AssemblyError where the mechanism does not close everywhere (as ``analyse``: peaks
    next to a position that does not close mean nothing)."""
    runs = []
    for step in steps:
        angles = mechanism.sweep.start + np.deg2rad(step) * np.arange(int(round(360 / step)) + 1)
        seconds, result = _timed(lambda: analyse_si(mechanism, crank_angle=angles), repeats)
        peaks = _peaks(mechanism, result.forces, result.rows, result.clearance)
        runs.append((f"{step:g}°", seconds, peaks or _kinematic_peaks(result),
                     f"{angles.size} positions"))
        if tick is not None:
            tick()
    return _compare("crank step", runs)


def _kinematic_peaks(result: Result) -> dict[str, float]:
    """Without forces: the largest angular acceleration of each link."""
    motion = result.kinematics.motion
    return {f"|alpha_{k}| max": float(np.nanmax(np.abs(motion.alpha[result.rows, k])))
            for k in result.mechanism.moving_links[1:]}


def friction_tol(mechanism: Mechanism, tols=FRICTION_TOLS, repeats: int = 3, tick=None
                 ) -> list[Row]:
    """Passes of the friction solution, time and peaks against the friction tolerance."""
    from dyade.linkage import friction, kinematics

    kin = kinematics.sweep(mechanism)
    runs = []
    for tol in tols:
        seconds, rubbing = _timed(lambda: friction.solve(mechanism, kin, tol=tol), repeats)
        its = rubbing.iterations[kin.valid]
        runs.append((f"{tol:g}", seconds, _peaks(mechanism, rubbing.forces, kin.valid),
                     f"passes {its.min():.0f}–{its.max():.0f} (mean {its.mean():.2f})"))
        if tick is not None:
            tick()
    return _compare("friction tol", runs)


def clearance_simulation(result: Result, steps=SIM_STEPS, repeats: int = 3) -> list[Row]:
    """Closed form against the direct simulation for the first reversal of each joint."""
    from dyade import clearance

    rows = []
    for check in result.clearance or []:
        if not check.reversals:
            continue
        peak = check.reversals[0].peak
        a, b = check.joint
        args = (peak.mass, peak.stiffness, peak.clearance, peak.slope)
        seconds, closed = _timed(lambda: clearance.peak_force(*args[:2], clearance=args[2],
                                                              slope=args[3]), repeats)
        rows.append(Row("clearance", "closed form", seconds, f"F12max {a}_{b}", closed.force,
                        np.nan, f"tau {closed.tau:.4g}"))
        for n in steps:
            seconds, sim = _timed(lambda: clearance.simulate(*args[:2], clearance=args[2],
                                                           slope=args[3], steps_per_period=n),
                                  repeats)
            rows.append(Row("clearance", f"RK4 {n}/period", seconds, f"F12max {a}_{b}",
                            sim.force, abs(sim.force - closed.force) / closed.force,
                            f"{sim.steps} steps"))
    return rows


DRIVE_LINE_FACTORS = (0.25, 0.5, 1.0, 2.0, 4.0)  # × the default steps; the last: reference


def drive_line_steps(mechanism: Mechanism, factors=DRIVE_LINE_FACTORS, repeats: int = 1,
                     tick=None) -> list[Row]:
    """The drive line's steady state (``dyade.linkage.drive_line``) against its RK4 steps
    per revolution: peak shaft torque, twist amplitude, speed fluctuation and the largest
    Floquet multiplier, each setting timed."""
    from dyade.linkage import drive_line
    from dyade.linkage.drive import crank_tables
    from dyade.machine import drive_line as engine

    line = engine.line_of(mechanism)
    probe = crank_tables(mechanism, engine.MIN_STEPS)
    speed = abs(mechanism.crank.speed)
    base = mechanism.drive_line.steps or engine.steps_for(line, float(np.min(probe.inertia)),
                                                          speed)
    runs = []
    for factor in factors:
        steps = max(36, int(round(base * factor)))
        seconds, state = _timed(lambda: drive_line.steady_state(mechanism, steps=steps,
                                                                accuracy=False), repeats)
        peaks = {"|shaft torque| max": float(np.max(np.abs(state.shaft_torque))),
                 "twist amplitude": float(np.ptp(state.twist) / 2.0),
                 "speed fluctuation": state.figures["fluctuation"],
                 "largest |mu|": state.figures["stability"]}
        runs.append((f"{steps} steps", seconds, peaks, f"{state.figures['iterations']} "
                                                      f"Newton iterations"))
        if tick is not None:
            tick()
    return _compare("drive line steps", runs)


def studies(mechanism: Mechanism, *, repeats: int = 3, progress=None) -> list[Row]:
    """Every study the mechanism calls for, as ``dyade accuracy`` shows them.

    The crank step always, the friction tolerance with friction, closed form against
    simulation with clearance data; each setting timed (best of ``repeats``) and its
    peaks compared with the finest one.

    Parameters
    ----------
    mechanism : Mechanism
        From ``read_mechanism`` or ``build_mechanism``.
    repeats : int
        Runs per setting; the best time counts.
    progress : callable, optional
        ``progress(done, total)`` is called after each setting.

    Returns
    -------
    list of Row
        One per setting: the study, the setting, its time and its deviation from the
        finest setting.

    Examples
    --------
    >>> import dyade
    >>> rows = dyade.accuracy_studies(dyade.read_mechanism("mechanisms/fourbar.toml"),
    ...                               repeats=1)
    >>> sorted({row.setting for row in rows if row.study == "crank step"})
    ['0.05°', '0.1°', '0.5°', '1°', '2°', '5°']
    >>> torque = [row for row in rows if row.quantity == "|M_drive| max"]
    >>> bool(torque[0].error > torque[-2].error)   # 5° is further off than 0.1°
    True"""
    the_plan = plan(mechanism)
    total = (len(STEPS_DEG) + bool(the_plan.friction) * len(FRICTION_TOLS)
             + bool(the_plan.clearance) + bool(the_plan.drive_line) * len(DRIVE_LINE_FACTORS))
    done = [0]

    def tick() -> None:
        done[0] += 1
        if progress is not None:
            progress(done[0], total)

    rows = crank_step(mechanism, repeats=repeats, tick=tick)
    if the_plan.friction:
        rows += friction_tol(mechanism, repeats=repeats, tick=tick)
    if the_plan.clearance:
        rows += clearance_simulation(analyse(mechanism), repeats=repeats)
        tick()
    if the_plan.drive_line:
        rows += drive_line_steps(mechanism, tick=tick)
    return rows


def with_sweep_of_one_revolution(mechanism: Mechanism) -> Mechanism:
    """The studies always cover one full revolution from the file's start angle."""
    sweep = mechanism.sweep
    return replace(mechanism, sweep=type(sweep)(sweep.start, sweep.start + 2 * np.pi, sweep.step))
