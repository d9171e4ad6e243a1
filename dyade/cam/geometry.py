"""The geometry of a disc cam from its follower's motion: pitch and working curves in
closed form, pressure angle, radii of curvature, undercut, the smallest base circle.

Frame (docs/guide/cams.md): the cam turns counter-clockwise about the origin O; its
angle θ [rad] grows counter-clockwise. A translating follower moves along the line
x = e (``offset``) in the direction +y, away from O; an oscillating follower turns about
the pivot A = (a, 0) (``pivot_distance``), its arm of length l (``arm_length``) making
the angle ψ = ψ0 + s with the line A→O, the roller rising (away from O) as s grows.
A curve "of the cam" is given in the cam's own frame: the fixed frame turned by θ. The
roller centre's path seen from the cam is the pitch curve; the working curve (the cam's
surface) is the pitch curve moved inwards by the roller radius along its normal.

The pressure angle α is the angle from the follower's direction of motion to the common
normal at the contact (the line of the contact force), positive counter-clockwise
(``atan2(f × n, f · n)``). For a translating roller follower it is
tan α = (s′ − e) / (s + √(r_p² − e²)); a clockwise cam is the mirror image in the y axis
(e -> -e, every curve with x -> -x, α as for the mirror).

The radius of curvature is positive where the curve is convex (a circle of radius R has
+R). Undercut: the working curve of a roller follower folds over itself (a cusp) where
the pitch curve is convex with a radius below the roller's; a flat face cannot follow a
cam whose working radius of curvature r_b + s + s″ falls to zero or below.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray

FOLLOWERS = ("translating-roller", "oscillating-roller", "translating-flat")
"""the follower kinds"""


@dataclass(frozen=True)
class CamGeometry:
    """The curves and checks of a disc cam at the cam angles ``theta``."""

    follower: str
    """one of ``FOLLOWERS``"""
    theta: FloatArray
    """cam angle θ [rad], shape (n,)"""
    pitch: FloatArray | None
    """pitch curve (roller centre seen from the cam) [m], shape (n, 2), cam frame; None
    for a flat face"""
    working: FloatArray
    """working curve (the cam's surface) [m], shape (n, 2), cam frame"""
    normal: FloatArray
    """outward unit normal of the cam at the contact, shape (n, 2), cam frame"""
    centre: FloatArray
    """the roller centre (flat face: the face's point on its line of motion) [m], shape
    (n, 2), fixed frame"""
    contact: FloatArray
    """the contact point [m], shape (n, 2), fixed frame"""
    contact_normal: FloatArray
    """the cam's outward unit normal at the contact (the line of the force on the
    follower), shape (n, 2), fixed frame"""
    direction: FloatArray
    """the follower's direction of motion at ``centre`` (unit), shape (n, 2), fixed
    frame"""
    pressure_angle: FloatArray
    """pressure angle α [rad], shape (n,)"""
    pitch_curvature_radius: FloatArray
    """radius of curvature of the pitch curve [m], convex positive, shape (n,); NaN for a
    flat face"""
    working_curvature_radius: FloatArray
    """radius of curvature of the working curve [m], convex positive, shape (n,)"""
    undercut: FloatArray
    """bool, shape (n,): the working curve folds (undercut) at this angle"""
    base_radius: float
    """base circle radius r_b [m] (the working curve's radius at s = 0)"""
    roller_radius: float = 0.0
    """roller radius r_r [m] (0 for a flat face)"""
    arm: float = 1.0
    """the follower's lever [m]: 1 for a translating follower (its force is along its
    motion), the arm length l of an oscillating one (its moment is N·l·cos α)"""
    clockwise: bool = False
    """the cam turns clockwise: every curve is the mirror image (x -> -x)"""


def _perp(v: FloatArray) -> FloatArray:
    """v turned by +90° (J·v), shape (n, 2)."""
    return np.stack((-v[:, 1], v[:, 0]), axis=1)


def _cross(a: FloatArray, b: FloatArray) -> FloatArray:
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def to_cam(theta: FloatArray, v: FloatArray) -> FloatArray:
    """Vectors of the fixed frame seen from the cam at angle θ: R(−θ)·v, shape (n, 2)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack((c * v[:, 0] + s * v[:, 1], -s * v[:, 0] + c * v[:, 1]), axis=1)


def _mirror(v: FloatArray | None) -> FloatArray | None:
    return None if v is None else v * np.array([-1.0, 1.0])


def _roller(follower: str, theta: FloatArray, centre: FloatArray, d_centre: FloatArray,
            dd_centre: FloatArray, direction: FloatArray, base_radius: float,
            roller_radius: float, arm: float, clockwise: bool) -> CamGeometry:
    """A roller follower's cam from its centre's path C(θ) in the fixed frame and its
    derivatives C′, C″ per radian of cam angle.

    Seen from the cam, P(θ) = R(−θ)·C, so P′ = R(−θ)·T with T = C′ − J·C (the centre's
    velocity relative to the cam) and P″ = R(−θ)·(C″ − 2·J·C′ − C); the outward normal
    is J·T/|T| (the cam turns counter-clockwise, so the contact runs clockwise round it).
    """
    tangent = d_centre - _perp(centre)
    bend = dd_centre - 2.0 * _perp(d_centre) - centre
    length = np.hypot(tangent[:, 0], tangent[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):  # a cusp of the pitch curve: NaN
        normal = _perp(tangent) / length[:, None]
        rho = -length ** 3 / _cross(tangent, bend)
    contact = centre - roller_radius * normal
    alpha = np.arctan2(_cross(direction, normal), np.einsum("ij,ij->i", direction, normal))
    undercut = (rho > 0.0) & (rho < roller_radius)
    pitch, working, normal_cam = to_cam(theta, centre), to_cam(theta, contact), to_cam(theta, normal)
    if clockwise:
        pitch, working, normal_cam = _mirror(pitch), _mirror(working), _mirror(normal_cam)
        centre, contact, direction = _mirror(centre), _mirror(contact), _mirror(direction)
        normal = _mirror(normal)
    return CamGeometry(follower, theta, pitch, working, normal_cam, centre, contact, normal,
                       direction,
                       alpha, rho, rho - roller_radius, undercut, base_radius, roller_radius,
                       arm, clockwise)


def translating_roller(theta, s, ds, dds, *, base_radius: float, roller_radius: float,
                       offset: float = 0.0, clockwise: bool = False) -> CamGeometry:
    """The cam of a translating roller follower with offset.

    Parameters
    ----------
    theta : ndarray, shape (n,)
        Cam angle θ [rad].
    s, ds, dds : ndarray, shape (n,)
        Follower lift s [m] and its derivatives s′ = ds/dθ [m/rad], s″ [m/rad²].
    base_radius : float
        Base circle radius r_b [m] (of the working curve; the pitch circle is
        r_p = r_b + r_r).
    roller_radius : float
        Roller radius r_r [m].
    offset : float
        Offset e [m] of the line of motion (x = e) from the cam centre.
    clockwise : bool
        The cam turns clockwise (the mirror image: e -> -e, curves x -> -x).

    Returns
    -------
    CamGeometry
        With tan α = (s′ − e)/(s + √(r_p² − e²)) (e -> -e for a clockwise cam).
    """
    theta, s, ds, dds = (np.asarray(x, dtype=np.float64) for x in (theta, s, ds, dds))
    e = -offset if clockwise else offset
    pitch_radius = base_radius + roller_radius
    if not pitch_radius > abs(e):
        raise ValueError(f"the pitch circle r_b + r_r = {pitch_radius:g} m must exceed the "
                         f"offset |e| = {abs(e):g} m")
    d = np.sqrt(pitch_radius ** 2 - e ** 2)
    zero = np.zeros_like(s)
    centre = np.stack((np.full_like(s, e), d + s), axis=1)
    d_centre = np.stack((zero, ds), axis=1)
    dd_centre = np.stack((zero, dds), axis=1)
    direction = np.stack((zero, np.ones_like(s)), axis=1)
    return _roller("translating-roller", theta, centre, d_centre, dd_centre, direction,
                   base_radius, roller_radius, 1.0, clockwise)


def outer_wall(geo: CamGeometry) -> tuple[FloatArray, FloatArray]:
    """The groove's outer flank of a roller follower's grooved cam (form closure): the
    pitch curve moved outwards by the roller radius along the cam's normal, and its
    radius of curvature ρ_p + r_r [m] (convex positive as a curve about the cam centre;
    the roller touches it from inside, where it is concave).

    Returns
    -------
    points : ndarray, shape (n, 2)
        [m], cam frame (the working curve, ``geo.working``, is the inner flank).
    radius : ndarray, shape (n,)
        ρ_p + r_r [m].
    """
    if geo.pitch is None:
        raise ValueError("a flat-faced follower has no groove: the outer flank belongs to a "
                         "roller follower")
    return geo.pitch + geo.roller_radius * geo.normal, geo.pitch_curvature_radius + geo.roller_radius


def rest_angle(pitch_radius: float, pivot_distance: float, arm_length: float) -> float:
    """ψ0 [rad]: the arm's angle to the line A→O with the roller on the pitch circle,
    cos ψ0 = (a² + l² − r_p²)/(2·a·l)."""
    cos = (pivot_distance ** 2 + arm_length ** 2 - pitch_radius ** 2) / (
        2.0 * pivot_distance * arm_length)
    if not -1.0 < cos < 1.0:
        raise ValueError(f"the roller cannot reach the pitch circle r_p = {pitch_radius:g} m "
                         f"from the pivot: |a − l| < r_p < a + l is needed (a = "
                         f"{pivot_distance:g} m, l = {arm_length:g} m)")
    return float(np.arccos(cos))


def oscillating_roller(theta, s, ds, dds, *, base_radius: float, roller_radius: float,
                       pivot_distance: float, arm_length: float,
                       clockwise: bool = False) -> CamGeometry:
    """The cam of an oscillating roller follower.

    Parameters
    ----------
    theta : ndarray, shape (n,)
        Cam angle θ [rad].
    s, ds, dds : ndarray, shape (n,)
        The arm's swing s [rad] from rest (ψ = ψ0 + s) and its derivatives s′ [-], s″
        [1/rad].
    base_radius, roller_radius : float
        r_b and r_r [m]; ψ0 puts the roller on the pitch circle r_p = r_b + r_r at s = 0.
    pivot_distance : float
        Distance a = |OA| [m] from the cam centre to the pivot A = (a, 0).
    arm_length : float
        Arm length l = |AC| [m], pivot to roller centre.
    clockwise : bool
        The cam turns clockwise (the mirror image: the pivot at (−a, 0)).

    Returns
    -------
    CamGeometry
        The pressure angle is measured from the roller centre's velocity (normal to the
        arm); by the instant centre of cam and arm on the line OA,
        tan α = (l·(1 + s′) − a·cos ψ)/(a·sin ψ) (Rothbart, ch. 6).
    """
    theta, s, ds, dds = (np.asarray(x, dtype=np.float64) for x in (theta, s, ds, dds))
    a, length = pivot_distance, arm_length
    psi = rest_angle(base_radius + roller_radius, a, length) + s
    c, sn = np.cos(psi), np.sin(psi)
    centre = np.stack((a - length * c, length * sn), axis=1)
    direction = np.stack((sn, c), axis=1)
    d_centre = length * ds[:, None] * direction
    dd_centre = length * (dds[:, None] * direction + (ds ** 2)[:, None] * np.stack((c, -sn), axis=1))
    return _roller("oscillating-roller", theta, centre, d_centre, dd_centre, direction,
                   base_radius, roller_radius, length, clockwise)


def translating_flat(theta, s, ds, dds, *, base_radius: float, offset: float = 0.0,
                     clockwise: bool = False) -> CamGeometry:
    """The cam of a flat-faced translating follower (the face normal to its motion).

    The face at height r_b + s touches the cam at x = s′ (the offset moves the stem, not
    the contact): the working curve is R(−θ)·(s′, r_b + s), its radius of curvature
    r_b + s + s″, and the pressure angle 0.

    Parameters
    ----------
    theta, s, ds, dds : ndarray, shape (n,)
        Cam angle θ [rad], lift s [m], s′ [m/rad], s″ [m/rad²].
    base_radius : float
        Base circle radius r_b [m].
    offset : float
        Offset e [m] of the stem (the line x = e); it moves no curve.
    clockwise : bool
        The cam turns clockwise (the mirror image, x -> -x).
    """
    theta, s, ds, dds = (np.asarray(x, dtype=np.float64) for x in (theta, s, ds, dds))
    e = -offset if clockwise else offset
    zero, one = np.zeros_like(s), np.ones_like(s)
    contact = np.stack((ds, base_radius + s), axis=1)
    centre = np.stack((np.full_like(s, e), base_radius + s), axis=1)
    direction = np.stack((zero, one), axis=1)
    working = to_cam(theta, contact)
    normal = to_cam(theta, direction)
    rho = base_radius + s + dds
    if clockwise:
        working, normal = _mirror(working), _mirror(normal)
        centre, contact, direction = _mirror(centre), _mirror(contact), _mirror(direction)
    return CamGeometry("translating-flat", theta, None, working, normal, centre, contact,
                       direction, direction, zero, np.full_like(s, np.nan), rho, ~(rho > 0.0),
                       base_radius, 0.0, 1.0, clockwise)


def smallest_pitch_radius(s, ds, pressure_angle_max: float, offset: float = 0.0) -> float:
    """The smallest pitch circle r_p [m] of a translating roller follower that keeps
    |α| ≤ α_max over the cycle: from |s′ − e| ≤ tan α_max·(s + d), d = √(r_p² − e²),
    d ≥ max(|s′ − e|/tan α_max − s) and r_p = √(d² + e²) (zero offset: r_p ≥ max(|s′|/
    tan α_max − s)). The offset is the counter-clockwise one (a clockwise cam: −e)."""
    s, ds = np.asarray(s, dtype=np.float64), np.asarray(ds, dtype=np.float64)
    d = max(float(np.max(np.abs(ds - offset) / np.tan(pressure_angle_max) - s)), 0.0)
    return float(np.hypot(d, offset))


ROOT_RTOL = 1e-12
"""[-] the relative tolerance in r_p to which ``smallest_oscillating_base_radius``
brackets its root"""
SCAN = 512
"""[-] pitch radii scanned over the reachable range to bracket the first crossing"""


def oscillating_pressure_angles(pitch_radius, s, ds, *, pivot_distance: float,
                                arm_length: float) -> FloatArray:
    """The pressure angles α [rad] of an oscillating roller follower, from the instant
    centre of cam and arm (Rothbart, ch. 6): α = atan2(l·(1 + s′) − a·cos ψ, a·sin ψ),
    ψ = ψ0(r_p) + s, vectorised over pitch radii (shape (m, 1) against angles (n,)).
    A swing past the line of centres (sin ψ ≤ 0) gives |α| ≥ 90°."""
    a, length = pivot_distance, arm_length
    cos = (a ** 2 + length ** 2 - np.asarray(pitch_radius, dtype=np.float64) ** 2) / (
        2.0 * a * length)
    psi = np.arccos(np.clip(cos, -1.0, 1.0)) + s
    return np.arctan2(length * (1.0 + ds) - a * np.cos(psi), a * np.sin(psi))


def smallest_oscillating_base_radius(s, ds, pressure_angle_max: float, *,
                                     roller_radius: float, pivot_distance: float,
                                     arm_length: float) -> float | None:
    """The smallest base circle r_b [m] of an oscillating roller follower's cam that
    keeps |α| ≤ α_max over the cycle (no closed form).

    f(r_p) = max over the cam angles of |α(r_p)| − α_max, r_p = r_b + r_r within the
    radii the arm reaches (|a − l| < r_p < a + l, ψ0 from 0 to π). ``SCAN`` pitch
    radii, spaced evenly, are evaluated at once (radii × angles) to bracket the first
    r_p where f ≤ 0; bisection (every step vectorised over the angles) then narrows the
    bracket to ``ROOT_RTOL`` relative: the value returned has f ≤ 0 and a pitch radius
    ``ROOT_RTOL``·r_p smaller has f > 0.

    Parameters
    ----------
    s, ds : ndarray, shape (n,)
        The arm's swing from rest [rad] and s′ = ds/dθ [-] over the cycle.
    pressure_angle_max : float
        α_max [rad].
    roller_radius, pivot_distance, arm_length : float
        r_r, a = |OA|, l = |AC| [m].

    Returns
    -------
    float or None
        r_b [m] (r_p − r_r; where the limit holds from the smallest reachable pitch
        circle on, that circle's); None where no pitch circle the arm reaches meets the
        limit (a longer arm or another pivot is needed).
    """
    s, ds = np.asarray(s, dtype=np.float64), np.asarray(ds, dtype=np.float64)
    a, length = pivot_distance, arm_length
    low, high = abs(a - length), a + length
    low = max(low, roller_radius)  # r_b > 0

    def excess(radii):
        alpha = oscillating_pressure_angles(np.asarray(radii)[..., None], s, ds,
                                            pivot_distance=a, arm_length=length)
        return np.max(np.abs(alpha), axis=-1) - pressure_angle_max

    if not high > low:
        return None
    radii = low + (high - low) * np.arange(1, SCAN) / SCAN  # open ends: ψ0 = 0, π
    meets = np.flatnonzero(excess(radii) <= 0.0)
    if meets.size == 0:
        return None
    first = int(meets[0])
    if first == 0:  # between the smallest reachable circle and the first scanned
        left = low
        if excess(low + (radii[0] - low) * 1e-9) <= 0.0:
            return float(low + (radii[0] - low) * 1e-9 - roller_radius)
    else:
        left = float(radii[first - 1])
    right = float(radii[first])
    while right - left > ROOT_RTOL * right:
        middle = 0.5 * (left + right)
        if excess(middle) <= 0.0:
            right = middle
        else:
            left = middle
    return right - roller_radius


def smallest_flat_base_radius(s, dds, curvature_radius_min: float = 0.0) -> float:
    """The smallest base circle r_b [m] of a flat-faced follower's cam whose working
    radius of curvature r_b + s + s″ stays at or above ``curvature_radius_min`` [m]."""
    s, dds = np.asarray(s, dtype=np.float64), np.asarray(dds, dtype=np.float64)
    return float(np.max(curvature_radius_min - s - dds))


def face_width(ds) -> tuple[float, float]:
    """The contact's travel (x_min, x_max) [m] on a flat face (its x = s′): the face
    must reach both."""
    ds = np.asarray(ds, dtype=np.float64)
    return float(ds.min()), float(ds.max())


def spans(theta: FloatArray, mask: FloatArray) -> list[tuple[float, float]]:
    """Cam-angle ranges [rad] (first, last) of runs of True in ``mask``; a run through
    the end of the cycle joins the one at its start when θ covers a whole turn."""
    mask = np.asarray(mask, dtype=bool)
    if not mask.any():
        return []
    padded = np.concatenate(([False], mask, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    out = [(float(theta[a]), float(theta[b - 1])) for a, b in zip(edges[::2], edges[1::2])]
    whole = theta.size > 1 and theta[-1] - theta[0] + (theta[1] - theta[0]) >= 2 * np.pi - 1e-9
    if whole and len(out) > 1 and mask[0] and mask[-1]:
        out[0] = (out[-1][0], out[0][1])
        out.pop()
    return out
