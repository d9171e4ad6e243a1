"""Self-locking test for sliders with friction (Thümmel & Bartke 1987, after Gumpert 1984).

The slider does not lock while

    |F_η| > μ·(|FN| + 3·|M + 0.5·FN·H·μ·sign ṡ| / L)

with FN, M the prismatic joint's normal force and moment on the slider, L and H the
slider's length and height. The margin |F_η| − μ(…) [N] is reported at every position.

F_η is read as the *driving* force: the component along the guide of the reactions of
the slider's other joints (the force the linkage pushes it with). With inertia and
applied loads included as well, the slider's along-guide equilibrium would make F_η
equal to the joint's own friction force and the test would degenerate; read this way
the margin is homogeneous in the pushing force, so it tests the geometry of the push
(its angle to the guide and its lever about the slider against μ and L), which is what
self-locking is. Only positions where friction opposes F_η count (F_η·ṡ ≥ 0: the drive
pushes along the motion, or the slider is at rest); a linkage braking a moving slider
is not self-locking.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.linkage.friction import FrictionResult, joint_forces_on
from dyade.linkage.motion import Motion, travel
from dyade.linkage.model import FloatArray, Mechanism, toward_higher


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Locking:
    """The test for one slider."""

    margin: FloatArray
    """(n,) |F_η| − μ(|FN| + 3|M + 0.5·FN·H·μ·sign ṡ|/L) [N]"""
    driving_force: FloatArray
    """(n,) F_η along the guide direction [N]"""
    locks: FloatArray
    """(n,) bool: margin < 0 where the test applies"""


def test(mechanism: Mechanism, motion: Motion, result: FrictionResult,
         valid: FloatArray) -> dict[tuple[int, int], Locking]:
    """Self-locking margin of every slider with friction at every crank position."""
    out = {}
    typical = abs(mechanism.crank.speed) * mechanism.crank.length
    for joint in mechanism.friction_sliders:
        s = joint.slider
        d = motion.direction(joint.carrier, joint.guide_angle)
        others = joint_forces_on(s, mechanism, result)
        others.pop(joint.name)
        pushing = sum(others.values()) if others else np.zeros_like(d)
        f_eta = np.sum(pushing * d, axis=1)
        towards = toward_higher(joint.name, joint.slider)  # reported -> on the slider
        normal = towards * result.forces.normal[joint.name]
        moment = towards * result.forces.moment[joint.name]
        velocity = travel(joint, motion)[1]
        sign = np.where(np.abs(velocity) <= 1e-9 * typical, 0.0, np.sign(velocity))
        mu, height, length = joint.friction, joint.slider_height, joint.slider_length
        resistance = mu * (np.abs(normal)
                           + 3.0 * np.abs(moment + 0.5 * normal * height * mu * sign) / length)
        margin = np.abs(f_eta) - resistance
        applies = f_eta * sign >= 0.0
        out[joint.name] = Locking(margin, f_eta, valid & applies & (margin < 0.0))
    return out
