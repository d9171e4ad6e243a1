"""The forces between a cam and its follower at a constant cam speed ω: the contact
force along the common normal, the speeds that keep the follower in contact (force
closure by a spring), the Hertz contact stress.

The follower's coordinate q is its lift s [m] (translating) or its swing [rad]
(oscillating); its inertia m the mass [kg] or the moment of inertia about the pivot
[kg·m²]; the spring (stiffness k [N/m or N·m/rad], preload q0 in the coordinate's unit:
the spring force is k·(q + q0)) and the external load F [N or N·m] both push the
follower towards the cam (a load against the rise is positive; gravity is part of F).
Without guide friction the balance along the follower's motion is

    N·h·cos α = m·q″·ω² + k·(q + q0) + F,

h the lever (1 for a translating follower, the arm length for an oscillating one), α
the pressure angle: N = (m·q″·ω² + k·(q + q0) + F)/(h·cos α). N > 0 presses the cam;
N < 0 pulls it: a spring-closed follower lifts off, a grooved cam carries the load on
its other flank.
"""

from __future__ import annotations

import numpy as np

from dyade.arrays import FloatArray


def contact_force(q, ddq, pressure_angle, speed: float, *, inertia: float, stiffness: float,
                  preload: float, load=0.0, lever: float = 1.0) -> FloatArray:
    """The contact force N [N] along the common normal at every cam angle.

    Parameters
    ----------
    q, ddq : ndarray, shape (n,)
        The follower's coordinate q [m or rad] and q″ = d²q/dθ² [per rad²].
    pressure_angle : ndarray, shape (n,)
        α [rad] (``CamGeometry.pressure_angle``).
    speed : float
        Cam speed ω [rad/s], constant.
    inertia, stiffness, preload, load
        m [kg or kg·m²], k [N/m or N·m/rad], q0 [m or rad], F [N or N·m] (a number or
        one per angle).
    lever : float
        h [m]: 1 for a translating follower, the arm length l for an oscillating one.
    """
    q, ddq, alpha = (np.asarray(x, dtype=np.float64) for x in (q, ddq, pressure_angle))
    along = inertia * ddq * speed ** 2 + stiffness * (q + preload) + np.asarray(load)
    return along / (lever * np.cos(alpha))


def contact_speeds(q, ddq, *, inertia: float, stiffness: float, preload: float,
                   load=0.0) -> tuple[float, float, int, int]:
    """The cam speeds [rad/s] between which a spring keeps the follower in contact.

    Contact needs m·q″·ω² + k·(q + q0) + F ≥ 0 at every angle. Where q″ < 0 (the
    follower decelerates away from the cam) that bounds ω from above,
    ω ≤ √((k·(q + q0) + F)/(−m·q″)): the lift-off speed is the least of these. Where the
    spring and load pull the follower off (k·(q + q0) + F < 0) with q″ > 0, only speed
    holds it on: ω ≥ √(−(k·(q + q0) + F)/(m·q″)).

    Returns
    -------
    lowest, highest : float
        Contact holds for lowest ≤ ω ≤ highest [rad/s] (highest = inf: it never lifts
        off); lowest > highest, or highest = 0 where the spring pulls it off while it
        decelerates: it can never keep contact.
    where_lowest, where_highest : int
        The index of the angle that sets each bound (-1 where none does).
    """
    q, ddq = np.asarray(q, dtype=np.float64), np.asarray(ddq, dtype=np.float64)
    static = stiffness * (q + preload) + np.asarray(load, dtype=np.float64) * np.ones_like(q)
    moving = inertia * ddq
    with np.errstate(divide="ignore", invalid="ignore"):  # q″ = 0: no bound from there
        ratio = np.where(moving != 0.0, static / np.where(moving != 0.0, -moving, 1.0), 0.0)
    upper = np.where(moving < 0.0, np.sqrt(np.maximum(ratio, 0.0)), np.inf)
    upper = np.where((moving == 0.0) & (static < 0.0), 0.0, upper)  # held off at any speed
    lower = np.where((moving > 0.0) & (static < 0.0), np.sqrt(np.maximum(-ratio, 0.0)), 0.0)
    k_high, k_low = int(np.argmin(upper)), int(np.argmax(lower))
    highest, lowest = float(upper[k_high]), float(lower[k_low])
    return (lowest, highest, k_low if lowest > 0.0 else -1,
            k_high if np.isfinite(highest) else -1)


def effective_modulus(young_1: float, poisson_1: float, young_2: float,
                      poisson_2: float) -> float:
    """E* [Pa] of two bodies in contact: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2."""
    return 1.0 / ((1.0 - poisson_1 ** 2) / young_1 + (1.0 - poisson_2 ** 2) / young_2)


def hertz_line_stress(force, radius_1, radius_2, width: float, modulus: float) -> FloatArray:
    """The Hertz contact pressure p0 [Pa] of two cylinders pressed together along a line.

    p0 = √(N·E*/(π·b·R)), 1/R = 1/ρ1 + 1/ρ2 (a concave radius negative, a flat face
    ρ = inf), half-width √(4·N·R/(π·b·E*)) (Johnson, Contact Mechanics, eq. (4.45)).
    NaN where N < 0 (no contact) or 1/R ≤ 0 (no Hertz contact: conforming or a cusp).

    Parameters
    ----------
    force : ndarray, shape (n,)
        N [N].
    radius_1, radius_2 : ndarray or float
        Radii of curvature [m], convex positive.
    width : float
        Contact length b [m] (the roller's or the cam's width, whichever is less).
    modulus : float
        E* [Pa] (``effective_modulus``).
    """
    force = np.asarray(force, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):  # a flat: 1/inf = 0; a cusp: NaN
        curvature = 1.0 / np.asarray(radius_1, dtype=np.float64) + 1.0 / np.asarray(
            radius_2, dtype=np.float64)
        valid = (force >= 0.0) & (curvature > 0.0)
        stress = np.sqrt(np.where(valid, force * modulus * curvature / (np.pi * width), np.nan))
    return stress


def drive_torque(contact, normal_fixed, force) -> FloatArray:
    """The torque M [N·m] that turns the cam against the contact force (no cam inertia):
    the follower pushes the cam with −N·n at the contact K, so M = N·(K × n) about O
    (counter-clockwise positive, the cam's sense of rotation).

    Parameters
    ----------
    contact : ndarray, shape (n, 2)
        The contact point K [m], fixed frame (``CamGeometry.contact``).
    normal_fixed : ndarray, shape (n, 2)
        The cam's outward unit normal at K, fixed frame.
    force : ndarray, shape (n,)
        N [N] (``contact_force``).
    """
    return np.asarray(force) * (contact[:, 0] * normal_fixed[:, 1] - contact[:, 1] * normal_fixed[:, 0])
