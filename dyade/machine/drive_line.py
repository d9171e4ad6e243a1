"""The elastic drive line: a machine whose crank is driven through torsional springs.

The line is a chain of nodes from the motor to the crank shaft, all reduced to the crank
shaft (a gear of ratio i = motor speed / crank speed multiplies the rotor's inertia by i²):

    motor (J_0, characteristic m(w), or an ideal motor at constant speed Ω)
      —k_0 ∥ b_0— node 1 (J_1) —k_1 ∥ b_1— … —k_{m−1} ∥ b_{m−1}— crank (J(φ), J′(φ), M_L, M_F)

A single shaft or coupling element is m = 1; the stiff coupling of Strümpfel
(``dyade.vibration.coupling``) sits in the line as m = 2 with its inertia J_K as node 1.
With θ_j the node angles and T_e = k_e·(θ_e − θ_{e+1}) + b_e·(θ̇_e − θ̇_{e+1}) the torque
in element e (θ_m = φ):

    J_0·θ̈_0 = m(θ̇_0) − T_0,    J_j·θ̈_j = T_{j−1} − T_j,
    J(φ)·φ̈ + ½·J′(φ)·φ̇² = T_{m−1} + M_L(φ) − M_F(φ)

(Dresig & Holzweißig, *Maschinendynamik*, the drive with a periodically varying reduced
inertia). Everything is taken in the running direction of the crank: u = s·(φ − φ0) the
path coordinate, v = du/dt > 0 the crank speed, the tables J(u), dJ/du, the load torque
s·M_L and the friction torque s·M_F ≥ 0 (which opposes the motion) at the half steps of a
uniform grid of N steps per revolution.

The equations are integrated over u (not t) by the classical Runge–Kutta method, so a
revolution is always 2π and the tables are read at the grid points. The state is the
crank speed's deviation δv = v − Ω_ref, the twists q_j = θ_j − u of the nodes against the
crank and the node speeds' deviations δw_j (an ideal motor has w_0 = Ω fixed: no state),
all small where the line is stiff, so no digits are lost to the mean rotation. The time
and the works of motor, loads, friction and damping ride along as quadratures.

The periodic steady state is the fixed point of the revolution map x(0) → x(2π)
(shooting), found by Newton's method with the Jacobian (the monodromy matrix) from
central differences of the map; its eigenvalues are the Floquet multipliers of the
motion linearised about the periodic solution itself (the Poincaré map at u = 0 is
conjugate to the stroboscopic map of the motion, so they are the same multipliers). It is
unstable where one exceeds 1 in modulus. Everything is vectorised over the lanes (speeds,
stiffnesses, dampings): the integration steps one after the other, each step for all lanes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError, InputError
from dyade.model.drive import Motor
from dyade.model.drive_line import DriveLineData
from dyade.model.mechanism import Mechanism

NEWTON_MAX_ITER = 40  # most shooting iterations
NEWTON_TOL = 1e-11  # [-] scaled residual of the revolution map that counts as periodic
DIFFERENCE = 1e-6  # [-] central-difference step of the monodromy matrix, per state scale
STEPS_PER_VIBRATION = 64  # RK4 steps per period of the highest natural frequency
MIN_STEPS = 720  # steps per revolution at least
UNSTABLE_MARGIN = 1e-6  # [-] |μ| above 1 + this: unstable


@dataclass(frozen=True, slots=True, eq=False)  # identity, not value, equality
class Line:
    """The elastic drive line reduced to the crank shaft (module docstring), SI.

    Parameters
    ----------
    inertias : tuple of float
        J_0 … J_{m−1}: the motor's rotor (reduced: i²·J_rotor) and the intermediate
        nodes [kg·m²]; J_0 is not used with an ideal motor.
    stiffness : tuple of float
        k_0 … k_{m−1}: element e joins node e to node e + 1 (the last to the crank)
        [N·m/rad], positive.
    damping : tuple of float
        b_0 … b_{m−1} [N·m·s/rad], not negative.
    motor : Motor or None
        The motor's characteristic on the crank shaft (``dyade.model.drive``); None: an
        ideal motor that turns at constant speed whatever the load.
    """

    inertias: tuple[float, ...]
    stiffness: tuple[float, ...]
    damping: tuple[float, ...]
    motor: Motor | None = None
    labels: tuple[str, ...] = field(default=("stiffness", "damping", "rotor_inertia"))
    """the names under which stiffness, damping and rotor inertia are reported in errors"""

    def __post_init__(self) -> None:
        m = len(self.stiffness)
        if m < 1 or len(self.damping) != m or len(self.inertias) != m:
            raise InputError.parameter("stiffness", "damping and inertias must list one value "
                                                    "per element of the line.")
        for k in self.stiffness:
            if not (math.isfinite(k) and k > 0.0):
                raise InputError.parameter(self.labels[0], f"must be a positive torsional "
                                                           f"stiffness [N·m/rad], got {k:g}.",
                                           value=k, unit="N·m/rad")
        for b in self.damping:
            if not (math.isfinite(b) and b >= 0.0):
                raise InputError.parameter(self.labels[1], f"must be a damping of zero or more "
                                                           f"[N·m·s/rad], got {b:g}.",
                                           value=b, unit="N·m·s/rad")
        for j, inertia in enumerate(self.inertias):
            needed = j > 0 or self.motor is not None
            if needed and not (math.isfinite(inertia) and inertia > 0.0):
                raise InputError.parameter(self.labels[2] if j == 0 else "inertias",
                                           f"must be a positive moment of inertia [kg·m²] "
                                           f"(a motor with a characteristic needs its rotor's "
                                           f"inertia), got {inertia:g}.", value=inertia,
                                           unit="kg·m²")

    @property
    def ideal(self) -> bool:
        """True for an ideal motor (constant speed)."""
        return self.motor is None

    @property
    def elements(self) -> int:
        return len(self.stiffness)

    @property
    def dimension(self) -> int:
        """The size of the state: δv, the m twists and the free node speeds."""
        return 1 + 2 * self.elements - (1 if self.ideal else 0)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Tables:
    """The crank shaft in the running direction at the half steps of the grid (2N
    entries each, entry j at u = j·h/2)."""

    inertia: FloatArray
    """J [kg·m²]"""
    slope: FloatArray
    """dJ/du [kg·m²/rad]"""
    load: FloatArray
    """s·M_L [N·m], positive where the loads drive the machine"""
    friction: FloatArray
    """s·M_F [N·m], ≥ 0 (opposes the motion)"""

    @property
    def steps(self) -> int:
        return self.inertia.size // 2


def natural_frequencies(line: Line, crank_inertia: FloatArray, stiffness: FloatArray | None = None
                        ) -> FloatArray:
    """The natural frequencies of the undamped line with the crank's inertia held fixed
    at each value of ``crank_inertia`` (its mean J̄ gives ω̄; its range over the cycle the
    range of ω), the rigid-body mode of a free motor left out.

    Parameters
    ----------
    line : Line
    crank_inertia : ndarray, shape (n,)
        J of the crank shaft [kg·m²].
    stiffness : ndarray, shape (n, m), optional
        Stiffnesses per value instead of the line's [N·m/rad].

    Returns
    -------
    ndarray, shape (n, m)
        Natural frequencies ω [rad/s], ascending.
    """
    crank_inertia = np.atleast_1d(np.asarray(crank_inertia, dtype=np.float64))
    n, m = crank_inertia.size, line.elements
    k = (np.broadcast_to(np.asarray(line.stiffness), (n, m)) if stiffness is None
         else np.asarray(stiffness, dtype=np.float64).reshape(n, m))
    first = 1 if line.ideal else 0  # an ideal motor's node is held
    size = m + 1 - first
    masses = np.empty((n, size))
    masses[:, :m - first] = np.asarray(line.inertias[first:])
    masses[:, -1] = crank_inertia
    K = np.zeros((n, m + 1, m + 1))
    for e in range(m):
        K[:, e, e] += k[:, e]
        K[:, e + 1, e + 1] += k[:, e]
        K[:, e, e + 1] -= k[:, e]
        K[:, e + 1, e] -= k[:, e]
    K = K[:, first:, first:]
    scale = 1.0 / np.sqrt(masses)
    eig = np.linalg.eigvalsh(K * scale[:, :, None] * scale[:, None, :])
    omega = np.sqrt(np.clip(eig, 0.0, None))
    return omega if line.ideal else omega[:, 1:]


def steps_for(line: Line, crank_inertia_min: float, speed_min: float,
              stiffness_max: FloatArray | None = None) -> int:
    """Steps per revolution: ``STEPS_PER_VIBRATION`` per period of the highest natural
    frequency (with the smallest crank inertia) at the lowest speed, at least 720."""
    k = None if stiffness_max is None else np.asarray(stiffness_max).reshape(1, -1)
    top = float(natural_frequencies(line, np.array([crank_inertia_min]), k)[0, -1])
    steps = STEPS_PER_VIBRATION * top / speed_min
    from dyade.limits import MAX_STEPS

    if not steps <= MAX_STEPS:  # refused before a table is made or a step taken
        from dyade.errors import InputError

        raise InputError(f"the drive line's highest natural frequency, {top:.3g} rad/s, is "
                         f"{top / speed_min:.3g} times the lowest speed: it would take "
                         f"{steps:.3g} steps per revolution (at most {MAX_STEPS:,}). A line "
                         f"this stiff is rigid: drop [drive_line] (or lower "
                         f"`drive_line.stiffness`), or set `drive_line.steps`.")
    return max(MIN_STEPS, int(math.ceil(steps)))


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Lanes:
    """Per lane (speed, stiffness, damping variant) parameters: shape (B,) or (B, m)."""

    speed: FloatArray
    """(B,) Ω_ref [rad/s]: the ideal motor's speed, else the reference the deviations
    are taken from"""
    stiffness: FloatArray
    """(B, m) [N·m/rad]"""
    damping: FloatArray
    """(B, m) [N·m·s/rad]"""

    @classmethod
    def of(cls, line: Line, speed: FloatArray, stiffness: FloatArray | None = None,
           damping: FloatArray | None = None) -> Lanes:
        speed = np.atleast_1d(np.asarray(speed, dtype=np.float64))
        b, m = speed.size, line.elements
        k = np.broadcast_to(np.asarray(line.stiffness if stiffness is None else stiffness,
                                       dtype=np.float64).reshape(-1, m), (b, m)).copy()
        c = np.broadcast_to(np.asarray(line.damping if damping is None else damping,
                                       dtype=np.float64).reshape(-1, m), (b, m)).copy()
        return cls(speed, k, c)

    def repeat(self, times: int) -> Lanes:
        return Lanes(np.repeat(self.speed, times), np.repeat(self.stiffness, times, axis=0),
                     np.repeat(self.damping, times, axis=0))


QUADRATURES = 5  # time, motor work, load work, friction work, damping work


def _rates(line: Line, lanes: Lanes, x: FloatArray, inertia: float, slope: float, load: float,
           friction: float, quadratures: bool = True
           ) -> tuple[FloatArray, FloatArray | None, FloatArray]:
    """d/du of the state and the quadratures, and the torques, at one grid point for all
    lanes. x: (B, d). Differences of speeds are taken between their deviations from Ω_ref
    (and the motor's torque as its change from m(Ω_ref)), so a small vibration keeps its
    digits. Without ``quadratures`` (shooting) their rates are not computed (None)."""
    m = line.elements
    omega = lanes.speed
    dv = x[:, 0]
    v = omega + dv
    q = x[:, 1:1 + m]
    if line.ideal:
        dw = np.concatenate((np.zeros((x.shape[0], 1)), x[:, 1 + m:]), axis=1)
    else:
        dw = x[:, 1 + m:]
    dw_next = np.concatenate((dw[:, 1:], dv[:, None]), axis=1)
    q_next = np.concatenate((q[:, 1:], np.zeros((q.shape[0], 1))), axis=1)
    torque = lanes.stiffness * (q - q_next) + lanes.damping * (dw - dw_next)  # (B, m)
    slow = 1.0 / np.where(v > 0.0, v, np.nan)  # v ≤ 0: the lane is lost (NaN)
    accel = (torque[:, -1] + load - friction - 0.5 * slope * v * v) / inertia
    if line.ideal:
        drive = torque[:, 0]
    else:
        drive = line.motor.torques(omega) + motor_change(line.motor, omega, dw[:, 0])
    inertias = np.asarray(line.inertias, dtype=np.float64)
    if line.ideal:  # its node does not move freely: no acceleration of its own
        inertias = np.where(np.arange(m) == 0, 1.0, inertias)
    before = np.concatenate((drive[:, None], torque[:, :-1]), axis=1)
    node_accel = (before - torque) / inertias  # (B, m); node 0 of an ideal motor unused
    dx = np.empty_like(x)
    dx[:, 0] = accel * slow
    dx[:, 1:1 + m] = (dw - dv[:, None]) * slow[:, None]
    dx[:, 1 + m:] = (node_accel[:, 1:] if line.ideal else node_accel) * slow[:, None]
    if not quadratures:
        return dx, None, torque
    dissipation = np.sum(lanes.damping * (dw - dw_next) ** 2, axis=1)
    dquad = np.stack((slow, drive * (omega + dw[:, 0]) * slow, -load * np.ones_like(v),
                      friction * np.ones_like(v), dissipation * slow), axis=1)
    return dx, dquad, torque


def motor_change(motor: Motor, speed: FloatArray, change: FloatArray) -> FloatArray:
    """m(w + δw) − m(w) without the round-off of the difference: exact for a linear
    characteristic and within a segment of a table."""
    from dyade.model.drive import Asynchronous, ConstantTorque

    if isinstance(motor, ConstantTorque):
        return np.zeros_like(change)
    if isinstance(motor, Asynchronous):
        return -motor.stiffness * change
    w, values = motor.speeds, motor.values
    k = np.clip(np.searchsorted(w, speed, side="right") - 1, 0, w.size - 2)
    k2 = np.clip(np.searchsorted(w, speed + change, side="right") - 1, 0, w.size - 2)
    slope = (values[k + 1] - values[k]) / (w[k + 1] - w[k])
    return np.where(k == k2, slope * change, motor.torques(speed + change) - motor.torques(speed))


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Orbit:
    """The motion of every lane over the grid nodes u_k = k·h (k = 0 … K)."""

    step: float
    """h [rad]"""
    state: FloatArray
    """(K+1, B, d) the state at the nodes (deviations from Ω_ref and twists)"""
    quadratures: FloatArray
    """(K+1, B, 5) time [s], work of the motor, of the loads (−∫s·M_L du), of friction
    and of damping [J] since u = 0"""
    torque: FloatArray
    """(K+1, B, m) torques in the elements [N·m] (the last: the shaft torque at the crank)"""
    acceleration: FloatArray
    """(K+1, B) crank acceleration dv/dt [rad/s²]"""


def integrate(line: Line, tables: Tables, lanes: Lanes, x0: FloatArray, revolutions: int = 1,
              keep: bool = True) -> Orbit | FloatArray:
    """RK4 over u from 0 over ``revolutions`` revolutions for all lanes from x0 (B, d).
    With ``keep`` False only the end state (B, d) is returned."""
    steps = tables.steps
    h = 2.0 * math.pi / steps
    inertia, slope = tables.inertia.tolist(), tables.slope.tolist()
    load, rub = tables.load.tolist(), tables.friction.tolist()
    period = 2 * steps
    x = np.array(x0, dtype=np.float64)
    quad = np.zeros((x.shape[0], QUADRATURES))
    total = steps * revolutions
    if keep:
        states = np.empty((total + 1,) + x.shape)
        quads = np.empty((total + 1, x.shape[0], QUADRATURES))
        torques = np.empty((total + 1, x.shape[0], line.elements))
        accels = np.empty((total + 1, x.shape[0]))
    for k in range(total):
        j = (2 * k) % period
        args = (inertia[j], slope[j], load[j], rub[j], keep)
        k1, c1, t1 = _rates(line, lanes, x, *args)
        if keep:
            states[k], quads[k], torques[k] = x, quad, t1
            accels[k] = k1[:, 0] * (lanes.speed + x[:, 0])
        mid = (inertia[j + 1], slope[j + 1], load[j + 1], rub[j + 1], keep)
        k2, c2, _ = _rates(line, lanes, x + 0.5 * h * k1, *mid)
        k3, c3, _ = _rates(line, lanes, x + 0.5 * h * k2, *mid)
        j2 = (j + 2) % period
        k4, c4, _ = _rates(line, lanes, x + h * k3, inertia[j2], slope[j2], load[j2], rub[j2],
                           keep)
        x = x + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        if keep:
            quad = quad + h / 6.0 * (c1 + 2.0 * c2 + 2.0 * c3 + c4)
    if not keep:
        return x
    k1, _, t1 = _rates(line, lanes, x, inertia[0], slope[0], load[0], rub[0])
    states[total], quads[total], torques[total] = x, quad, t1
    accels[total] = k1[:, 0] * (lanes.speed + x[:, 0])
    return Orbit(h, states, quads, torques, accels)


def scales(line: Line, tables: Tables, lanes: Lanes) -> FloatArray:
    """(B, d) the size of each state component, from the twist that the rigid machine's
    largest drive torque ½·J′·Ω² − M_L + M_F would put into the softest element, and the
    speed of a vibration of that twist at the highest natural frequency (the crank's
    mean inertia); Ω and Ω/ω where the machine asks for no torque."""
    m = line.elements
    b = lanes.speed.size
    crank = float(np.mean(tables.inertia))
    top = np.sqrt(np.max(lanes.stiffness, axis=1) / crank)
    drive = np.max(np.abs(0.5 * tables.slope[None, :] * lanes.speed[:, None] ** 2
                          - tables.load + tables.friction), axis=1)
    twist = drive / np.min(lanes.stiffness, axis=1)
    twist = np.where(twist > 0.0, twist, lanes.speed / top)
    out = np.empty((b, line.dimension))
    out[:, 0] = twist * top
    out[:, 1:1 + m] = twist[:, None]
    out[:, 1 + m:] = (twist * top)[:, None]
    return out


def monodromy(line: Line, tables: Tables, lanes: Lanes, x0: FloatArray, scale: FloatArray
              ) -> tuple[FloatArray, FloatArray]:
    """The end state of one revolution (B, d) and the Jacobian ∂x(2π)/∂x(0) (B, d, d) by
    central differences, all 2d + 1 runs of every lane in one integration."""
    b, d = x0.shape
    delta = DIFFERENCE * scale  # (B, d)
    batch = np.repeat(x0[:, None, :], 2 * d + 1, axis=1)  # (B, 2d+1, d)
    for i in range(d):
        batch[:, 1 + 2 * i, i] += delta[:, i]
        batch[:, 2 + 2 * i, i] -= delta[:, i]
    end = integrate(line, tables, lanes.repeat(2 * d + 1), batch.reshape(-1, d), keep=False)
    end = end.reshape(b, 2 * d + 1, d)
    jac = (end[:, 1::2, :] - end[:, 2::2, :]) / (2.0 * delta[:, :, None])  # (B, i, out)
    return end[:, 0, :], np.swapaxes(jac, 1, 2)


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Periodic:
    """The periodic steady states of the lanes."""

    start: FloatArray
    """(B, d) the state at u = 0"""
    converged: FloatArray
    """(B,) bool: the shooting converged (False also where the crank would stop or turn
    back: the model does not describe that)"""
    iterations: int
    """Newton iterations"""
    residual: FloatArray
    """(B,) scaled residual of the revolution map [-]"""
    multipliers: FloatArray
    """(B, d) complex Floquet multipliers, largest modulus first"""

    @property
    def stability(self) -> FloatArray:
        """(B,) the largest |μ| (NaN where not converged)."""
        return np.where(self.converged, np.abs(self.multipliers[:, 0]), np.nan)

    @property
    def unstable(self) -> FloatArray:
        """(B,) bool: a multiplier outside the unit circle."""
        return self.stability > 1.0 + UNSTABLE_MARGIN


def periodic(line: Line, tables: Tables, lanes: Lanes, guess: FloatArray,
             progress: Callable[[int], None] | None = None) -> Periodic:
    """The periodic steady state of every lane by shooting (module docstring), from the
    state ``guess`` (B, d) at u = 0; the Floquet multipliers at the solution.
    ``progress(iteration)`` hears each Newton iteration done."""
    scale = scales(line, tables, lanes)
    x = np.array(guess, dtype=np.float64)
    b, d = x.shape
    done = np.zeros(b, dtype=bool)
    residual = np.full(b, np.inf)
    jac = np.full((b, d, d), np.nan)
    iteration = 0
    for iteration in range(1, NEWTON_MAX_ITER + 1):
        end, jac = monodromy(line, tables, lanes, x, scale)
        if progress is not None:
            progress(iteration)
        miss = end - x
        residual = np.max(np.abs(miss) / scale, axis=1)
        residual = np.where(np.isfinite(residual), residual, np.inf)
        done = residual <= NEWTON_TOL
        if done.all():
            break
        system = jac - np.eye(d)
        good = np.isfinite(system).all(axis=(1, 2)) & ~done
        stepped = np.zeros_like(x)
        if good.any():
            try:
                stepped[good] = np.linalg.solve(system[good], -miss[good][:, :, None])[:, :, 0]
            except np.linalg.LinAlgError:  # a singular lane: leave it where it is
                pass
        # damp large steps: at most a share of the state's scale per iteration
        size = np.max(np.abs(stepped) / scale, axis=1, keepdims=True)
        factor = np.minimum(1.0, 0.5 / np.maximum(size, 1e-300))
        x = np.where(done[:, None], x, x + factor * stepped)
        x = np.where(np.isfinite(x), x, guess)
    mult = np.linalg.eigvals(np.where(np.isfinite(jac), jac, 0.0))
    order = np.argsort(-np.abs(mult), axis=1)
    mult = np.take_along_axis(mult, order, axis=1)
    return Periodic(x, done, iteration, residual, mult)


def rest_guess(line: Line, tables: Tables, lanes: Lanes) -> FloatArray:
    """A starting state: the crank at Ω_ref and the static twists that carry the mean
    drive torque of the rigid machine at that speed (its load, friction and, for a motor
    with a characteristic, what the motor gives there)."""
    m = line.elements
    need = float(np.mean(tables.friction - tables.load))  # ½·J′·Ω² has zero mean
    x = np.zeros((lanes.speed.size, line.dimension))
    twist = np.zeros((lanes.speed.size, m))
    for e in range(m - 1, -1, -1):
        twist[:, e] = need / lanes.stiffness[:, e] + (twist[:, e + 1] if e < m - 1 else 0.0)
    x[:, 1:1 + m] = twist
    return x


def linear_guess(line: Line, tables: Tables, lanes: Lanes) -> FloatArray:
    """A starting state from the line linearised about uniform rotation at Ω_ref with the
    crank's mean inertia: the static twists plus the steady harmonic response to the
    rigid machine's drive torque ½·J′·Ω² − M_L + M_F, harmonic by harmonic."""
    x = rest_guess(line, tables, lanes)
    steps = tables.steps
    m = line.elements
    drive = (0.5 * tables.slope[0::2][None, :] * lanes.speed[:, None] ** 2
             - tables.load[0::2] + tables.friction[0::2])  # (B, N)
    spectrum = np.fft.rfft(drive, axis=1) / steps  # exciting torque on the crank: −drive
    count = spectrum.shape[1]
    first = 1 if line.ideal else 0
    size = m + 1 - first
    masses = np.concatenate((np.asarray(line.inertias[first:]), [np.mean(tables.inertia)]))
    harmonics = np.arange(1, count)
    b = lanes.speed.size
    omega = harmonics[None, :] * lanes.speed[:, None]  # (B, H)
    Z = np.zeros((b, count - 1, m + 1, m + 1), dtype=complex)
    for e in range(m):
        kc = lanes.stiffness[:, e][:, None] + 1j * omega * lanes.damping[:, e][:, None]
        Z[:, :, e, e] += kc
        Z[:, :, e + 1, e + 1] += kc
        Z[:, :, e, e + 1] -= kc
        Z[:, :, e + 1, e] -= kc
    Z = Z[:, :, first:, first:]
    Z -= omega[:, :, None, None] ** 2 * np.eye(size) * masses
    if not line.ideal:  # the motor's slope acts as a damper to the ground
        slope = _motor_slope(line.motor, lanes.speed)
        Z[:, :, 0, 0] -= 1j * omega * slope[:, None]
    force = np.zeros((b, count - 1, size), dtype=complex)
    force[:, :, -1] = -spectrum[:, 1:] * np.where(harmonics == steps // 2, 0.5, 1.0)
    try:
        disp = np.linalg.solve(Z, force[..., None])[..., 0]  # (B, H, size): e^{ik u} phasors
    except np.linalg.LinAlgError:
        return x
    if not np.all(np.isfinite(disp)):
        return x
    value = 2.0 * np.sum(disp, axis=1).real  # at u = 0 (t = 0)
    rate = 2.0 * np.sum(1j * omega[:, :, None] * disp, axis=1).real
    nodes = np.zeros((b, m + 1))
    speeds = np.zeros((b, m + 1))
    nodes[:, first:] = value
    speeds[:, first:] = rate
    x[:, 0] += speeds[:, -1]
    x[:, 1:1 + m] += nodes[:, :m] - nodes[:, -1:]
    x[:, 1 + m:] += speeds[:, 1:m] if line.ideal else speeds[:, :m]
    return x


def _motor_slope(motor: Motor, speed: FloatArray) -> FloatArray:
    """dm/dw at the speeds [N·m·s/rad]."""
    return np.array([motor.at(float(w))[1] for w in speed])


def mean_speed(orbit: Orbit) -> FloatArray:
    """(B,) 2π over the period [rad/s]."""
    return 2.0 * math.pi / orbit.quadratures[-1, :, 0]


def check_tables(tables: Tables) -> None:
    bad = ~(np.isfinite(tables.inertia) & (tables.inertia > 0.0)) | ~np.isfinite(tables.load)
    if bad.any():
        raise DyadeError("the drive line cannot be solved: the crank shaft's reduced moment of "
                         "inertia is zero or undefined somewhere in the cycle.")


def line_from(data: DriveLineData, motor: Motor | None) -> Line:
    """The line of a ``[drive_line]`` table with ``motor`` (None: an ideal motor at
    constant speed)."""
    rotor = (data.rotor_inertia or 0.0) * data.ratio ** 2
    if motor is not None and not data.rotor_inertia:
        raise InputError("the drive line with a [drive] motor needs the motor's rotor "
                         "inertia: give `drive_line.rotor_inertia` [kg·m²] (without "
                         "[drive] the motor is ideal and turns at constant speed).",
                         key="drive_line.rotor_inertia")
    labels = ("drive_line.stiffness", "drive_line.damping", "drive_line.rotor_inertia")
    if data.coupling is not None:
        c = data.coupling
        return Line((rotor, c.inertia), (c.c2, c.c1), (c.b2, c.b1), motor, labels)
    return Line((rotor,), (data.stiffness,), (data.damping,), motor, labels)


def line_data(mechanism: Mechanism) -> DriveLineData:
    """The ``[drive_line]`` table of ``mechanism`` (an ``InputError`` saying what to give
    when it has none)."""
    if mechanism.drive_line is None:
        raise InputError(f"{mechanism.name}: no [drive_line] table: give the elastic element "
                         f"between motor and crank (`drive_line.stiffness` [N·m/rad], or "
                         f"`drive_line.coupling` = a coupling file), see `dyade help drive-line`.",
                         key="drive_line")
    return mechanism.drive_line


def line_of(mechanism: Mechanism, *, ideal: bool = False) -> Line:
    """The drive line of ``mechanism``: its ``[drive]`` motor (or an ideal motor when the
    file has none, or with ``ideal``)."""
    data = line_data(mechanism)
    motor = None if ideal or mechanism.drive is None else mechanism.drive.motor
    return line_from(data, motor)


def sense_of(mechanism: Mechanism) -> float:
    """+1 when the crank turns counter-clockwise, −1 when clockwise: the running direction."""
    return 1.0 if mechanism.crank.speed > 0 else -1.0


class Periodic1D:
    """A table over one revolution (uniform samples from u = 0) as its Fourier series,
    evaluated at any u [rad]: exact for trigonometric polynomials of the grid's order."""

    def __init__(self, values: FloatArray, share: float = 1e-13) -> None:
        spectrum = np.fft.rfft(values) / values.size
        keep = np.abs(spectrum) > share * max(float(np.max(np.abs(spectrum))), 1e-300)
        keep[0] = True
        self.orders = np.flatnonzero(keep)
        weights = np.where(self.orders == 0, 1.0, 2.0)
        if values.size % 2 == 0:
            weights = np.where(self.orders == values.size // 2, 1.0, weights)
        self.coefficients = spectrum[self.orders] * weights

    def __call__(self, u: float) -> float:
        return float(np.dot(self.coefficients, np.exp(1j * self.orders * u)).real)

    def at(self, u: FloatArray) -> FloatArray:
        """The series at every u [rad] (vectorised)."""
        return (np.exp(1j * np.outer(u, self.orders)) @ self.coefficients).real


def halves(nodes: FloatArray) -> FloatArray:
    """A table at the N nodes of a revolution extended to its 2N half steps, the
    midpoints by its Fourier series."""
    steps = nodes.size
    out = np.empty(2 * steps)
    out[0::2] = nodes
    out[1::2] = Periodic1D(nodes).at(2.0 * math.pi / steps * (np.arange(steps) + 0.5))
    return out


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class RunUp:
    """A run-up from rest in time."""

    time: FloatArray
    """(K,) t [s]"""
    path: FloatArray
    """(K,) u: the crank's angle travelled in the running direction [rad]"""
    crank_speed: FloatArray
    """(K,) v [rad/s]"""
    motor_speed: FloatArray
    """(K,) w_0 [rad/s]"""
    shaft_torque: FloatArray
    """(K,) torque of the last element into the crank shaft [N·m]"""
    twist: FloatArray
    """(K,) θ_0 − u [rad]"""
    settled: bool
    """True when the mean speed over a revolution stopped changing (to ``tol``)"""
    revolutions: int
    """revolutions completed"""
    mean_speed: float = math.nan
    """2π over the time of the last whole revolution [rad/s]"""


def run_up(line: Line, tables: Tables, *, dt: float, t_max: float, tol: float = 1e-6,
           max_revolutions: int = 500, progress: Callable[[int], None] | None = None
           ) -> RunUp:
    """The run-up from rest (everything at rest and untwisted at u = 0) under the motor's
    characteristic, by RK4 in time with the step ``dt`` [s], until the mean speed over a
    revolution changes by less than ``tol`` from one to the next (relative), or up to
    ``t_max`` [s] or ``max_revolutions``. The tables enter as Fourier series in u; the
    friction torque, a table for forward motion, acts against the crank's motion.
    ``progress(revolutions)`` hears each revolution completed."""
    if line.ideal:
        raise InputError.parameter("motor", "a run-up needs a motor with a characteristic "
                                            "(a [drive] table), not an ideal motor.")
    m = line.elements
    inertia, slope = Periodic1D(tables.inertia), Periodic1D(tables.slope)
    load, rub = Periodic1D(tables.load), Periodic1D(tables.friction)
    k, b = np.asarray(line.stiffness), np.asarray(line.damping)
    nodes = np.asarray(line.inertias)
    torques = line.motor.torques

    def rates(y: FloatArray) -> tuple[FloatArray, float]:
        u, v = y[0], y[1]
        theta, w = y[2:2 + m], y[2 + m:]
        angles = np.append(theta, u)
        speeds = np.append(w, v)
        element = k * (angles[:-1] - angles[1:]) + b * (speeds[:-1] - speeds[1:])
        drive = float(torques(np.array([w[0]]))[0])
        before = np.concatenate(([drive], element[:-1]))
        friction = rub(u) * np.tanh(v / FRICTION_SPEED)
        accel = (element[-1] + load(u) - friction - 0.5 * slope(u) * v * v) / inertia(u)
        return np.concatenate(([v, accel], w, (before - element) / nodes)), float(element[-1])

    y = np.zeros(2 + 2 * m)
    rows = [(0.0, *y[:2], y[2 + m], rates(y)[1], 0.0)]
    t, turn, last_mark, last_mean, settled = 0.0, 1, 0.0, None, False
    while t < t_max:
        k1, torque = rates(y)
        k2, _ = rates(y + 0.5 * dt * k1)
        k3, _ = rates(y + 0.5 * dt * k2)
        k4, _ = rates(y + dt * k3)
        before = y
        y = y + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        t += dt
        rows.append((t, y[0], y[1], y[2 + m], rates(y)[1], y[2] - y[0]))
        if y[0] >= 2.0 * math.pi * turn:  # a revolution completed: when, to O(dt⁴)
            mark = t - dt + dt * _crossing(before[0], y[0], dt * before[1], dt * y[1],
                                           2.0 * math.pi * turn)
            mean = 2.0 * math.pi / (mark - last_mark)
            if turn > 1 and last_mean is not None and abs(mean - last_mean) <= tol * mean:
                settled, last_mean = True, mean
                break
            last_mark, last_mean, turn = mark, mean, turn + 1
            if progress is not None:
                progress(turn - 1)
            if turn > max_revolutions:
                break
    data = np.array(rows)
    return RunUp(data[:, 0], data[:, 1], data[:, 2], data[:, 3], data[:, 4], data[:, 5],
                 settled, turn - 1, math.nan if last_mean is None else last_mean)


def _crossing(u0: float, u1: float, d0: float, d1: float, target: float) -> float:
    """x ∈ [0, 1] where the cubic Hermite through (u0, d0), (u1, d1) (slopes per unit x)
    reaches ``target`` (Newton from the linear estimate)."""
    x = (target - u0) / (u1 - u0) if u1 != u0 else 1.0
    for _ in range(20):
        x2, x3 = x * x, x * x * x
        value = ((2 * x3 - 3 * x2 + 1) * u0 + (x3 - 2 * x2 + x) * d0 + (3 * x2 - 2 * x3) * u1
                 + (x3 - x2) * d1)
        change = ((6 * x2 - 6 * x) * u0 + (3 * x2 - 4 * x + 1) * d0 + (6 * x - 6 * x2) * u1
                  + (3 * x2 - 2 * x) * d1)
        if change <= 0.0:
            break
        step = (value - target) / change
        x = min(max(x - step, 0.0), 1.0)
        if abs(step) < 1e-15:
            break
    return x


FRICTION_SPEED = 1e-3  # [rad/s] the friction torque's sign is smoothed below this crank speed


# -- the line as a problem of the periodic-orbit engine (``dyade.machine.periodic``) -----
def lanes_of(line: Line, p: FloatArray) -> Lanes:
    """The lanes of parameter rows ``p`` (L, 1 + 2m): Ω_ref [rad/s], the m stiffnesses
    [N·m/rad], the m dampings [N·m·s/rad]."""
    m = line.elements
    return Lanes(p[:, 0], p[:, 1:1 + m], p[:, 1 + m:1 + 2 * m])


def parameters(line: Line, speed: FloatArray, stiffness: FloatArray | None = None,
               damping: FloatArray | None = None) -> FloatArray:
    """The parameter rows (B, 1 + 2m) of ``problem`` for speeds Ω [rad/s] (and per lane
    stiffnesses and dampings, default the line's)."""
    lanes = Lanes.of(line, speed, stiffness, damping)
    return np.column_stack((lanes.speed, lanes.stiffness, lanes.damping))


def problem(line: Line, tables_at: Callable[[int], Tables], steps: int, works: bool = False):
    """The line with its crank shaft as a ``periodic.Problem`` in the crank's path u
    (period 2π), the parameters per lane ``parameters(...)`` (p[0] = Ω is continued);
    ``tables_at(n)`` gives the crank shaft on n steps per revolution; ``steps`` is the
    first step count. With ``works`` (an ideal motor and one shaft only) the state
    carries three quadratures more: the work of the motor, of damping and of the loads
    (∫ s·M_L du) since u = 0 [J] (for ``periodic.trajectory``, not for shooting)."""
    if works and not (line.ideal and line.elements == 1):
        raise ValueError("the works ride along only on an ideal motor's single shaft")
    from dyade.machine.periodic import Problem

    coarse = tables_at(steps)
    m = line.elements

    def field(n: int):
        tables = coarse if n == steps else tables_at(n)
        period = 2 * n
        inertia = np.append(tables.inertia, tables.inertia[0])
        slope = np.append(tables.slope, tables.slope[0])
        drive = np.append(tables.load - tables.friction, tables.load[0] - tables.friction[0])
        if line.ideal and m == 1:  # the scans' line: δv and the twist, a lean field
            def f(k: int, x: FloatArray, p: FloatArray) -> FloatArray:
                dv = x[:, 0]
                v = p[:, 0] + dv
                slow = 1.0 / np.where(v > 0.0, v, np.nan)
                out = np.empty_like(x)
                torque = p[:, 1] * x[:, 1] - p[:, 2] * dv
                out[:, 0] = (torque + drive[k] - 0.5 * slope[k] * v * v) * slow / inertia[k]
                out[:, 1] = -dv * slow
                if works:
                    out[:, 2] = torque * p[:, 0] * slow
                    out[:, 3] = p[:, 2] * dv * dv * slow
                    out[:, 4] = drive[k]
                return out
            return f
        rub = np.append(tables.friction, tables.friction[0])
        load = np.append(tables.load, tables.load[0])

        def f(k: int, x: FloatArray, p: FloatArray) -> FloatArray:
            return _rates(line, lanes_of(line, p), x, inertia[k], slope[k], load[k], rub[k],
                          False)[0]
        return f

    # the crank shaft at any u (a mesh of its own per lane): the tables as Fourier series
    # (all four on one set of orders: one exp per call)
    series = [Periodic1D(values[0::2]) for values in (coarse.inertia, coarse.slope,
                                                       coarse.load, coarse.friction)]
    orders = np.unique(np.concatenate([table.orders for table in series]))
    weights = np.zeros((orders.size, 4), dtype=complex)
    for column, table in enumerate(series):
        weights[np.searchsorted(orders, table.orders), column] = table.coefficients
    cos_w, sin_w = weights.real, -weights.imag

    def field_at(u: FloatArray, x: FloatArray, p: FloatArray) -> FloatArray:
        angle = np.multiply.outer(u, orders)
        inertia, slope, load, rub = (np.cos(angle) @ cos_w + np.sin(angle) @ sin_w).T
        if line.ideal and m == 1:
            dv = x[:, 0]
            v = p[:, 0] + dv
            slow = 1.0 / np.where(v > 0.0, v, np.nan)
            out = np.empty_like(x)
            torque = p[:, 1] * x[:, 1] - p[:, 2] * dv
            out[:, 0] = (torque + load - rub - 0.5 * slope * v * v) * slow / inertia
            out[:, 1] = -dv * slow
            if works:
                out[:, 2] = torque * p[:, 0] * slow
                out[:, 3] = p[:, 2] * dv * dv * slow
                out[:, 4] = load - rub
            return out
        return _rates(line, lanes_of(line, p), x, inertia, slope, load, rub, False)[0]

    def pace(x: FloatArray, p: FloatArray) -> FloatArray:  # Ω over the crank's speed
        v = p[:, 0] + x[..., 0]
        return (p[:, 0] / np.where(v > 0.0, v, np.nan)) ** 2

    def scale(p: FloatArray) -> FloatArray:
        return scales(line, coarse, lanes_of(line, p))

    def span(p: FloatArray) -> FloatArray:  # speeds: Ω; twists and node speeds: a radian
        out = np.ones((p.shape[0], line.dimension))
        out[:, 0] = p[:, 0]
        out[:, 1 + m:] = p[:, :1]
        return np.maximum(out * SPAN, scale(p))

    if works:
        def wide(p: FloatArray) -> FloatArray:
            return np.pad(scale(p), ((0, 0), (0, 3)), constant_values=1.0)
        return Problem(line.dimension + 3, field, wide, 2.0 * math.pi, steps,
                       field_at=field_at, pace=pace)
    return Problem(line.dimension, field, scale, 2.0 * math.pi, steps, span, field_at, pace)


SPAN = 0.1  # [-] a branch's step is measured against this share of Ω and of a radian


def problem_in_time(line: Line, tables_at: Callable[[int], Tables], steps: int,
                    works: bool = False):
    """The scans' line (an ideal motor, one shaft) as a ``periodic.Problem`` in time:
    the independent variable s = Ω·t, the motor's angle (period 2π), the state the
    same (δv [rad/s], the twist [rad]) and the crank at φ = s − twist, the crank
    shaft's tables as Fourier series at φ. Where the crank nearly stops (or turns back
    for a moment) its path u is a poor variable (``problem``: the steps in u are long
    steps in time); in time the steps stay as fine as the vibration asks. The periodic
    solution's section is s = 0 (not u = 0); its Floquet multipliers are the same (the
    two period maps are conjugate). With ``works`` the state carries the three works
    of ``problem`` (motor, damping, loads' ∫ M_L dφ) [J]."""
    if not (line.ideal and line.elements == 1):
        raise ValueError("the line in time is the scans' line: an ideal motor, one shaft")
    from dyade.machine.periodic import Problem

    coarse = tables_at(steps)
    series = [Periodic1D(values[0::2]) for values in (coarse.inertia, coarse.slope,
                                                       coarse.load - coarse.friction)]
    orders = np.unique(np.concatenate([table.orders for table in series]))
    weights = np.zeros((orders.size, 3), dtype=complex)
    for column, table in enumerate(series):
        weights[np.searchsorted(orders, table.orders), column] = table.coefficients
    def field_at(s: FloatArray, x: FloatArray, p: FloatArray) -> FloatArray:
        turn = np.exp(1j * np.multiply.outer(s - x[:, 1], orders))
        inertia, slope, drive = (turn @ weights).real.T
        omega = p[:, 0]
        dv = x[:, 0]
        v = omega + dv
        torque = p[:, 1] * x[:, 1] - p[:, 2] * dv
        out = np.empty_like(x)
        out[:, 0] = (torque + drive - 0.5 * slope * v * v) / (inertia * omega)
        out[:, 1] = -dv / omega
        if works:
            out[:, 2] = torque
            out[:, 3] = p[:, 2] * dv * dv / omega
            out[:, 4] = drive * v / omega
        return out

    def field(n: int):
        h = math.pi / n

        def f(k: int, x: FloatArray, p: FloatArray) -> FloatArray:
            return field_at(k * h, x, p)
        return f

    def scale(p: FloatArray) -> FloatArray:
        return scales(line, coarse, lanes_of(line, p))

    if works:
        def wide(p: FloatArray) -> FloatArray:
            return np.pad(scale(p), ((0, 0), (0, 3)), constant_values=1.0)
        return Problem(line.dimension + 3, field, wide, 2.0 * math.pi, steps, field_at=field_at)
    return Problem(line.dimension, field, scale, 2.0 * math.pi, steps, field_at=field_at)


def section_in_time(path: FloatArray, nodes: FloatArray) -> FloatArray:
    """The states (L, d) where each lane's orbit in u (``path`` (K + 1, L, d) at the
    nodes ``nodes`` (K + 1, L) of one revolution, the twist second) passes the motor's
    angle s = u + twist ≡ 0 (mod 2π): the section of ``problem_in_time``, by linear
    interpolation between the nodes."""
    s = nodes + path[:, :, 1]
    target = np.where(s[0] > 0.0, 2.0 * math.pi, 0.0)  # s rises by 2π over the revolution
    past = s >= target[None, :]
    i = np.clip(np.argmax(past, axis=0) - 1, 0, s.shape[0] - 2)
    lanes = np.arange(s.shape[1])
    s0, s1 = s[i, lanes], s[i + 1, lanes]
    frac = np.clip((target - s0) / np.where(s1 > s0, s1 - s0, 1.0), 0.0, 1.0)
    return path[i, lanes] + frac[:, None] * (path[i + 1, lanes] - path[i, lanes])
