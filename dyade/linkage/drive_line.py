"""A linkage driven through an elastic drive line (``[drive_line]``): what a designer asks.

The linkage enters as the crank shaft of the line (``dyade.machine.drive_line``): its
reduced inertia J(φ), the slope J′(φ) and the load torque M_L(φ) from the kinematics at
unit crank speed (``dyade.linkage.reduced``), on the integration grid. The motor is the
``[drive]`` motor with the rotor inertia of the ``[drive_line]`` table, or, without a
``[drive]`` table, an ideal motor at the crank's constant speed. Joint friction enters
the steady state as the friction torque M_F(φ) from the kinetostatics with friction at
the vibrating crank's motion, found by passes (as for the rigid ``[drive]``); the scans
over speed and the run-up leave it out (the command line notes that).

- ``natural_frequency``: ω̄ (the lowest natural frequency with the mean inertia J̄), its
  range over the cycle from J(φ), the ratio Ω/ω̄ and the VDI 2149 check (Ω/ω̄ ≤ 0.1);
- ``steady_state``: the periodic motion at the operating speed next to the rigid drive's;
- ``resonance_curve``: peak shaft torque, twist amplitude, speed fluctuation and the
  largest Floquet multiplier over a range of speeds of an ideal motor;
- ``stability_map``: the largest Floquet multiplier over speed × stiffness or damping,
  and the boundary of its unstable regions traced between the cells (``trace_edges``);
- ``run_up``: from rest under the motor's characteristic, in time.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError, InputError
from dyade.linkage.drive import CrankShaft, crank_shaft, crank_tables, natural_frequency
from dyade.machine import drive_line as engine
from dyade.machine.drive_line import line_data, line_of, sense_of
from dyade.machine.motor import operating_speed
from dyade.model.drive import ConstantTorque, Motor
from dyade.model.mechanism import Mechanism
from dyade.units import RAD_PER_S_TO_RPM

HARMONIC_SHARE = 1e-3  # [-] harmonics of J or M_L above this share of the largest are labelled


def _steps(shaft: CrankShaft, line: engine.Line, speed_min: float,
           stiffness_max: FloatArray | None = None) -> tuple[int, engine.Tables]:
    coarse = shaft.tables
    steps = line_data(shaft.mechanism).steps or engine.steps_for(
        line, float(np.min(coarse.inertia)), speed_min, stiffness_max)
    return steps, shaft.tables_at(steps)


def resonances(mechanism: Mechanism, omega_bar: float, low: float, high: float, *,
               shaft: CrankShaft | None = None) -> list[tuple[int, float, str]]:
    """The speeds [rad/s] within [low, high] where resonances are to be expected: forced
    at Ω = ω̄/k for each harmonic k present in J(φ) or M_L(φ), parametric at Ω = 2ω̄/k
    for each harmonic k of J(φ). (k, speed, "forced" | "parametric"), by speed.
    ``shaft``: the mechanism's crank shaft, when the caller has it."""
    tables = shaft.tables if shaft is not None else crank_tables(mechanism, engine.MIN_STEPS)
    out = []
    for values, kinds in ((tables.inertia, ("forced", "parametric")),
                          (tables.load, ("forced",))):
        spectrum = np.abs(np.fft.rfft(values[0::2]))[1:]
        if not spectrum.size or spectrum.max() == 0.0:
            continue
        present = np.flatnonzero(spectrum > HARMONIC_SHARE * spectrum.max()) + 1
        for k in present:
            for kind in kinds:
                speed = omega_bar * (2.0 if kind == "parametric" else 1.0) / k
                if low <= speed <= high and (int(k), kind) not in {(a, c) for a, _, c in out}:
                    out.append((int(k), speed, kind))
    return sorted(out, key=lambda row: row[1])


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class SteadyState:
    """The periodic steady state of the drive line over one revolution, and the rigid
    drive's at the same speed. Torques and speeds in the running direction of the crank."""

    crank_angle: FloatArray
    """(n,) φ [rad] at the grid nodes of one revolution"""
    shaft_torque: FloatArray
    """(n,) T: the torque the elastic element puts into the crank shaft [N·m]"""
    crank_speed: FloatArray
    """(n,) |φ̇| [rad/s]"""
    crank_acceleration: FloatArray
    """(n,) φ̈ in the running direction [rad/s²]"""
    twist: FloatArray
    """(n,) twist of the line, motor side against crank, reduced to the crank [rad]"""
    rigid_torque: FloatArray
    """(n,) the drive torque of the rigid drive at the same mean speed [N·m]"""
    rigid_speed: FloatArray
    """(n,) |φ̇| of the rigid drive [rad/s]"""
    rigid_acceleration: FloatArray
    """(n,) φ̈ of the rigid drive [rad/s²]"""
    multipliers: FloatArray
    """(d,) the Floquet multipliers (complex), largest modulus first"""
    figures: dict = field(default_factory=dict)
    """mean speed, ω̄, η, works over the period, accuracy, iterations"""

    @property
    def stable(self) -> bool:
        return bool(np.abs(self.multipliers[0]) <= 1.0 + engine.UNSTABLE_MARGIN)


def _reference_speed(mechanism: Mechanism, motor: Motor | None, tables: engine.Tables) -> float:
    nominal = abs(mechanism.crank.speed)
    if motor is None:
        return nominal
    if not isinstance(motor, ConstantTorque):
        return operating_speed(motor, float(np.mean(tables.friction - tables.load)), nominal)
    raise DyadeError("a constant-torque motor has no definite steady speed on an elastic drive "
                     "line (its speed drifts until the damping balances the torque): give an "
                     "asynchronous motor or a torque-speed table, or leave out [drive] for an "
                     "ideal motor at the crank's speed. A run-up works with it.")


def _solve(line: engine.Line, tables: engine.Tables, lanes: engine.Lanes,
           progress: Callable[[int], None] | None = None) -> engine.Periodic:
    return engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes),
                           progress)


def steady_state(mechanism: Mechanism, *, speed_rpm: float | None = None,
                 steps: int | None = None, accuracy: bool = True,
                 shaft: CrankShaft | None = None,
                 progress: Callable[[int], None] | None = None) -> SteadyState:
    """The periodic steady state at the operating speed (the ideal motor's speed
    ``speed_rpm``, default the crank's), by shooting, next to the rigid drive's.

    With ``accuracy`` the state is solved again with half the steps and the largest
    change of the shaft torque, relative to its largest value, is reported as
    ``figures["accuracy"]`` (RK4: the error of the finer solution is about a fifteenth).

    Parameters
    ----------
    mechanism : Mechanism
        With a ``[drive_line]`` table; its ``[drive]`` motor, or an ideal motor.
    speed_rpm : float, optional
        The ideal motor's speed [rpm] (not with a ``[drive]`` motor).
    steps : int, optional
        RK4 steps per revolution (default: the table's, else 64 per period of the
        highest natural frequency, at least 720).
    accuracy : bool
        Also solve with half the steps and report the change (``figures["accuracy"]``).
    shaft : CrankShaft, optional
        The mechanism's crank shaft (``crank_shaft``), when the caller has it: its line,
        tables and natural frequency are not computed again.
    progress : callable, optional
        ``progress(iteration)`` hears each Newton iteration of the shooting.

    Returns
    -------
    SteadyState
        Over one revolution at the grid nodes, with the rigid drive's values and the
        Floquet multipliers.

    Examples
    --------
    >>> import dyade
    >>> m = dyade.read_mechanism("mechanisms/slider-crank.toml", {
    ...     "drive_line.stiffness": 1000.0, "drive_line.damping": 0.05,
    ...     "links.2.inertia": 0.01})
    >>> state = steady_state(m, accuracy=False)
    >>> round(float(abs(state.shaft_torque).max()), 1), round(float(
    ...     abs(state.rigid_torque).max()), 1), state.stable             # [N·m]
    (176.2, 22.5, True)

    Raises
    ------
    DyadeError
        No periodic state (the crank would stop or turn back in the cycle, or the
        shooting does not converge).
    """
    shaft = shaft or crank_shaft(mechanism)
    line = shaft.line
    if speed_rpm is not None and not line.ideal:
        raise InputError.parameter("speed_rpm", "is for an ideal motor; a [drive] motor finds "
                                                "its own speed.")
    probe = shaft.tables
    speed = _reference_speed(mechanism, line.motor, probe) if speed_rpm is None else abs(
        speed_rpm) / RAD_PER_S_TO_RPM
    if not speed > 0.0:
        raise InputError.parameter("speed_rpm", f"must be a positive speed, got {speed_rpm}.")
    n = steps or line_data(mechanism).steps or engine.steps_for(line, float(np.min(probe.inertia)),
                                                            speed)
    tables = shaft.tables_at(n)
    lanes = engine.Lanes.of(line, [speed])
    try:
        solution, orbit, passes = _with_friction(shaft, tables, lanes, progress=progress)
    except DyadeError:
        if not (line.ideal and line.elements == 1 and not shaft.friction):
            raise
        reached = _reached(shaft, speed, n)
        if reached is None:
            raise
        n, solution, before = reached
        tables = shaft.tables_at(n)
        orbit = engine.integrate(line, tables, lanes, solution.start)
        passes = {"reached_from_rpm": REACH * speed * RAD_PER_S_TO_RPM}
    out = _steady(shaft, tables, lanes, orbit, solution)
    out.figures.update(passes)
    if accuracy:
        coarse_tables = shaft.tables_at(max(n // 2, 36))
        if "reached_from_rpm" in passes:  # the solution at half the steps: _reached's last
            coarse = before
        else:
            coarse, _, _ = _with_friction(shaft, coarse_tables, lanes, strict=False,
                                          progress=progress)
        if coarse.converged[0]:
            coarse_orbit = engine.integrate(line, coarse_tables, lanes, coarse.start)
            fine = orbit.torque[::2, 0, -1] if n % 2 == 0 else None
            if fine is not None and fine.size == coarse_orbit.torque.shape[0]:
                scale = float(np.max(np.abs(orbit.torque[:, 0, -1]))) or 1.0
                out.figures["accuracy"] = float(np.max(np.abs(
                    fine - coarse_orbit.torque[:, 0, -1]))) / scale
    return out


REACH = 0.9  # [-] a steady state the shooting misses is followed up from this share
REACH_SPEEDS = 11  # [-] of its speed in this many speeds (``resonance_curve``)


def _reached(shaft: CrankShaft, speed: float, steps: int
             ) -> tuple[int, engine.Periodic, engine.Periodic] | None:
    """The steady state at ``speed`` [rad/s] where the shooting from the linear response
    misses it (a crank that nearly stops in a resonance): the branch followed up from
    ``REACH``·speed (``resonance_curve``: continuation, meshes where the crank is slow),
    its stable solution at the speed (the smallest |μ| where several coexist) shot again
    on a uniform grid, the steps doubled until its multipliers change by less than
    ``periodic.ACCURACY``: (steps, solution, the solution on half the steps), or None."""
    from dyade.machine import periodic

    line = shaft.line
    curve = resonance_curve(shaft.mechanism, np.linspace(REACH, 1.0, REACH_SPEEDS) * speed
                            * RAD_PER_S_TO_RPM, shaft=shaft)
    rows = np.flatnonzero(curve.converged & (curve.speed == curve.speed.max()))
    if not rows.size:
        return None
    row = rows[np.argmin(curve.stability[rows])]
    lanes = engine.Lanes.of(line, [speed])
    start, before = curve.start[row][None, :], None
    n = steps
    while n <= MAX_REACH_STEPS:
        solution = engine.periodic(line, shaft.tables_at(n), lanes, start)
        if solution.converged[0]:
            if (before is not None and periodic.multiplier_change(
                    solution.multipliers, before.multipliers)[0] <= periodic.ACCURACY):
                return n, solution, before
            start, before = solution.start, solution
        n *= 2
    return None


MAX_REACH_STEPS = 92160  # [-] the most uniform steps per revolution of ``_reached``


def has_friction(mechanism: Mechanism) -> bool:
    """True when the sweep of ``mechanism`` runs the friction solution."""
    from dyade.linkage.plan import plan

    return bool(plan(mechanism).friction)


def _with_friction(shaft: CrankShaft, tables: engine.Tables, lanes: engine.Lanes,
                   strict: bool = True, progress: Callable[[int], None] | None = None
                   ) -> tuple[engine.Periodic, engine.Orbit, dict]:
    """The periodic state of one lane; with joint friction by passes, as for the rigid
    [drive] (``dyade.linkage.drive``): solve with the friction torque M_F frozen (zero at
    first), compute it anew from the kinetostatics with friction at the resulting crank
    speed and acceleration, until it changes by less than ``[friction] tol`` of the
    largest torque. ``tables.friction`` is left holding it."""
    mechanism, line = shaft.mechanism, shaft.line
    solution = _solve(line, tables, lanes, progress)
    if strict and not solution.converged[0]:
        raise DyadeError(f"no periodic steady state of the drive line at "
                         f"{lanes.speed[0] * RAD_PER_S_TO_RPM:.5g} rpm: the crank would stop or "
                         f"turn back within the cycle, or the shooting did not converge (scaled "
                         f"residual {solution.residual[0]:.2g}); the model does not describe that "
                         f"motion.")
    orbit = engine.integrate(line, tables, lanes, solution.start)
    if not shaft.friction:
        return solution, orbit, {}
    change, count = math.inf, 0
    for count in range(1, mechanism.friction_max_iter + 1):
        speed = lanes.speed[0] + orbit.state[:-1, 0, 0]
        new = engine.halves(friction_torque(mechanism, tables, speed, orbit.acceleration[:-1, 0]))
        change = float(np.max(np.abs(new - tables.friction)))
        scale = max(float(np.max(np.abs(new))), float(np.max(np.abs(orbit.torque[:, 0, -1]))))
        tables.friction = new
        solution = _solve(line, tables, lanes, progress)
        if not solution.converged[0]:
            if strict:
                raise DyadeError("no periodic steady state of the drive line with joint "
                                 "friction: the shooting did not converge in a friction pass.")
            break
        orbit = engine.integrate(line, tables, lanes, solution.start)
        if change <= mechanism.friction_tol * scale:
            break
    return solution, orbit, {"friction_passes": count, "friction_change": change}


def friction_torque(mechanism: Mechanism, tables: engine.Tables, speed: FloatArray,
                    acceleration: FloatArray) -> FloatArray:
    """s·M_F [N·m] at the N grid nodes of a revolution: the drive torque of the
    kinetostatics with friction at the crank's ``speed`` and ``acceleration`` (running
    direction) less what inertia and loads ask, J·φ̈ + ½·J′·φ̇² − M_L."""
    from dyade.linkage import friction, kinematics

    sense = sense_of(mechanism)
    steps = tables.steps
    angle = mechanism.sweep.start + sense * 2.0 * math.pi / steps * np.arange(steps)
    kin = kinematics.sweep(mechanism, angle, crank_speed=sense * speed,
                           crank_acceleration=sense * acceleration)
    drive = friction.solve(mechanism, kin).forces.drive_torque
    if not np.all(np.isfinite(drive)):
        raise DyadeError("the drive line with joint friction cannot be solved: the forces are "
                         "undefined at a dead centre or a self-locking position of the cycle.")
    inertia, slope, load = tables.inertia[0::2], tables.slope[0::2], tables.load[0::2]
    return sense * drive - (inertia * acceleration + 0.5 * slope * speed ** 2 - load)


def _steady(shaft: CrankShaft, tables, lanes, orbit, solution) -> SteadyState:
    mechanism, line = shaft.mechanism, shaft.line
    sense = sense_of(mechanism)
    steps = tables.steps
    u = orbit.step * np.arange(steps + 1)
    speed = lanes.speed[0] + orbit.state[:, 0, 0]
    m = line.elements
    twist = np.sum(orbit.state[:, 0, 1:1 + m][:, :1], axis=1)  # motor node against crank
    period = float(orbit.quadratures[-1, 0, 0])
    mean = 2.0 * math.pi / period
    # the rigid drive: constant speed for an ideal motor, else the rigid equation of
    # motion with the rotor's inertia on the crank
    inertia, slope, load = tables.inertia[0::2], tables.slope[0::2], tables.load[0::2]
    rub = np.zeros(steps)  # the rigid drive's friction: at constant speed
    if shaft.friction:
        rub = friction_torque(mechanism, tables, np.full(steps, mean), np.zeros(steps))
    if line.ideal:
        rigid_speed = np.full(steps + 1, lanes.speed[0])
        rigid_accel = np.zeros(steps + 1)
    else:
        from dyade.machine import equation

        rotor = line.inertias[0] + sum(line.inertias[1:])
        eq = equation.Tables(tables.inertia + rotor, tables.load, engine.halves(rub),
                             tables.slope)
        path = equation.periodic(eq, line.motor, 1.0, steps, mean, 1e-12, mean)
        rigid_speed = path.speed
        g = path.slope
        rigid_accel = (g - 0.5 * np.append(slope, slope[0]) * rigid_speed ** 2) / (
            np.append(inertia, inertia[0]) + rotor)
    close = np.append(np.arange(steps), 0)
    rigid_torque = (inertia[close] * rigid_accel + 0.5 * slope[close] * rigid_speed ** 2
                    - load[close] + rub[close])
    quad = orbit.quadratures[-1, 0]
    figures = {"speed_mean": mean, "period": period,
               "fluctuation": float((speed.max() - speed.min()) / mean),
               "rigid_fluctuation": float((rigid_speed.max() - rigid_speed.min()) / mean),
               "work_motor": float(quad[1]), "work_load": float(quad[2]),
               "work_friction": float(quad[3]), "work_damping": float(quad[4]),
               "iterations": solution.iterations, "steps_per_revolution": steps,
               "stability": float(np.abs(solution.multipliers[0, 0]))}
    freq = shaft.frequency
    figures.update({"omega_bar": freq.omega_bar, "eta": mean / freq.omega_bar})
    return SteadyState(mechanism.sweep.start + sense * u, orbit.torque[:, 0, -1], speed,
                       orbit.acceleration[:, 0], twist, rigid_torque, rigid_speed, rigid_accel,
                       solution.multipliers[0], figures)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class ResonanceCurve:
    """The periodic states of the line with an ideal motor over a range of speeds: one
    row per periodic solution found at a speed (several where a resonance's branch folds
    over: the coexisting solutions), one row with ``converged`` False where none was
    found to the tolerance (its values NaN: no verdict)."""

    speed: FloatArray
    """(r,) Ω [rad/s]"""
    eta: FloatArray
    """(r,) Ω/ω̄ [-]"""
    solution: FloatArray
    """(r,) int: the solution's number at its speed (1, 2, …, by twist amplitude)"""
    peak_torque: FloatArray
    """(r,) largest |shaft torque| over the cycle [N·m]; NaN where no periodic state"""
    rigid_peak_torque: FloatArray
    """(r,) largest |drive torque| of the rigid drive at that speed [N·m]"""
    twist_amplitude: FloatArray
    """(r,) (max − min)/2 of the twist [rad]"""
    twist_max: FloatArray
    """(r,) the largest |twist| over the period [rad]"""
    fluctuation: FloatArray
    """(r,) (max − min)/mean of the crank speed [-]"""
    stability: FloatArray
    """(r,) the largest |Floquet multiplier| [-]"""
    converged: FloatArray
    """(r,) bool: periodic to the tolerance and unchanged (to ``tolerance``) with twice
    the steps"""
    kind: list
    """(r,) how the solution is unstable: "" (stable or not converged), "fold",
    "period doubling", "Neimark–Sacker" (``dyade.machine.periodic``)"""
    steps_used: FloatArray
    """(r,) RK4 steps per revolution of the solution"""
    accuracy: FloatArray
    """(r,) the change of the solution and its multipliers with twice the steps [-]"""
    balance: FloatArray
    """(r,) the energy balance over the period: |motor + loads − friction − damping|
    over the largest of them [-]"""
    reason: list
    """(r,) why a row has no periodic state ("" where it has one)"""
    omega_bar: float
    """ω̄ [rad/s]"""
    resonances: list
    """(k, speed [rad/s], "forced" | "parametric") expected in the range"""
    steps: int
    """RK4 steps per revolution to start with"""
    folds: list = field(default_factory=list)
    """(speed [rad/s], upper) of each fold of the branches: upper True where a sweep
    upwards jumps (the branch's speed is largest there), False where a sweep downwards
    jumps"""
    branches: list = field(default_factory=list)
    """(speed (n,) [rad/s], twist_max (n,) [rad], unstable (n,) bool, kind list, largest
    |μ| (n,)) of each branch followed by continuation"""
    tolerance: float = math.nan
    """the accuracy asked for [-]"""
    stopped: list = field(default_factory=list)
    """why a continuation stopped before the end of the range (worded), if one did"""
    start: FloatArray | None = None
    """(r, d) each row's state at u = 0 (δv [rad/s], twist [rad]; NaN where not
    converged); at the motor's angle s = 0 where the row is ``in_time``"""
    in_time: FloatArray | None = None
    """(r,) bool: the solution was found in time (``engine.problem_in_time``): the crank
    nearly stops or turns back for a moment, where its angle is no variable"""
    slowest: FloatArray | None = None
    """(r,) the crank's slowest speed over the cycle over Ω [-] (negative: it turns
    back for a moment); NaN where not converged"""
    period_two: PeriodTwo | None = None
    """the period-2 motions at the speeds of a flip region (``period_two``), where the
    caller asked for them (``dyade.analyses.drive_line``: ``period_two=True``)"""

    @property
    def unstable(self) -> FloatArray:
        """(r,) bool: a multiplier outside the unit circle (False where not converged)."""
        return self.converged & (np.nan_to_num(self.stability) > 1.0 + engine.UNSTABLE_MARGIN)

    @property
    def verdict(self) -> FloatArray:
        """(r,) object: True unstable, False stable, None not converged (no verdict)."""
        return np.array([bool(u) if ok else None for u, ok in zip(self.unstable,
                                                                   self.converged)],
                        dtype=object)


CONTINUATION_INTEGRATIONS = 400  # [-] the most integrations of a branch's continuation
# (and 4 per speed asked, at least 100)
BALANCE_TOL = 1e-5  # [-] the energy balance over the period, of the largest work
SAME = 1e-6  # [-] two solutions at one speed closer than this (scaled) are one


def _speeds(speeds_rpm) -> FloatArray:
    speeds = np.atleast_1d(np.asarray(speeds_rpm, dtype=np.float64))
    if speeds.size == 0 or not np.all(np.isfinite(speeds)):
        raise InputError.parameter("speeds_rpm", "must be finite crank speeds [rpm].")
    if np.any(speeds <= 0.0) and np.any(speeds >= 0.0) or np.any(speeds == 0.0):
        raise InputError.parameter("speeds_rpm", f"must not run through 0 rpm (from "
                                                 f"{speeds.min():g} to {speeds.max():g}): the "
                                                 f"periodic motion needs the crank turning.",
                                   unit="rpm")
    return np.abs(speeds) / RAD_PER_S_TO_RPM


def resonance_curve(mechanism: Mechanism, speeds_rpm, *, steps: int | None = None,
                    tolerance: float | None = None, follow: bool = True,
                    shaft: CrankShaft | None = None,
                    progress: Callable[[int], None] | None = None) -> ResonanceCurve:
    """The resonance curve and the Floquet multipliers over the ideal motor's speeds
    ``speeds_rpm`` [rpm]: peak shaft torque, twist, speed fluctuation against speed, the
    resonances to be expected in the range, every periodic solution found at each speed.
    A ``[drive]`` motor is replaced by an ideal one (the speed is what is scanned).

    All speeds are shot at once from the line's linear response (``dyade.machine.
    periodic.shoot``: the steps doubled until the solution and its multipliers change by
    less than ``tolerance``); then (``follow``) the branch is followed in speed by
    pseudo-arclength continuation over the whole range, through its folds, and every
    further solution it passes at a speed of the range is shot there too: the
    coexisting solutions of a resonance that folds over, the jump speeds of a sweep up
    and down (``folds``). Speeds still without one are shot from their neighbours' on
    meshes of their own, then in time (``_fill``, ``_fill_in_time``); last, every
    stable solution is carried to the neighbouring speeds and on (``_carry``: the
    coexisting stable motions a long integration from a neighbour's state settles on),
    the fold where a carried branch ends located in time. A speed without a solution
    periodic to the tolerance is a row with ``converged`` False and its ``reason``: no
    verdict.

    Parameters
    ----------
    mechanism : Mechanism
        With a ``[drive_line]`` table.
    speeds_rpm : array_like
        Crank speeds [rpm], all of one sign, none zero.
    steps : int, optional
        RK4 steps per revolution to start with (default as for ``steady_state``, at the
        lowest speed); doubled by accuracy.
    tolerance : float, optional
        The change with twice the steps that counts as converged [-] (default
        ``dyade.machine.periodic.ACCURACY``).
    follow : bool
        Follow the branches by continuation (False: each speed alone).
    shaft : CrankShaft, optional
        The mechanism's crank shaft (``crank_shaft``), when the caller has it.
    progress : callable, optional
        ``progress(count)`` hears each integration (all speeds at once).

    Returns
    -------
    ResonanceCurve

    Examples
    --------
    >>> import dyade
    >>> m = dyade.read_mechanism("mechanisms/dyade-16.toml", {
    ...     "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04})
    >>> curve = resonance_curve(m, [3450.0, 3575.0], follow=False)  # near 2·ω̄
    >>> curve.unstable.tolist(), [round(float(mu), 3) for mu in curve.stability]
    ([False, True], [0.988, 1.039])
    """
    from dyade.machine import periodic

    tol = periodic.ACCURACY if tolerance is None else float(tolerance)
    speeds = _speeds(speeds_rpm)
    shaft = shaft or crank_shaft(mechanism)
    line = shaft.ideal_line
    n, tables = (steps, shaft.tables_at(steps)) if steps else _steps(
        shaft, line, float(speeds.min()))
    count = 0

    def tick() -> None:
        nonlocal count
        count += 1
        if progress is not None:
            progress(count)

    problem = engine.problem(line, lambda k: tables if k == n else shaft.tables_at(k), n)
    p = engine.parameters(line, speeds)
    guess = engine.linear_guess(line, tables, engine.Lanes.of(line, speeds))
    first = periodic.shoot(problem, p, guess, tol=tol, progress=tick)
    starts = [[first.start[j]] if first.converged[j] else [] for j in range(speeds.size)]
    found = [[j] if first.converged[j] else [] for j in range(speeds.size)]
    records = {"start": list(first.start), "steps": list(first.steps),
               "accuracy": list(first.accuracy), "mult": list(first.multipliers),
               "converged": list(first.converged), "reason": list(first.reason),
               "speed": list(speeds), "mesh": [None] * speeds.size}
    folds, branches, stopped = [], [], []
    if follow and first.converged.any() and speeds.size > 1:
        low, high = float(speeds.min()), float(speeds.max())
        j0 = int(np.flatnonzero(first.converged)[np.argmin(speeds[first.converged])])
        level = max(n, int(first.steps[j0]) // 2)
        followed = []
        most = max(40, 2 * speeds.size)  # the points of a branch, at most
        for direction in (1.0, -1.0):
            if direction < 0 and speeds[j0] <= low:
                continue
            followed.append(periodic.continuation(problem, first.start[j0], p[j0], (low, high),
                                                  steps=level, direction=direction, most=most,
                                                  finest=n * 2 ** periodic.MOST_DOUBLINGS,
                                                  integrations=min(CONTINUATION_INTEGRATIONS,
                                                                   max(100, 4 * speeds.size)),
                                                  progress=tick))
        scale = problem.scale(p)
        extra_p, extra_x, extra_j, extra_n = [], [], [], []
        for branch in followed:
            folds += [(fold.parameter, fold.upper) for fold in branch.folds]
            for j in range(speeds.size):
                for i, frac in branch.crossings(float(speeds[j])):
                    x = branch.start[i] + frac * (branch.start[i + 1] - branch.start[i])
                    known = starts[j] + [extra_x[k] for k in range(len(extra_x))
                                         if extra_j[k] == j]
                    if all(np.max(np.abs(x - y) / scale[j]) > 1e-3 for y in known):
                        extra_p.append(p[j])
                        extra_x.append(x)
                        extra_j.append(j)
                        extra_n.append(int(max(branch.steps[i], branch.steps[i + 1])))
        if extra_x:  # shot from the branch's own steps (finer where the crank nearly stops)
            extra_n = np.array(extra_n)
            more = periodic.Solutions(np.array(extra_p), np.array(extra_x),
                                      np.zeros(len(extra_x), dtype=bool), extra_n,
                                      np.full(len(extra_x), np.nan), np.full(len(extra_x), np.inf),
                                      np.zeros((len(extra_x), 2, 2)),
                                      np.zeros((len(extra_x), line.dimension), complex),
                                      [""] * len(extra_x))
            for level in np.unique(extra_n):
                idx = np.flatnonzero(extra_n == level)
                part = periodic.shoot(problem, np.array(extra_p)[idx], np.array(extra_x)[idx],
                                      tol=tol, steps=int(level), progress=tick,
                                      doublings=max(1, periodic.MOST_DOUBLINGS
                                                    - int(round(math.log2(level / n)))))
                more.start[idx], more.converged[idx] = part.start, part.converged
                more.steps[idx], more.accuracy[idx] = part.steps, part.accuracy
                more.multipliers[idx] = part.multipliers
            for i, j in enumerate(extra_j):
                if not more.converged[i]:
                    continue
                if any(np.max(np.abs(more.start[i] - y) / scale[j]) <= SAME for y in starts[j]):
                    continue
                starts[j].append(more.start[i])
                found[j].append(len(records["start"]))
                for key, value in (("start", more.start[i]), ("steps", more.steps[i]),
                                   ("accuracy", more.accuracy[i]),
                                   ("mult", more.multipliers[i]), ("converged", True),
                                   ("reason", ""), ("speed", speeds[j]), ("mesh", None)):
                    records[key].append(value)
        branches = [_branch_curve(line, shaft, branch) for branch in followed]
        stopped = [f"{branch.stopped}, at {branch.parameter[-1, 0] * RAD_PER_S_TO_RPM:.6g} rpm"
                   for branch in followed if branch.stopped and branch.parameter.size]
    if follow and speeds.size > 1:
        _fill(problem, p, speeds, records, found, n, tol, tick)
        _fill_in_time(line, shaft, problem, p, speeds, records, found, n, tol, tick)
        folds += _carry(line, shaft, problem, p, speeds, records, found, n, tol, tick, folds)
    rows = []  # (record, speed index)
    for j in range(speeds.size):
        rows += [(r, j) for r in found[j]] or [(j, j)]
    record = np.array([r for r, _ in rows])
    where = np.array([j for _, j in rows])
    start = np.array(records["start"])[record]
    used = np.array(records["steps"])[record]
    converged = np.array(records["converged"], dtype=bool)[record]
    mult = np.array(records["mult"])[record]
    meshes = [records["mesh"][r] for r in record]
    values = _orbit_values(line, shaft, speeds[where], start, used, converged, meshes)
    twist_amplitude, twist_max, peak, fluctuation, balance, slowest = values
    bad = converged & ~(balance <= BALANCE_TOL)
    reason = [records["reason"][r] for r in record]
    for k in np.flatnonzero(bad):
        reason[k] = (f"the energy balance over the period is off by {balance[k]:.2g} of the "
                     f"largest work (tolerance {BALANCE_TOL:g})")
    converged &= ~bad
    nan = np.where(converged, 1.0, np.nan)
    stability = np.abs(mult[:, 0]) * nan
    # number the solutions at each speed by twist amplitude
    solution = np.zeros(where.size, dtype=int)
    for j in np.unique(where):
        rows_j = np.flatnonzero(where == j)
        order = np.argsort(np.nan_to_num(twist_amplitude[rows_j], nan=-1.0), kind="stable")
        solution[rows_j[order]] = np.arange(1, rows_j.size + 1)
    rigid = 0.5 * tables.slope[0::2, None] * speeds[None, :] ** 2 - tables.load[0::2, None]
    omega_bar = shaft.frequency.omega_bar
    kinds = [periodic.kind_of(mu) if ok else "" for mu, ok in zip(mult, converged)]
    return ResonanceCurve(speeds[where], speeds[where] / omega_bar, solution, peak * nan,
                          np.max(np.abs(rigid), axis=0)[where], twist_amplitude * nan,
                          twist_max * nan, fluctuation * nan, stability, converged, kinds,
                          used, np.array(records["accuracy"], dtype=float)[record], balance,
                          reason, omega_bar,
                          resonances(mechanism, omega_bar, speeds.min(), speeds.max(),
                                     shaft=shaft), n, sorted(folds), branches, tol, stopped,
                          np.where(converged[:, None], start, np.nan),
                          np.array([isinstance(mesh, str) for mesh in meshes], dtype=bool),
                          slowest * nan)


IN_TIME = "time"
"""a record's "mesh" where its solution is in time (``engine.problem_in_time``)"""


def _fill_in_time(line, shaft, problem, p, speeds, records, found, steps, tol, tick) -> None:
    """Speeds still without a converged solution, shot in time (``engine.
    problem_in_time``: where the crank nearly stops or turns back for a moment the path u
    is no variable), from a converged neighbour's solution (one in u carried to the
    section s = 0 first), inwards from both sides of every gap, all fronts at once."""
    from dyade.machine import periodic

    in_time = engine.problem_in_time(line, shaft.tables_at, steps)
    gap = {j for j in range(speeds.size) if not found[j]}  # a front may cross another's
    scale = in_time.scale(p)
    tried = set()
    while True:
        pairs = []  # (speed j, record of its neighbour)
        for j in sorted(gap):
            for k in (j - 1, j + 1):
                if 0 <= k < speeds.size:
                    pairs += [(j, r) for r in found[k] if (j, r) not in tried]
        if not pairs:
            return
        tried.update(pairs)
        js = np.array([j for j, _ in pairs])
        x = np.empty((len(pairs), line.dimension))
        for i, (_, r) in enumerate(pairs):
            source = records["mesh"][r]
            if isinstance(source, str):
                x[i] = records["start"][r]
                continue
            p_from = p[int(np.argmin(np.abs(speeds - records["speed"][r])))][None, :]
            n = int(records["steps"][r])
            mesh = None if source is None else source[None, :]
            path = periodic.trajectory(problem, n, np.asarray(records["start"][r])[None, :],
                                       p_from, mesh=mesh)
            nodes = (np.linspace(0.0, 2.0 * math.pi, n + 1) if source is None
                     else source)[:, None]
            x[i] = engine.section_in_time(path, nodes)[0]
        shot = periodic.shoot(in_time, p[js], x, tol=tol, progress=tick)
        for i, j in enumerate(js):
            if not shot.converged[i] or any(  # the gap's speeds: every distinct solution
                    np.max(np.abs(shot.start[i] - records["start"][r]) / scale[j]) <= 1e-3
                    for r in found[j]):
                continue
            found[j].append(len(records["start"]))
            for key, value in (("start", shot.start[i]), ("steps", shot.steps[i]),
                               ("accuracy", shot.accuracy[i]), ("mult", shot.multipliers[i]),
                               ("converged", True), ("reason", ""), ("speed", speeds[j]),
                               ("mesh", IN_TIME)):
                records[key].append(value)


CARRY_SAME = 1e-4  # [-] two solutions at one speed closer than this (scaled) are one orbit
CARRY_SAME_ACROSS = 1e-3  # [-] ... when one is in crank angle and one in time (the section
# s = 0 of the one in u by linear interpolation between its nodes), their multipliers then
# also within CARRY_SAME
CARRY_FOLD_POINTS = 16  # [-] the most points of the continuation that locates a fold
CARRY_FOLD_INTEGRATIONS = 80  # [-] ... and its most integrations


def _carry(line, shaft, problem, p, speeds, records, found, nodes, tol, tick,
           known_folds) -> list:
    """Every stable solution carried to the neighbouring speeds, whatever they hold
    already: shot there from its state (in its own variable: on its steps, on a mesh of
    its own, or in time), a converged solution that is no row of that speed yet becomes
    one, and a new stable one is carried on (all fronts at once, round by round): the
    coexisting stable motions that a long integration from a neighbour's state settles
    on (the turning-back motion carried past the gap that ``_fill_in_time`` filled, a
    stable motion where the shooting from the linear response found only a saddle).
    Where a stable branch ends between two speeds (its shot at the next speed fails or
    lands on a solution that does not lead back to it), the branch is continued in time
    between the two (``periodic.continuation``) and the fold found there is returned
    (speed [rad/s], upper) for the jump speeds (those within 1e-6 of ``known_folds``
    left out)."""
    from dyade.machine import periodic

    in_time = engine.problem_in_time(line, shaft.tables_at, nodes)
    scale = problem.scale(p)
    sections: dict = {}

    def section(r):
        """The record's state at the section s = 0 of ``problem_in_time``."""
        if r not in sections:
            source = records["mesh"][r]
            if isinstance(source, str):
                sections[r] = np.asarray(records["start"][r])
            else:
                j = int(np.argmin(np.abs(speeds - records["speed"][r])))
                n = int(records["steps"][r])
                path = periodic.trajectory(problem, n, np.asarray(records["start"][r])[None, :],
                                           p[j:j + 1], mesh=None if source is None
                                           else source[None, :])
                at = (np.linspace(0.0, 2.0 * math.pi, n + 1) if source is None
                      else source)[:, None]
                sections[r] = engine.section_in_time(path, at)[0]
        return sections[r]

    def same(r, x, mesh, mult, steps, k) -> bool:
        """Record ``r`` is the solution (x, mesh, mult, steps) at speed k."""
        timed = isinstance(mesh, str)
        if timed == isinstance(records["mesh"][r], str):
            return bool(np.max(np.abs(x - records["start"][r]) / scale[k]) <= CARRY_SAME)
        a = x if timed else None
        b = section(r) if timed else np.asarray(records["start"][r])
        if a is None:  # x in u, r in time
            a, b = _section_of(problem, p[k], x, mesh, int(steps)), records["start"][r]
        close = np.max(np.abs(a - b) / scale[k]) <= CARRY_SAME_ACROSS
        return bool(close and periodic.multiplier_change(
            np.asarray(mult)[None], np.asarray(records["mult"][r])[None])[0] <= CARRY_SAME)

    def stable(r) -> bool:
        return bool(np.abs(records["mult"][r][0]) <= 1.0 + engine.UNSTABLE_MARGIN)

    def shoot(pairs):
        """Shoot the pairs (speed k, record r) from r's state: [(x, mesh, mult, steps,
        accuracy) or None]."""
        groups: dict = {}
        for i, (k, r) in enumerate(pairs):
            source = records["mesh"][r]
            key = (IN_TIME if isinstance(source, str) else
                   ("mesh", source.size) if source is not None else "uniform")
            groups.setdefault(key, []).append(i)
        out = [None] * len(pairs)
        for key, members in groups.items():
            ks = np.array([pairs[i][0] for i in members])
            rs = [pairs[i][1] for i in members]
            x = np.array([records["start"][r] for r in rs])
            mesh = None
            if key == IN_TIME:
                shot = periodic.shoot(in_time, p[ks], x, tol=tol, progress=tick)
            elif key == "uniform":
                shot = periodic.shoot(problem, p[ks], x, tol=tol, progress=tick)
            else:
                p_from = np.array([p[int(np.argmin(np.abs(speeds - records["speed"][r])))]
                                   for r in rs])
                mesh = periodic.mesh_of(problem, key[1], x, p_from, nodes,
                                        np.array([records["mesh"][r] for r in rs]))
                shot = periodic.shoot(problem, p[ks], x, tol=tol, mesh=mesh, progress=tick)
            for m, i in enumerate(members):
                if shot.converged[m]:
                    where = (IN_TIME if key == IN_TIME else None if key == "uniform"
                             else shot.mesh[m])
                    out[i] = (shot.start[m], where, shot.multipliers[m], shot.steps[m],
                              shot.accuracy[m])
        return out

    hit: dict = {}  # (speed k, record r) -> the record at k the shot from r landed on
    tried: set = set()
    continued: set = set()  # the ends continued in time already
    out = []
    whole = float(speeds.max() - speeds.min())
    while True:  # carried, then the ends continued; again where that gave new rows
        for _ in range(2 * speeds.size):  # rounds: at most one per speed and side
            pairs = [(k, r) for j in range(speeds.size) for r in found[j] if stable(r)
                     for k in (j - 1, j + 1) if 0 <= k < speeds.size and (k, r) not in tried]
            if not pairs:
                break
            tried.update(pairs)
            for (k, r), result in zip(pairs, shoot(pairs)):
                if result is None:
                    hit[(k, r)] = None
                    continue
                x, mesh, mult, steps, accuracy = result
                match = [q for q in found[k] if same(q, x, mesh, mult, steps, k)]
                if match:
                    hit[(k, r)] = match[0]
                    continue
                hit[(k, r)] = len(records["start"])
                found[k].append(len(records["start"]))
                for key, value in (("start", x), ("steps", steps), ("accuracy", accuracy),
                                   ("mult", mult), ("converged", True), ("reason", ""),
                                   ("speed", speeds[k]), ("mesh", mesh)):
                    records[key].append(value)
        # where a stable branch ends: its shot at the next speed failed, or landed on a
        # solution whose shot back does not land on it (the unstable ones shot back now)
        back = [(int(np.argmin(np.abs(speeds - records["speed"][r]))), q)
                for (k, r), q in hit.items() if q is not None and (
                    int(np.argmin(np.abs(speeds - records["speed"][r]))), q) not in hit]
        back = sorted(set(back))
        for (j, q), result in zip(back, shoot(back) if back else []):
            hit[(j, q)] = None if result is None else next(
                (r for r in found[j] if same(r, *result[:4], j)), None)
        ends = []
        for (k, r), q in hit.items():
            if not stable(r) or (k, r) in continued:
                continue
            j = int(np.argmin(np.abs(speeds - records["speed"][r])))
            if q is None or hit.get((j, q)) != r:
                ends.append((j, k, r))
        seeds = []  # (speed k, a state on the branch there): a shot too far for Newton
        for j, k, r in ends:
            continued.add((k, r))
            low, high = sorted((float(speeds[j]), float(speeds[k])))
            branch = periodic.continuation(in_time, section(r), p[j], (low, high),
                                           steps=2 * nodes, direction=1.0 if k > j else -1.0,
                                           width=whole, most=CARRY_FOLD_POINTS,
                                           ds=0.5 * (high - low) / whole,
                                           integrations=CARRY_FOLD_INTEGRATIONS, progress=tick)
            between = [fold for fold in branch.folds if low <= fold.parameter <= high]
            for fold in between:
                if not any(abs(fold.parameter - f) <= 1e-6 * f and up == fold.upper
                           for f, up in known_folds + out):
                    out.append((fold.parameter, fold.upper))
            if not between:  # the branch goes on to speed k: seeded from where it crosses
                seeds += [(k, x) for x in periodic.branch_guesses(branch, float(speeds[k]))]
        added = 0
        if seeds:
            ks = np.array([k for k, _ in seeds])
            shot = periodic.shoot(in_time, p[ks], np.array([x for _, x in seeds]), tol=tol,
                                  progress=tick)
            for m, k in enumerate(ks.tolist()):
                if not shot.converged[m] or any(
                        same(q, shot.start[m], IN_TIME, shot.multipliers[m], shot.steps[m], k)
                        for q in found[k]):
                    continue
                found[k].append(len(records["start"]))
                added += 1
                for key, value in (("start", shot.start[m]), ("steps", shot.steps[m]),
                                   ("accuracy", shot.accuracy[m]), ("mult", shot.multipliers[m]),
                                   ("converged", True), ("reason", ""), ("speed", speeds[k]),
                                   ("mesh", IN_TIME)):
                    records[key].append(value)
        if not added:
            break
    return out


def _section_of(problem, p, x, mesh, steps: int) -> FloatArray:
    """The state (d,) at the section s = 0 of ``engine.problem_in_time`` of the solution
    ``x`` in u at the parameters ``p`` (q,) on ``mesh`` (None: ``steps`` uniform steps)."""
    from dyade.machine import periodic

    n = steps
    path = periodic.trajectory(problem, n, np.asarray(x)[None, :], np.asarray(p)[None, :],
                               mesh=None if mesh is None else np.asarray(mesh)[None, :])
    at = (np.linspace(0.0, 2.0 * math.pi, n + 1) if mesh is None else np.asarray(mesh))
    return engine.section_in_time(path, at[:, None])[0]


def _fill(problem, p, speeds, records, found, nodes, tol, tick) -> None:
    """Speeds still without a converged solution, shot from a converged neighbour's
    solution on a mesh of their own (``periodic.mesh_of``: the nodes gathered where the
    crank nearly stops, the steps halved by accuracy), speed by speed inwards from both
    sides of every gap, all gaps' fronts at once."""
    from dyade.machine import periodic

    tried = set()
    while True:
        pairs = []  # (speed j, record of its neighbour)
        for j in range(speeds.size):
            if found[j]:
                continue
            for k in (j - 1, j + 1):
                if 0 <= k < speeds.size:
                    pairs += [(j, r) for r in found[k] if (j, r) not in tried]
        if not pairs:
            return
        tried.update(pairs)
        groups: dict = {}
        for j, r in pairs:
            source = records["mesh"][r]
            if isinstance(source, str):  # in time: for ``_fill_in_time``
                continue
            key = ("mesh", source.size) if source is not None else ("steps",
                                                                     int(records["steps"][r]))
            groups.setdefault(key, []).append((j, r))
        for (what, size), group in groups.items():
            js = np.array([j for j, _ in group])
            rs = [r for _, r in group]
            x = np.array([records["start"][r] for r in rs])
            p_from = np.array([p[int(np.argmin(np.abs(speeds - records["speed"][r])))]
                               for r in rs])
            source = np.array([records["mesh"][r] for r in rs]) if what == "mesh" else None
            mesh = periodic.mesh_of(problem, size, x, p_from, nodes, source)
            shot = periodic.shoot(problem, p[js], x, tol=tol, mesh=mesh, progress=tick)
            for i, j in enumerate(js):
                if not shot.converged[i] or found[j]:
                    continue
                found[j].append(len(records["start"]))
                for key, value in (("start", shot.start[i]), ("steps", shot.steps[i]),
                                   ("accuracy", shot.accuracy[i]),
                                   ("mult", shot.multipliers[i]), ("converged", True),
                                   ("reason", ""), ("speed", speeds[j]),
                                   ("mesh", shot.mesh[i])):
                    records[key].append(value)


def _orbit_values(line, shaft, speed, start, steps, converged, meshes=None):
    """Twist amplitude and largest |twist| [rad], peak shaft torque [N·m], speed
    fluctuation [-], the energy balance [-] and the crank's slowest speed over Ω [-]
    (negative: it turns back for a moment) of each row's orbit (NaN where not
    converged), one integration per step count (or per size of the rows' own
    ``meshes``, or in time where a row's mesh is ``IN_TIME``) (the scans' line: an
    ideal motor, one shaft)."""
    from dyade.machine import periodic

    rows = speed.size
    out = [np.full(rows, np.nan) for _ in range(6)]
    meshes = meshes or [None] * rows
    sizes = np.array([-2 if isinstance(mesh, str) else -1 if mesh is None else mesh.size
                      for mesh in meshes])
    for n, size in {(int(n), int(z)) for n, z, ok in zip(steps, sizes, converged) if ok}:
        idx = np.flatnonzero(converged & (steps == n) & (sizes == size))
        problem = (engine.problem_in_time if size == -2 else engine.problem)(
            line, shaft.tables_at, int(n), works=True)
        p = engine.parameters(line, speed[idx])
        x0 = np.pad(start[idx], ((0, 0), (0, 3)))
        mesh = None if size < 0 else np.array([meshes[i] for i in idx])
        path = periodic.trajectory(problem, int(n), x0, p, mesh=mesh)
        twist = path[:, :, 1]
        crank = speed[idx][None, :] + path[:, :, 0]
        torque = p[:, 1] * path[:, :, 1] - p[:, 2] * path[:, :, 0]
        out[0][idx] = 0.5 * (twist.max(axis=0) - twist.min(axis=0))
        out[1][idx] = np.max(np.abs(twist), axis=0)
        out[2][idx] = np.max(np.abs(torque), axis=0)
        out[3][idx] = (crank.max(axis=0) - crank.min(axis=0)) / speed[idx]
        work = path[-1, :, 2:]  # motor, damping, loads (∫ s·M_L du: what they give) [J]
        out[4][idx] = (np.abs(work[:, 0] + work[:, 2] - work[:, 1])
                       / np.maximum(np.max(np.abs(work), axis=1), 1e-300))
        out[5][idx] = crank.min(axis=0) / speed[idx]
    return out


def _branch_curve(line, shaft, branch) -> tuple:
    """(speed, largest |twist|, unstable, kind, largest |μ|) along a branch of the
    continuation."""
    from dyade.machine import periodic

    if not branch.parameter.shape[0]:
        return (np.empty(0), np.empty(0), np.empty(0, dtype=bool), [], np.empty(0))
    speed = branch.parameter[:, 0]
    twist = np.empty(speed.size)
    for n in np.unique(branch.steps):
        idx = np.flatnonzero(branch.steps == n)
        problem = engine.problem(line, shaft.tables_at, int(n))
        path = periodic.trajectory(problem, int(n), branch.start[idx], branch.parameter[idx])
        twist[idx] = np.max(np.abs(path[:, :, 1]), axis=0)
    return speed, twist, branch.unstable, branch.kind, np.abs(branch.multipliers[:, 0])


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class StabilityMap:
    """The largest Floquet multiplier over speed × a parameter of the line."""

    speed: FloatArray
    """(s,) Ω [rad/s]"""
    parameter: str
    """"stiffness" [N·m/rad] or "damping" [N·m·s/rad]"""
    values: FloatArray
    """(p,) the parameter's values"""
    stability: FloatArray
    """(p, s) the largest ``|μ|`` [-]; NaN where no periodic state was found"""
    edges: Edges | None = None
    """the boundaries of the unstable regions traced between the cells (``trace_edges``);
    None when not traced"""

    @property
    def unstable(self) -> FloatArray:
        return self.stability > 1.0 + engine.UNSTABLE_MARGIN


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Edges:
    """Points of the stability boundary of a map, each solved in speed at its row's
    parameter value (``periodic.boundary``: a multiplier at −1 or +1 to its tolerance)."""

    speed: FloatArray
    """(e,) Ω at the boundary [rad/s] (converged points only)"""
    values: FloatArray
    """(e,) the parameter's value of each point (the row of the map)"""
    kind: list
    """(e,) ``periodic.FLIP`` (a multiplier through −1) or ``periodic.FOLD`` (+1)"""
    missed: list = field(default_factory=list)
    """why a crossing between two cells was not traced: (value, speed low, speed high,
    reason) — a complex pair leaving the unit circle (not traced), or a point that did
    not converge"""


def trace_edges(shaft: CrankShaft, line: engine.Line, name: str, values: FloatArray,
                speeds: FloatArray, solution: engine.Periodic, steps: int,
                progress: Callable[[], None] | None = None) -> Edges:
    """The boundary |μ| = 1 of a sampled map traced: between every two neighbouring
    cells of a row (a value of ``name``) of which one is stable and one unstable, the
    speed where the multiplier leaving the unit circle is −1 (period doubling) or +1
    (fold), solved by ``periodic.boundary`` from the linear interpolation of the cells
    (all crossings of a kind in one integration), converged to ``periodic.ACCURACY``
    with twice the steps. ``solution`` is the map's (values × speeds, row by row)."""
    from dyade.machine import periodic

    s, v = speeds.size, values.size
    mult = solution.multipliers.reshape(v, s, -1)
    stab = np.where(solution.converged, np.abs(solution.multipliers[:, 0]),
                    np.nan).reshape(v, s)
    bad = stab > 1.0 + engine.UNSTABLE_MARGIN
    given = np.isfinite(stab)
    row, col = np.nonzero(given[:, :-1] & given[:, 1:] & (bad[:, :-1] != bad[:, 1:]))
    missed, todo = [], {1.0: [], -1.0: []}
    for j, i in zip(row, col):
        top = mult[j, i + 1 if bad[j, i + 1] else i, 0]
        if abs(top.imag) > periodic.REAL * abs(top):
            missed.append((values[j], speeds[i], speeds[i + 1],
                           "a complex pair leaves the unit circle (not traced)"))
            continue
        todo[1.0 if top.real > 0.0 else -1.0].append((j, i))
    problem = engine.problem(line, shaft.tables_at, steps)
    column = 1 if name == "stiffness" else 2
    found_speed, found_value, kinds = [], [], []
    for sigma, pairs in todo.items():
        if not pairs:
            continue
        j, i = np.array(pairs).T
        g0 = np.prod(mult[j, i] - sigma, axis=1).real
        g1 = np.prod(mult[j, i + 1] - sigma, axis=1).real
        share = np.clip(np.where(g0 != g1, g0 / np.where(g0 != g1, g0 - g1, 1.0), 0.5), 0, 1)
        guess_speed = speeds[i] + share * (speeds[i + 1] - speeds[i])
        k = np.full(j.size, line.stiffness[0]) if name != "stiffness" else values[j]
        b = np.full(j.size, line.damping[0]) if name != "damping" else values[j]
        rows = engine.parameters(line, guess_speed, k[:, None], b[:, None])
        stable_cell = np.where(bad[j, i], i + 1, i)
        start = solution.start.reshape(v, s, -1)[j, stable_cell]
        edge = periodic.boundary(problem, rows, start, crossing=sigma, block=j.size,
                                 steps=steps, doublings=1, along=column, follow=False,
                                 reach=speeds[i + 1] - speeds[i], progress=progress)
        for n in range(j.size):
            ok = (edge.converged[n] and
                  speeds[i[n]] - 1e-9 <= edge.parameter[n, 0] <= speeds[i[n] + 1] + 1e-9)
            if ok:
                found_speed.append(edge.parameter[n, 0])
                found_value.append(values[j[n]])
                kinds.append(edge.kind)
            else:
                missed.append((values[j[n]], speeds[i[n]], speeds[i[n] + 1], edge.reason[n]
                               or "the boundary point left its two cells"))
    order = np.lexsort((np.array(found_speed), np.array(found_value))) if found_speed else []
    return Edges(np.array(found_speed)[order] if found_speed else np.empty(0),
                 np.array(found_value)[order] if found_speed else np.empty(0),
                 [kinds[n] for n in order], missed)


def stability_map(mechanism: Mechanism, speeds_rpm, *, stiffness=None, damping=None,
                  steps: int | None = None, shaft: CrankShaft | None = None,
                  edges_too: bool = True,
                  progress: Callable[[int], None] | None = None) -> StabilityMap:
    """The largest Floquet multiplier over the ideal motor's speeds ``speeds_rpm`` [rpm]
    and the shaft's ``stiffness`` [N·m/rad] or ``damping`` [N·m·s/rad] values (one of
    the two), all lanes in one integration.

    Parameters
    ----------
    mechanism : Mechanism
        With a ``[drive_line]`` shaft (not a coupling).
    speeds_rpm : array_like
        Crank speeds of the ideal motor [rpm].
    stiffness, damping : array_like
        The values to map [N·m/rad] or [N·m·s/rad]: give one of the two.
    steps : int, optional
        RK4 steps per revolution.
    shaft : CrankShaft, optional
        The mechanism's crank shaft (``crank_shaft``), when the caller has it.
    edges_too : bool
        Trace the boundaries of the unstable regions between the cells
        (``trace_edges``; default True).
    progress : callable, optional
        ``progress(iteration)`` hears each Newton iteration of the shooting.

    Returns
    -------
    StabilityMap
        ``stability`` (values, speeds): the largest ``|μ|``; ``edges``: the traced
        boundary.

    Examples
    --------
    >>> import dyade
    >>> m = dyade.read_mechanism("mechanisms/dyade-16.toml", {"drive_line.stiffness": 1000.0})
    >>> chart = stability_map(m, [3575.0], damping=[0.04, 0.3])   # [N·m·s/rad]
    >>> chart.unstable[:, 0].tolist()                 # damping above ≈ 0.17 removes it
    [True, False]
    """
    if (stiffness is None) == (damping is None):
        raise InputError.parameter(("stiffness", "damping"), "give one of the two to map.")
    speeds = _speeds(speeds_rpm)
    shaft = shaft or crank_shaft(mechanism)
    line = shaft.ideal_line
    if line.elements != 1:
        raise InputError.parameter("stiffness", "maps only a shaft, not a coupling, over "
                                                "its stiffness or damping.")
    name = "stiffness" if stiffness is not None else "damping"
    values = np.atleast_1d(np.asarray(stiffness if stiffness is not None else damping,
                                      dtype=np.float64))
    bad = ~np.isfinite(values) | (values <= 0.0 if name == "stiffness" else values < 0.0)
    if bad.any():
        need = "positive" if name == "stiffness" else "zero or more"
        raise InputError.parameter(name, f"must be {need}, got {values[bad][0]:g}.")
    grid_speed = np.tile(speeds, values.size)
    grid_value = np.repeat(values, speeds.size)
    k = grid_value if name == "stiffness" else np.full(grid_value.size, line.stiffness[0])
    b = grid_value if name == "damping" else np.full(grid_value.size, line.damping[0])
    n, tables = (steps, shaft.tables_at(steps)) if steps else _steps(
        shaft, line, float(speeds.min()), np.array([k.max()]))
    lanes = engine.Lanes.of(line, grid_speed, k[:, None], b[:, None])
    solution = _solve(line, tables, lanes, progress)
    edges = None
    if edges_too and speeds.size > 1:
        tick = None if progress is None else (lambda: progress(0))
        edges = trace_edges(shaft, line, name, values, speeds, solution, n, tick)
    return StabilityMap(speeds, name, values, solution.stability.reshape(values.size, -1),
                        edges)


RUN_UP_TOL = 1e-5  # [-] change of the mean speed from one revolution to the next: at speed
STEPS_PER_VIBRATION_IN_TIME = 40  # RK4 time steps per period of the highest natural frequency


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class RunUp:
    """The run-up from rest through the resonances under the motor's characteristic."""

    time: FloatArray
    """(K,) t [s]"""
    crank_angle: FloatArray
    """(K,) φ [rad] (unwrapped)"""
    crank_speed: FloatArray
    """(K,) crank speed in the running direction [rad/s]"""
    motor_speed: FloatArray
    """(K,) motor speed reduced to the crank shaft [rad/s]"""
    shaft_torque: FloatArray
    """(K,) torque of the elastic element into the crank shaft [N·m]"""
    twist: FloatArray
    """(K,) twist of the line [rad]"""
    figures: dict
    """largest |shaft torque|, when and at which speed; the time to speed; revolutions"""


def run_up(mechanism: Mechanism, *, steps: int | None = None,
           shaft: CrankShaft | None = None,
           progress: Callable[[int], None] | None = None) -> RunUp:
    """The run-up from rest at the sweep's start angle (the line untwisted) with the
    ``[drive]`` motor, in time, until the mean speed over a revolution settles; the
    largest shaft torque on the way.

    Parameters
    ----------
    mechanism : Mechanism
        With ``[drive]`` (the motor) and ``[drive_line]`` (with ``rotor_inertia``).
    steps : int, optional
        Grid of the crank shaft's tables per revolution (default: the table's, else 720).
    shaft : CrankShaft, optional
        The mechanism's crank shaft (``crank_shaft``), when the caller has it.
    progress : callable, optional
        ``progress(revolutions)`` hears each revolution completed.

    Returns
    -------
    RunUp
        The history in time and ``figures`` (largest shaft torque, when, at which speed).

    Examples
    --------
    >>> import dyade
    >>> m = dyade.read_mechanism("mechanisms/dyade-16.toml", {
    ...     "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04,
    ...     "drive_line.rotor_inertia": 0.01, "drive.motor": "asynchronous",
    ...     "drive.rated_torque": 20.0, "drive.rated_speed_rpm": 290.0,
    ...     "drive.synchronous_speed_rpm": 300.0})
    >>> run = run_up(m)
    >>> speed_mean = float(run.figures["speed_mean"]) * RAD_PER_S_TO_RPM   # [rpm]
    >>> round(run.figures["peak_torque"], 1), round(speed_mean, 1)
    (146.4, 298.9)

    Raises
    ------
    InputError
        No ``[drive]`` motor (an ideal motor has no run-up).
    DyadeError
        The machine never reaches speed within ``[drive] max_revolutions`` (or the time
        they would take at half the steady speed): the motor cannot bring it up.
    """
    if mechanism.drive is None:
        raise InputError(f"{mechanism.name}: a run-up needs the motor's characteristic: add a "
                         f"[drive] table (and `drive_line.rotor_inertia`).", key="drive")
    shaft = shaft or crank_shaft(mechanism)
    line = shaft.line
    if isinstance(line.motor, ConstantTorque) and line.motor.torque is None:
        raise InputError("a run-up needs the torque of the constant-torque motor: give "
                         "`drive.torque` [N·m].", key="drive.torque")
    n = steps or line_data(mechanism).steps or engine.MIN_STEPS
    tables = shaft.tables_at(n)
    top = float(engine.natural_frequencies(line, np.array([np.min(tables.inertia)]))[0, -1])
    dt = 2.0 * math.pi / (STEPS_PER_VIBRATION_IN_TIME * top)
    reference = (abs(mechanism.crank.speed) if isinstance(line.motor, ConstantTorque)
                 else _reference_speed(mechanism, line.motor, tables))
    revolutions = mechanism.drive.max_revolutions
    t_max = 2.0 * revolutions * 2.0 * math.pi / reference
    path = engine.run_up(line, tables, dt=dt, t_max=t_max, tol=RUN_UP_TOL,
                         max_revolutions=revolutions, progress=progress)
    sense = sense_of(mechanism)
    if not path.settled:
        raise DyadeError(f"the machine does not reach speed: after {path.time[-1]:.4g} s and "
                         f"{path.revolutions} revolutions its speed still changes (top crank "
                         f"speed {np.max(path.crank_speed) * RAD_PER_S_TO_RPM:.5g} rpm): the "
                         f"motor cannot bring it up, or nothing holds its speed (a constant "
                         f"torque against loads that do not rise with speed), or it needs more than "
                         f"`drive.max_revolutions`.")
    peak = int(np.argmax(np.abs(path.shaft_torque)))
    figures = {"peak_torque": float(path.shaft_torque[peak]), "peak_time": float(path.time[peak]),
               "peak_speed": float(path.crank_speed[peak]), "duration": float(path.time[-1]),
               "revolutions": path.revolutions, "speed_mean": path.mean_speed,
               "time_step": dt,
               "omega_bar": shaft.frequency.omega_bar}
    return RunUp(path.time, mechanism.sweep.start + sense * path.path, path.crank_speed,
                 path.motor_speed, path.shaft_torque, path.twist, figures)


def forces(mechanism: Mechanism, state: SteadyState, **options):
    """The sweep of ``mechanism`` at the real crank motion of the drive line's steady
    state: every joint force, the drive torque (which is then the shaft torque) and all
    other columns, at the state's positions (one revolution, without its repeated end),
    by ``dyade.analyse`` with the crank's speed and acceleration per position.
    ``options`` go to ``dyade.analyse``."""
    from dyade.linkage.sweep import analyse

    sense = sense_of(mechanism)
    return analyse(mechanism, crank_angle_deg=np.degrees(state.crank_angle[:-1]),
                   crank_speed=sense * state.crank_speed[:-1],
                   crank_acceleration=sense * state.crank_acceleration[:-1],
                   constant_speed=True, **options)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class PeriodTwo:
    """The period-2 motions of the line (an ideal motor, one shaft) where the period-1
    motion loses its stability by period doubling (a multiplier below −1): shot over
    two revolutions in time (``engine.problem_in_time``)."""

    speed: FloatArray
    """(s,) Ω [rad/s]"""
    eta: FloatArray
    """(s,) Ω/ω̄ [-]"""
    found: FloatArray
    """(s,) bool: a period-2 orbit, periodic to the tolerance and distinct from the
    period-1 orbit"""
    start: FloatArray
    """(s, d) its state at the motor's angle s = 0 (δv [rad/s], twist [rad]); NaN where
    not found"""
    multipliers: FloatArray
    """(s, d) its Floquet multipliers over two revolutions, largest modulus first"""
    single: FloatArray
    """(s, d) the multipliers of the period-1 orbit it bifurcated from"""
    reason: list
    """(s,) why none was found ("" where one was)"""
    steps: FloatArray | None = None
    """(s,) RK4 steps per revolution of the period-2 orbit (0 where not found)"""
    twist_amplitude: FloatArray | None = None
    """(s,) (max − min)/2 of the twist over the two revolutions [rad]; NaN where not
    found"""
    twist_max: FloatArray | None = None
    """(s,) the largest |twist| over the two revolutions [rad]"""
    peak_torque: FloatArray | None = None
    """(s,) the largest |shaft torque| over the two revolutions [N·m]"""
    fluctuation: FloatArray | None = None
    """(s,) (max − min)/Ω of the crank speed over the two revolutions [-]"""
    accuracy: FloatArray | None = None
    """(s,) the change of the orbit and its multipliers with twice the steps [-]"""
    balance: FloatArray | None = None
    """(s,) the energy balance over the two revolutions, of the largest work [-]"""
    slowest: FloatArray | None = None
    """(s,) the crank's slowest speed over Ω [-] (negative: it turns back)"""

    @property
    def stability(self) -> FloatArray:
        """(s,) the largest |μ| over two revolutions (NaN where not found)."""
        return np.where(self.found, np.abs(self.multipliers[:, 0]), np.nan)


PERIOD_TWO_SEEDS = (0.05, -0.05, 0.3, -0.3, 1.0, -1.0)
"""[-] the displacements from the period-1 orbit along the eigenvector of its multiplier
below −1 (the largest component, of the state's scale) that seed the period-2 shooting"""


def period_two(mechanism: Mechanism, speeds_rpm, *, steps: int | None = None,
               tolerance: float | None = None, shaft: CrankShaft | None = None,
               curve: ResonanceCurve | None = None) -> PeriodTwo:
    """The period-2 motions at the ideal motor's speeds ``speeds_rpm`` [rpm]: where the
    period-1 orbit (shot in time from the linear response) has a multiplier below −1,
    shot over two revolutions from it displaced along that multiplier's eigenvector
    (``PERIOD_TWO_SEEDS``, all speeds and seeds at once), the steps doubled by accuracy;
    a solution that is the period-1 orbit again does not count. Where no seed leads to
    one, the machine's own motion is followed: a long integration from the unstable
    orbit (``_settle``: ``PERIOD_TWO_SETTLE`` revolutions) and the period-2 orbit shot
    from where it arrives (dyade-16 at 3575 rpm: the period-2 motion lies about 1.7 rad
    of twist away from the period-1 orbit, out of the seeds' reach).

    Parameters
    ----------
    mechanism : Mechanism
        With a ``[drive_line]`` shaft.
    speeds_rpm : array_like
        Crank speeds [rpm], all of one sign, none zero.
    steps : int, optional
        RK4 steps per revolution to start with (default as for ``resonance_curve``).
    tolerance : float, optional
        The change with twice the steps that counts as converged [-].
    shaft : CrankShaft, optional
        The mechanism's crank shaft, when the caller has it.
    curve : ResonanceCurve, optional
        A scan of these speeds (``resonance_curve``): its flipping period-1 orbit at a
        speed (carried to the section s = 0 where it was found in crank angle) is the
        guess of the period-1 shooting in time there, not the linear response.

    Returns
    -------
    PeriodTwo
    """
    from dyade.machine import periodic

    tol = periodic.ACCURACY if tolerance is None else float(tolerance)
    speeds = _speeds(speeds_rpm)
    shaft = shaft or crank_shaft(mechanism)
    line = shaft.ideal_line
    if line.elements != 1:
        raise InputError.parameter("speeds_rpm", "period-2 motions are for a shaft, not a "
                                                 "coupling.")
    n, tables = (steps, shaft.tables_at(steps)) if steps else _steps(
        shaft, line, float(speeds.min()))
    problem = engine.problem_in_time(line, shaft.tables_at, n)
    p = engine.parameters(line, speeds)
    guess = engine.linear_guess(line, tables, engine.Lanes.of(line, speeds))
    if curve is not None:
        guess = _scan_guess(line, shaft, curve, speeds, p, guess)
    one = periodic.shoot(problem, p, guess, tol=tol)
    d = line.dimension
    found = np.zeros(speeds.size, dtype=bool)
    start = np.full((speeds.size, d), np.nan)
    mult = np.full((speeds.size, d), np.nan, dtype=complex)
    reason = [""] * speeds.size
    flip = np.zeros(speeds.size, dtype=bool)
    vectors = np.zeros((speeds.size, d))
    for j in range(speeds.size):
        if not one.converged[j]:
            reason[j] = f"no period-1 orbit to start from: {one.reason[j]}"
            continue
        values, vecs = np.linalg.eig(one.monodromy[j])
        k = int(np.argmin(values.real))
        if not (abs(values[k].imag) <= periodic.REAL * abs(values[k])
                and values[k].real < -1.0 - periodic.UNSTABLE_MARGIN):
            reason[j] = "the period-1 orbit has no multiplier below −1 (no period doubling)"
            continue
        flip[j] = True
        vectors[j] = vecs[:, k].real / np.max(np.abs(vecs[:, k].real))
    scale = problem.scale(p)
    todo = np.flatnonzero(flip)
    used = np.zeros(speeds.size, dtype=int)
    accuracy = np.full(speeds.size, np.nan)
    settled = np.zeros(speeds.size, dtype=bool)
    for stage in ("seeds", "settled"):
        todo = todo[~found[todo]]
        if not todo.size:
            break
        if stage == "seeds":  # every speed's seeds along its flip direction at once
            amounts = np.array(PERIOD_TWO_SEEDS)
            lanes = np.repeat(todo, amounts.size)
            seed = (one.start[lanes] + np.tile(amounts, todo.size)[:, None] * vectors[lanes]
                    * scale[lanes])
        else:  # what the machine does: a long integration from the unstable orbit
            lanes = todo
            seed = _settle(problem, one.start[todo], vectors[todo] * scale[todo], p[todo])
            settled[todo] = np.all(np.isfinite(seed), axis=1)
            lanes, seed = lanes[settled[todo]], seed[settled[todo]]
            if not lanes.size:
                break
        shot = periodic.shoot(problem, p[lanes], seed, tol=tol, periods=2,
                              retry=stage == "settled")
        apart = np.max(np.abs(shot.start - one.start[lanes]) / scale[lanes], axis=1) > 1e-3
        for m in np.flatnonzero(shot.converged & apart):
            j = lanes[m]
            if found[j]:
                continue
            found[j] = True
            start[j], mult[j] = shot.start[m], shot.multipliers[m]
            used[j], accuracy[j] = shot.steps[m], shot.accuracy[m]
    for j in np.flatnonzero(flip & ~found):
        reason[j] = ("no period-2 orbit found beside the period-1 orbit: the shooting from its "
                     "flip direction converged to nothing else, and "
                     + (f"{PERIOD_TWO_SETTLE} revolutions from it (a long integration) settle "
                        "on no period-2 motion (a longer period, a quasi-periodic or a "
                        "chaotic motion)" if settled[j] else
                        "a long integration from it is lost (the crank stops)"))
    values = [np.full(speeds.size, np.nan) for _ in range(6)]
    for level in np.unique(used[found]):  # the orbit over its two revolutions, with works
        idx = np.flatnonzero(found & (used == level))
        path = periodic.trajectory(engine.problem_in_time(line, shaft.tables_at, int(level),
                                                          works=True),
                                   int(level), np.pad(start[idx], ((0, 0), (0, 3))), p[idx],
                                   periods=2)
        twist = path[:, :, 1]
        crank = speeds[idx][None, :] + path[:, :, 0]
        torque = p[idx, 1] * twist - p[idx, 2] * path[:, :, 0]
        values[0][idx] = 0.5 * (twist.max(axis=0) - twist.min(axis=0))
        values[1][idx] = np.max(np.abs(twist), axis=0)
        values[2][idx] = np.max(np.abs(torque), axis=0)
        values[3][idx] = np.ptp(crank, axis=0) / speeds[idx]
        work = path[-1, :, 2:]  # motor, damping, loads [J] (as ``_orbit_values``)
        values[4][idx] = (np.abs(work[:, 0] + work[:, 2] - work[:, 1])
                          / np.maximum(np.max(np.abs(work), axis=1), 1e-300))
        values[5][idx] = crank.min(axis=0) / speeds[idx]
    for j in np.flatnonzero(found & ~(values[4] <= BALANCE_TOL)):
        found[j] = False
        reason[j] = (f"the energy balance over the two revolutions is off by {values[4][j]:.2g} "
                     f"of the largest work (tolerance {BALANCE_TOL:g})")
    return PeriodTwo(speeds, speeds / shaft.frequency.omega_bar, found, start, mult,
                     one.multipliers, reason, used, *values[:4], accuracy, *values[4:])


PERIOD_TWO_SETTLE = 400  # [-] revolutions of the long integration from the unstable orbit
PERIOD_TWO_SETTLE_STEPS = 90  # [-] its RK4 steps per revolution (a guess, not an answer: the
# period-2 orbit is then shot from it with the steps by accuracy)
PERIOD_TWO_PUSH = 0.1  # [-] the push off the unstable orbit along its flip direction, of the
# state's scale


def _settle(problem, start: FloatArray, direction: FloatArray, p: FloatArray) -> FloatArray:
    """Where the machine goes from its unstable period-1 orbit ``start`` (L, d) pushed by
    ``PERIOD_TWO_PUSH`` along its flip ``direction`` (L, d; of the scale): the state after
    ``PERIOD_TWO_SETTLE`` revolutions (an even count) on a coarse grid of
    ``PERIOD_TWO_SETTLE_STEPS`` per revolution, all speeds at once; NaN where lost. Near
    a flip whose period-2 branch folds back (subcritical) the period-2 motion lies far
    from the orbit, beyond the reach of the pushes of ``PERIOD_TWO_SEEDS``."""
    from dyade.machine import periodic

    x = periodic.flow(problem, PERIOD_TWO_SETTLE_STEPS, start + PERIOD_TWO_PUSH * direction, p,
                      periods=PERIOD_TWO_SETTLE)
    return np.where(np.all(np.isfinite(x), axis=1)[:, None], x, np.nan)


def _scan_guess(line, shaft, curve: ResonanceCurve, speeds, p, guess) -> FloatArray:
    """``guess`` (s, d) with the scan's own flipping period-1 orbit at each speed it has
    one (a converged row with a multiplier below −1), at the section s = 0 of
    ``engine.problem_in_time``: as it is where the row was found in time, else its orbit
    in crank angle integrated over one revolution and cut there."""
    from dyade.machine import periodic

    guess = np.array(guess, dtype=np.float64)
    in_time = np.zeros(len(curve.speed), dtype=bool) if curve.in_time is None else curve.in_time
    pick = []  # (speed index, row)
    for j, speed in enumerate(speeds):
        rows = np.flatnonzero(np.isclose(curve.speed, speed, rtol=1e-9) & curve.converged
                              & np.array([k == periodic.FLIP for k in curve.kind], dtype=bool))
        if rows.size:
            pick.append((j, int(rows[0])))
    for j, r in pick:
        if in_time[r]:
            guess[j] = curve.start[r]
    for n in {int(curve.steps_used[r]) for j, r in pick if not in_time[r]}:
        chosen = [(j, r) for j, r in pick if not in_time[r] and int(curve.steps_used[r]) == n]
        js = np.array([j for j, _ in chosen])
        x0 = np.array([curve.start[r] for _, r in chosen])
        path = periodic.trajectory(engine.problem(line, shaft.tables_at, n), n, x0, p[js])
        nodes = np.repeat(np.linspace(0.0, 2.0 * math.pi, n + 1)[:, None], js.size, axis=1)
        guess[js] = engine.section_in_time(path, nodes)
    return guess
