"""The linkage reduced to its crank: moment of inertia, its slope and the load torque.

With the crank angle φ as the generalised coordinate every velocity is proportional to
φ̇: v_S = v̂_S(φ)·φ̇, ω = ω̂(φ)·φ̇ (Dresig & Holzweißig, *Maschinendynamik*). Then

    J(φ)  = Σ_k m_k·|v̂_Sk|² + J_Sk·ω̂_k²                       reduced moment of inertia,
    J′(φ) = dJ/dφ = 2·Σ_k m_k·v̂_Sk·â_Sk + J_Sk·ω̂_k·α̂_k           its slope,
    M_L(φ) = P_loads/φ̇                                          reduced load torque,

â = a/Ω², α̂ = α/Ω² from the kinematics at a constant speed Ω, and P_loads the power
of gravity, the applied loads and the springs (positive where they drive the machine).
The kinetic energy is ½·J·φ̇², and at constant speed without friction the drive torque
is M_drive = ½·J′·Ω² − M_L: its power feeds the kinetic energy and the loads.
The crank's own inertia is included, and with it a flywheel of the ``[drive]`` table
(a cam-driven mechanism: the flywheel on the cam shaft, added to J; φ is the cam angle).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage import kinematics
from dyade.linkage.kinetostatics import add_loads_and_springs
from dyade.model.mechanism import CRANK, FRAME, Mechanism


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Reduced:
    """The linkage reduced to the crank angle, per position."""

    inertia: FloatArray
    """(n,) J [kg·m²]"""
    slope: FloatArray
    """(n,) J′ = dJ/dφ [kg·m²/rad]"""
    load: FloatArray
    """(n,) M_L [N·m], counter-clockwise positive"""


def reduced(mechanism: Mechanism, kin: kinematics.Kinematics) -> Reduced:
    """J, J′ and M_L at the positions of ``kin`` (module docstring).

    At a constant crank speed the velocities of ``kin`` give them directly; otherwise the
    kinematics is run again at unit crank speed (they depend on the position only).

    >>> import dyade
    >>> from dyade.linkage import kinematics
    >>> slider_crank = dyade.read_mechanism("mechanisms/slider-crank.toml")
    >>> machine = reduced(slider_crank, kinematics.sweep(slider_crank, [0.0, 1.5707963]))
    >>> [round(float(j), 8) for j in machine.inertia]          # [kg·m²]
    [0.00032565, 0.00176]
    """
    motion = kin.motion
    speed = motion.omega[:, CRANK]
    constant = (mechanism.cam is None  # (a cam's speed is not link 2's)
                and speed.size > 0 and speed[0] != 0.0 and np.all(speed == speed[0])
                and not np.any(motion.alpha[:, CRANK]))
    if constant:
        omega = float(speed[0])
    else:
        kin = kinematics.sweep(mechanism, kin.crank_angle, crank_speed=1.0)
        motion, omega = kin.motion, 1.0
    n = kin.crank_angle.shape[0]
    energy, rate = np.zeros(n), np.zeros(n)
    external = np.zeros((mechanism.max_link + 1, 3, n))
    gravity = np.asarray(mechanism.gravity)
    # each term computed once (the centre's position from point_motion serves the
    # weight's moment, J_S·ω both sums), with the operations of add_force: the same bits
    for number, link in mechanism.links.items():
        if number == FRAME or not link.has_mass:
            continue
        w, a = motion.omega[:, number], motion.alpha[:, number]
        if np.any(link.mass):  # (a number, or one per position: variants of a study)
            x, y, vx, vy, ax, ay = motion.point_motion(number, link.centre)
            energy += link.mass * (vx * vx + vy * vy)
            rate += link.mass * (vx * ax + vy * ay)
            if gravity.any():  # the weight m·g at the centre
                weight_x, weight_y = link.mass * gravity[0], link.mass * gravity[1]
                fx, fy, moment = external[number]
                fx += weight_x
                fy += weight_y
                moment += x * weight_y - y * weight_x
        if np.any(link.inertia):
            spin = link.inertia * w
            energy += spin * w
            rate += spin * a
    add_loads_and_springs(external, mechanism, kin)
    power = np.zeros(n)
    origin, velocity, spins = motion.origin.T, motion.velocity.T, motion.omega.T  # link-major
    for number in mechanism.moving_links:
        fx, fy, moment = external[number]
        (x, y), (vx, vy), w = origin[:, number], velocity[:, number], spins[number]
        power += fx * (vx + w * y) + fy * (vy - w * x) + moment * w  # wrench · twist
    inertia = energy / omega ** 2
    if mechanism.cam is not None and mechanism.drive is not None:  # on the cam shaft
        inertia = inertia + mechanism.drive.flywheel_inertia
    return Reduced(inertia, 2.0 * rate / omega ** 3, power / omega)
