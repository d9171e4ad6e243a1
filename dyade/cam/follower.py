"""The cam as the chain's input: the follower (link 2) over the cam angle, in the
mechanism's frame (``dyade.model.cam.CamDrive``).

The linkage engine sweeps a cam-driven mechanism over the cam angle θ: link 2's
coordinate q (the travel s [m] of a translating follower along its guide, the lever
angle φ [rad] of an oscillating one) and its derivatives per radian of cam angle, q′ and
q″, come from the cam's motion profile here, so that q̇ = q′·θ̇ and q̈ = q″·θ̇² + q′·θ̈
(``dyade.linkage.kinematics.sweep``). The cam drives link 2 through the contact force N
along the common normal n at the contact K (both in the mechanism's frame, from
``dyade.cam.geometry``): its wrench about the world origin is N·(n, K × n).

This module imports nothing of the linkage engine (which imports it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray


@dataclass(frozen=True)
class FollowerMotion:
    """Link 2 driven by the cam at the cam angles ``theta`` (SI, mechanism frame)."""

    theta: FloatArray
    """cam angle θ [rad], shape (n,)"""
    lift: FloatArray
    """the profile's s [m] (translating) or swing [rad] (oscillating)"""
    q: FloatArray
    """link 2's coordinate: travel along its guide [m] or lever angle φ [rad]"""
    dq: FloatArray
    """q′ = dq/dθ [m/rad or -]"""
    ddq: FloatArray
    """q″ [m/rad² or 1/rad]"""
    contact: FloatArray
    """the contact point K [m], shape (n, 2)"""
    normal: FloatArray
    """the cam's outward unit normal at K (the line of the force on link 2), (n, 2)"""
    pressure_angle: FloatArray
    """α [rad] (``dyade.cam.geometry``)"""
    spring: FloatArray
    """the follower's own spring and load k·(s + s0) + F of the ``[follower]`` table,
    acting against the lift [N] (oscillating: [N·m] against the swing)"""
    sense: float
    """dq/ds: +1 translating; the lever's sense (−1 counter-clockwise cam, +1 clockwise)"""
    speed: FloatArray | float = 0.0
    """the cam's speed θ̇ [rad/s] at each angle (its sense of rotation; set by the sweep)"""
    acceleration: FloatArray | float = 0.0
    """θ̈ [rad/s²] (0 at a constant speed)"""


def curves(cam, theta: FloatArray):
    """The cam's geometry (``dyade.cam.geometry.CamGeometry``) at ``theta`` [rad] and s,
    s′, s″, s‴ of its profile (SI): the one place that picks the follower's curves."""
    from dyade.cam import geometry
    from dyade.motion.profile import evaluate

    m = evaluate(cam.profile, theta)
    s, v, a = m.s, m.v, m.a
    if cam.follower == "translating-roller":
        geo = geometry.translating_roller(theta, s, v, a, base_radius=cam.base_radius,
                                          roller_radius=cam.roller_radius, offset=cam.offset,
                                          clockwise=cam.clockwise)
    elif cam.follower == "oscillating-roller":
        geo = geometry.oscillating_roller(theta, s, v, a, base_radius=cam.base_radius,
                                          roller_radius=cam.roller_radius,
                                          pivot_distance=cam.pivot_distance,
                                          arm_length=cam.arm_length, clockwise=cam.clockwise)
    else:
        geo = geometry.translating_flat(theta, s, v, a, base_radius=cam.base_radius,
                                        offset=cam.offset, clockwise=cam.clockwise)
    return geo, (s, v, a, m.j)


def follower_motion(drive, theta: FloatArray) -> FollowerMotion:
    """Link 2 over the cam angles ``theta`` [rad].

    Parameters
    ----------
    drive : dyade.model.cam.CamDrive
        The cam, its centre and frame in the mechanism.
    theta : ndarray, shape (n,)
        Cam angle θ [rad], in the cam's sense of rotation.
    """
    cam = drive.cam
    theta = np.asarray(theta, dtype=np.float64)
    geo, (s, v, a, _) = curves(cam, theta)
    c, sn = math.cos(drive.angle), math.sin(drive.angle)
    turn = np.array([[c, -sn], [sn, c]])
    contact = geo.contact @ turn.T + np.asarray(drive.centre, dtype=np.float64)
    normal = geo.contact_normal @ turn.T
    if drive.sliding:
        sense, q = 1.0, s
    else:  # the lever's angle: β + the arm's direction in the cam's fixed frame
        pivot = np.array([-cam.pivot_distance if cam.clockwise else cam.pivot_distance, 0.0])
        arm = geo.centre - pivot
        sense = 1.0 if cam.clockwise else -1.0  # the arm angle is ψ (cw) or π − ψ (ccw)
        q = drive.angle + np.arctan2(arm[:, 1], arm[:, 0])
    spring = cam.stiffness * (s + cam.preload) + cam.load
    return FollowerMotion(theta, s, q, sense * v, sense * a, contact, normal,
                          geo.pressure_angle, spring, sense)
