"""The translating follower's guide: Coulomb friction in a two-point guide and the jam
of the follower, read as dyade reads a slider's self-locking (``dyade.linkage.
self_locking``): the margin of a push along the guide.

The follower's stem slides in a guide of length L, its near end (the end towards the
cam) at the overhang b from the roller centre (a flat face: from the face) at zero lift;
the guide is fixed, so the overhang at lift s is b − s. With clearance the stem bears at
the guide's two ends: the contact force N·n (n the cam's outward normal at the contact
C) is balanced across the axis by the reactions R1 at the near end and R2 at the far
end,

    R2 = N·((C − G1) × n)/L,     R1 = −N·n_x − R2,

(G1 the near end on the line of motion; the moment about G1), and the guide's friction
μ·(|R1| + |R2|) = μ·|N|·p acts along the guide against the follower's sliding. Per unit
push along the guide (N·n_y = 1) the guide carries the pressure p/n_y, and, as a
slider's lock margin,

    margin = 1 − μ·(|R1| + |R2|)/|F_η| = 1 − μ·p/n_y,       F_η = N·n_y,

depends on the geometry alone. The follower moves while the cam pushes it (the rise,
or a groove's return) only where margin > 0: where it is ≤ 0 no contact force moves it,
the follower **jams**. For a roller follower (the force through the roller's centre,
at b' = b − s below the near end, at the pressure angle α) p = |sin α|·(1 + 2·b'/L) and
the follower jams where tan |α| ≥ L/(μ·(L + 2·b')): the classic two-point guide. For a
flat face (α = 0) the force along the guide at the distance d = s′ from the line of
motion tilts the stem: p = 2·|d|/L, a jam where 2·μ·|d| ≥ L.

The balance along the guide with friction, σ = sign ṡ (0 at rest: the dwells),

    N·(n_y − μ·p·σ·sign N) = m·s″·ω² + k·(s + s0) + F,

gives the contact force; without friction it is ``dyade.cam.forces.contact_force``.
The reactions' own friction moment (the stem's width) is left out.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray

AT_REST_RTOL = 1e-9  # [-] |s′| below this share of the largest counts as at rest


@dataclass(frozen=True)
class Guide:
    """The guide of a translating follower over the cam angles (SI)."""

    pressure: FloatArray
    """p = (|R1| + |R2|)/|N|, the guide's reactions per unit contact force [-]"""
    margin: FloatArray
    """1 − μ·p/n_y [-]: ≤ 0 where a push along the guide cannot move the follower"""
    sliding: FloatArray
    """σ = sign ṡ [-] (0 at rest)"""
    overhang: FloatArray
    """b − s, the roller centre's (face's) distance below the guide's near end [m]"""


def guide(geometry, s: FloatArray, v: FloatArray, *, friction: float, length: float,
          overhang: float) -> Guide:
    """The two-point guide's pressure and lock margin at every cam angle.

    Parameters
    ----------
    geometry : dyade.cam.geometry.CamGeometry
        A translating follower's (roller or flat face).
    s, v : ndarray, shape (n,)
        The lift s [m] and s′ = ds/dθ [m/rad].
    friction : float
        μ [-] of the guide.
    length : float
        L [m], the guide's length (between the two bearing points).
    overhang : float
        b [m], from the roller centre (flat face: the face) to the guide's near end at
        zero lift.
    """
    s, v = np.asarray(s, dtype=np.float64), np.asarray(v, dtype=np.float64)
    n = geometry.contact_normal
    base = geometry.centre[:, 1] - s  # the roller centre (face) at zero lift: constant
    near = np.stack((geometry.centre[:, 0], base + overhang), axis=1)  # G1, on the line
    arm = geometry.contact - near
    moment = arm[:, 0] * n[:, 1] - arm[:, 1] * n[:, 0]  # (C − G1) × n, per unit N
    far = moment / length
    pressure = np.abs(-n[:, 0] - far) + np.abs(far)
    with np.errstate(divide="ignore", invalid="ignore"):
        margin = 1.0 - friction * pressure / n[:, 1]
    typical = float(np.max(np.abs(v))) if v.size else 0.0
    sliding = np.where(np.abs(v) <= AT_REST_RTOL * typical, 0.0, np.sign(v))
    return Guide(pressure, margin, sliding, overhang - s)


def contact_force(along: FloatArray, normal_y: FloatArray, guided: Guide,
                  friction: float) -> tuple[FloatArray, FloatArray]:
    """The contact force N [N] with the guide's friction, and where the follower jams.

    Parameters
    ----------
    along : ndarray, shape (n,)
        m·s″·ω² + k·(s + s0) + F [N]: what the contact force must carry along the guide.
    normal_y : ndarray, shape (n,)
        n_y, the normal's component along the line of motion (cos α).
    guided : Guide
    friction : float
        μ [-].

    Returns
    -------
    force : ndarray, shape (n,)
        N [N]; NaN where the follower jams.
    jammed : ndarray of bool, shape (n,)
        The cam pushes the follower along its motion (σ·sign N > 0) and the margin is
        ≤ 0: no contact force moves it.
    """
    along = np.asarray(along, dtype=np.float64)
    pushed = guided.sliding * np.sign(along)  # +1: the contact force drives the sliding
    denominator = normal_y - friction * guided.pressure * pushed
    jammed = (pushed > 0) & (guided.margin <= 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        force = np.where(jammed, np.nan, along / denominator)
    return force, jammed
