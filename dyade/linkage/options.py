"""A sweep's options checked and applied before anything runs (``configure``): the
range of crank angles (``with_sweep``), the friction solution's tolerance and passes,
the validity bands, the plan, and the memory the sweep may take (``check_size``, with
the estimates of a sweep in one block, collected in blocks, or in blocks written as they
come). The API's angles come in degrees (``sweep_in_degrees``, ``radians``,
``angles_in_degrees``) and are radians from here on."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from dyade.errors import InputError
from dyade.limits import BYTES_PER_VALUE, check_memory
from dyade.linkage.plan import Plan
from dyade.linkage.plan import plan as infer_plan
from dyade.model.mechanism import Mechanism, Revolute, Sweep, sweep_problem


def with_sweep(mechanism: Mechanism, start: float | None = None, stop: float | None = None,
               step: float | None = None) -> Mechanism:
    """The mechanism with its sweep changed [rad]; ``stop`` defaults to one revolution
    after a given ``start`` (else the mechanism's own)."""
    if start is None and stop is None and step is None:
        return mechanism
    current = mechanism.sweep
    for name, value in (("start", start), ("stop", stop), ("step", step)):
        if value is not None and not math.isfinite(value):
            raise InputError.parameter(name, f"must be a finite angle [rad], got {value}.",
                                       value=value, unit="rad")
    if stop is None:
        stop = current.stop if start is None else start + 2 * math.pi
    start = current.start if start is None else start
    step = current.step if step is None else step
    if step <= 0:
        raise InputError.parameter("step", f"must be positive [rad], got {step:g}.", value=step,
                                   unit="rad")
    if stop < start:
        raise InputError.parameter("stop", f"must not be below the start angle [rad], got "
                                           f"{stop:g}.", value=stop, unit="rad")
    problem = sweep_problem(start, stop, step)
    if problem:
        raise InputError.parameter("sweep", f"{problem}.", unit="rad")
    return replace(mechanism, sweep=Sweep(start, stop, step))


def radians(value_deg: float | None, name: str) -> float | None:
    """An angle of the API [°] -> [rad] (None stays None); ``name``: the parameter, for
    the error of a value that is not a finite number."""
    if value_deg is None:
        return None
    try:
        value = float(value_deg)
    except (TypeError, ValueError):
        raise InputError.parameter(name, f"must be an angle [°], got {value_deg!r}.",
                                   value=value_deg, unit="°") from None
    if not math.isfinite(value):
        raise InputError.parameter(name, f"must be a finite angle [°], got {value}.",
                                   value=value, unit="°")
    return math.radians(value)


def angles_in_degrees(angles_deg, name: str = "crank_angle_deg") -> np.ndarray | None:
    """Crank angles of the API [°] (the parameter ``name``) -> [rad] (None stays None)."""
    if angles_deg is None:
        return None
    try:
        angles = np.asarray(angles_deg, dtype=np.float64)
    except (TypeError, ValueError):
        raise InputError.parameter(name, "must be crank angles [°] (numbers).",
                                   unit="°") from None
    if angles.ndim > 1 or not np.all(np.isfinite(angles)):
        raise InputError.parameter(name, "must be one finite crank angle [°] or "
                                                      "a sequence of them.", unit="°")
    return np.deg2rad(np.atleast_1d(angles))


def sweep_in_degrees(mechanism: Mechanism, start_deg: float | None = None,
                     stop_deg: float | None = None, step_deg: float | None = None
                     ) -> Mechanism:
    """The mechanism with the sweep the API asks for in degrees (``with_sweep``), with
    the values that look wrong refused, naming the fix: a step above one revolution (an
    angle in radians would give a few positions at most) and a sweep of one position."""
    if start_deg is None and stop_deg is None and step_deg is None:
        return mechanism
    start = radians(start_deg, "start_deg")
    stop = radians(stop_deg, "stop_deg")
    step = radians(step_deg, "step_deg")
    if step is not None and step <= 0:
        raise InputError.parameter("step_deg", f"must be positive [°], got {step_deg:g}.",
                                   value=step_deg, unit="°")
    if step_deg is not None and step_deg > 360.0:
        raise InputError.parameter(
            "step_deg", f"is {step_deg:g}°, more than one revolution. It is in degrees: "
                        f"step_deg=0.5 sweeps every half degree.", value=step_deg, unit="°")
    if start is not None and stop is not None and stop < start:
        raise InputError.parameter("stop_deg", f"must not be below start_deg, got "
                                               f"{stop_deg:g}° < {start_deg:g}°.",
                                   value=stop_deg, unit="°")
    swept = with_sweep(mechanism, start, stop, step)
    if swept.sweep.count < 2:
        sweep = swept.sweep
        given = tuple(name for name, value in (("start_deg", start_deg), ("stop_deg", stop_deg),
                                               ("step_deg", step_deg)) if value is not None)
        reason = (f"the sweep from {math.degrees(sweep.start):g}° to "
                  f"{math.degrees(sweep.stop):g}° in steps of {math.degrees(sweep.step):g}° has "
                  f"one position: give a smaller step_deg or a wider range (stop_deg above "
                  f"start_deg), or crank_angle_deg=[...] for single positions.")
        err = InputError(f"{', '.join(given)}: {reason}", key=given[0], unit="°", reason=reason)
        err.parameters = given
        raise err
    return swept




def column_count(mechanism: Mechanism) -> int:
    """How many columns a sweep of ``mechanism`` gives (about: the friction determinants
    and lock margins are not counted)."""
    revolute = sum(isinstance(j, Revolute) for j in mechanism.joints)
    prismatic = len(mechanism.joints) - revolute
    columns = (1 + 3 * len(mechanism.moving_links) + 6 * revolute + 3 * prismatic
               + 6 * len(mechanism.named_points) + len(mechanism.dyads))
    if mechanism.has_dynamics:
        rubbing = sum(j.friction > 0.0 for j in mechanism.joints)
        columns += 3 * revolute + 2 * prismatic + 6 + 2 * rubbing + (2 if rubbing else 0)
    return columns


def memory_estimate(mechanism: Mechanism, positions: int) -> int:
    """What a sweep of ``positions`` in one block will take [B], from its column count."""
    return BYTES_PER_VALUE * column_count(mechanism) * positions + (50 << 20)


def collect_estimate(block_size: int):
    """What ``analyse`` needs [B] in blocks of ``block_size`` positions, as
    ``configure``'s ``estimate``: its columns (8 B per value) and one block."""
    def estimate(mechanism: Mechanism, positions: int) -> int:
        if positions <= block_size:
            return memory_estimate(mechanism, positions)
        return 8 * column_count(mechanism) * positions + memory_estimate(mechanism, block_size)

    return estimate


def check_size(mechanism: Mechanism, positions: int, max_memory: float | None,
               estimate=None, advice: str = "Use a coarser step or a shorter range") -> None:
    """Refuse a sweep that would take more than ``max_memory`` [B], before allocating;
    ``estimate(mechanism, positions)`` [B] (default ``memory_estimate``); ``advice``:
    what the caller can ask for instead (only what it has options for)."""
    need = (estimate or memory_estimate)(mechanism, positions)
    check_memory(need, f"this sweep of {positions:,} positions", max_memory, advice)


def stream_estimate(block_size: int):
    """What a sweep in blocks of ``block_size`` positions needs [B] besides its output,
    as ``configure``'s ``estimate``: one block's columns and arrays, and the
    per-position arrays kept for the whole sweep."""
    def estimate(mechanism: Mechanism, positions: int) -> int:
        if positions <= block_size:  # one block: the whole sweep in memory
            return memory_estimate(mechanism, positions)
        per_position = 17 * len(mechanism.dyads) + KEPT_PER_POSITION + 16 * sum(
            isinstance(j, Revolute) for j in mechanism.joints)
        if mechanism.has_dynamics and any(j.friction > 0.0 for j in mechanism.joints):
            # the residual; not solved, locked; near per dyad; at rest and locks per joint
            per_position += 10 + len(mechanism.dyads) + 2 * len(mechanism.joints)
        block = memory_estimate(mechanism, min(positions, block_size)) - (50 << 20)
        return 2 * block + per_position * positions + (60 << 20)

    return estimate


KEPT_PER_POSITION = 64
"""[B] what a sweep in blocks keeps per position besides the per-dyad arrays: crank
angle, speed and acceleration, masks, the clearance joints' forces"""


def configure(mechanism: Mechanism, *, positions: int | None = None,
              friction_tol: float | None = None, friction_max_iter: int | None = None,
              plan: Plan | None = None, max_memory: float | None = None,
              dead_centre: float | None = None, transmission_warning: float | None = None,
              given_speed: bool = False, constant_speed: bool = False, run_up: bool = False,
              estimate=None) -> tuple[Mechanism, Plan]:
    """``analyse``'s options checked and applied (in SI units: the validity bands
    ``dead_centre`` and ``transmission_warning`` [rad]; the sweep is the mechanism's):
    the mechanism to sweep and its plan.
    ``positions``: how many crank angles are given (default: the sweep's); ``estimate``:
    the memory the sweep needs [B] as a function of (mechanism, positions) (default
    ``memory_estimate``)."""
    if friction_tol is not None:
        if not (math.isfinite(friction_tol) and friction_tol > 0):
            raise InputError.parameter("friction_tol", f"must be a positive number [-], got "
                                                       f"{friction_tol}.", value=friction_tol)
        mechanism = replace(mechanism, friction_tol=friction_tol)
    if friction_max_iter is not None:
        if friction_max_iter < 1:
            raise InputError.parameter("friction_max_iter", f"must be at least 1, got "
                                                            f"{friction_max_iter}.",
                                       value=friction_max_iter)
        mechanism = replace(mechanism, friction_max_iter=friction_max_iter)
    if dead_centre is not None or transmission_warning is not None:
        hard = mechanism.dead_centre_angle if dead_centre is None else dead_centre
        soft = mechanism.transmission_warning if transmission_warning is None else transmission_warning
        if not (math.isfinite(hard) and math.isfinite(soft) and 0.0 <= hard < soft <= np.pi / 2):
            raise InputError.parameter(("dead_centre_deg", "transmission_warning_deg"),
                                       f"must satisfy 0 ≤ the dead-centre band < the warning angle ≤ "
                                       f"90°, got {np.rad2deg(hard):g}° and {np.rad2deg(soft):g}°.")
        mechanism = replace(mechanism, dead_centre_angle=hard, transmission_warning=soft)
    positions = mechanism.sweep.count if positions is None else positions
    check_size(mechanism, positions, max_memory, estimate)
    if max_memory is not None:  # the [drive]'s grid and run-up are bounded by it too
        mechanism = replace(mechanism, max_memory=max_memory)
    the_plan = plan if plan is not None else infer_plan(mechanism)
    if constant_speed and the_plan.equation_of_motion:
        the_plan = replace(the_plan, equation_of_motion="")
    if run_up and not the_plan.equation_of_motion:
        raise InputError.parameter("run_up", "needs a [drive] table in the mechanism (a motor "
                                             "to run it up with).", value=run_up)
    if the_plan.equation_of_motion and given_speed:
        raise InputError.parameter(("crank_speed", "crank_acceleration"),
                                   "cannot be given with a [drive] table: its equation of "
                                   "motion sets the crank's speed (analyse at constant speed "
                                   "to give them).")
    return mechanism, the_plan
