"""The equation of motion of a machine with one degree of freedom, the crank angle φ:

    J(φ)·φ̈ + ½·J′(φ)·φ̇² = M_M(φ̇) + M_L(φ) − M_F(φ)

(Dresig & Holzweißig, *Maschinendynamik*; VDI 2149). J is the reduced moment of inertia
(flywheel included), M_M the motor torque, M_L the reduced load torque (positive where
the loads drive the machine) and M_F the friction torque. With the kinetic energy
E = ½·J·φ̇² as the state and the crank angle as the independent variable it is of first
order, because dE/dt = φ̇·(J·φ̈ + ½·J′·φ̇²):

    dE/dφ = M_M(φ̇) + M_L(φ) − M_F(φ),   φ̇ = s·√(2E/J),   s = ±1 the sense of rotation,

and J′ drops out. It is integrated by the classical Runge–Kutta method over a uniform
grid of N steps per revolution in the running direction; the tables hold J, M_L and M_F
at the nodes and the midpoints of the steps. The periodic steady state is the fixed point
of the revolution map E(φ0) → E(φ0 + s·2π), found by Newton's method on the energy at φ0
with the variational equation (shooting); the run-up starts from rest, E = 0. M_F is a
table over the path: the caller freezes it, solves, computes it anew from the forces and
repeats (``dyade.linkage.drive``). The integration steps in angle, one step after the
other; everything after it is vectorised.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError
from dyade.model.drive import ConstantTorque, Motor
from dyade.units import RAD_PER_S_TO_RPM

NEWTON_MAX_ITER = 50  # most shooting iterations
NEUTRAL = 1e-12  # [-] |dP/dE0 − 1| below this: the revolution map does not depend on E0


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Tables:
    """The reduced machine at the half steps of the grid, in the running direction:
    entry j is at the crank angle φ0 + s·j·h/2. ``inertia`` and ``load`` repeat every
    revolution (2N entries); ``friction`` covers one revolution (2N) or the whole path."""

    inertia: FloatArray
    """J [kg·m²], flywheel included"""
    load: FloatArray
    """M_L [N·m], crank-angle convention (positive counter-clockwise)"""
    friction: FloatArray
    """M_F [N·m], crank-angle convention (it opposes the motion: s·M_F ≥ 0)"""
    inertia_slope: FloatArray
    """J′ = dJ/dφ [kg·m²/rad] (not needed by the integration, only for the time)"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Path:
    """The motion at the grid nodes u_k = k·h along the running direction (crank angle
    φ0 + s·u_k)."""

    step: float
    """h [rad]"""
    sense: float
    """s = ±1"""
    energy: FloatArray
    """(K+1,) E = ½·J·φ̇² at the nodes [J]"""
    slope: FloatArray
    """(K+1,) dE/dφ = M_M + M_L − M_F at the nodes [N·m]"""
    middle: FloatArray
    """(K,) E at the midpoints of the steps (cubic Hermite) [J]"""
    time: FloatArray
    """(K+1,) time since φ0 [s]"""
    speed: FloatArray | None = None
    """(K+1,) |φ̇| at the nodes [rad/s]"""
    start: Start | None = None
    """a run-up's first steps from rest, integrated in time"""
    motor_torque: float | None = None
    """the constant motor torque found for a ConstantTorque motor without a torque"""
    iterations: int = 0
    """shooting iterations (steady state) or revolutions (run-up)"""
    settled: bool = True
    """False when a run-up did not become periodic within the revolutions allowed"""

    def energy_at(self, u: FloatArray) -> FloatArray:
        """E at path coordinates u ∈ [0, K·h] [rad] (cubic Hermite on the nodes, with
        their slopes dE/du = s·dE/dφ): fourth-order accurate."""
        return _hermite(u, self.step, self.energy, self.sense * self.slope)

    def speed_at(self, u: FloatArray, inertia: FloatArray) -> FloatArray:
        """|φ̇| = √(2E/J) at path coordinates u with the reduced inertia J there; over a
        run-up's first steps from its integration in time."""
        speed = np.sqrt(2.0 * np.maximum(self.energy_at(u), 0.0) / inertia)
        if self.start is not None:
            near = u < self.start.steps * self.step
            speed[near] = self.start.at(u[near])[0]
        return speed

    def time_at(self, u: FloatArray) -> FloatArray:
        """t at path coordinates u [s] (cubic Hermite with the slopes dt/du = 1/|φ̇|;
        over a run-up's first steps from its integration in time)."""
        with np.errstate(divide="ignore"):  # at rest: not used (the first steps below)
            slow = np.where(self.speed > 0.0, 1.0 / self.speed, 0.0)
        out = _hermite(u, self.step, self.time, slow)
        if self.start is not None:
            near = u < self.start.steps * self.step
            out[near] = self.start.at(u[near])[1]
        return out


def along(table: FloatArray, count: int, period: int) -> FloatArray:
    """The first ``count`` entries of a table along the path: a table shorter than the
    path repeats its last ``period`` entries (its last revolution)."""
    j = np.arange(count)
    span = table.size
    return table[np.where(j < span, j, span - period + (j - span) % period)]


def _hermite(u: FloatArray, h: float, values: FloatArray, slopes: FloatArray) -> FloatArray:
    k = np.clip(np.floor(u / h).astype(np.int64), 0, values.size - 2)
    x = u / h - k
    x2, x3 = x * x, x * x * x
    return ((2 * x3 - 3 * x2 + 1) * values[k] + (x3 - 2 * x2 + x) * h * slopes[k]
            + (3 * x2 - 2 * x3) * values[k + 1] + (x3 - x2) * h * slopes[k + 1])


class Stall(DyadeError):
    """The machine comes to rest: the kinetic energy would turn negative."""

    def __init__(self, message: str, node: int) -> None:
        super().__init__(message)
        self.node = node


def _march(energy: float, first: int, steps: int, h: float, s: float, tables: Tables,
           motor: Motor, variational: bool = False) -> tuple[list, list, float]:
    """RK4 over ``steps`` steps from node ``first`` with E = ``energy`` there: E and dE/dφ
    at the nodes, and dE_end/dE_start (the variational equation) when asked."""
    inertia, load = tables.inertia.tolist(), tables.load.tolist()
    friction = tables.friction.tolist()
    period, span = len(inertia), len(friction)
    torque = motor.at

    def rhs(j: int, e: float) -> tuple[float, float]:
        if e < 0.0:
            raise Stall("", j // 2)
        inertia_j = inertia[j % period]
        w = math.sqrt(2.0 * e / inertia_j)
        m, dm = torque(w)
        rub = friction[j] if j < span else friction[span - period + (j - span) % period]
        g = s * m + load[j % period] - rub
        if not variational:
            return g, 0.0
        return g, (s * dm / (inertia_j * w) if w > 0.0 else 0.0)

    out_e, out_g = [energy], []
    sens = 1.0
    e = energy
    dphi = s * h
    for k in range(first, first + steps):
        j = 2 * k
        g1, d1 = rhs(j, e)
        g2, d2 = rhs(j + 1, e + 0.5 * dphi * g1)
        g3, d3 = rhs(j + 1, e + 0.5 * dphi * g2)
        g4, d4 = rhs(j + 2, e + dphi * g3)
        if variational:
            s1 = d1 * sens
            s2 = d2 * (sens + 0.5 * dphi * s1)
            s3 = d3 * (sens + 0.5 * dphi * s2)
            s4 = d4 * (sens + dphi * s3)
            sens += dphi * (s1 + 2.0 * s2 + 2.0 * s3 + s4) / 6.0
        out_g.append(g1)
        e += dphi * (g1 + 2.0 * g2 + 2.0 * g3 + g4) / 6.0
        out_e.append(e)
    out_g.append(rhs(2 * (first + steps), e)[0])
    return out_e, out_g, sens


START_STEPS = 16  # steps of a run-up integrated in time, where |φ̇| ∝ √u is not smooth in u


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Start:
    """A run-up's first steps from rest, integrated in time."""

    steps: int
    """M: the nodes 0 … M are covered"""
    energy: FloatArray
    """(2M+1,) E at the half steps [J]"""
    time: FloatArray
    """(2M+1,) t at the half steps [s]"""
    works: tuple[float, float, float]
    """motor work, work on the loads (−∫M_L dφ) and friction work (∫M_F dφ) up to node M [J]"""
    times: FloatArray
    """(m,) the instants of the integration in time [s]"""
    states: FloatArray
    """(m, 5) u, w and the three works there"""
    rates: FloatArray
    """(m, 5) their time derivatives"""

    def at(self, u: FloatArray) -> tuple[FloatArray, FloatArray]:
        """|φ̇| [rad/s] and t [s] at path coordinates u within the start."""
        state, time = _locate(self.times, self.states, self.rates, u)
        return state[:, 1], time


def _locate(times: FloatArray, states: FloatArray, rates: FloatArray, u: FloatArray
            ) -> tuple[FloatArray, FloatArray]:
    """The states (n, 5) and instants where u(t) = u, from a time history: Newton on
    the cubic Hermite of u over its time step (u̇ = w), the state on its cubic Hermite
    (its rates known), for all u at once."""
    k = np.clip(np.searchsorted(states[:, 0], u) - 1, 0, times.size - 2)
    span = (times[k + 1] - times[k])[:, None]
    y0, y1, d0, d1 = states[k], states[k + 1], span * rates[k], span * rates[k + 1]
    x = np.clip((u - y0[:, 0]) / (y1[:, 0] - y0[:, 0]), 0.0, 1.0)
    for _ in range(50):  # Newton on the cubic of u
        value, change = _cubic(x, y0[:, 0], y1[:, 0], d0[:, 0], d1[:, 0])
        miss = value - u
        done = np.abs(miss) <= 1e-15 * (1.0 + np.abs(u))
        if done.all():
            break
        with np.errstate(divide="ignore", invalid="ignore"):  # only where not done
            x = np.where(done, x, x - miss / change)
    return _cubic(x[:, None], y0, y1, d0, d1)[0], times[k] + x * span[:, 0]


def _cubic(x: float, y0, y1, d0, d1):
    """The cubic Hermite on [0, 1] (slopes scaled to it) and its derivative at x."""
    x2, x3 = x * x, x * x * x
    value = (2 * x3 - 3 * x2 + 1) * y0 + (x3 - 2 * x2 + x) * d0 + (3 * x2 - 2 * x3) * y1 \
        + (x3 - x2) * d1
    change = (6 * x2 - 6 * x) * y0 + (3 * x2 - 4 * x + 1) * d0 + (6 * x - 6 * x2) * y1 \
        + (3 * x2 - 2 * x) * d1
    return value, change


def _start(h: float, s: float, tables: Tables, motor: Motor, steps: int) -> Start:
    """The first ``steps`` steps of a run-up from rest, where |φ̇| ∝ √u is not smooth in
    the angle but everything is in time: RK4 in time on u̇ = w, ẇ = s·(dE/dφ − ½·J′·w²)/J
    from u = w = 0, with the works as integrals over time (motor m·w, loads −s·M_L·w,
    friction s·M_F·w); each half step u = j·h/2 is located on the cubic Hermite of u(t)
    (u̇ = w known), w and the works there on theirs. Between the grid values J, J′ and
    M_L are quadratic in u over each step, M_F quadratic in σ = √u (it follows the
    acceleration, which has a √u term; its value at rest is the limit as the machine
    moves off, ``dyade.linkage.drive``)."""
    period = tables.inertia.size
    points = 2 * steps + 1
    j = np.arange(points)
    inertia, slope = tables.inertia[j % period], tables.inertia_slope[j % period]
    load, friction = tables.load[j % period], along(tables.friction, points, period)
    sigma = np.sqrt(0.5 * h * j)

    def quadratic(values, u):  # over the step that holds u, through its three points
        k = min(int(u / h), steps - 1)
        a, b, c = values[2 * k], values[2 * k + 1], values[2 * k + 2]
        x = u / h - k
        return a * (1 - x) * (1 - 2 * x) + 4 * b * x * (1 - x) + c * x * (2 * x - 1)

    def in_sigma(values, u):  # the same in σ = √u (M_F follows φ̈, which has a √u term)
        k = min(int(u / h), steps - 1)
        x0, x1, x2 = sigma[2 * k], sigma[2 * k + 1], sigma[2 * k + 2]
        x = math.sqrt(u)
        return (values[2 * k] * (x - x1) * (x - x2) / ((x0 - x1) * (x0 - x2))
                + values[2 * k + 1] * (x - x0) * (x - x2) / ((x1 - x0) * (x1 - x2))
                + values[2 * k + 2] * (x - x0) * (x - x1) / ((x2 - x0) * (x2 - x1)))

    def rates(u: float, w: float) -> tuple[float, float, float, float]:
        """ẇ and the powers of motor, loads and friction."""
        m = motor.at(w)[0]
        torque_load, torque_rub = quadratic(load, u), in_sigma(friction, u)
        g = s * m + torque_load - torque_rub
        accel = s * (g - 0.5 * quadratic(slope, u) * w * w) / quadratic(inertia, u)
        return accel, m * w, -s * torque_load * w, s * torque_rub * w

    end = steps * h
    first_dt = math.sqrt(2.0 * h / rates(0.0, 0.0)[0]) / 16.0
    state = np.zeros(5)  # u, w, motor work, load work, friction work
    t = 0.0
    history = [(t, state.copy(), np.array([0.0, *rates(0.0, 0.0)]))]

    def derivative(y):
        accel, *powers = rates(y[0], y[1])
        return np.array([y[1], accel, *powers])

    while state[0] < end:
        dt = min(first_dt, h / (8.0 * state[1])) if state[1] > 0.0 else first_dt
        k1 = history[-1][2]
        k2 = derivative(state + 0.5 * dt * k1)
        k3 = derivative(state + 0.5 * dt * k2)
        k4 = derivative(state + dt * k3)
        state = state + dt * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0
        t += dt
        if state[1] <= 0.0:
            raise Stall("", int(state[0] / h))
        history.append((t, state.copy(), derivative(state)))
    times = np.array([entry[0] for entry in history])
    states = np.array([entry[1] for entry in history])
    slopes = np.array([entry[2] for entry in history])
    here, time = _locate(times, states, slopes, 0.5 * h * j[1:])
    energy = np.concatenate(([0.0], 0.5 * inertia[1:] * here[:, 1] ** 2))
    time = np.concatenate(([0.0], time))
    works = (float(here[-1, 2]), float(here[-1, 3]), float(here[-1, 4]))
    return Start(steps, energy, time, works, times, states, slopes)


def _path(energy: list, slope: list, h: float, s: float, tables: Tables, motor: Motor,
          **extra) -> Path:
    """Midpoint energies and the time along the path from the node values.

    The time t = ∫ dφ/|φ̇| comes per step from Simpson's rule in the angle, except
    where the speed changes by more than 1 % within the step at an acceleration of one
    sign that varies by less than a factor 2 (a run-up): there t = ∫ d|φ̇|/(s·φ̈) by the
    three-point rule in the speed, φ̈ = (dE/dφ − ½·J′·φ̇²)/J. A run-up's first steps
    come from their integration in time (``start``)."""
    e, g = np.asarray(energy), np.asarray(slope)
    middle = 0.5 * (e[:-1] + e[1:]) + s * h * (g[:-1] - g[1:]) / 8.0
    count = e.size - 1
    period = tables.inertia.size
    j_node, j_mid = (2 * np.arange(count + 1)) % period, (2 * np.arange(count) + 1) % period
    friction = along(tables.friction, 2 * count + 1, period)
    inertia_mid = tables.inertia[j_mid]
    speed = np.sqrt(2.0 * np.maximum(e, 0.0) / tables.inertia[j_node])
    speed_mid = np.sqrt(2.0 * np.maximum(middle, 0.0) / inertia_mid)
    g_mid = (s * motor.torques(speed_mid) + tables.load[j_mid] - friction[1::2])
    accel = s * (g - 0.5 * tables.inertia_slope[j_node] * speed ** 2) / tables.inertia[j_node]
    accel_mid = s * (g_mid - 0.5 * tables.inertia_slope[j_mid] * speed_mid ** 2) / inertia_mid
    w0, w1, a0, a1 = speed[:-1], speed[1:], accel[:-1], accel[1:]
    with np.errstate(divide="ignore", invalid="ignore"):  # each rule only where it holds
        by_angle = h / 6.0 * (1.0 / w0 + 4.0 / speed_mid + 1.0 / w1)
        low, high = np.minimum(np.minimum(a0, a1), accel_mid), np.maximum(
            np.maximum(a0, a1), accel_mid)
        steady_sign = (low > 0.0) | (high < 0.0)
        gentle = np.abs(high) < 2.0 * np.abs(low)
        fast = np.abs(w1 - w0) > 0.01 * np.maximum(w0, w1)
        a, b = speed_mid - w0, w1 - speed_mid
        span = a + b
        by_speed = span / 6.0 * ((2.0 - b / a) / a0 + span * span / (a * b) / accel_mid
                                 + (2.0 - a / b) / a1)
    dt = np.where(steady_sign & gentle & fast, by_speed, by_angle)
    start = extra.get("start")
    if start is not None:  # a run-up's first steps, integrated in time
        middle[:start.steps] = start.energy[1::2]
        dt[:start.steps] = np.diff(start.time[0::2])
    time = np.concatenate(([0.0], np.cumsum(dt)))
    return Path(h, s, e, g, middle, time, speed, **extra)


def periodic(tables: Tables, motor: Motor, sense: float, steps: int, guess: float,
             tol: float, mean_speed: float | None = None) -> Path:
    """The periodic steady state over one revolution (N = ``steps`` steps).

    Parameters
    ----------
    tables : Tables
        The machine over one revolution (2N entries each).
    motor : Motor
        A ``ConstantTorque`` without a torque is given the constant torque that balances
        the cycle, and the state whose mean speed is ``mean_speed``.
    sense : {+1, −1}
        The sense of rotation s.
    guess : float
        Speed |φ̇| [rad/s] to start the shooting from.
    tol : float
        Relative change of E over a revolution that counts as periodic [-].
    mean_speed : float, optional
        2π/T [rad/s] for a constant-torque motor (whose periodic states form a family).

    Raises
    ------
    DyadeError
        No periodic state: the motor cannot carry the machine round, or a constant torque
        does not balance the load.
    """
    h = 2.0 * math.pi / steps
    constant = isinstance(motor, ConstantTorque)
    if constant and motor.torque is None:  # balance the cycle with it
        motor = ConstantTorque(sense * cycle_mean(tables.friction - tables.load))
    energy0 = 0.5 * tables.inertia[0] * guess * guess
    for iteration in range(1, NEWTON_MAX_ITER + 1):
        try:
            energy, slope, sens = _march(energy0, 0, steps, h, sense, tables, motor, True)
        except Stall:
            energy0 *= 4.0  # too slow to get round: start faster
            continue
        miss = energy[-1] - energy0
        if constant:  # its periodic states form a family: the mean speed picks one
            return _neutral(tables, motor, sense, steps, energy, slope, miss, tol, mean_speed)
        if abs(miss) <= tol * energy0:
            return _path(energy, slope, h, sense, tables, motor, iterations=iteration,
                         motor_torque=motor.torque if constant else None)
        if abs(sens - 1.0) < NEUTRAL:
            return _neutral(tables, motor, sense, steps, energy, slope, miss, tol, mean_speed)
        new = energy0 - miss / (sens - 1.0)
        energy0 = new if new > 0.0 else 0.25 * energy0
    raise DyadeError(f"no periodic steady state found in {NEWTON_MAX_ITER} shooting "
                     f"iterations: the motor's characteristic may cross the machine's load "
                     f"torque more than once, or not at all near "
                     f"{guess * RAD_PER_S_TO_RPM:.4g} rpm.")


def cycle_mean(values: FloatArray) -> float:
    """Mean over a revolution of a table at the half steps (Simpson's rule, the
    quadrature the RK4 steps apply to a function of φ alone)."""
    nodes, middle = values[0::2], values[1::2]
    return float((np.sum(nodes) + 2.0 * np.sum(middle)) / (nodes.size + middle.size * 2.0))


def _neutral(tables, motor, sense, steps, energy, slope, miss, tol, mean_speed) -> Path:
    """A motor whose torque does not depend on the speed: periodic for every E0 when the
    torque balances the cycle, for none otherwise; the mean speed picks the state."""
    h = 2.0 * math.pi / steps
    gain = np.asarray(energy) - energy[0]  # W(φ) = ∫ (M_M + M_L − M_F) dφ
    if abs(miss) > tol * max(np.max(np.abs(gain)), 1e-300) * 10.0:
        balance = sense * cycle_mean(tables.friction - tables.load)
        raise DyadeError(f"no periodic steady state: the motor's constant torque "
                         f"{motor.torque:g} N·m does not balance the machine (it would need "
                         f"{balance:.6g} N·m); the kinetic energy changes by {miss:.4g} J every "
                         f"revolution. Leave the torque out to have it balanced, or run up.")
    if mean_speed is None:
        raise DyadeError("a constant-torque motor has a periodic state at every speed: give "
                         "the mean speed.")
    g = np.asarray(slope)
    inertia_nodes = tables.inertia[0::2]
    inertia_mid = tables.inertia[1::2]
    gain_mid = 0.5 * (gain[:-1] + gain[1:]) + sense * h * (g[:-1] - g[1:]) / 8.0
    weights = np.concatenate((inertia_nodes, inertia_mid))
    offsets = np.concatenate((gain[:-1], gain_mid))
    factors = np.concatenate((2.0 * np.ones(steps), 4.0 * np.ones(steps)))  # periodic Simpson
    floor = -float(np.min(offsets))  # E0 above this keeps E > 0 everywhere

    def period(e0: float) -> float:  # T = ∫ dφ/|φ̇| (Simpson)
        return float(h / 6.0 * np.sum(factors / np.sqrt(2.0 * (e0 + offsets) / weights)))

    target = 2.0 * math.pi / mean_speed
    low, high = floor, max(floor, 0.0) + 0.5 * float(np.max(weights)) * mean_speed ** 2
    while period(high) > target:
        high *= 2.0
    for _ in range(200):  # bisection: T falls monotonically with E0
        middle = 0.5 * (low + high)
        if period(middle) > target:
            low = middle
        else:
            high = middle
        if high - low <= 1e-15 * high:
            break
    energy0 = 0.5 * (low + high)
    energy, slope, _ = _march(energy0, 0, steps, h, sense, tables, motor)
    return _path(energy, slope, h, sense, tables, motor, iterations=1, motor_torque=motor.torque)


def run_up(tables: Tables, motor: Motor, sense: float, steps: int, tol: float,
           max_revolutions: int, revolutions: int | None = None) -> Path:
    """The run-up from rest at φ0: revolution after revolution until the kinetic energy
    at φ0 repeats to ``tol`` (or for exactly ``revolutions`` revolutions).

    Raises
    ------
    DyadeError
        The motor cannot start the machine, or it stops again.
    """
    h = 2.0 * math.pi / steps
    start = sense * motor.at(0.0)[0] + tables.load[0] - tables.friction[0]
    if sense * start <= 0.0:
        raise DyadeError(f"the motor cannot start the machine from rest: its starting torque "
                         f"{motor.at(0.0)[0]:.6g} N·m does not exceed the load torque "
                         f"{-sense * tables.load[0]:.6g} N·m at the start angle.")
    try:
        begin = _start(h, sense, tables, motor, min(START_STEPS, steps))
    except Stall as stall:
        raise DyadeError(f"the machine stops during the run-up after {stall.node / steps:.3g} "
                         f"revolutions: the motor cannot carry it over the load there.") from None
    energy = begin.energy[0::2].tolist()
    period = tables.inertia.size
    nodes = 2 * np.arange(1, begin.steps)  # dE/dφ at the nodes of the start
    speed = np.sqrt(2.0 * begin.energy[nodes] / tables.inertia[nodes % period])
    slope = [start] + (sense * motor.torques(speed) + tables.load[nodes % period]
                       - along(tables.friction, 2 * begin.steps, period)[nodes]).tolist()
    count = 0
    settled = False
    limit = revolutions or max_revolutions
    while count < limit and not (settled and revolutions is None):
        try:
            if count == 0:
                more, more_slope, _ = _march(energy[-1], begin.steps, steps - begin.steps, h,
                                             sense, tables, motor)
            else:
                more, more_slope, _ = _march(energy[-1], count * steps, steps, h, sense,
                                             tables, motor)
        except Stall as stall:
            turns = stall.node / steps
            raise DyadeError(f"the machine stops during the run-up after {turns:.3g} "
                             f"revolutions: the motor cannot carry it over the load there."
                             ) from None
        before = energy[0] if count == 0 else energy[-1]
        energy.extend(more[1:])
        slope.extend(more_slope[:-1])
        last_slope = more_slope[-1]
        count += 1
        settled = count > 1 and abs(energy[-1] - before) <= tol * energy[-1]
    slope.append(last_slope)
    return _path(energy, slope, h, sense, tables, motor, iterations=count, settled=settled,
                 start=begin)
