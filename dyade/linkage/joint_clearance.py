"""The clearance check over a linkage's cycle (Dresig & Thümmel; closed form in
``dyade.clearance``).

For each revolute joint: the dominant line of action of its rigid-body force over the
cycle, whether the force keeps to it (else the model does not apply: the pin travels
around the bearing instead of crossing it), and every reversal of its sense with the
slope F0/t0 = |dF/dφ21|·Ω, the peak force and its amplification over the rigid force.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.clearance import Peak, peak_force, reduced_mass
from dyade.errors import InputError
from dyade.model.mechanism import ClearanceData, Mechanism, Revolute

MISSING = {
    "data": ("no clearance data: give {stiffness} and {clearance}, or "
             "`clearance = {{ gap = …, stiffness = … }}` in its joint table"),
    "mass": ("no reduced mass: give {mass} or `clearance.mass` (links {a} and {b} have no "
             "mass to estimate it from)"),
    "forces": ("no crank position of the sweep has its joint forces given (every position "
               "is withheld: `dyade analyse` says why)")}
"""why a joint cannot be checked: what is missing -> the reason, its inputs as fields"""
MAX_WANDER_DEG = 20.0  # [°] largest direction change off the line of action (API default)
MAX_WANDER = np.deg2rad(MAX_WANDER_DEG)  # [rad] the same, inside the engine
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
    missing: str = ""
    """what the check lacks: "data" (clearance data), "mass", "forces" (the sweep gives
    them at no position) or "" (see ``MISSING``)"""


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


@dataclass(frozen=True, slots=True)
class ForceLine:
    """A revolute joint's force over the cycle seen along its dominant line of action:
    where it reverses its sense (what the clearance check and the polar diagram show)."""

    joint: tuple[int, int]
    line_angle: float
    """direction of the dominant line of action [rad], in [0, π); NaN without force"""
    wander: float
    """largest angle between the force and that line [rad] (forces ≥ 25 % of the peak)"""
    applies: bool
    """the force keeps to one line within ``max_wander`` (else no reversals are given)"""
    reason: str
    """why it does not ('' when it does)"""
    reversal_angles: FloatArray
    """(k,) crank angles of the sense reversals [rad], in the order found, within the
    sweep's range (a full cycle's last one may pass its end: take it modulo 2π)"""
    slopes: FloatArray
    """(k,) |dF/dφ21| along the line at each reversal [N/rad]"""
    reversal_forces: FloatArray
    """(k, 2) the force vector at each reversal, interpolated as the angle is [N]"""
    cycle_angles: FloatArray
    """(m,) the finite positions of one cycle [rad] (a repeated 360° left out)"""
    cycle_magnitudes: FloatArray
    """(m,) |F| at those positions [N]"""


NO_FORCE = "the joint carries no force"
"""the reason of a ``ForceLine`` whose force is zero wherever it is given"""
NOT_GIVEN = ("its force is not given at the positions (fewer than 3 have it: the others are "
             "withheld)")
"""the reason of a ``ForceLine`` whose force is not given: nothing is known of it"""


def force_line(name: tuple[int, int], crank_angle: FloatArray, force: FloatArray,
               full_cycle: bool, max_wander: float = MAX_WANDER) -> ForceLine:
    """The dominant line of action of one joint's force (n, 2) [N] over the crank angles
    (n,) [rad] (NaN rows: not given) and the sense reversals along it; on a full cycle
    the last position is compared with the first."""
    keep = np.all(np.isfinite(force), axis=1)
    phi, force = crank_angle[keep], force[keep]
    nothing, pair = np.empty(0), np.empty((0, 2))
    if phi.size < 3:  # withheld (beyond what a machine has, dead centres): not zero
        return ForceLine(name, np.nan, np.nan, False, NOT_GIVEN, nothing, nothing, pair,
                         nothing, nothing)
    if not np.any(np.hypot(force[:, 0], force[:, 1]) > 0):
        return ForceLine(name, np.nan, np.nan, False, NO_FORCE, nothing, nothing, pair,
                         nothing, nothing)
    angle, wander = line_of_action(force)
    if wander > max_wander:
        return ForceLine(name, angle, wander, False,
                         f"the force direction wanders up to {np.rad2deg(wander):.0f}° off its "
                         f"dominant line of action (the model needs one line, within "
                         f"{np.rad2deg(max_wander):.0f}°): the pin travels around the bearing "
                         f"instead of crossing it", nothing, nothing, pair, nothing, nothing)
    u = np.array([np.cos(angle), np.sin(angle)])
    magnitude = np.hypot(force[:, 0], force[:, 1])
    if full_cycle and np.isclose(phi[-1] - phi[0], 2 * np.pi):
        phi, force, magnitude = phi[:-1], force[:-1], magnitude[:-1]  # 360° repeats 0°
    along = force @ u
    phi_all = phi.copy()
    if full_cycle:  # the cycle closes: compare the last position with the first
        along_next, force_next = np.roll(along, -1), np.roll(force, -1, axis=0)
        phi_next = np.append(phi[1:], phi[0] + 2 * np.pi)
    else:
        along, along_next, phi_next, phi = along[:-1], along[1:], phi[1:], phi[:-1]
        force, force_next = force[:-1], force[1:]
    crossing = np.flatnonzero((along >= 0.0) != (along_next >= 0.0))
    a, b = along[crossing], along_next[crossing]
    dphi = phi_next[crossing] - phi[crossing]
    share = a / (a - b)
    at = phi[crossing] + share * dphi
    slope = np.abs(b - a) / dphi
    vector = force[crossing] + share[:, None] * (force_next[crossing] - force[crossing])
    return ForceLine(name, angle, wander, True, "", at, slope, vector, phi_all, magnitude)


def check_joint(name: tuple[int, int], crank_angle: FloatArray, force: FloatArray,
                speed: float, data, mass: float, mass_source: str,
                full_cycle: bool, max_wander: float = MAX_WANDER) -> JointCheck:
    """Find the reversals of one joint's force and their peak forces (eqs. (27), (36))."""
    line = force_line(name, crank_angle, force, full_cycle, max_wander)
    if not line.applies:
        return JointCheck(name, line.line_angle, line.wander, False, line.reason, (),
                          mass_source)
    period = 2 * np.pi if full_cycle else None
    reversals = []
    for at, slope in zip(line.reversal_angles, line.slopes):
        peak = peak_force(mass, data.stiffness, clearance=data.clearance, slope=slope * abs(speed))
        later = at + speed * peak.time_to_peak  # crank angle when the peak occurs
        rigid = float(np.interp(later, line.cycle_angles, line.cycle_magnitudes, period=period))
        reversals.append(Reversal(float(at % (2 * np.pi)), float(slope), peak, rigid))
    return JointCheck(name, line.line_angle, line.wander, True, "", tuple(reversals),
                      mass_source)


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


def needs_forces(result, what: str) -> None:
    """An ``InputError`` where the sweep ``result`` has no forces (no masses, loads or
    springs), for ``what`` needs them."""
    if result.forces_valid is None:
        raise InputError(f"{what} needs joint forces: the file has no masses, loads or "
                         f"springs (add mass data, see `dyade help mechanism-file`).")


def _revolute(mechanism, name: tuple[int, int]) -> Revolute:
    """The revolute joint ``name``, or an error listing the mechanism's revolute joints."""
    by_name = {j.name: j for j in mechanism.joints}
    joint = by_name.get(name)
    if joint is None or not isinstance(joint, Revolute):
        kinds = ", ".join(f"({a},{b})" for a, b in by_name if isinstance(by_name[(a, b)], Revolute))
        raise InputError.parameter("joints", f"{name[0]},{name[1]}: the mechanism has no "
                                             f"revolute joint ({name[0]},{name[1]}); its "
                                             f"revolute joints are {kinds}.", value=name)
    return joint


def _cycle(mechanism, result) -> tuple[FloatArray, bool]:
    """The reported crank angles [rad] and whether they make a full cycle."""
    phi = result.crank_angle[result.rows]
    return phi, bool((phi[-1] - phi[0]) >= 2 * np.pi - 1.5 * mechanism.sweep.step)


def _joint_force(result, forces: dict, name: tuple[int, int]) -> FloatArray:
    """(n, 2) a joint's reported force [N] (of ``forces``: joint -> (n, 2) at every
    position of the sweep ``result``), NaN where the forces are not given."""
    force = forces[name][result.rows]
    return np.where(result.forces_valid[result.rows][:, None], force, np.nan)


def force_lines(result, joints=None, *, max_wander: float = MAX_WANDER) -> list[ForceLine]:
    """The dominant line of action and the sense reversals of revolute joints' forces,
    exactly as the clearance check finds them (without peak forces: no clearance data
    needed).

    Parameters
    ----------
    result : Result
        An analysis with joint forces (``dyade.analyse``).
    joints : iterable of (int, int), optional
        Revolute joints (default: every revolute joint).
    max_wander : float
        How far [rad] the force may leave its line for reversals to be given.

    Examples
    --------
    >>> import dyade
    >>> from dyade.linkage.joint_clearance import force_lines
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/dyade-16.toml"))
    >>> line, = force_lines(result, [(5, 6)])
    >>> [round(float(a), 1) for a in line.reversal_angles * 180 / 3.141592653589793]
    [104.4, 329.2]
    """
    mechanism = result.mechanism
    needs_forces(result, "a line of action")
    if joints is None:
        joints = [j.name for j in mechanism.joints if isinstance(j, Revolute)]
    phi, full = _cycle(mechanism, result)
    forces = result.forces.revolute
    out = []
    for a, b in joints:
        name = (a, b) if a < b else (b, a)
        _revolute(mechanism, name)
        out.append(force_line(name, phi, _joint_force(result, forces, name), full, max_wander))
    return out


def check_mechanism(mechanism, result, forces: dict, joints, override=None,
                    mass_override=None, max_wander: float = MAX_WANDER) -> list[JointCheck]:
    """Clearance check of the given revolute joints from a sweep's outcome ``result``
    (``verdicts.Outcome``: its positions, the forces given, the crank's motion) and
    ``forces`` (joint -> (n, 2) force [N] at each of its positions).

    ``override``: ClearanceData applied to every joint (CLI), ``mass_override`` [kg],
    ``max_wander`` [rad]: how far the force may leave its line of action."""
    needs_forces(result, "the clearance check")
    phi, full = _cycle(mechanism, result)
    speed = mechanism.crank.speed  # with a drive: its mean speed 2π/T
    if getattr(result, "drive", None) is not None:
        speed = math.copysign(result.drive.figures["speed_mean"], speed)
    checks = []
    for name in joints:
        joint = _revolute(mechanism, name)
        data = override or joint.clearance
        mass, source = (mass_override, "given") if mass_override else joint_mass(mechanism, joint)
        missing = None
        if data is None:
            missing = "data"
        elif mass is None:
            missing = "mass"
        if missing:
            reason = MISSING[missing].format(a=name[0], b=name[1], stiffness="the stiffness",
                                             clearance="the clearance", mass="the mass")
            checks.append(JointCheck(name, np.nan, np.nan, False, reason, (), "", missing))
            continue
        checks.append(check_joint(name, phi, _joint_force(result, forces, name), speed, data,
                                  mass, source, full, max_wander))
    return checks
