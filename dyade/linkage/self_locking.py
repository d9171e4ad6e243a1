"""Self-locking of sliders: the test of Thümmel & Bartke (1987, after Gumpert), read so
that it is the exact jam condition of a pushed block, and the verdict of the friction
solution (``dyade.linkage.friction``).

The paper's test: a slider does not lock while

    |F_η| > μ·(|FN| + 3·|M + ½·FN·H·μ·sign ṡ| / L)

with F_η the force along the guide that drives it, FN and M the prismatic joint's normal
force and moment (about the slider point) that balance that drive, L and H the slider's
length and height. Evaluated on the converged reactions it degenerates (the slider's own
equilibrium makes |F_η| equal to the friction it already carries), so dyade evaluates it
on **the push**: a force F_η along the guide, in the direction of motion, applied to the
slider through its frictionless dyad (row k of M⁻¹, the kinematics' inverse) with no
other load. FN and M are then the joint's reactions to that push alone. For a block
pushed by a two-force member (a rod pinned at both ends) the push runs along the rod, at
the angle β to the guide and with its line of action at the lever e about the block, and
the inequality is the condition under which any push moves the block, with the bound
|FN| + 3·|M'|/L in place of the block's pressure (docs/guide/friction.md). Everything is
proportional to F_η, so

    lock_margin = 1 − μ·(|FN| + 3·|M + ½·FN·H·μ·sign ṡ|/L) / |F_η|      [-]

depends on the geometry alone and its sign is never decided by round-off: 1 for a push
straight along the guide through the block's centre, negative where a push along the
motion through the linkage might jam the block. Without edge friction
(``edge_friction = false``) the 3·|…|/L term is left out here as in the friction model.

**The margin is conservative.** |FN| + 3·|M'|/L is an upper bound of the block's total
pressure ∫|p| dx, which the friction model uses (``dyade.linkage.friction.laws``): equal
to it only where FN = 0 or M' = 0. So a positive margin means no push through the
linkage can jam the block; a negative one means it might. The exact jam condition is
the sign of the dyad's determinant below.

Whether the slider *does* lock is the friction solution's verdict: its dyad's
friction-augmented equilibrium has no solution (a friction dead centre) and this joint's
friction is the cause. The verdict's determinant is that of the equilibrium's Jacobian at
the solution relative to the frictionless one, det(I + K) with K from the laws'
gradients there; a sign change against the frictionless one (≤ 0) marks the lock. For a
block pushed by a two-force member with friction in its guide only it is 1 − μ·∫|p| dx
per unit push along the guide, and the lock begins where it crosses zero, at or after
the margin's zero; a negative margin elsewhere (the linkage brakes the slider, other
joints carry the motion, or the bound overstates the pressure) is no self-locking.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.friction import AT_REST_RTOL, EDGE, FrictionResult
from dyade.linkage.kinematics import Kinematics
from dyade.linkage.motion import guide_direction, travel
from dyade.model.mechanism import Mechanism, Prismatic


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Locking:
    """The self-locking verdict for one joint, and a slider's margin."""

    locks: FloatArray
    """(n,) bool: the joint's dyad self-locks here and this joint's friction is the cause"""
    dyad: int
    """the number of the joint's dyad"""
    determinant: FloatArray
    """(n,) determinant of that dyad's friction-augmented equilibrium's Jacobian at the
    solution, relative to the frictionless one [-] (1 without friction, ≤ 0
    self-locking: the lowest met where it locks; NaN where not computed)"""
    margin: FloatArray | None = None
    """slider: (n,) 1 − μ·(|FN| + 3·|M + ½·FN·H·μ·sign ṡ|/L)/|F_η| for a push F_η along
    the motion through the frictionless dyad [-], the paper's test: a conservative lock
    margin (> 0: no push can jam the block); None for a revolute joint"""


def test(mechanism: Mechanism, kin: Kinematics, result: FrictionResult
         ) -> dict[tuple[int, int], Locking]:
    """Every slider with friction (its margin) and every joint that self-locks."""
    where = {joint.name: (group, k, number) for group, number in
             zip(kin.groups, (dyad.number for dyad in mechanism.dyads))
             for k, joint in enumerate(group.joints)}
    out = {}
    for joint in mechanism.joints:
        name = joint.name
        sliding = isinstance(joint, Prismatic) and joint.friction > 0.0
        if not sliding and name not in result.locks:
            continue
        group, k, number = where[name]
        n = kin.crank_angle.shape[0]
        locks = result.locks.get(name, np.zeros(n, dtype=bool))
        margin = push_margin(mechanism, kin, joint, group, k) if sliding else None
        out[name] = Locking(locks, number, result.determinant[number], margin)
    return out


def push_margin(mechanism: Mechanism, kin: Kinematics, joint: Prismatic, group, k: int
                ) -> FloatArray:
    """(n,) the margin of the module docstring for slider ``joint``, joint k of ``group``."""
    motion = kin.motion
    typical = abs(mechanism.crank.speed) * mechanism.crank.length
    velocity = travel(joint, motion)[1]
    sign = np.where(np.abs(velocity) <= AT_REST_RTOL * typical, 0.0, np.sign(velocity))
    # W_k = ±R_k carries a unit load along the joint's freedom: the joint's reaction to a
    # unit push along the guide. Its sense does not matter: reversed, FN and M both
    # reverse, and with them M + ½·FN·H·μ·sign ṡ (the motion fixes sign ṡ, the face
    # carrying FN carries the friction's part μ·|FN|).
    fx, fy, moment = group.inverse[k]
    dx, dy = guide_direction(joint, motion)
    sx, sy = motion.point_xy(joint.slider, joint.slider_point)
    normal = dx * fy - dy * fx
    about = moment - (sx * fy - sy * fx)
    mu = joint.friction
    resistance = np.abs(normal)
    if joint.edge_friction:
        tilt = about + 0.5 * normal * joint.slider_height * mu * sign
        resistance = resistance + EDGE * np.abs(tilt) / joint.slider_length
    return 1.0 - mu * resistance
