"""The crank's real motion under a motor: the equation of motion of a linkage with a
``[drive]`` table, solved over the crank angle (``dyade.machine.equation``).

The linkage enters through its reduced moment of inertia J(φ), its slope J′(φ) and its
reduced load torque M_L(φ) (``dyade.linkage.reduced``), computed once by the vectorised
kinematics at unit crank speed on the integration grid, block by block (of the
kinematics only a block of positions is kept; the grid of a 0.001° sweep has 720 000
points). Coulomb friction enters as the
torque M_F that the friction adds to the drive torque; it depends on the joint forces
and so on the motion itself. It is found by passes: solve the motion with M_F frozen
(zero at first), run the kinetostatics with friction at the resulting speeds and
accelerations at every grid point (block by block, each solved as within the whole
grid: ``friction.Coupling``), take

    M_F = M_drive(with friction) − (J·φ̈ + ½·J′·φ̇² − M_L),

and repeat until M_F no longer changes. The result gives the crank's speed and
acceleration at any crank angle, with which the whole kinematics and kinetostatics
run again (``dyade.linkage.pipeline``).

The same tables on the grid of an elastic drive line (``[drive_line]``) are the linkage as
the line's crank shaft: ``crank_tables``, and from them the line's natural frequency with
the VDI 2149 check (``natural_frequency``; the sweep notes it, ``dyade.linkage.drive_line``
answers the designer's questions on the line).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError, InputError
from dyade.limits import check_memory
from dyade.linkage import kinematics
from dyade.linkage.blocks import BLOCK_SIZE, friction_coupling, spans
from dyade.linkage.options import memory_estimate
from dyade.linkage.reduced import Reduced, reduced
from dyade.machine import drive_line as line_engine, equation
from dyade.machine.motor import operating_speed
from dyade.model.drive import ConstantTorque, Motor, TorqueSpeedTable
from dyade.model.mechanism import Mechanism
from dyade.units import RAD_PER_S_TO_RPM

MIN_STEPS = 720  # integration steps per revolution unless the file says otherwise
AT_REST_NUDGE = 1e-6  # [-] share of the top speed at which friction is taken at rest


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class CrankMotion:
    """The crank's motion from the equation of motion."""

    state: str
    """"steady" (the periodic steady state) or "run-up" (from rest)"""
    crank_angle: FloatArray
    """(n,) the positions asked for [rad]"""
    speed: FloatArray
    """(n,) φ̇21 [rad/s]"""
    acceleration: FloatArray
    """(n,) φ̈21 [rad/s²]"""
    time: FloatArray
    """(n,) time since the start angle φ0 [s]"""
    motor_torque: FloatArray
    """(n,) M_M, the motor's torque on the crank shaft, counter-clockwise positive [N·m]"""
    friction_torque: FloatArray
    """(n,) M_F, the friction's share of the drive torque [N·m]"""
    figures: dict
    """speed extremes and fluctuation, period, iterations; a run-up's work balance"""

    def part(self, first: int, last: int) -> CrankMotion:
        """The motion at positions first..last−1 (the figures are the whole motion's)."""
        return replace(self, **{name: getattr(self, name)[first:last] for name in (
            "crank_angle", "speed", "acceleration", "time", "motor_torque",
            "friction_torque")})


def steps_for(mechanism: Mechanism) -> int:
    """Integration steps per revolution: ``[drive] steps``, else a multiple of the sweep's
    steps per revolution (so that its positions fall on the grid), at least 720."""
    if mechanism.drive.steps:
        return mechanism.drive.steps
    per_turn = 2.0 * math.pi / mechanism.sweep.step
    whole = round(per_turn)
    if whole >= 1 and abs(per_turn - whole) < 1e-9 * per_turn:
        return whole * math.ceil(MIN_STEPS / whole)
    return MIN_STEPS


RUN_UP_BYTES = 160  # [B] per integration step of a run-up: the path's arrays, kept whole


def check_drive_size(mechanism: Mechanism, steps: int, run_up: bool) -> None:
    """Refuse, before anything is allocated, a ``[drive]`` whose grid (2·steps half-steps
    with the machine's kinetostatics at each) or run-up (up to max_revolutions × steps
    steps) would take more than the memory bound (``dyade.limits``)."""
    check_memory(memory_estimate(mechanism, 2 * steps),
                 f"the equation of motion's grid of {steps:,} steps per revolution",
                 mechanism.max_memory, advice="Give fewer `drive.steps`")
    if run_up:
        revolutions = mechanism.drive.max_revolutions
        check_memory(RUN_UP_BYTES * float(steps) * revolutions + (50 << 20),
                     f"a run-up of up to {revolutions:,} revolutions at {steps:,} steps each",
                     mechanism.max_memory, advice="Give fewer `drive.max_revolutions` or `drive.steps`")


def solve(mechanism: Mechanism, crank_angle: FloatArray | None = None, *, run_up: bool = False,
          friction: bool = False) -> CrankMotion:
    """The crank's motion under the ``[drive]`` of ``mechanism``: the periodic steady state
    (or the run-up from rest at the sweep's start angle), evaluated at ``crank_angle``
    (default: the sweep; for a run-up: the whole run-up at the sweep's step).

    Raises
    ------
    DyadeError
        No periodic state, the motor cannot start or carry the machine, or the reduced
        inertia vanishes or is undefined somewhere (a dead centre).
    """
    drive = mechanism.drive
    if run_up and isinstance(drive.motor, ConstantTorque) and drive.motor.torque is None:
        raise InputError("a run-up needs the torque of the constant-torque motor: give "
                         "`drive.torque` [N·m] (without it the motor only holds the nominal "
                         "speed in the steady state).", key="drive.torque")
    steps = steps_for(mechanism)
    check_drive_size(mechanism, steps, run_up)
    h = 2.0 * math.pi / steps
    sense = 1.0 if mechanism.crank.speed > 0 else -1.0
    start = mechanism.sweep.start
    grid = start + sense * 0.5 * h * np.arange(2 * steps)
    machine = machine_tables(mechanism, grid)
    tables = equation.Tables(machine.inertia, machine.load, np.zeros(2 * steps), machine.slope)
    nominal = abs(mechanism.crank.speed)
    motor = drive.motor
    passes = 0
    friction_tol = mechanism.friction_tol
    converged, change = True, 0.0
    while True:
        passes += 1
        if run_up:
            path = equation.run_up(tables, motor, sense, steps, drive.tol, drive.max_revolutions)
        else:
            path = equation.periodic(tables, motor, sense, steps,
                                     _guess(motor, tables, sense, nominal), drive.tol, nominal)
        if path.motor_torque is not None and isinstance(motor, ConstantTorque):
            motor_now = ConstantTorque(path.motor_torque)
        else:
            motor_now = motor
        if not friction:
            break
        new = _friction_torque(mechanism, path, tables, machine, motor_now, start, steps,
                               run_up)
        if tables.friction.shape == new.shape:
            change = float(np.max(np.abs(new - tables.friction)))
        else:  # a run-up of another length: not settled yet
            change = math.inf
        scale = float(np.max(np.abs(new))) + 1e-300
        tables.friction = new
        converged = change <= friction_tol * max(scale, _torque_scale(tables))
        if converged or passes >= mechanism.friction_max_iter:
            path = (equation.run_up(tables, motor, sense, steps, drive.tol, drive.max_revolutions)
                    if run_up else
                    equation.periodic(tables, motor, sense, steps,
                                      _guess(motor, tables, sense, nominal), drive.tol, nominal))
            break
    motor = ConstantTorque(path.motor_torque) if path.motor_torque is not None else motor
    _check_table(motor, path, tables)
    if crank_angle is None:
        if run_up:
            total = path.step * (path.energy.size - 1)
            count = int(math.floor(total / mechanism.sweep.step + 1e-9)) + 1
            crank_angle = start + sense * mechanism.sweep.step * np.arange(count)
        else:
            crank_angle = mechanism.sweep.angles()
    crank_angle = np.asarray(crank_angle, dtype=np.float64)
    out = _at(mechanism, path, tables, motor, crank_angle, start, run_up)
    out.figures.update(_figures(path, tables, motor, start, steps, run_up))
    out.figures.update({"passes": passes, "steps_per_revolution": steps,
                        "friction_converged": converged, "friction_change": change})
    return out


def machine_tables(mechanism: Mechanism, angles: FloatArray) -> Reduced:
    """J, J′, M_L at ``angles``; an error where the machine has no inertia or a dead centre
    leaves it undefined. Computed in blocks of positions (``blocks.spans``): the grid of a fine
    sweep has hundreds of thousands of points, and only these three arrays are kept."""
    closes = np.empty((angles.shape[0], len(mechanism.dyads)), dtype=bool)
    machine = _reduced(mechanism, angles, closes)
    if not closes.all():
        col = int(np.flatnonzero(~closes.all(axis=0))[0])
        where = np.rad2deg(angles[~closes[:, col]][0])
        raise DyadeError(f"the equation of motion needs the whole revolution, but "
                         f"{mechanism.dyads[col].label} cannot close at crank angle "
                         f"{where:.2f}°.")
    bad = ~np.isfinite(machine.inertia) | ~(machine.inertia > 0.0) | ~np.isfinite(machine.load)
    if bad.any():
        where = np.rad2deg(angles[bad][0])
        raise DyadeError(f"the equation of motion cannot be solved: the reduced moment of "
                         f"inertia is zero or undefined at crank angle {where:.2f}° (a dead "
                         f"centre, or no moving mass there); give the crank or a flywheel "
                         f"inertia ([drive] flywheel_inertia).")
    return machine


def _reduced(mechanism: Mechanism, angles: FloatArray, closes: FloatArray | None = None
             ) -> Reduced:
    """J, J′, M_L at ``angles`` (``reduced``), block by block (``blocks.spans``): of the
    kinematics only a block at a time is kept. With ``closes`` ((n, dyads) bool), where
    the dyads close is written into it, and a block where one does not is left NaN."""
    n = angles.shape[0]
    inertia, slope, load = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    for first, last in spans(n, BLOCK_SIZE):
        kin = kinematics.sweep(mechanism, angles[first:last], crank_speed=1.0)
        if closes is not None:
            closes[first:last] = kin.closes
            if not kin.closes.all():
                continue
        part = reduced(mechanism, kin)
        inertia[first:last], slope[first:last], load[first:last] = (
            part.inertia, part.slope, part.load)
    return Reduced(inertia, slope, load)


def _torque_scale(tables: equation.Tables) -> float:
    return float(np.max(np.abs(tables.load))) + 1e-300


def _guess(motor: Motor, tables: equation.Tables, sense: float, nominal: float) -> float:
    """A starting speed [rad/s] for the shooting: where the motor's torque meets the mean
    load, else the crank's nominal speed."""
    return operating_speed(motor, sense * equation.cycle_mean(tables.friction - tables.load),
                           nominal)


def _states(path: equation.Path, tables: equation.Tables, motor: Motor, sense: float,
            points: int) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """At the first ``points`` half steps of the path: E, φ̇, the motor torque and dE/dφ."""
    energy = np.empty(2 * path.middle.size + 1)
    energy[0::2] = path.energy
    energy[1::2] = path.middle
    energy = energy[:points]
    j = np.arange(points)
    inertia = tables.inertia[j % tables.inertia.size]
    speed = sense * np.sqrt(2.0 * np.maximum(energy, 0.0) / inertia)
    torque = sense * motor.torques(np.abs(speed))
    rub = equation.along(tables.friction, points, tables.inertia.size)
    slope = torque + tables.load[j % tables.load.size] - rub
    return energy, speed, torque, slope


def _friction_torque(mechanism: Mechanism, path: equation.Path, tables: equation.Tables,
                     machine: Reduced, motor: Motor, start: float, steps: int, run_up: bool
                     ) -> FloatArray:
    """M_F at every half step of the path from the kinetostatics with friction."""
    from dyade.linkage import friction

    points = 2 * (path.energy.size - 1) if run_up else 2 * steps
    _, speed, _, slope = _states(path, tables, motor, path.sense, points)
    j = np.arange(points)
    inertia = tables.inertia[j % tables.inertia.size]
    jslope = machine.slope[j % machine.slope.size]
    load = tables.load[j % tables.load.size]
    acceleration = (slope - 0.5 * jslope * speed ** 2) / inertia
    if run_up:  # at rest the friction's sense is undefined: take its limit as it moves off
        speed[0] = path.sense * AT_REST_NUDGE * max(float(np.max(np.abs(speed))), 1.0)
    angle = start + path.sense * 0.5 * path.step * j
    # block by block, each solved as within the whole grid (``blocks.friction_coupling``)
    coupling = friction_coupling(mechanism, angle, speed, acceleration, BLOCK_SIZE)
    drive = np.empty(points)
    for first, last in spans(points, BLOCK_SIZE):
        kin = kinematics.sweep(mechanism, angle[first:last], crank_speed=speed[first:last],
                               crank_acceleration=acceleration[first:last])
        drive[first:last] = friction.solve(mechanism, kin,
                                           coupling=coupling).forces.drive_torque
    if not np.all(np.isfinite(drive)):
        raise DyadeError("the equation of motion with friction cannot be solved: the forces "
                         "are undefined at a dead centre or a self-locking position of the "
                         "cycle.")
    return drive - (inertia * acceleration + 0.5 * jslope * speed ** 2 - load)


def _check_table(motor: Motor, path: equation.Path, tables: equation.Tables) -> None:
    if not isinstance(motor, TorqueSpeedTable):
        return
    speeds = np.sqrt(2.0 * path.energy / tables.inertia[(2 * np.arange(path.energy.size))
                                                        % tables.inertia.size])
    rpm = RAD_PER_S_TO_RPM
    if not (motor.covers(float(speeds.min())) and motor.covers(float(speeds.max()))):
        raise DyadeError(f"the crank speed runs from {speeds.min() * rpm:.4g} to "
                         f"{speeds.max() * rpm:.4g} rpm, outside the motor's torque-speed "
                         f"table ({motor.speeds[0] * rpm:g}–{motor.speeds[-1] * rpm:g} rpm): "
                         f"extend the table.")


def _at(mechanism: Mechanism, path: equation.Path, tables: equation.Tables, motor: Motor,
        crank_angle: FloatArray, start: float, run_up: bool) -> CrankMotion:
    """The motion at arbitrary crank angles: E by cubic Hermite on the nodes, then φ̇ and
    φ̈ from J, J′, M_L there and the equation of motion."""
    sense, h = path.sense, path.step
    along = sense * (crank_angle - start)
    period = 2.0 * math.pi
    length = h * (path.energy.size - 1)
    if run_up:
        if np.any(along < -1e-9) or np.any(along > length * (1 + 1e-12)):
            raise DyadeError("crank angles outside the run-up were asked for.")
        u, turns = np.clip(along, 0.0, length), np.zeros_like(along)
    else:
        turns = np.floor(along / period + 1e-12)
        u = np.clip(along - turns * period, 0.0, period)
    machine = _reduced(mechanism, crank_angle)
    speed = sense * path.speed_at(u, machine.inertia)
    torque = sense * motor.torques(np.abs(speed))
    # M_F on the half-step grid, linear in between (exact on the grid)
    half = 0.5 * h
    points = 2 * (path.energy.size - 1)
    grid_u = half * np.arange(points + 1)
    values = equation.along(tables.friction, points + 1, tables.inertia.size)
    if not run_up:  # the revolution closes
        values[-1] = values[0]
    friction_torque = np.interp(u, grid_u, values)
    slope = torque + machine.load - friction_torque
    acceleration = (slope - 0.5 * machine.slope * speed ** 2) / machine.inertia
    time = path.time_at(u) + turns * path.time[-1]
    return CrankMotion("run-up" if run_up else "steady", crank_angle, speed, acceleration, time,
                       torque, friction_torque, {})


def _figures(path: equation.Path, tables: equation.Tables, motor: Motor, start: float,
             steps: int, run_up: bool) -> dict:
    """Speed extremes (over the last revolution), mean speed 2π/T, fluctuation; for a
    run-up the work balance; shooting iterations or revolutions."""
    sense = path.sense
    points = 2 * (path.energy.size - 1)
    energy, speed, torque, _ = _states(path, tables, motor, sense, points + 1)
    last = slice(points - 2 * steps, points + 1)
    w = np.abs(speed[last])
    j = np.arange(points + 1)[last]
    period = path.time[-1] - path.time[-1 - steps]
    mean = 2.0 * math.pi / period
    lo, hi = int(np.argmin(w)), int(np.argmax(w))
    angle = start + sense * 0.5 * path.step * j
    out = {"speed_mean": mean, "speed_min": float(w[lo]), "speed_max": float(w[hi]),
           "angle_min": float(np.mod(angle[lo], 2 * math.pi)),
           "angle_max": float(np.mod(angle[hi], 2 * math.pi)),
           "fluctuation": float((w[hi] - w[lo]) / mean), "period": float(period),
           "motor_torque_mean": _mean_over_time(torque[last], w),
           "inertia_mean": float(np.mean(tables.inertia))}
    if path.motor_torque is not None:
        out["motor_torque"] = path.motor_torque
    if run_up:
        dphi = path.step * sense
        index = np.arange(points + 1)
        begin = path.start
        later = index >= 2 * begin.steps  # the first steps were integrated in time

        def work(values):  # ∫ values dφ along the rest of the path (Simpson)
            weights = np.where(index % 2 == 1, 4.0, 2.0)
            weights[2 * begin.steps] = weights[-1] = 1.0
            return float(dphi / 6.0 * np.sum((weights * values)[later]))

        load = tables.load[index % tables.load.size]
        rub = equation.along(tables.friction, points + 1, tables.inertia.size)
        motor_work, load_work, friction_work = begin.works
        out.update({"revolutions": path.iterations, "settled": path.settled,
                    "duration": float(path.time[-1]),
                    "work_motor": motor_work + work(torque),
                    "work_load": load_work - work(load),
                    "work_friction": friction_work + work(rub),
                    "kinetic_energy": float(path.energy[-1])})
    else:
        out["iterations"] = path.iterations
    return out


def _mean_over_time(torque: FloatArray, speed: FloatArray) -> float:
    """Time mean of a torque sampled at the half steps of one revolution (dt = dφ/w)."""
    weights = np.where(np.arange(torque.size) % 2 == 1, 4.0, 2.0)
    weights[0] = weights[-1] = 1.0
    weights = weights / speed
    return float(np.sum(weights * torque) / np.sum(weights))


# -- the linkage as the crank shaft of an elastic drive line ([drive_line]) ---------------
# its tables J(φ), dJ/du, M_L on the line's integration grid and the natural frequency with
# the VDI 2149 check (what ``dyade analyse`` notes); ``dyade.linkage.drive_line`` builds the
# designer's questions on them, ``dyade.machine.drive_line`` integrates the line
VDI_2149_RATIO = 0.1  # [-] largest Ω/ω̄ for which the rigid model holds (VDI 2149 Part 1)


def crank_tables(mechanism: Mechanism, steps: int) -> line_engine.Tables:
    """J, dJ/du, s·M_L at the half steps of ``steps`` steps per revolution from the
    sweep's start in the running direction (no friction: not part of this model)."""
    sense = line_engine.sense_of(mechanism)
    grid = mechanism.sweep.start + sense * math.pi / steps * np.arange(2 * steps)
    machine = machine_tables(mechanism, grid)
    tables = line_engine.Tables(machine.inertia, sense * machine.slope, sense * machine.load,
                                np.zeros(2 * steps))
    line_engine.check_tables(tables)
    return tables


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class NaturalFrequency:
    """The natural frequencies of the drive line and the VDI 2149 check."""

    omega_bar: float
    """ω̄ [rad/s]: the lowest natural frequency with the linkage's mean reduced inertia J̄"""
    omega_min: float
    """the lowest natural frequency's smallest value over the cycle (J(φ) largest) [rad/s]"""
    omega_max: float
    """… and its largest (J(φ) smallest) [rad/s]"""
    inertia_mean: float
    """J̄ [kg·m²]"""
    speed: float
    """the crank's operating speed |Ω| [rad/s]"""
    crank_angle: FloatArray
    """(n,) [rad]"""
    frequency: FloatArray
    """(n,) the lowest natural frequency with J frozen at J(φ) [rad/s]"""

    @property
    def ratio(self) -> float:
        """η = Ω/ω̄ [-]"""
        return self.speed / self.omega_bar

    @property
    def vdi_2149(self) -> bool:
        """True when Ω/ω̄ ≤ 0.1: the rigid model of the drive holds (VDI 2149 Part 1)."""
        return self.ratio <= VDI_2149_RATIO


def natural_frequency(mechanism: Mechanism) -> NaturalFrequency:
    """ω̄, the range of the lowest natural frequency over the cycle, and Ω/ω̄.

    Parameters
    ----------
    mechanism : Mechanism
        With a ``[drive_line]`` table (else ``InputError``).

    Returns
    -------
    NaturalFrequency
        ω̄ [rad/s], its range with J(φ) frozen over the cycle, Ω/ω̄ and the VDI 2149
        verdict (``vdi_2149``: Ω/ω̄ ≤ 0.1).

    Examples
    --------
    >>> import dyade
    >>> m = dyade.read_mechanism("mechanisms/slider-crank.toml",
    ...                          {"drive_line.stiffness": 1000.0, "links.2.inertia": 0.01})
    >>> f = natural_frequency(m)
    >>> round(f.omega_bar, 2), round(f.ratio, 4), f.vdi_2149     # [rad/s], [-]
    (300.8, 0.5222, False)
    """
    line = line_engine.line_of(mechanism)
    steps = line_engine.MIN_STEPS
    tables = crank_tables(mechanism, steps)
    inertia = tables.inertia[0::2]
    mean = float(np.mean(tables.inertia))
    every = line_engine.natural_frequencies(line, np.concatenate(([mean], inertia)))[:, 0]
    angle = mechanism.sweep.start + line_engine.sense_of(mechanism) * 2.0 * math.pi / steps * \
        np.arange(steps)
    return NaturalFrequency(float(every[0]), float(np.min(every[1:])), float(np.max(every[1:])),
                            mean, abs(mechanism.crank.speed), angle, every[1:])
