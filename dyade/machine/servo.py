"""The servo motor behind a gear: its torque over the machine cycle, the figures it is
sized by, the gear ratio that minimises its RMS torque, a catalogue checked motor by
motor, and the machine's equation of motion integrated in time under a given torque.

The crank shaft needs the torque M_c(t) (the linkage's inverse dynamics,
M_c = J(φ)·φ̈ + ½·J′(φ)·φ̇² − M_L(φ) + M_F, ``dyade.linkage.servo``) at the speed φ̇ and
acceleration φ̈. Behind a gear of ratio i (motor speed ω = i·φ̇), efficiency η and its
own inertia J_G on the motor shaft, a motor of rotor inertia J_M gives

    M = (J_M + J_G)·i·φ̈ + M_c/(i·η)     while the motor drives the crank (M_c·φ̇ ≥ 0),
    M = (J_M + J_G)·i·φ̈ + M_c·η/i       while the crank drives the motor (M_c·φ̇ < 0),

and the gear loses P_loss = M_in·ω − M_c·φ̇ ≥ 0 (M_in the gear's input torque). The
figures (VDI 2143 sizing practice, Dresig & Holzweißig ch. 3): the peak |M|, the RMS
torque √(1/T·∫M²dt) (the motor's heating), the top speed max|ω|, the inertia ratio
λ = (max J(φ)/i² + J_G)/J_M and the energy fed back per cycle ∫max(−M·ω, 0)dt.

With an ideal gear (η = 1) M = i·a(t) + b(t)/i, so the RMS torque is smallest at
i⁴ = ∫b²/∫a²; for a pure inertia load this is i = √(J_L/J_M). ``optimal_ratio`` finds
the minimum by golden-section search on log i (any efficiency and gear inertia).

Nothing here knows about linkages: the crank torque and motion come in as arrays over
the cycle, the reduced machine as a function of the crank angle.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.model.servo import Gear, ServoMotor

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0  # [-]
RATIO_RTOL = 1e-10  # [-] golden-section search stops when the bracket is this narrow


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Cycle:
    """The crank over one machine cycle, sampled at the instants ``time`` (uniform,
    both ends included)."""

    time: FloatArray
    """(n,) t [s], 0 … T"""
    speed: FloatArray
    """(n,) φ̇ [rad/s]"""
    acceleration: FloatArray
    """(n,) φ̈ [rad/s²]"""
    torque: FloatArray
    """(n,) M_c, the torque the crank shaft needs [N·m] (inverse dynamics)"""
    inertia: FloatArray
    """(n,) J(φ) [kg·m²] the reduced inertia of the linkage at the instants"""

    @property
    def period(self) -> float:
        return float(self.time[-1] - self.time[0])


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class MotorLoad:
    """The motor's torque, speed and power over the cycle for one or several gear
    ratios (rows) at the cycle's instants (columns)."""

    ratio: FloatArray
    """(r,) i [-]"""
    torque: FloatArray
    """(r, n) M [N·m], the motor's torque"""
    speed: FloatArray
    """(r, n) ω [rad/s]"""
    gear_loss: FloatArray
    """(r, n) P_loss ≥ 0 [W], the power the gear loses"""
    rotor_inertia: float
    """J_M [kg·m²]"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Sizing:
    """The figures a servo motor is sized by, one per gear ratio."""

    ratio: FloatArray
    """(r,) i [-]"""
    peak_torque: FloatArray
    """(r,) max |M| [N·m]"""
    rms_torque: FloatArray
    """(r,) √(1/T·∫M²dt) [N·m]"""
    top_speed: FloatArray
    """(r,) max |ω| [rad/s]"""
    inertia_ratio: FloatArray
    """(r,) λ = (max J/i² + J_G)/J_M [-] (NaN without a rotor inertia)"""
    regenerated: FloatArray
    """(r,) ∫max(−M·ω, 0)dt [J] per cycle, the energy the motor feeds back"""
    peak_at: FloatArray
    """(r,) the instant of the peak torque [s]"""


def motor_load(cycle: Cycle, gear: Gear, rotor_inertia: float,
               ratios: FloatArray | float | None = None) -> MotorLoad:
    """The motor's torque over the cycle (module docstring) for the gear's ratio or for
    each of ``ratios``.

    >>> t = np.linspace(0.0, 1.0, 5)
    >>> cycle = Cycle(t, np.ones(5), np.full(5, 2.0), np.full(5, 3.0), np.full(5, 1.0))
    >>> load = motor_load(cycle, Gear(ratio=2.0), rotor_inertia=0.5)
    >>> float(load.torque[0, 0])    # 0.5·2·2 + 3/2 [N·m]
    3.5
    """
    ratio = np.atleast_1d(np.asarray(gear.ratio if ratios is None else ratios,
                                     dtype=np.float64))[:, None]
    crank_power = cycle.torque * cycle.speed
    driving = crank_power >= 0.0
    eta = gear.efficiency
    gear_input = np.where(driving, cycle.torque / (ratio * eta), cycle.torque * eta / ratio)
    speed = ratio * cycle.speed
    torque = (rotor_inertia + gear.inertia) * ratio * cycle.acceleration + gear_input
    loss = gear_input * speed - crank_power
    return MotorLoad(ratio[:, 0], torque, speed, loss, rotor_inertia)


def trapezoid(values: FloatArray, time: FloatArray) -> FloatArray:
    """∫ values dt over the last axis by the trapezoidal rule (exact for the periodic
    trigonometric polynomials of a smooth cycle sampled finely enough)."""
    dt = np.diff(time)
    return np.sum(0.5 * (values[..., 1:] + values[..., :-1]) * dt, axis=-1)


def sizing(cycle: Cycle, load: MotorLoad, gear: Gear) -> Sizing:
    """Peak, RMS, top speed, inertia ratio and regenerated energy for each ratio."""
    period = cycle.period
    magnitude = np.abs(load.torque)
    peak_index = np.argmax(magnitude, axis=1)
    rows = np.arange(load.ratio.size)
    rms = np.sqrt(trapezoid(load.torque ** 2, cycle.time) / period)
    power = load.torque * load.speed
    regenerated = trapezoid(np.maximum(-power, 0.0), cycle.time)
    inertia_ratio = ((float(np.max(cycle.inertia)) / load.ratio ** 2 + gear.inertia)
                     / load.rotor_inertia if load.rotor_inertia > 0.0
                     else np.full(load.ratio.shape, np.nan))  # no rotor: not defined
    return Sizing(load.ratio, magnitude[rows, peak_index], rms,
                  np.max(np.abs(load.speed), axis=1), inertia_ratio, regenerated,
                  cycle.time[peak_index])


def rms_torque(cycle: Cycle, gear: Gear, rotor_inertia: float, ratio: float) -> float:
    """The motor's RMS torque over the cycle at the gear ratio ``ratio`` [N·m]."""
    load = motor_load(cycle, gear, rotor_inertia, ratio)
    return float(np.sqrt(trapezoid(load.torque[0] ** 2, cycle.time) / cycle.period))


def golden_section(function: Callable[[float], float], low: float, high: float,
                   rtol: float = RATIO_RTOL, max_iter: int = 200) -> float:
    """The minimum of a unimodal ``function`` of x in [low, high] (0 < low < high),
    searched on log x by the golden section until the bracket is narrower than ``rtol``
    relative; an end of the interval where the minimum lies at it."""
    a, b = math.log(low), math.log(high)
    c, d = b - GOLDEN * (b - a), a + GOLDEN * (b - a)
    fc, fd = function(math.exp(c)), function(math.exp(d))
    for _ in range(max_iter):
        if b - a <= rtol:
            break
        if fc <= fd:
            b, d, fd = d, c, fc
            c = b - GOLDEN * (b - a)
            fc = function(math.exp(c))
        else:
            a, c, fc = c, d, fd
            d = a + GOLDEN * (b - a)
            fd = function(math.exp(d))
    return math.exp(0.5 * (a + b))


def optimal_ratio(cycle: Cycle, gear: Gear, rotor_inertia: float,
                  bounds: tuple[float, float]) -> float:
    """The gear ratio in ``bounds`` at which the motor's RMS torque is smallest
    (golden-section search on log i, to ``RATIO_RTOL``)."""
    return golden_section(lambda i: rms_torque(cycle, gear, rotor_inertia, i), *bounds)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Check:
    """One motor checked at one or several gear ratios: each margin is 1 − used/available
    (≥ 0 passes; the smallest over the cycle)."""

    motor: ServoMotor
    sizing: Sizing
    thermal: FloatArray
    """(r,) 1 − RMS/M_N [-]"""
    peak: FloatArray
    """(r,) min over the cycle of 1 − |M|/envelope(ω) [-] (−1 where ω is beyond the
    top speed: no torque there)"""
    speed: FloatArray
    """(r,) 1 − max|ω|/n_max [-]"""
    inertia: FloatArray
    """(r,) 1 − λ/λ_max [-]"""

    @property
    def passes(self) -> FloatArray:
        """(r,) every margin ≥ 0"""
        return ((self.thermal >= 0.0) & (self.peak >= 0.0) & (self.speed >= 0.0)
                & (self.inertia >= 0.0))

    @property
    def best(self) -> int | None:
        """The ratio (row) that passes with the least thermal use, or None."""
        passing = np.flatnonzero(self.passes)
        if passing.size == 0:
            return None
        return int(passing[np.argmax(self.thermal[passing])])

    def failed(self, row: int) -> list[str]:
        """The names of the checks the motor fails at ratio row ``row``."""
        return [name for name, margin in (("thermal (RMS)", self.thermal),
                                          ("peak within the envelope", self.peak),
                                          ("top speed", self.speed),
                                          ("inertia ratio", self.inertia))
                if margin[row] < 0.0]


def check_motor(cycle: Cycle, gear: Gear, motor: ServoMotor, ratios: FloatArray,
                max_inertia_ratio: float) -> Check:
    """The four checks of a motor (thermal by RMS, peak within its envelope at its speed,
    top speed, inertia ratio) at each of ``ratios``."""
    load = motor_load(cycle, gear, motor.rotor_inertia, ratios)
    figures = sizing(cycle, load, gear)
    available = motor.envelope(load.speed)
    with np.errstate(divide="ignore", invalid="ignore"):  # no torque beyond the top speed
        use = np.where(available > 0.0, np.abs(load.torque) / available, 2.0)
    return Check(motor, figures, 1.0 - figures.rms_torque / motor.rated_torque,
                 np.min(1.0 - use, axis=1), 1.0 - figures.top_speed / motor.top_speed,
                 1.0 - figures.inertia_ratio / max_inertia_ratio)


def catalogue_checks(cycle: Cycle, gear: Gear, motors, ratios: FloatArray,
                     max_inertia_ratio: float, bounds: tuple[float, float] | None = None
                     ) -> list[Check]:
    """Every motor checked at ``ratios`` and, where ``bounds`` is given, at its own
    RMS-optimal ratio within them too (the last row)."""
    out = []
    for motor in motors:
        these = np.asarray(ratios, dtype=np.float64)
        if bounds is not None:
            these = np.append(these, optimal_ratio(cycle, gear, motor.rotor_inertia, bounds))
        out.append(check_motor(cycle, gear, motor, these, max_inertia_ratio))
    return out


def smallest_passing(checks: list[Check]) -> Check | None:
    """The check of the smallest motor (by rated torque, then rotor inertia) that passes
    at some ratio, or None."""
    order = sorted(range(len(checks)), key=lambda k: (checks[k].motor.rated_torque,
                                                      checks[k].motor.rotor_inertia, k))
    for k in order:
        if checks[k].best is not None:
            return checks[k]
    return None


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Followed:
    """The crank's motion integrated forward in time under a given torque."""

    time: FloatArray
    """(n,) t [s]"""
    angle: FloatArray
    """(n,) φ [rad]"""
    speed: FloatArray
    """(n,) φ̇ [rad/s]"""


def follow(machine: Callable[[float], tuple[float, float, float]], torque: FloatArray,
           friction: FloatArray, time: FloatArray, angle: float, speed: float) -> Followed:
    """The machine's equation of motion in time, J(φ)·φ̈ + ½·J′(φ)·φ̇² = M(t) + M_L(φ) −
    M_F(t) (``dyade.machine.equation``), integrated by the classical Runge–Kutta method
    from φ = ``angle``, φ̇ = ``speed`` at ``time[0]``.

    Parameters
    ----------
    machine : callable
        φ [rad] -> (J [kg·m²], J′ [kg·m²/rad], M_L [N·m]).
    torque, friction : ndarray, shape (2K+1,)
        M(t) and M_F(t) [N·m] at the half steps of ``time``'s steps.
    time : ndarray, shape (2K+1,)
        The instants of the half steps [s], uniform.

    Returns
    -------
    Followed
        φ and φ̇ at the steps' ends (``time[0::2]``).
    """
    drive = (torque - friction).tolist()
    dt = float(time[2] - time[0])
    phi, w = float(angle), float(speed)

    def accel(j: int, p: float, v: float) -> float:
        inertia, slope, load = machine(p)
        return (drive[j] + load - 0.5 * slope * v * v) / inertia

    angles, speeds = rk4(accel, phi, w, dt, len(drive))
    return Followed(np.asarray(time[0::2]), np.array(angles), np.array(speeds))


def rk4(accel: Callable[[int, float, float], float], phi: float, w: float, dt: float,
        points: int) -> tuple[list[float], list[float]]:
    """φ and φ̇ at the ends of the classical Runge–Kutta steps of φ̈ = accel(j, φ, φ̇)
    over ``points`` half-step instants (j: the instant's index; a step of ``dt`` spans
    j, j + 1, j + 2), from φ = ``phi``, φ̇ = ``w``. A step in time needs the one before:
    a loop over steps."""
    angles, speeds = [phi], [w]
    for k in range(0, points - 1, 2):
        a1 = accel(k, phi, w)
        p2, v2 = phi + 0.5 * dt * w, w + 0.5 * dt * a1
        a2 = accel(k + 1, p2, v2)
        p3, v3 = phi + 0.5 * dt * v2, w + 0.5 * dt * a2
        a3 = accel(k + 1, p3, v3)
        p4, v4 = phi + dt * v3, w + dt * a3
        a4 = accel(k + 2, p4, v4)
        phi += dt * (w + 2.0 * v2 + 2.0 * v3 + v4) / 6.0
        w += dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0
        angles.append(phi)
        speeds.append(w)
    return angles, speeds


LINE_TOL = 1e-10  # [-] periodic when the state repeats to this share of its scale
LINE_MAX_ITER = 20  # most Newton (shooting) iterations of the elastic line


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class LineCycle:
    """The crank's periodic motion behind an elastic line whose motor end follows the
    profile, at the steps' ends."""

    time: FloatArray
    """(K+1,) t [s]"""
    angle: FloatArray
    """(K+1,) φ [rad]"""
    speed: FloatArray
    """(K+1,) φ̇ [rad/s]"""
    torque: FloatArray
    """(K+1,) the line's torque on the crank T = k·(φ_p − φ) + b·(φ̇_p − φ̇) [N·m]"""
    iterations: int
    """shooting iterations"""
    miss: float
    """|state(T) − state(0) − advance| at the end, scaled [-]"""


def line_periodic(machine: Callable[[float], tuple[float, float, float]], angle: FloatArray,
                  speed: FloatArray, friction: FloatArray, time: FloatArray, stiffness: float,
                  damping: float, advance: float) -> LineCycle:
    """The periodic motion of a crank driven through an elastic line (stiffness k,
    damping b, as the crank shaft sees them) whose other end follows the profile
    φ_p(t) exactly (a stiff servo):

        J(φ)·φ̈ + ½·J′(φ)·φ̇² = k·(φ_p − φ) + b·(φ̇_p − φ̇) + M_L(φ) − M_F(t),

    RK4 in time over the half steps of ``time`` (``angle``, ``speed``, ``friction``: φ_p,
    φ̇_p and M_F there), the periodic state (φ(T) = φ(0) + ``advance``, φ̇(T) = φ̇(0))
    by shooting: Newton's method on the state at t = 0 with the Jacobian by forward
    differences, from the profile's own state.

    Raises
    ------
    DyadeError
        No periodic state within ``LINE_MAX_ITER`` iterations (a line in resonance
        without damping).
    """
    from dyade.errors import DyadeError

    p, v, rub = angle.tolist(), speed.tolist(), friction.tolist()
    dt = float(time[2] - time[0])

    def accel(j: int, phi: float, w: float) -> float:
        inertia, slope, load = machine(phi)
        line = stiffness * (p[j] - phi) + damping * (v[j] - w)
        return (line + load - rub[j] - 0.5 * slope * w * w) / inertia

    def cycle(phi: float, w: float) -> tuple[list, list]:
        return rk4(accel, phi, w, dt, len(p))

    scale_phi = max(abs(advance), float(np.max(np.abs(angle - angle[0]))), 1e-3)
    scale_w = max(float(np.max(np.abs(speed))), scale_phi / float(time[-1] - time[0]))
    state = np.array([p[0], v[0]])
    miss = math.inf
    for iteration in range(1, LINE_MAX_ITER + 1):
        angles, speeds = cycle(*state)
        residual = np.array([angles[-1] - state[0] - advance, speeds[-1] - state[1]])
        miss = float(max(abs(residual[0]) / scale_phi, abs(residual[1]) / scale_w))
        if miss <= LINE_TOL:
            phi, w = np.array(angles), np.array(speeds)
            torque = stiffness * (angle[0::2] - phi) + damping * (speed[0::2] - w)
            return LineCycle(np.asarray(time[0::2]), phi, w, torque, iteration, miss)
        jacobian = np.empty((2, 2))
        for column, size in enumerate((1e-7 * scale_phi, 1e-7 * scale_w)):
            moved = state.copy()
            moved[column] += size
            a2, s2 = cycle(*moved)
            jacobian[:, column] = (np.array([a2[-1] - moved[0] - advance, s2[-1] - moved[1]])
                                   - residual) / size
        state = state - np.linalg.solve(jacobian, residual)
    raise DyadeError(f"the crank behind the elastic drive line has no periodic motion under "
                     f"the profile within {LINE_MAX_ITER} shooting iterations (left "
                     f"{miss:.3g} of the state's scale): the line may be in resonance with "
                     f"the profile's harmonics; give it damping or stiffness.")
