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
- ``stability_map``: the largest Floquet multiplier over speed × stiffness or damping;
- ``run_up``: from rest under the motor's characteristic, in time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError, InputError
from dyade.linkage.drive import crank_tables, natural_frequency
from dyade.machine import drive_line as engine
from dyade.machine.drive_line import line_data, line_of, sense_of
from dyade.machine.motor import operating_speed
from dyade.model.drive import ConstantTorque, Motor
from dyade.model.mechanism import Mechanism
from dyade.units import RAD_PER_S_TO_RPM

HARMONIC_SHARE = 1e-3  # [-] harmonics of J or M_L above this share of the largest are labelled


def _steps(mechanism: Mechanism, line: engine.Line, speed_min: float,
           stiffness_max: FloatArray | None = None) -> tuple[int, engine.Tables]:
    data = line_data(mechanism)
    coarse = crank_tables(mechanism, engine.MIN_STEPS)
    steps = data.steps or engine.steps_for(line, float(np.min(coarse.inertia)), speed_min,
                                           stiffness_max)
    return steps, (coarse if steps == engine.MIN_STEPS else crank_tables(mechanism, steps))


def resonances(mechanism: Mechanism, omega_bar: float, low: float, high: float
               ) -> list[tuple[int, float, str]]:
    """The speeds [rad/s] within [low, high] where resonances are to be expected: forced
    at Ω = ω̄/k for each harmonic k present in J(φ) or M_L(φ), parametric at Ω = 2ω̄/k
    for each harmonic k of J(φ). (k, speed, "forced" | "parametric"), by speed."""
    tables = crank_tables(mechanism, engine.MIN_STEPS)
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


def _solve(line: engine.Line, tables: engine.Tables, lanes: engine.Lanes) -> engine.Periodic:
    return engine.periodic(line, tables, lanes, engine.linear_guess(line, tables, lanes))


def steady_state(mechanism: Mechanism, *, speed_rpm: float | None = None,
                 steps: int | None = None, accuracy: bool = True) -> SteadyState:
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
    line = line_of(mechanism)
    if speed_rpm is not None and not line.ideal:
        raise InputError.parameter("speed_rpm", "is for an ideal motor; a [drive] motor finds "
                                                "its own speed.")
    probe = crank_tables(mechanism, engine.MIN_STEPS)
    speed = _reference_speed(mechanism, line.motor, probe) if speed_rpm is None else abs(
        speed_rpm) / RAD_PER_S_TO_RPM
    if not speed > 0.0:
        raise InputError.parameter("speed_rpm", f"must be a positive speed, got {speed_rpm}.")
    n = steps or line_data(mechanism).steps or engine.steps_for(line, float(np.min(probe.inertia)),
                                                            speed)
    tables = crank_tables(mechanism, n)
    lanes = engine.Lanes.of(line, [speed])
    solution, orbit, passes = _with_friction(mechanism, line, tables, lanes)
    out = _steady(mechanism, line, tables, lanes, orbit, solution)
    out.figures.update(passes)
    if accuracy:
        coarse_tables = crank_tables(mechanism, max(n // 2, 36))
        coarse, _, _ = _with_friction(mechanism, line, coarse_tables, lanes, strict=False)
        if coarse.converged[0]:
            coarse_orbit = engine.integrate(line, coarse_tables, lanes, coarse.start)
            fine = orbit.torque[::2, 0, -1] if n % 2 == 0 else None
            if fine is not None and fine.size == coarse_orbit.torque.shape[0]:
                scale = float(np.max(np.abs(orbit.torque[:, 0, -1]))) or 1.0
                out.figures["accuracy"] = float(np.max(np.abs(
                    fine - coarse_orbit.torque[:, 0, -1]))) / scale
    return out


def has_friction(mechanism: Mechanism) -> bool:
    """True when the sweep of ``mechanism`` runs the friction solution."""
    from dyade.linkage.plan import plan

    return bool(plan(mechanism).friction)


def _with_friction(mechanism: Mechanism, line: engine.Line, tables: engine.Tables,
                   lanes: engine.Lanes, strict: bool = True
                   ) -> tuple[engine.Periodic, engine.Orbit, dict]:
    """The periodic state of one lane; with joint friction by passes, as for the rigid
    [drive] (``dyade.linkage.drive``): solve with the friction torque M_F frozen (zero at
    first), compute it anew from the kinetostatics with friction at the resulting crank
    speed and acceleration, until it changes by less than ``[friction] tol`` of the
    largest torque. ``tables.friction`` is left holding it."""
    solution = _solve(line, tables, lanes)
    if strict and not solution.converged[0]:
        raise DyadeError(f"no periodic steady state of the drive line at "
                         f"{lanes.speed[0] * RAD_PER_S_TO_RPM:.5g} rpm: the crank would stop or "
                         f"turn back within the cycle, or the shooting did not converge (scaled "
                         f"residual {solution.residual[0]:.2g}); the model does not describe that "
                         f"motion.")
    orbit = engine.integrate(line, tables, lanes, solution.start)
    if not has_friction(mechanism):
        return solution, orbit, {}
    change, count = math.inf, 0
    for count in range(1, mechanism.friction_max_iter + 1):
        speed = lanes.speed[0] + orbit.state[:-1, 0, 0]
        new = engine.halves(friction_torque(mechanism, tables, speed, orbit.acceleration[:-1, 0]))
        change = float(np.max(np.abs(new - tables.friction)))
        scale = max(float(np.max(np.abs(new))), float(np.max(np.abs(orbit.torque[:, 0, -1]))))
        tables.friction = new
        solution = _solve(line, tables, lanes)
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


def _steady(mechanism, line, tables, lanes, orbit, solution) -> SteadyState:
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
    if has_friction(mechanism):
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
    freq = natural_frequency(mechanism)
    figures.update({"omega_bar": freq.omega_bar, "eta": mean / freq.omega_bar})
    return SteadyState(mechanism.sweep.start + sense * u, orbit.torque[:, 0, -1], speed,
                       orbit.acceleration[:, 0], twist, rigid_torque, rigid_speed, rigid_accel,
                       solution.multipliers[0], figures)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class ResonanceCurve:
    """The periodic states of the line with an ideal motor over a range of speeds."""

    speed: FloatArray
    """(s,) Ω [rad/s]"""
    eta: FloatArray
    """(s,) Ω/ω̄ [-]"""
    peak_torque: FloatArray
    """(s,) largest |shaft torque| over the cycle [N·m]; NaN where no periodic state"""
    rigid_peak_torque: FloatArray
    """(s,) largest |drive torque| of the rigid drive at that speed [N·m]"""
    twist_amplitude: FloatArray
    """(s,) (max − min)/2 of the twist [rad]"""
    fluctuation: FloatArray
    """(s,) (max − min)/mean of the crank speed [-]"""
    stability: FloatArray
    """(s,) the largest |Floquet multiplier| [-]"""
    converged: FloatArray
    """(s,) bool"""
    omega_bar: float
    """ω̄ [rad/s]"""
    resonances: list
    """(k, speed [rad/s], "forced" | "parametric") expected in the range"""
    steps: int
    """RK4 steps per revolution"""

    @property
    def unstable(self) -> FloatArray:
        return self.stability > 1.0 + engine.UNSTABLE_MARGIN


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


def resonance_curve(mechanism: Mechanism, speeds_rpm, *, steps: int | None = None
                    ) -> ResonanceCurve:
    """The resonance curve and the Floquet multipliers over the ideal motor's speeds
    ``speeds_rpm`` [rpm] (vectorised over speeds): peak shaft torque, twist amplitude,
    speed fluctuation against speed, and the resonances to be expected in the range.
    A ``[drive]`` motor is replaced by an ideal one (the speed is what is scanned).

    Parameters
    ----------
    mechanism : Mechanism
        With a ``[drive_line]`` table.
    speeds_rpm : array_like
        Crank speeds [rpm], all of one sign, none zero.
    steps : int, optional
        RK4 steps per revolution (default as for ``steady_state``, at the lowest speed).

    Returns
    -------
    ResonanceCurve

    Examples
    --------
    >>> import dyade
    >>> m = dyade.read_mechanism("mechanisms/dyade-16.toml", {
    ...     "drive_line.stiffness": 1000.0, "drive_line.damping": 0.04})
    >>> curve = resonance_curve(m, [3450.0, 3575.0])     # near 2·ω̄: J(φ)'s 1st harmonic
    >>> curve.unstable.tolist(), [round(float(mu), 3) for mu in curve.stability]
    ([False, True], [0.988, 1.039])
    """
    speeds = _speeds(speeds_rpm)
    line = line_of(mechanism, ideal=True)
    n, tables = (steps, crank_tables(mechanism, steps)) if steps else _steps(
        mechanism, line, float(speeds.min()))
    lanes = engine.Lanes.of(line, speeds)
    solution = _solve(line, tables, lanes)
    orbit = engine.integrate(line, tables, lanes, solution.start)
    ok = solution.converged
    torque = orbit.torque[:, :, -1]
    twist = orbit.state[:, :, 1]
    speed = speeds[None, :] + orbit.state[:, :, 0]
    nan = np.where(ok, 1.0, np.nan)
    rigid = 0.5 * tables.slope[0::2, None] * speeds[None, :] ** 2 - tables.load[0::2, None]
    omega_bar = natural_frequency(mechanism).omega_bar
    return ResonanceCurve(speeds, speeds / omega_bar, np.max(np.abs(torque), axis=0) * nan,
                          np.max(np.abs(rigid), axis=0),
                          0.5 * (twist.max(axis=0) - twist.min(axis=0)) * nan,
                          (speed.max(axis=0) - speed.min(axis=0)) / speeds * nan,
                          solution.stability, ok, omega_bar,
                          resonances(mechanism, omega_bar, speeds.min(), speeds.max()), n)


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

    @property
    def unstable(self) -> FloatArray:
        return self.stability > 1.0 + engine.UNSTABLE_MARGIN


def stability_map(mechanism: Mechanism, speeds_rpm, *, stiffness=None, damping=None,
                  steps: int | None = None) -> StabilityMap:
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

    Returns
    -------
    StabilityMap
        ``stability`` (values, speeds): the largest ``|μ|``.

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
    line = line_of(mechanism, ideal=True)
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
    n, tables = (steps, crank_tables(mechanism, steps)) if steps else _steps(
        mechanism, line, float(speeds.min()), np.array([k.max()]))
    lanes = engine.Lanes.of(line, grid_speed, k[:, None], b[:, None])
    solution = _solve(line, tables, lanes)
    return StabilityMap(speeds, name, values, solution.stability.reshape(values.size, -1))


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


def run_up(mechanism: Mechanism, *, steps: int | None = None) -> RunUp:
    """The run-up from rest at the sweep's start angle (the line untwisted) with the
    ``[drive]`` motor, in time, until the mean speed over a revolution settles; the
    largest shaft torque on the way.

    Parameters
    ----------
    mechanism : Mechanism
        With ``[drive]`` (the motor) and ``[drive_line]`` (with ``rotor_inertia``).
    steps : int, optional
        Grid of the crank shaft's tables per revolution (default: the table's, else 720).

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
    line = line_of(mechanism)
    if isinstance(line.motor, ConstantTorque) and line.motor.torque is None:
        raise InputError("a run-up needs the torque of the constant-torque motor: give "
                         "`drive.torque` [N·m].", key="drive.torque")
    n = steps or line_data(mechanism).steps or engine.MIN_STEPS
    tables = crank_tables(mechanism, n)
    top = float(engine.natural_frequencies(line, np.array([np.min(tables.inertia)]))[0, -1])
    dt = 2.0 * math.pi / (STEPS_PER_VIBRATION_IN_TIME * top)
    reference = (abs(mechanism.crank.speed) if isinstance(line.motor, ConstantTorque)
                 else _reference_speed(mechanism, line.motor, tables))
    revolutions = mechanism.drive.max_revolutions
    t_max = 2.0 * revolutions * 2.0 * math.pi / reference
    path = engine.run_up(line, tables, dt=dt, t_max=t_max, tol=RUN_UP_TOL,
                         max_revolutions=revolutions)
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
               "omega_bar": natural_frequency(mechanism).omega_bar}
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
