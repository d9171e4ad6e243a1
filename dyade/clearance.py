"""Peak force in a revolute joint with clearance (Dresig & Thümmel; SPEC §2).

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

from dyade.errors import InputError
from dyade.arrays import FloatArray


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


def check_positive(**values: float) -> None:
    """Reject zero, negative or non-finite inputs with a message naming each one."""
    units = {"mass": "kg", "stiffness": "N/m", "clearance": "m", "slope": "N/s"}
    for name, value in values.items():
        if not np.isfinite(value) or value <= 0.0:
            raise InputError(f"--{name} must be a positive number [{units.get(name, '')}], "
                             f"got {value:g}.")


def peak_force(mass: float, stiffness: float, clearance: float, slope: float) -> Peak:
    """Closed-form peak force of SPEC §2 for reduced mass m [kg], contact stiffness c
    [N/m], clearance 2s [m] and force slope F0/t0 [N/s]."""
    check_positive(mass=mass, stiffness=stiffness, clearance=clearance, slope=slope)
    s = clearance / 2.0
    t1 = np.cbrt(12.0 * mass * s / slope)
    omega = np.sqrt(stiffness / mass)
    tau = omega * t1
    f = float(f_of_tau(tau))
    return Peak(mass, stiffness, clearance, slope, float(t1), 6.0 * s / t1, float(tau), f,
                stiffness * s * f, float(t1 + peak_angle(tau) / omega))


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


def simulate(mass: float, stiffness: float, clearance: float, slope: float,
             steps_per_period: int = 400) -> Simulation:
    """Integrate m·z'' = k·t − c·max(z − 2s, 0) from rest at z = 0 (pin against the far
    side of the bearing at the reversal, t = 0). Free flight to z = 2s, then contact;
    the joint force is c·(z − 2s). The impact instant is located by bisection on the
    cubic Hermite interpolant, so the kink of the contact law does not cost order."""
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
    t_impact = t
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
    return Simulation(float(peak_force), float(peak_time), float(t_impact), steps, separates,
                      float(separation_time), float(rebound), contact_ok)


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


# -- over a mechanism ------------------------------------------------------------------
MAX_WANDER = np.deg2rad(20.0)  # [rad] largest direction change off the line of action
SMALL_FORCE = 0.25  # [-] forces below this share of the peak do not count for the wander


@dataclass(frozen=True, slots=True)
class Reversal:
    """One sense reversal of a joint force, and its clearance peak."""

    crank_angle: float
    """[rad] where the force along its line of action passes zero"""
    slope_per_rad: float
    """|dF/dφ21| at the reversal [N/rad]"""
    peak: Peak
    rigid_force: float
    """|F| of the rigid model when the peak occurs [N]"""

    @property
    def amplification(self) -> float:
        return self.peak.force / self.rigid_force if self.rigid_force > 0 else float("nan")


@dataclass(frozen=True, slots=True)
class JointCheck:
    """The clearance check of one revolute joint over a mechanism's cycle."""

    joint: tuple[int, int]
    line_angle: float
    """direction of the dominant line of action [rad], in [0, π)"""
    wander: float
    """largest angle between the force and that line [rad] (forces ≥ 25 % of the peak)"""
    applies: bool
    reason: str
    """why the model does not apply ('' when it does)"""
    reversals: tuple[Reversal, ...]
    mass_source: str


def line_of_action(force: FloatArray) -> tuple[float, float]:
    """Dominant line of action of force vectors (n, 2): its angle in [0, π) and the
    largest angle between a (non-small) force and that line [rad]."""
    second = force.T @ force
    values, vectors = np.linalg.eigh(second)
    u = vectors[:, np.argmax(values)]
    angle = float(np.arctan2(u[1], u[0]) % np.pi)
    u = np.array([np.cos(angle), np.sin(angle)])
    size = np.hypot(force[:, 0], force[:, 1])
    big = size >= SMALL_FORCE * size.max()
    along = force @ u
    across = force[:, 0] * u[1] - force[:, 1] * u[0]
    off = np.arctan2(np.abs(across[big]), np.abs(along[big]))
    return angle, float(off.max(initial=0.0))


def check_joint(name: tuple[int, int], crank_angle: FloatArray, force: FloatArray,
                speed: float, data, mass: float, mass_source: str,
                full_cycle: bool, max_wander: float = MAX_WANDER) -> JointCheck:
    """Find the reversals of one joint's force and their peak forces (SPEC §2)."""
    keep = np.all(np.isfinite(force), axis=1)
    phi, force = crank_angle[keep], force[keep]
    if phi.size < 3 or not np.any(np.hypot(force[:, 0], force[:, 1]) > 0):
        return JointCheck(name, np.nan, np.nan, False, "the joint carries no force", (),
                          mass_source)
    angle, wander = line_of_action(force)
    if wander > max_wander:
        return JointCheck(name, angle, wander, False,
                          f"the force direction wanders up to {np.rad2deg(wander):.0f}° off its "
                          f"dominant line of action (the model needs one line, within "
                          f"{np.rad2deg(max_wander):.0f}°): the pin travels around the bearing "
                          f"instead of crossing it", (), mass_source)
    u = np.array([np.cos(angle), np.sin(angle)])
    magnitude = np.hypot(force[:, 0], force[:, 1])
    if full_cycle and np.isclose(phi[-1] - phi[0], 2 * np.pi):
        phi, force, magnitude = phi[:-1], force[:-1], magnitude[:-1]  # 360° repeats 0°
    along = force @ u
    phi_all, magnitude_all = phi.copy(), magnitude
    if full_cycle:  # the cycle closes: compare the last position with the first
        along_next = np.roll(along, -1)
        phi_next = np.append(phi[1:], phi[0] + 2 * np.pi)
    else:
        along, along_next, phi_next, phi = along[:-1], along[1:], phi[1:], phi[:-1]
    positive = along >= 0.0
    crossing = np.flatnonzero(positive != (along_next >= 0.0))
    period = 2 * np.pi if full_cycle else None
    reversals = []
    for k in crossing:
        a, b = along[k], along_next[k]
        dphi = phi_next[k] - phi[k]
        at = phi[k] + a / (a - b) * dphi
        slope = abs(b - a) / dphi
        peak = peak_force(mass, data.stiffness, data.clearance, slope * abs(speed))
        later = at + speed * peak.time_to_peak  # crank angle when the peak occurs
        rigid = float(np.interp(later, phi_all, magnitude_all, period=period))
        reversals.append(Reversal(float(at % (2 * np.pi)), float(slope), peak, rigid))
    return JointCheck(name, angle, wander, True, "", tuple(reversals), mass_source)


def joint_mass(mechanism, joint) -> tuple[float | None, str]:
    """Reduced mass for a joint: given, or m_i·m_j/(m_i + m_j) of its two links (the
    frame counts as infinitely heavy). None if neither is known."""
    if joint.clearance is not None and joint.clearance.mass is not None:
        return joint.clearance.mass, "given"
    masses = [mechanism.links[link].mass for link in joint.links if link != 1]
    if not masses or any(m <= 0.0 for m in masses):
        return None, ""
    if len(masses) == 1:
        return masses[0], f"mass of link {[l for l in joint.links if l != 1][0]} (frame side rigid)"
    a, b = joint.links
    return reduced_mass(*masses), f"reduced mass of links {a} and {b} (eq. 17)"


def check_mechanism(mechanism, result, joints, override=None, mass_override=None,
                    max_wander: float = MAX_WANDER) -> list:
    """Clearance check of the given revolute joints from an analysis result.

    ``override``: ClearanceData applied to every joint (CLI), ``mass_override`` [kg],
    ``max_wander`` [rad]: how far the force may leave its line of action."""
    from dyade.linkage.model import Revolute

    forces = result.forces
    if forces is None:
        raise InputError("the clearance check needs joint forces: the file has no masses, "
                         "loads or springs (add mass data, see mechanisms/README.md).")
    by_name = {j.name: j for j in mechanism.joints}
    phi = result.crank_angle[result.rows]
    full = (phi[-1] - phi[0]) >= 2 * np.pi - 1.5 * mechanism.sweep.step
    checks = []
    for name in joints:
        joint = by_name.get(name)
        if joint is None or not isinstance(joint, Revolute):
            kinds = ", ".join(f"({a},{b})" for a, b in by_name if isinstance(by_name[(a, b)], Revolute))
            raise InputError(f"--joint {name[0]},{name[1]}: the mechanism has no revolute joint "
                             f"({name[0]},{name[1]}); its revolute joints are {kinds}.")
        data = override or joint.clearance
        mass, source = (mass_override, "given") if mass_override else joint_mass(mechanism, joint)
        missing = None
        if data is None:
            missing = ("no clearance data: give --stiffness and --clearance, or "
                       "`clearance = { gap = …, stiffness = … }` in its joint table")
        elif mass is None:
            missing = (f"no reduced mass: give --mass or `clearance.mass` (links {name[0]} and "
                       f"{name[1]} have no mass to estimate it from)")
        if missing:
            checks.append(JointCheck(name, np.nan, np.nan, False, missing, (), ""))
            continue
        force = forces.revolute[name][result.rows]
        force = np.where(forces.valid[result.rows][:, None], force, np.nan)
        checks.append(check_joint(name, phi, force, mechanism.crank.speed, data, mass, source,
                                  bool(full), max_wander))
    return checks
