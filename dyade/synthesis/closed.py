"""The classical closed forms of dimensional synthesis: Freudenstein's equation for
function generation through three precision points (with Chebyshev spacing), motion
generation through three poses, the Burmester centre- and circle-point curves of four
poses, and the Roberts–Chebyshev cognates of a four-bar's coupler curve.

Conventions: the four-bar A0–A–B–B0 with the crank a = |A0A|, the coupler b = |AB|, the
rocker c = |B0B| and the frame d = |A0B0|; angles are measured from the frame line
A0→B0 (counter-clockwise), the crank angle φ of A0→A and the output angle ψ of B0→B.
Points are complex numbers x + iy [m] where that is shorter.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError, InputError


# -- function generation: Freudenstein ------------------------------------------------
@dataclass(frozen=True, slots=True)
class FourBar:
    """A four-bar in the frame A0 = (0, 0), B0 = (d, 0) [m] and its coupler point P at
    (p, q) in the coupler's frame (origin A, ξ towards B) [m]. ``a`` may be negative:
    the crank pin then lies at (a, 0) in the crank's frame (on the other side of the
    pivot), so that the crank angle stays the one asked for; likewise ``c``."""

    a: float
    b: float
    c: float
    d: float
    p: float = 0.0
    q: float = 0.0
    variant: int = 1
    """the assembly: +1 B left of the directed line A→B0, −1 right (dyade's RRR rule)"""


def freudenstein(crank: FloatArray, output: FloatArray, frame: float = 1.0) -> FourBar:
    """The four-bar whose output angle ψ passes through three precision points (φ_i, ψ_i).

    Freudenstein's equation (Freudenstein 1955), from |B − A|² = b² with
    A = a·e^{iφ}, B = d + c·e^{iψ}:

        K1·cos ψ − K2·cos φ + K3 = cos(φ − ψ),
        K1 = d/a,  K2 = d/c,  K3 = (a² − b² + c² + d²)/(2ac),

    linear in K1, K2, K3: three points give them exactly.

    Parameters
    ----------
    crank, output : ndarray, shape (3,)
        φ_i and ψ_i [rad], measured from the frame line A0→B0.
    frame : float
        d [m].

    Returns
    -------
    FourBar
        with signed ``a`` and ``c`` (negative: the pin on the other side), and the
        assembly variant that passes through the first point.

    Raises
    ------
    DyadeError
        The three points give no four-bar (a singular system, b² < 0).
    """
    phi, psi = np.asarray(crank, dtype=float), np.asarray(output, dtype=float)
    if phi.shape != (3,) or psi.shape != (3,):
        raise InputError("Freudenstein's equation needs exactly three precision points, "
                         f"got {phi.size}.")
    matrix = np.column_stack([np.cos(psi), -np.cos(phi), np.ones(3)])
    rhs = np.cos(phi - psi)
    if abs(np.linalg.det(matrix)) < 1e-12:
        raise DyadeError("the three precision points give a singular Freudenstein system "
                         "(two points coincide in φ or ψ): choose distinct points.")
    k1, k2, k3 = np.linalg.solve(matrix, rhs)
    if k1 == 0.0 or k2 == 0.0:
        raise DyadeError("the precision points need an infinitely long crank or rocker.")
    a, c = frame / k1, frame / k2
    square = a * a + c * c + frame * frame - 2.0 * a * c * k3
    if not square > 0.0:
        raise DyadeError(f"the precision points give b² = {square:.4g} m² < 0: no four-bar "
                         "passes through them; choose other points or spacing.")
    b = float(np.sqrt(square))
    ax, ay = a * np.cos(phi[0]), a * np.sin(phi[0])
    bx, by = frame + c * np.cos(psi[0]), c * np.sin(psi[0])
    side = (bx - ax) * (0.0 - ay) - (by - ay) * (frame - ax)  # (B−A)×(B0−A)
    return FourBar(float(a), b, float(c), float(frame), variant=1 if side < 0.0 else -1)


def output_angle(linkage: FourBar, crank: FloatArray) -> FloatArray:
    """ψ(φ) of a four-bar in closed form [rad] (NaN where it does not close), its
    rocker pin on the side of its sign."""
    phi = np.asarray(crank, dtype=float)
    ax, ay = linkage.a * np.cos(phi), linkage.a * np.sin(phi)
    b = rrr(ax, ay, linkage.d, 0.0, linkage.b, abs(linkage.c), linkage.variant)
    psi = np.arctan2(b[1], b[0] - linkage.d)
    return psi if linkage.c > 0 else psi + np.pi


def rrr(ax, ay, cx, cy, l_i, l_j, variant: int):
    """B of an RRR dyad (dyade's closure, ``dyade.linkage.dyads.rrr``): |B − A| = l_i,
    |B − C| = l_j, B left of A→C for variant +1; NaN where it does not close."""
    dx, dy = cx - ax, cy - ay
    dist_sq = dx * dx + dy * dy
    with np.errstate(divide="ignore", invalid="ignore"):
        inverse = 1.0 / np.sqrt(dist_sq)
        along = (dist_sq + (l_i * l_i - l_j * l_j)) * (0.5 * inverse)
        height = np.sqrt(l_i * l_i - along * along)
    side = height if variant > 0 else -height
    ux, uy = dx * inverse, dy * inverse
    return ax + along * ux - side * uy, ay + along * uy + side * ux


def chebyshev(start: float, stop: float, count: int = 3) -> FloatArray:
    """Chebyshev's spacing of ``count`` precision points over [start, stop]:
    x_j = (start + stop)/2 − (stop − start)/2·cos((2j − 1)π/(2n)), j = 1..n."""
    j = np.arange(1, count + 1)
    return 0.5 * (start + stop) - 0.5 * (stop - start) * np.cos((2 * j - 1) * np.pi / (2 * count))


# -- motion generation ------------------------------------------------------------------
def circumcentre(points: np.ndarray) -> complex:
    """The centre of the circle through three points (complex) [m]."""
    z1, z2, z3 = points
    w = (z3 - z1) / (z2 - z1)
    if abs(w.imag) < 1e-14 * abs(w):
        raise DyadeError("three positions of a moving pivot lie on a line: no fixed pivot "
                         "(choose another moving pivot).")
    c = (z2 - z1) * (w - abs(w) ** 2) / (2j * w.imag * 1.0)
    return complex(z1 + c)


def pose_points(poses: np.ndarray, local) -> np.ndarray:
    """The world positions of coupler points ``local`` (complex, world positions in pose
    0; a number or an array) in every pose (x, y, θ): (..., poses) complex [m]."""
    poses = np.asarray(poses, dtype=float)
    origin = poses[:, 0] + 1j * poses[:, 1]
    turn = np.exp(1j * (poses[:, 2] - poses[0, 2]))
    return origin + (np.asarray(local)[..., None] - origin[0]) * turn


def three_poses(poses: np.ndarray, moving: tuple[complex, complex]) -> tuple[complex, ...]:
    """Motion generation through three poses: the fixed pivots (centre points) of the
    moving pivots ``moving`` (circle points, world positions in pose 0) [m].

    Each moving pivot's three positions lie on a circle about its fixed pivot: the
    circumcentre. Returns (A0, A, B0, B) with A, B the moving pivots in pose 0.
    """
    a, b = moving
    a0 = circumcentre(pose_points(poses, a))
    b0 = circumcentre(pose_points(poses, b))
    return a0, complex(a), b0, complex(b)


@dataclass(frozen=True, slots=True)
class Burmester:
    """The centre-point and circle-point curves of four poses, sampled: each point of the
    one pairs with the point of the other at the same index."""

    centre: np.ndarray
    """(m,) complex centre points (fixed pivots) [m]"""
    circle: np.ndarray
    """(m,) complex circle points (moving pivots, in pose 0) [m]"""
    crank: np.ndarray
    """(m, 3) the crank's rotations β_j from pose 0 to poses 1..3 [rad]"""


def burmester(poses: np.ndarray, samples: int = 720) -> Burmester:
    """The Burmester curves of four poses (x, y, θ) [m, rad], by the standard dyad
    equation of each moving pivot (Erdman & Sandor, "Mechanism Design", §8):

        W·(e^{iβ_j} − 1) + Z·(e^{iα_j} − 1) = δ_j,   j = 1, 2, 3,

    with α_j the coupler's and β_j the crank's rotation from pose 0, δ_j the
    displacement of the pose's point. Compatibility (the 3×3 augmented matrix of rank 2)
    Δ1 + Δ2·e^{iβ1} + Δ3·e^{iβ2} + Δ4·e^{iβ3} = 0, solved for β2 and β3 over β1 in
    ``samples`` steps as a triangle of sides |Δ3|, |Δ4| (two closures), gives W and Z:
    the circle point P0 − Z, the centre point P0 − Z − W.
    """
    poses = np.asarray(poses, dtype=float)
    if poses.shape != (4, 3):
        raise InputError(f"the Burmester curves need exactly four poses, got {len(poses)}.")
    p = poses[:, 0] + 1j * poses[:, 1]
    alpha = poses[1:, 2] - poses[0, 2]
    delta = p[1:] - p[0]
    za = np.exp(1j * alpha) - 1.0
    # det [[e^{iβ1}−1, za1, δ1], ...] = Σ (e^{iβj} − 1)·C_j, C_j the cofactors
    cof = np.array([za[1] * delta[2] - za[2] * delta[1],
                    -(za[0] * delta[2] - za[2] * delta[0]),
                    za[0] * delta[1] - za[1] * delta[0]])
    beta1 = np.linspace(0.0, 2.0 * np.pi, samples, endpoint=False)[1:]
    rest = -(-cof.sum() + cof[0] * np.exp(1j * beta1))  # Δ3·e^{iβ2} + Δ4·e^{iβ3} = rest
    centres, circles, cranks = [], [], []
    r3, r4 = abs(cof[1]), abs(cof[2])
    length = np.abs(rest)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos_gamma = (length ** 2 + r3 ** 2 - r4 ** 2) / (2.0 * length * r3)
    closes = np.abs(cos_gamma) <= 1.0
    gamma = np.arccos(np.clip(cos_gamma, -1.0, 1.0))
    for sign in (1.0, -1.0):
        u = rest * np.exp(1j * sign * gamma) / np.where(length > 0, length, 1.0)  # unit
        e2 = r3 * u / cof[1]  # e^{iβ2}
        e3 = (rest - cof[1] * e2) / cof[2]  # e^{iβ3}
        e1 = np.exp(1j * beta1)
        # W, Z from the first two equations
        m11, m12, m21, m22 = e1 - 1.0, za[0], e2 - 1.0, za[1]
        det = m11 * m22 - m12 * m21
        ok = closes & (np.abs(det) > 1e-12) & (np.abs(np.abs(e3) - 1.0) < 1e-6)
        w = (delta[0] * m22 - m12 * delta[1]) / np.where(ok, det, 1.0)
        z = (m11 * delta[1] - m21 * delta[0]) / np.where(ok, det, 1.0)
        circle = p[0] - z
        centres.append((circle - w)[ok])
        circles.append(circle[ok])
        cranks.append(np.angle(np.column_stack([e1, e2, e3]))[ok])
    return Burmester(np.concatenate(centres), np.concatenate(circles),
                     np.concatenate(cranks))


def _circumcentres(points: np.ndarray) -> np.ndarray:
    """(m,) complex: the centres of the circles through rows of three points (m, 3)."""
    z1, z2, z3 = points[:, 0], points[:, 1], points[:, 2]
    with np.errstate(invalid="ignore", divide="ignore"):
        w = (z3 - z1) / (z2 - z1)
        return z1 + (z2 - z1) * (w - np.abs(w) ** 2) / (2j * w.imag)


def _five(poses: np.ndarray, moving: np.ndarray) -> np.ndarray:
    """(m, 2): how far poses 4 and 5 put each moving pivot (m,) off the circle of its
    first three positions [m] (zero at a Ball–Burmester point)."""
    at = pose_points(poses, moving)
    centre = _circumcentres(at[:, :3])
    radius = np.abs(at[:, 0] - centre)
    return np.column_stack([np.abs(at[:, 3] - centre) - radius,
                            np.abs(at[:, 4] - centre) - radius])


def ball_burmester(poses: np.ndarray, samples: int = 2880) -> tuple[np.ndarray, np.ndarray]:
    """The Ball–Burmester points of five poses: the moving pivots (circle points, world
    positions in pose 0) whose five positions lie on one circle, and that circle's
    centre (the fixed pivot) [m]: the points of the circle-point curve of poses 1–4
    (``burmester``) where the fifth position's distance from the centre changes sign,
    each refined by Newton's method on both conditions. None, two or four exist (one
    between samples too close to tell apart may be missed).

    Returns
    -------
    (centres, circles) : ndarray, ndarray
        (k,) complex each, k ≤ 4.
    """
    poses = np.asarray(poses, dtype=float)
    if poses.shape != (5, 3):
        raise InputError(f"the Ball–Burmester points need exactly five poses, got "
                         f"{len(poses)}.")
    z = poses[:, 0] + 1j * poses[:, 1]
    size = max(float(np.ptp(z.real)), float(np.ptp(z.imag)), 1e-9)
    curve = burmester(poses[:4], samples).circle
    f = _five(poses, curve)[:, 1]
    near = np.abs(np.diff(curve)) < 0.05 * size  # neighbours on one branch of the curve
    change = np.flatnonzero(near & (np.sign(f[:-1]) * np.sign(f[1:]) < 0))
    found: list[complex] = []
    for k in change:  # a few points: Newton from each bracket, vectorised within
        x = np.array([0.5 * (curve[k] + curve[k + 1])])
        for _ in range(50):
            g = _five(poses, x)[0]
            h = 1e-7 * size
            jac = np.column_stack([(_five(poses, x + h)[0] - g) / h,
                                   (_five(poses, x + 1j * h)[0] - g) / h])
            if not np.all(np.isfinite(jac)) or abs(np.linalg.det(jac)) < 1e-300:
                break
            step = np.linalg.solve(jac, -g)
            x = x + complex(step[0], step[1])
            if abs(complex(step[0], step[1])) < 1e-14 * size:
                break
        if np.all(np.abs(_five(poses, x)[0]) < 1e-10 * size) and not any(
                abs(x[0] - other) < 1e-8 * size for other in found):
            found.append(complex(x[0]))
    circles = np.array(found, dtype=complex)
    centres = _circumcentres(pose_points(poses, circles)[:, :3]) if found else circles
    return centres, circles


# -- cognates ------------------------------------------------------------------------------
def points(linkage: FourBar, crank: float) -> dict[str, complex]:
    """A0, A, B, B0 and the coupler point P of a four-bar at crank angle φ [rad]."""
    a = linkage.a * np.exp(1j * crank)
    bx, by = rrr(a.real, a.imag, linkage.d, 0.0, linkage.b, abs(linkage.c), linkage.variant)
    b = complex(bx, by)
    e = (b - a) / abs(b - a)
    return {"A0": 0j, "A": complex(a), "B": b, "B0": complex(linkage.d),
            "P": complex(a + e * (linkage.p + 1j * linkage.q))}


@dataclass(frozen=True, slots=True)
class Cognate:
    """A four-bar in world coordinates: its fixed pivots, moving pivots (at one position)
    and coupler point, each complex [m]."""

    fixed: tuple[complex, complex]
    """(the driven link's pivot, the other's)"""
    moving: tuple[complex, complex]
    """(on the driven link, on the other)"""
    point: complex
    """the coupler point"""


def cognates(linkage: FourBar, crank: float = 0.3) -> tuple[Cognate, Cognate, Cognate]:
    """The linkage and its two Roberts–Chebyshev cognates, which trace the same coupler
    curve (Roberts 1875; Hartenberg & Denavit, "Kinematic Synthesis of Linkages", §6.3).

    With r1 = B0 − A0, r2 = A − A0, r3 = B − A, r4 = B − B0 and ρ = (P − A)/(B − A),
    the third fixed pivot is C0 = A0 + ρ·r1, and

    - cognate 2: A0 –(ρ·r3)– D –(ρ·r2)– E –(ρ·r4)– C0, P − D = r2;
    - cognate 3: C0 –((1 − ρ)·r2)– G –((1 − ρ)·r4)– F –((ρ − 1)·r3)– B0, P − F = r4.

    Each is given at crank angle ``crank`` of the original, driven by the link that
    turns with the original crank where one does (cognate 3 by C0–G), else by its link
    at A0 (cognate 2).
    """
    at = points(linkage, crank)
    a0, a, b, b0, p = at["A0"], at["A"], at["B"], at["B0"], at["P"]
    r1, r2, r3 = b0 - a0, a - a0, b - a
    rho = (p - a) / (b - a)
    c0 = a0 + rho * r1
    d = a0 + rho * r3
    e = d + rho * r2
    g = c0 + (1 - rho) * r2
    f = b0 + (rho - 1) * r3
    return (Cognate((a0, b0), (a, b), p), Cognate((a0, c0), (d, e), p),
            Cognate((c0, b0), (g, f), p))
