"""Peak force in a revolute joint with clearance (Dresig & Thümmel).

Near a reversal the rigid joint force is a ramp F = k·t (k = F0/t0 [N/s]). The pin
crosses the clearance 2s in free flight and strikes after t1 = cbrt(12·m·s/k) (15)
with v1 = 6·s/t1 (16); in contact (stiffness c, ω² = c/m, τ = ω·t1) the joint force is
eq. (26), whose first maximum is F12max = c·s·f(τ) (27).

The stationary points of (26) satisfy cos θ = x = (4 − 2τ³ − 2τ²)/(4 + τ⁴) and
sin θ = τ(τ − 2)(τ² + 2τ + 2)/(4 + τ⁴), so the first maximum is at

    θ* = 2·atan2(τ, τ − 2)     and     f(τ) = 6/τ + 12/τ² + 12·θ*/τ³.

For τ ≥ 2 this is eq. (36) exactly (θ* = arccos x); the atan2 form has no cancellation
at x → ±1 (τ → 0 and τ = 2). For τ < 2 the first maximum lies beyond the first
half-wave (θ* > π) and eq. (36) read with the principal arccos is not a maximum of (26)
at all; dyade uses θ* and flags such a "soft" impact (``Peak.soft``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import InputError


@dataclass(frozen=True, slots=True)
class Peak:
    """Closed-form result for one reversal (SI)."""

    mass: float
    """reduced mass m [kg]"""
    stiffness: float
    """contact stiffness c [N/m]"""
    clearance: float
    """clearance 2s [m]"""
    slope: float
    """force slope F0/t0 [N/s]"""
    t1: float
    """time of free flight across the clearance [s], eq. (15)"""
    v1: float
    """impact speed [m/s], eq. (16)"""
    tau: float
    """τ = ω·t1 [-], eq. (23)"""
    f_tau: float
    """f(τ) [-], eq. (36) (atan2 form)"""
    force: float
    """peak joint force F12max = c·s·f(τ) [N], eq. (27)"""
    time_to_peak: float
    """time from the reversal to the peak, t1 + θ*/ω [s]"""

    @property
    def clearance_share(self) -> float:
        """6·c·s/τ [N]: the part due to the impact across the clearance."""
        return 6.0 * self.stiffness * self.clearance / 2.0 / self.tau

    @property
    def rigid_share(self) -> float:
        """F12max − 6·c·s/τ [N]: the rigid force reached by then."""
        return self.force - self.clearance_share

    @property
    def soft(self) -> bool:
        """τ < 2: the peak comes after the first contact half-wave."""
        return self.tau < 2.0


def peak_angle(tau: FloatArray | float) -> FloatArray:
    """θ* = ω·t̃ of the first maximum of eq. (26) [rad], in (0, 2π)."""
    tau = np.asarray(tau, dtype=np.float64)
    return 2.0 * np.arctan2(tau, tau - 2.0)


def f_of_tau(tau: FloatArray | float) -> FloatArray:
    """f(τ) of eq. (36), stable for all τ > 0 (module docstring)."""
    tau = np.asarray(tau, dtype=np.float64)
    return 6.0 / tau + 12.0 / tau ** 2 + 12.0 * peak_angle(tau) / tau ** 3


def reduced_mass(m11: float, m22: float) -> float:
    """m = m11·m22/(m11 + m22), eq. (17) [kg]."""
    return m11 * m22 / (m11 + m22)


UNITS = {"mass": "kg", "stiffness": "N/m", "clearance": "m", "slope": "N/s"}


def check_positive(**values: float) -> None:
    """Reject zero, negative or non-finite inputs with an error naming each parameter."""
    for name, value in values.items():
        if not np.isfinite(value) or value <= 0.0:
            raise InputError.parameter(name, f"must be a positive number "
                                             f"[{UNITS.get(name, '')}], got {value:g}.",
                                       value=value, unit=UNITS.get(name))


def peak_force(mass: float, stiffness: float, *, clearance: float, slope: float) -> Peak:
    """Closed-form peak force at a reversal of a joint force (eqs. (15)-(36)).

    Parameters
    ----------
    mass : float
        Reduced mass m [kg], eq. (17) (``reduced_mass`` of the two masses).
    stiffness : float
        Contact stiffness c [N/m] (typical 1e7 … 1e9).
    clearance : float
        Clearance (radial play) 2s [m] (typical 2e-5 … 2e-4).
    slope : float
        Slope F0/t0 of the rigid joint force at the reversal [N/s].

    Returns
    -------
    Peak
        t1, v1, τ, f(τ) and the peak force F12max = c·s·f(τ) [N], with its shares.

    Examples
    --------
    The paper's warp-knitting needle drive, joint (5,6) (section 4): 2182 N.

    >>> from dyade.clearance import peak_force
    >>> peak = peak_force(mass=3.6, stiffness=1e7, clearance=1e-4, slope=3.6e5)
    >>> round(peak.force), round(peak.tau, 4)
    (2182, 3.0285)
    """
    check_positive(mass=mass, stiffness=stiffness, clearance=clearance, slope=slope)
    s = clearance / 2.0
    t1 = float(np.cbrt(12.0 * mass * s / slope))
    omega = float(np.sqrt(stiffness / mass))
    tau = omega * t1
    f = float(f_of_tau(tau))
    return Peak(float(mass), float(stiffness), float(clearance), float(slope), t1,
                6.0 * s / t1, tau, f, stiffness * s * f, float(t1 + peak_angle(tau) / omega))


def contact_force(peak: Peak, time: FloatArray | float) -> FloatArray:
    """The joint force of the closed form over time from the reversal [N], eq. (26):
    zero in free flight (t < t1), then

        F12 = (12·c·s/τ²)·[1 + ω·t̃/τ + (τ/2 − 1/τ)·sin ω·t̃ − cos ω·t̃],  t̃ = t − t1,

    valid while the masses stay in contact (the closed form's assumption; see
    ``simulate`` for when they separate). Its first maximum is ``peak.force``.

    Parameters
    ----------
    peak : Peak
        From ``peak_force``.
    time : array_like
        Times from the reversal [s].

    Examples
    --------
    >>> import numpy as np
    >>> peak = peak_force(3.6, 1e7, clearance=1e-4, slope=3.6e5)
    >>> round(float(contact_force(peak, peak.time_to_peak)))    # the peak, eq. (27)
    2182
    """
    time = np.asarray(time, dtype=np.float64)
    omega = peak.tau / peak.t1
    s, tau = peak.clearance / 2.0, peak.tau
    theta = omega * np.maximum(time - peak.t1, 0.0)
    force = (12.0 * peak.stiffness * s / tau ** 2) * (
        1.0 + theta / tau + (tau / 2.0 - 1.0 / tau) * np.sin(theta) - np.cos(theta))
    return np.where(time < peak.t1, 0.0, force)


# -- direct simulation of the two-stage model -----------------------------------------
@dataclass(frozen=True, slots=True)
class Simulation:
    """The two-mass model integrated directly (RK4, fixed step)."""

    force: float
    """first peak of the contact force [N]"""
    time_to_peak: float
    """[s] from the reversal"""
    t1: float
    """impact time [s]"""
    steps: int
    """RK4 steps taken"""
    separates: bool
    """the contact force returns to zero within one contact period after the peak"""
    separation_time: float
    """[s] from the reversal (NaN if it stays in contact)"""
    rebound_speed: float
    """relative speed at separation [m/s] (NaN if it stays in contact)"""
    contact_to_peak: bool
    """contact held without interruption from impact to the peak (the closed form's
    assumption)"""
    time: FloatArray | None = None
    """(k,) with ``history=True``: every step's time from the reversal [s]"""
    contact_force: FloatArray | None = None
    """(k,) with ``history=True``: the contact force c·max(z − 2s, 0) at those times [N]"""


def simulate(mass: float, stiffness: float, *, clearance: float, slope: float,
             steps_per_period: int = 400, history: bool = False) -> Simulation:
    """Integrate m·z'' = k·t − c·max(z − 2s, 0) from rest at z = 0 (pin against the far
    side of the bearing at the reversal, t = 0). Free flight to z = 2s, then contact;
    the joint force is c·(z − 2s). The impact instant is located by bisection on the
    cubic Hermite interpolant, so the kink of the contact law does not cost order.
    With ``history`` the result keeps the time and contact force of every step (an
    RK4 step depends on the one before: the integration itself is sequential).

    Parameters
    ----------
    mass : float
        Reduced mass m [kg] (eq. 17).
    stiffness : float
        Contact stiffness c [N/m].
    clearance : float
        Clearance 2s [m].
    slope : float
        Slope F0/t0 of the rigid force at the reversal [N/s].
    steps_per_period : int
        RK4 steps per contact period 2π/ω.
    history : bool
        Keep the time and contact force of every step.

    Returns
    -------
    Simulation
        The peak contact force, when it occurs, and (with ``history``) the force history.

    Examples
    --------

    >>> sim = simulate(3.6, 1e7, clearance=1e-4, slope=3.6e5, history=True)
    >>> round(sim.force), sim.time.size == sim.steps + 1           # 2182 N, eq. (36)
    (2182, True)
    >>> closed = contact_force(peak_force(3.6, 1e7, clearance=1e-4, slope=3.6e5), sim.time)
    >>> bool(abs(sim.contact_force - closed).max() < 1e-3)         # [N], eq. (26)
    True
    """
    check_positive(mass=mass, stiffness=stiffness, clearance=clearance, slope=slope)
    gap, k, c, m = clearance, slope, stiffness, mass
    omega = np.sqrt(c / m)
    period = 2.0 * np.pi / omega
    t_flight = np.cbrt(6.0 * m * gap / k)  # scale of stage 1 (exact value not used)
    h = min(period, t_flight) / steps_per_period

    def accel(t: float, z: float) -> float:
        return (k * t - c * max(z - gap, 0.0)) / m

    def rk4(t: float, z: float, v: float, dt: float) -> tuple[float, float]:
        a1 = accel(t, z)
        z2, v2 = z + 0.5 * dt * v, v + 0.5 * dt * a1
        a2 = accel(t + 0.5 * dt, z2)
        z3, v3 = z + 0.5 * dt * v2, v + 0.5 * dt * a2
        a3 = accel(t + 0.5 * dt, z3)
        z4, v4 = z + dt * v3, v + dt * a3
        a4 = accel(t + dt, z4)
        return (z + dt / 6.0 * (v + 2 * v2 + 2 * v3 + v4),
                v + dt / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4))

    t, z, v, steps = 0.0, 0.0, 0.0, 0
    times, positions = ([0.0], [0.0]) if history else (None, None)
    # stage 1: free flight (z < gap), step until the crossing, then locate it
    while True:
        z_new, v_new = rk4(t, z, v, h)
        steps += 1
        if z_new >= gap:
            lo, hi = 0.0, h
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if rk4(t, z, v, mid)[0] >= gap:
                    hi = mid
                else:
                    lo = mid
            z, v = rk4(t, z, v, hi)
            z = gap
            t += hi
            break
        t, z, v = t + h, z_new, v_new
        if history:
            times.append(t)
            positions.append(z)
    t_impact = t
    if history:
        times.append(t)
        positions.append(z)
    # stage 2: contact; a fresh step grid from the impact on
    h = min(period / steps_per_period, h * 4)
    peak_force = peak_time = np.nan
    contact_ok = True
    separation_time = rebound = np.nan
    t_end = t_impact + 3.0 * period + 2.0 * (2.0 * np.pi / omega)
    prev_v = v
    while t < t_end:
        z_new, v_new = rk4(t, z, v, h)
        steps += 1
        if np.isnan(peak_force) and prev_v > 0.0 >= v_new:
            # peak of z (and of the force) inside this step: cubic Hermite maximum
            peak_z, peak_dt = _hermite_peak(z, v, z_new, v_new, accel(t, z), h)
            peak_force, peak_time = c * (peak_z - gap), t + peak_dt
        if history:
            times.append(t + h)
            positions.append(z_new)
        if z_new < gap:
            if np.isnan(peak_force):
                contact_ok = False
            separation_time, rebound = t + h, -v_new
            t, z, v = t + h, z_new, v_new
            break
        t, z, v, prev_v = t + h, z_new, v_new, v_new
        if not np.isnan(peak_force) and t > peak_time + period:
            break
    separates = not np.isnan(separation_time)
    time = force = None
    if history:
        time = np.array(times)
        force = c * np.maximum(np.array(positions) - gap, 0.0)
    return Simulation(float(peak_force), float(peak_time), float(t_impact), steps, separates,
                      float(separation_time), float(rebound), contact_ok, time, force)


def _hermite_peak(z0: float, v0: float, z1: float, v1: float, a0: float, h: float
                  ) -> tuple[float, float]:
    """Maximum of the cubic Hermite interpolant of z over one step (v changes sign)."""
    # v(s) is quadratic in s ∈ [0, 1] on the Hermite cubic; find its root
    # z(s) = h00 z0 + h10 h v0 + h01 z1 + h11 h v1
    p = np.polynomial.Polynomial
    h00, h10, h01, h11 = p([1, 0, -3, 2]), p([0, 1, -2, 1]), p([0, 0, 3, -2]), p([0, 0, -1, 1])
    cubic = h00 * z0 + h10 * (h * v0) + h01 * z1 + h11 * (h * v1)
    roots = [r.real for r in cubic.deriv().roots() if abs(r.imag) < 1e-12 and -1e-9 <= r.real <= 1 + 1e-9]
    if not roots:
        return (z0, 0.0) if z0 >= z1 else (z1, h)
    best = max(roots, key=lambda r: cubic(r))
    return float(cubic(best)), float(best * h)


def peaks_over_speed(mass: float, stiffness: float, *, clearance: float, slope: float,
                     speed_rpm: float, speeds_rpm) -> list[tuple[float, Peak]]:
    """The peak force against crank speed: the force slope at the reversal grows with
    Ω³ (eq. (30): F0/t0 = k1·Ω³), from ``slope`` [N/s] at ``speed_rpm`` [rpm].

    Returns (speed [rpm], Peak) for every speed of ``speeds_rpm``.

    >>> [round(p.force) for _, p in peaks_over_speed(3.6, 1e7, clearance=1e-4, slope=3.6e5,
    ...                                                    speed_rpm=300, speeds_rpm=[300, 600])]
    [2182, 11099]
    """
    if not np.isfinite(speed_rpm) or speed_rpm <= 0.0:
        raise InputError.parameter("speed_rpm", f"must be a positive speed [rpm], got "
                                                f"{speed_rpm:g}.", value=speed_rpm, unit="rpm")
    return [(float(rpm), peak_force(mass, stiffness, clearance=clearance,
                                    slope=scaled_slope(slope, speed_rpm, rpm)))
            for rpm in speeds_rpm]


def scaled_slope(slope: float, speed_rpm: float, rpm: float) -> float:
    """The force slope [N/s] at ``rpm`` from ``slope`` at ``speed_rpm`` (∝ Ω³, eq. (30))."""
    return slope * (rpm / speed_rpm) ** 3
