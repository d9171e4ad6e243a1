"""The Coulomb law of a joint (Thümmel & Bartke 1987, section 4), in the wrench form of
``dyade.linkage.kinetostatics``: friction is the part τ = S·W that a joint carries along
its freedom S (relative rate r along S):

* revolute joint: τ = −μ·r_z·|F|·sign(r), a moment about the pin;
* prismatic joint: τ = −μ·(|FN| + 3·|M'|/L)·sign(r), a force along the guide. M' =
  M + ½·FN·H·μ·sign(r) is the tilting moment that the normal pressures carry (M: the
  joint's moment about the slider point), and 3·|M'|/L the sum of the two edge pressures
  of a linear pressure distribution over the block length L: the paper's edge friction.
  The part μ·|FN| acts at the guide surface, H/2 from the slider point on the side that
  carries the normal force (so it shifts the reported moment); the edge part acts on
  both faces alike and has no moment. ``edge_friction = false`` leaves out 3·|M'|/L.

Every law reads τ_k = −c_k·g_k(W_k) with c_k = μ·sign(r_k) and g_k ≥ 0 positively
homogeneous of degree 1 in the joint's wrench W_k. For a fixed *pattern* — the direction
of a pin's force, the signs of a slider's FN and M' — g_k is linear: g_k = a_k·W_k.

Where a relative velocity is zero the friction direction is undefined: sign(0) = 0 is
used (``AT_REST_RTOL``) and the caller reports those positions.
"""

from __future__ import annotations

import numpy as np

from dyade.linkage.kinematics import Group
from dyade.linkage.model import FloatArray, Joint, Revolute

AT_REST_RTOL = 1e-9  # [-] relative velocity below this share of the typical one counts as zero
EDGE = 3.0  # [-] sum of the edge pressures of a linear distribution over L: 3·|M'|/L


def has_friction(joint: Joint) -> bool:
    """The joint has a Coulomb law: μ > 0."""
    return joint.friction > 0.0


class Law:
    """The Coulomb law of one joint of a group (module docstring): g(W) ≥ 0, its pattern
    and gradient a, and the part of a slider's friction at the guide surface."""

    def __init__(self, k: int, joint: Joint, group: Group, offset, coefficient: FloatArray,
                 motion):
        self.k, self.name = k, joint.name
        self.side = -1.0 if k == 2 else 1.0  # s_k: W_k = s_k·W_B + q_k
        self.offset = offset  # q_k (3, n) or None
        self.c = coefficient  # μ·sign(r) (n,)
        self.revolute = isinstance(joint, Revolute)
        # μ·r_z or μ: the friction load per newton of joint force, for relative changes
        self.unit = max(joint.friction * (joint.pin_radius if self.revolute else 1.0), 1e-300)
        self.arm = joint.pin_radius if self.revolute else 1.0
        if self.revolute:
            self.arrays = ("c",)
            return
        ax, ay = group.screws[k][0], group.screws[k][1]  # ζ·d
        self.ax, self.ay = ax, ay
        self.zeta = 1.0 if group.on[k] == joint.slider else -1.0
        px, py = motion.point_xy(joint.slider, joint.slider_point)
        h = 0.5 * joint.slider_height * coefficient  # ½·H·μ·sign(r)
        self.edge = EDGE / joint.slider_length if joint.edge_friction else 0.0
        # M' = ζ·(m − p_x·f_y + p_y·f_x) + h·FN = ζ·m + tx·f_x + ty·f_y
        self.tx, self.ty = self.zeta * py - h * ay, h * ax - self.zeta * px
        self.arrays = ("c", "ax", "ay", "tx", "ty")

    def take(self, index) -> Law:
        """The law at the positions ``index`` only."""
        out = object.__new__(Law)
        out.__dict__.update(self.__dict__)
        out.offset = None if self.offset is None else self.offset[:, index]
        for name in self.arrays:
            setattr(out, name, getattr(self, name)[index])
        return out

    def component(self, w_b: FloatArray, index: int) -> FloatArray:
        """Component ``index`` of W_k = s_k·W_B + q_k, the joint's wrench on ``on[k]``."""
        part = w_b[index]
        if self.offset is None:
            return part if self.side > 0 else -part
        return self.offset[index] + part if self.side > 0 else self.offset[index] - part

    def measure(self, w_b: FloatArray) -> tuple[FloatArray, tuple]:
        """g(W_k) (n,) and the parts its pattern and gradient need: (f_x, f_y, |F|) of
        a pin, (FN, M', |FN|) of a slider (FN, M' on the slider)."""
        wx, wy = self.component(w_b, 0), self.component(w_b, 1)
        if self.revolute:
            size = np.sqrt(wx * wx + wy * wy)
            return self.arm * size, (wx, wy, size)
        normal = self.ax * wy - self.ay * wx
        size = np.abs(normal)
        if not self.edge:
            return size, (normal, None, size)
        wm = self.component(w_b, 2)
        tilt = self.tx * wx + self.ty * wy
        tilt += wm if self.zeta > 0 else -wm
        return size + self.edge * np.abs(tilt), (normal, tilt, size)

    def pattern(self, parts: tuple) -> tuple:
        """A slider's pattern: the signs of FN and M' (a pin's direction is continuous)."""
        if self.revolute:
            return ()
        return (parts[0] > 0.0,) if parts[1] is None else (parts[0] > 0.0, parts[1] > 0.0)

    def choices(self) -> list[tuple[float, ...]]:
        """Every pattern a restart may force (``gradient``): the signs of FN and M' of a
        slider, the sense of a pin's force relative to the one measured."""
        if self.revolute:
            return [(1.0,), (-1.0,)]
        if not self.edge:
            return [(1.0,), (-1.0,)]
        return [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]

    def gradient(self, parts: tuple, forced: tuple | None = None, factor=1.0) -> tuple:
        """``factor``·a, with g = a·W_k at the pattern of ``parts``, or at the ``forced``
        one (``choices``): three (n,) arrays (or 0.0)."""
        if self.revolute:
            wx, wy, size = parts
            scale = factor * self.arm / np.maximum(size, 1e-300)  # |F| = 0: f = 0
            if forced is not None:
                scale *= forced[0]
            return wx * scale, wy * scale, 0.0
        normal, tilt, _ = parts
        sn = (np.sign(normal) if forced is None else forced[0]) * factor
        if tilt is None:
            return -self.ay * sn, self.ax * sn, 0.0
        st = (np.sign(tilt) if forced is None else forced[1]) * (self.edge * factor)
        gx = st * self.tx
        gx -= self.ay * sn
        gy = st * self.ty
        gy += self.ax * sn
        return gx, gy, st * self.zeta
