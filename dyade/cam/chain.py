"""A cam–linkage chain: a disc cam whose follower is the input link (link 2) of a dyad
chain, assembled and solved by the linkage engine itself.

A mechanism file's ``[cam]`` makes link 2 the follower (``dyade.model.cam.CamDrive``):
a translating follower slides along its guide, an oscillating one is the lever about
its pivot. A cam file's ``[chain]`` names a mechanism whose crank is an oscillating
follower's lever, placed by ``placement``; ``drive_of`` turns it into the same
cam-driven mechanism. The engine sweeps it over the cam angle θ (``kinematics.sweep``:
link 2's q, q̇ = q′·ω, q̈ = q″·ω² from the cam's profile, ``dyade.cam.follower``) and
finds the load −S₁₂·Q₂ that link 2 needs (``kinetostatics.solve``: inertia, gravity,
loads, springs of every link, the follower's own spring k·(s + s0) + F against its lift
or swing). The cam supplies it through the contact force N along the common normal n
at the contact K,

    N·S₁₂·(n, K × n) = −S₁₂·Q₂   (the lever: N·((K − A) × n); the slider: N·(n · d)),

and the cam shaft's drive torque is M = −S₁₂·Q₂·q′ in its sense of rotation: its
power M·ω equals the power the chain takes.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
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
    """``dyade.linkage.kinetostatics.Forces`` of the cam-driven chain (its
    ``drive_torque`` is the cam shaft's, ``input_load`` the lever's)"""
    lever_torque: FloatArray
    """the load the cam must put on link 2 along its twist: the torque on the lever
    [N·m], mechanism frame, CCW positive (a translating follower: the force along its
    guide [N])"""
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


def drive_of(cam, mechanism):
    """The mechanism the cam drives, with its ``CamDrive`` (``dyade.model.cam``): a
    mechanism file's ``[cam]`` has it already; a cam file's ``[chain]`` places the cam by
    ``placement`` (its follower's own inertia J about the pivot joins the lever's)."""
    from dyade.model.cam import CamDrive
    from dyade.model.mechanism import CRANK

    if mechanism.cam is not None:
        return mechanism
    centre, beta = placement(cam, mechanism)
    links = dict(mechanism.links)
    lever = links[CRANK]
    links[CRANK] = dataclasses.replace(lever, inertia=lever.inertia + cam.mass)
    own = dataclasses.replace(cam, chain=None, chain_centre=None, mass=0.0)
    return dataclasses.replace(mechanism, links=links,
                               cam=CamDrive(own, tuple(float(v) for v in centre), beta))


def solve(cam, mechanism, geometry: CamGeometry, s, v, a, speed: float) -> ChainResult:
    """The chain driven by the cam at the cam angles of ``geometry``: the linkage
    engine's own sweep and kinetostatics of the cam-driven mechanism
    (``dyade.linkage.kinematics.sweep`` over the cam angle, ``Forces.contact_force`` and
    the cam shaft's ``drive_torque``).

    Parameters
    ----------
    cam : dyade.model.cam.Cam
        The cam (a cam file's, ``chain_centre`` set, or a mechanism file's).
    mechanism : dyade.model.mechanism.Mechanism
        The chain; link 2 is the follower (a cam file's chain: its crank is the lever).
    geometry : CamGeometry
        The cam's geometry at the cam angles (``dyade.cam.checks.curves``).
    s, v, a : ndarray, shape (n,)
        The follower's s and s′, s″ per radian of cam angle (kept for the callers; the
        engine evaluates the profile itself).
    speed : float
        Cam speed ω [rad/s].
    """
    from dyade.linkage import kinematics, kinetostatics

    driven = drive_of(cam, mechanism)
    driven = dataclasses.replace(driven, crank=dataclasses.replace(driven.crank, speed=speed))
    kin = kinematics.sweep(driven, geometry.theta)
    chain = kinetostatics.solve(driven, kin)
    follower = kin.follower
    return ChainResult(follower.q, follower.dq * speed, follower.ddq * speed ** 2, kin, chain,
                       chain.input_load, chain.contact_force, chain.drive_torque,
                       chain.valid & np.isfinite(chain.contact_force))
