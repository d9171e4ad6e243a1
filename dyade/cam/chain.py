"""A cam–linkage chain: a disc cam whose oscillating roller follower is the input link
(link 2, the "crank") of a dyad chain, assembled and solved by the linkage engine.

The chain is a mechanism (``dyade.model.mechanism.Mechanism``) whose crank turns about
the follower's pivot A with the arm length l as its length: the lever. The cam turns at
a constant speed ω about its centre O (a point of the mechanism's frame); the lever's
angle φ(θ), its speed φ̇ = φ′·ω and acceleration φ̈ = φ″·ω² follow from the cam's motion
profile, and the linkage engine sweeps the chain with them (``kinematics.sweep`` with a
crank speed and acceleration per position) and finds the torque M_d the lever needs
(``kinetostatics.solve``: inertia, gravity, loads, springs of every link of the chain,
the lever's own included). The cam supplies it through the contact force N along the
common normal n at the contact K:

    N·((K − A) × n) = M_d + (k·(s + s0) + F)·dφ/dψ,

the second term the follower's own torsion spring and load of the cam file (they act
against the swing ψ); the cam's drive torque is N·(K × n) about O, in its sense of
rotation. Its power M·ω equals the power the chain takes, M_d·φ̇ plus the spring's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.cam import forces as cam_forces
from dyade.cam.geometry import CamGeometry

PLACE_RTOL = 1e-9  # [-] the lever's pivot and length agree with the cam's to this share


@dataclass(frozen=True)
class ChainResult:
    """A cam–linkage chain over the cam angles (SI)."""

    lever_angle: FloatArray
    """the lever's (crank's) angle φ in the mechanism's frame [rad], shape (n,)"""
    lever_speed: FloatArray
    """φ̇ [rad/s]"""
    lever_acceleration: FloatArray
    """φ̈ [rad/s²]"""
    kinematics: object
    """``dyade.linkage.kinematics.Kinematics`` of the chain"""
    forces: object
    """``dyade.linkage.kinetostatics.Forces`` of the chain (its ``drive_torque`` is the
    torque M_d on the lever)"""
    lever_torque: FloatArray
    """the torque the cam must put on the lever [N·m], mechanism frame, CCW positive"""
    contact_force: FloatArray
    """N [N] along the common normal (negative: pulled; a spring-closed follower lifts
    off)"""
    drive_torque: FloatArray
    """the cam shaft's torque [N·m] in its sense of rotation"""
    valid: FloatArray
    """bool: the chain closes and is not singular here"""


def placement(cam, mechanism) -> tuple[FloatArray, float]:
    """The cam centre O [m] in the mechanism's frame and the angle β [rad] of the cam's
    fixed frame there: the mechanism's crank pivot must lie at the cam's pivot distance
    from O and the crank be as long as the arm.

    The cam's fixed frame (``dyade.cam.geometry``) has the pivot at (a, 0) (a clockwise
    cam: (−a, 0)); β turns it onto the line from O to the mechanism's crank pivot.
    """
    centre = np.asarray(cam.chain_centre, dtype=np.float64)
    pivot = np.asarray(mechanism.crank.pivot, dtype=np.float64)
    towards = pivot - centre if not cam.clockwise else centre - pivot
    distance = float(np.hypot(*towards))
    if abs(distance - cam.pivot_distance) > PLACE_RTOL * cam.pivot_distance:
        raise ValueError(f"the crank pivot lies {distance:.9g} m from the cam centre, the "
                         f"follower's pivot_distance is {cam.pivot_distance:.9g} m")
    if abs(mechanism.crank.length - cam.arm_length) > PLACE_RTOL * cam.arm_length:
        raise ValueError(f"the crank is {mechanism.crank.length:.9g} m long, the follower's "
                         f"arm_length is {cam.arm_length:.9g} m")
    return centre, math.atan2(towards[1], towards[0])


def solve(cam, mechanism, geometry: CamGeometry, s, v, a, speed: float) -> ChainResult:
    """The chain driven by the cam at the cam angles of ``geometry``.

    Parameters
    ----------
    cam : dyade.model.cam.Cam
        An oscillating roller follower's cam (``chain_centre`` set).
    mechanism : dyade.model.mechanism.Mechanism
        The chain; its crank (link 2) is the lever.
    geometry : CamGeometry
        ``dyade.cam.geometry.oscillating_roller`` at the cam angles.
    s, v, a : ndarray, shape (n,)
        The swing s [rad] and s′, s″ per radian of cam angle.
    speed : float
        Cam speed ω [rad/s].
    """
    from dyade.linkage import kinematics, kinetostatics

    centre, beta = placement(cam, mechanism)
    c, sn = math.cos(beta), math.sin(beta)
    turn = np.array([[c, -sn], [sn, c]])
    pivot_fixed = np.array([-cam.pivot_distance if cam.clockwise else cam.pivot_distance, 0.0])
    arm = geometry.centre - pivot_fixed
    sense = 1.0 if cam.clockwise else -1.0  # dφ/dψ: the arm angle is ψ (cw) or π − ψ (ccw)
    phi = beta + np.arctan2(arm[:, 1], arm[:, 0])
    phi_speed = sense * v * speed
    phi_acceleration = sense * a * speed ** 2
    kin = kinematics.sweep(mechanism, phi, phi_speed, phi_acceleration)
    chain = kinetostatics.solve(mechanism, kin)
    spring = cam.stiffness * (s + cam.preload) + cam.load
    needed = chain.drive_torque + cam.mass * phi_acceleration + spring * sense
    contact = geometry.contact @ turn.T + centre
    normal = geometry.contact_normal @ turn.T
    lever = contact - np.asarray(mechanism.crank.pivot)
    arm_of_force = lever[:, 0] * normal[:, 1] - lever[:, 1] * normal[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):  # the normal through the pivot
        force = needed / arm_of_force
    torque = cam_forces.drive_torque(geometry.contact, geometry.contact_normal, force)
    if cam.clockwise:
        torque = -torque
    return ChainResult(phi, phi_speed, phi_acceleration, kin, chain, needed, force, torque,
                       chain.valid & np.isfinite(force))
