"""A cam's checks over its turn and the profile to manufacture, from a ``Cam`` model:
the follower's motion from its profile, the curves, the pressure angle against its
limit, the curvature and undercut, the contact force, the speeds that keep contact, the
Hertz stress, the drive torque, the smallest base circle, the exported points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.cam import export, forces, geometry
from dyade.cam.follower import curves


@dataclass(frozen=True)
class Manufacture:
    """A curve to manufacture: points of the closed curve in the cam's frame at the
    chord tolerance."""

    name: str
    """"working" (the cam's surface; a groove's inner flank), "outer" (a groove's outer
    flank) or "cutter" (the cutter centre's path along the working curve)"""
    points: FloatArray
    """[m], shape (k, 2), cam frame, in the order of the cam angle"""
    theta: FloatArray
    """cam angle [rad] of each point, shape (k,)"""
    tolerance: float
    """the chord tolerance [m]: every point of the curve lies this close to the polygon"""
    deviation: float
    """the largest distance [m] of the densely sampled curve from the polygon"""


@dataclass(frozen=True)
class CamResult:
    """The checks of a cam over its turn (SI)."""

    cam: object
    """the ``dyade.model.cam.Cam``"""
    geometry: geometry.CamGeometry
    s: FloatArray
    """follower lift [m] or swing [rad], shape (n,)"""
    v: FloatArray
    """ds/dθ [m/rad or -]"""
    a: FloatArray
    """d²s/dθ² [m/rad² or 1/rad]"""
    j: FloatArray
    """d³s/dθ³ [m/rad³ or 1/rad²]"""
    contact_force: FloatArray
    """N [N] along the common normal (spring closure: NaN where the follower has lifted
    off; groove: negative on the other flank)"""
    lifted: FloatArray
    """bool: the follower has lifted off here (spring closure, N < 0)"""
    hertz_stress: FloatArray
    """p0 [Pa] (NaN where not given: no width, no contact)"""
    drive_torque: FloatArray
    """the torque turning the cam against the follower [N·m], in the cam's sense of
    rotation"""
    contact_speeds: tuple[float, float]
    """(lowest, highest) cam speeds [rad/s] that keep contact (spring closure)"""
    contact_speed_angles: tuple[float | None, float | None]
    """the cam angles [rad] that set them (None where none does)"""
    smallest_base_radius: float | None
    """the smallest r_b [m] for the pressure-angle limit (roller followers; None where no
    pitch circle the oscillating follower's arm reaches meets it) or for a cusp-free
    flat-faced cam; 0 where any base circle does"""
    manufacture: tuple[Manufacture, ...]
    profile_notes: tuple[str, ...]
    """the motion profile's own notes (allowed acceleration jumps)"""
    chain: object = None
    """``dyade.cam.chain.ChainResult`` of the linkage the follower drives (None: none)"""
    guide: object = None
    """``dyade.cam.guide.Guide`` of a translating follower with guide friction (None:
    none)"""
    jammed: FloatArray | None = None
    """bool, shape (n,): the follower jams in its guide here (None: no guide friction)"""
    outer_flank: FloatArray | None = None
    """bool, shape (n,): a grooved cam's outer flank carries the load here (N < 0: the
    outer wall pushes the roller towards the cam centre); None: spring closure"""


def manufacture(cam, coarse: geometry.CamGeometry) -> tuple[Manufacture, ...]:
    """The working curve (and the cutter's path) at the cam's chord tolerance."""
    tolerance = cam.chord_tolerance
    length = float(np.sum(np.hypot(*np.diff(coarse.working, axis=0).T)))
    radius = np.abs(coarse.working_curvature_radius)
    radius_min = float(np.nanmin(radius)) if np.isfinite(radius).any() else tolerance
    n = export.dense_count(length, radius_min, tolerance)
    theta = np.linspace(0.0, 2.0 * math.pi, n + 1)[:-1]
    dense, _ = curves(cam, theta)
    wanted = [("working", dense.working, dense.working_curvature_radius)]
    if cam.closure == "groove" and dense.pitch is not None:
        wanted.append(("outer", *geometry.outer_wall(dense)))
    if cam.cutter_radius is not None:
        wanted.append(("cutter", export.offset_curve(dense.working, dense.normal,
                                                     cam.cutter_radius),
                       dense.working_curvature_radius + cam.cutter_radius))
    out = []
    for name, points, rho in wanted:
        keep = export.chord_points(points, rho, tolerance)
        deviation = float(export.deviations(points, keep).max())
        out.append(Manufacture(name, points[keep], theta[keep], tolerance, deviation))
    return tuple(out)


def check(cam, step: float = math.radians(1.0), make: bool = True) -> CamResult:
    """The cam's checks at the cam angles 0, step, … below one turn.

    Parameters
    ----------
    cam : dyade.model.cam.Cam
    step : float
        Cam-angle step [rad] of the checks.
    make : bool
        Compute the profile to manufacture (a dense sampling at the chord tolerance).

    Returns
    -------
    CamResult

    Raises
    ------
    InputError
        The profile jumps in position or velocity (``dyade.motion.profile.check``).
    """
    from dyade.motion.profile import check as check_profile

    notes = check_profile(cam.profile)
    theta = np.arange(0.0, 2.0 * math.pi - 1e-12, step)
    geo, (s, v, a, j) = curves(cam, theta)
    omega = cam.speed
    along = dict(inertia=cam.mass, stiffness=cam.stiffness, preload=cam.preload, load=cam.load)
    driven = None
    guided = jammed = None
    if cam.guide_friction > 0.0:
        from dyade.cam import guide

        guided = guide.guide(geo, s, v, friction=cam.guide_friction, length=cam.guide_length,
                             overhang=cam.guide_overhang)
        pushed = cam.mass * a * omega ** 2 + cam.stiffness * (s + cam.preload) + cam.load
        force, jammed = guide.contact_force(
            pushed, np.sum(geo.contact_normal * geo.direction, axis=1), guided,
            cam.guide_friction)
        lowest, highest, k_low, k_high = forces.contact_speeds(s, a, **along)
    elif cam.chain is None:
        force = forces.contact_force(s, a, geo.pressure_angle, omega, lever=cam.lever, **along)
        lowest, highest, k_low, k_high = forces.contact_speeds(s, a, **along)
    else:
        from dyade.cam import chain

        driven = chain.solve(cam, cam.chain, geo, s, v, a, omega)
        force = np.where(driven.valid, driven.contact_force, np.nan)
        # N = N0 + ω²·N2: the chain at rest gives N0 (gravity, loads, springs), the rest
        # grows with the square of the speed
        at_rest = chain.solve(cam, cam.chain, geo, s, v, a, 0.0).contact_force
        growth = (driven.contact_force - at_rest) / omega ** 2 if omega > 0 else 0.0 * s
        lowest, highest, k_low, k_high = forces.contact_speeds(
            np.zeros_like(s), np.where(driven.valid, growth, 0.0), inertia=1.0, stiffness=0.0,
            preload=0.0, load=np.where(driven.valid, at_rest, 1.0))
    # with guide friction N·(n_y ∓ μ·p) keeps the sign of the load where the follower
    # moves at all: contact is lost where the friction-free balance loses it
    lifted = (force < 0.0) if cam.closure == "spring" else np.zeros(theta.size, dtype=bool)
    force = np.where(lifted, np.nan, force)
    torque = (forces.drive_torque(geo.contact, geo.contact_normal, force) if driven is None
              else np.where(np.isfinite(force), driven.drive_torque, np.nan))
    if cam.clockwise and driven is None:  # the mirror image: the torque in the cam's own sense
        torque = -torque
    outer = None
    radius = geo.working_curvature_radius
    if cam.closure == "groove":
        outer = force < 0.0  # the outer flank pushes the roller towards the cam centre
        if geo.pitch is not None:  # the roller inside the outer wall: concave there
            radius = np.where(outer, -(geo.pitch_curvature_radius + geo.roller_radius), radius)
    stress = np.full(theta.size, np.nan)
    if cam.width is not None:
        modulus = forces.effective_modulus(*cam.cam_material, *cam.follower_material)
        stress = forces.hertz_line_stress(np.abs(force), radius, geo.roller_radius or np.inf,
                                          cam.width, modulus)
    if cam.follower == "translating-roller":
        offset = -cam.offset if cam.clockwise else cam.offset
        smallest = max(geometry.smallest_pitch_radius(s, v, cam.limit, offset)
                       - cam.roller_radius, 0.0)  # 0: any base circle meets the limit
    elif cam.follower == "translating-flat":
        smallest = max(geometry.smallest_flat_base_radius(s, a), 0.0)
    else:
        smallest = geometry.smallest_oscillating_base_radius(
            s, v, cam.limit, roller_radius=cam.roller_radius,
            pivot_distance=cam.pivot_distance, arm_length=cam.arm_length)
    made = manufacture(cam, geo) if make else ()
    return CamResult(cam, geo, s, v, a, j, force, lifted, stress, torque, (lowest, highest),
                     (float(theta[k_low]) if k_low >= 0 else None,
                      float(theta[k_high]) if k_high >= 0 else None),
                     smallest, made, tuple(notes), driven, guided, jammed, outer)
