"""The Coulomb law of a joint (Thümmel & Bartke 1987, section 4), in the wrench form of
``dyade.linkage.kinetostatics``: friction is the part τ = S·W that a joint carries along
its freedom S (relative rate r along S):

* revolute joint: τ = −μ·r_z·|F|·sign(r), a moment about the pin;
* prismatic joint: τ = −μ·N(FN, M')·sign(r), a force along the guide, with N the total
  normal pressure of a block of length L that carries the normal force FN and the
  tilting moment M' = M + ½·FN·H·μ·sign(r) (M: the joint's moment about the slider
  point). With the linear pressure distribution p(x) = FN/L + 12·M'·x/L³ over the block,

      N = ∫|p| dx = |FN|                              while 6·|M'| ≤ |FN|·L,
      N = FN²·L/(12·|M'|) + 3·|M'|/L                  beyond (the pressure changes sign),

  continuous with its gradient at 6·|M'| = |FN|·L, and 3·|M'|/L at FN = 0: the paper's
  edge friction, the pressure of the two edges under a pure tilting moment. (The sum
  |FN| + 3·|M'|/L, the paper's self-locking test, is the conservative upper bound of N:
  ``dyade.linkage.self_locking``.) Whatever N, the friction's moment about the slider
  point is that of μ·|FN| acting at the face that carries FN, H/2 from the slider
  point (the rest, μ·(N − |FN|), is shared equally by both faces and has no moment): the
  ½·FN·H·μ term of M'. ``edge_friction = false`` keeps point contact: N = |FN|.

Every law reads τ_k = −c_k·g_k(W_k) with c_k = μ·sign(r_k) and g_k ≥ 0 positively
homogeneous of degree 1 in the joint's wrench W_k, so g_k = a_k·W_k with a_k its gradient
(Euler). For a pin and a slider whose pressure keeps its sign, a_k is constant for a fixed
*pattern* — the direction of a pin's force, the signs of a slider's FN and M'; beyond,
it turns with FN/M' (``curved``) and Newton's method renews it at every pass.

Where a relative velocity is zero the friction direction is undefined: sign(0) = 0 is
used (``AT_REST_RTOL``) and the caller reports those positions.
"""

from __future__ import annotations

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.kinematics import Group
from dyade.model.mechanism import Joint, Revolute

AT_REST_RTOL = 1e-9  # [-] relative velocity below this share of the typical one counts as zero
EDGE = 3.0  # [-] sum of the edge pressures of a linear distribution over L: 3·|M'|/L
TILT = 6.0  # [-] the pressure over the block keeps its sign while 6·|M'| ≤ |FN|·L


def pressure(normal: FloatArray, tilt: FloatArray, length: float) -> FloatArray:
    """N(FN, M') (module docstring): the total normal pressure ∫|p| dx of a block of
    length ``length`` [m] carrying the normal force ``normal`` and the tilting moment
    ``tilt`` with a linear pressure distribution (arrays or floats)."""
    size, turn = np.abs(normal), np.abs(tilt)
    beyond = TILT * turn > size * length
    curved = size * size * (length / (2.0 * TILT)) / np.where(beyond, turn, 1.0)
    curved += EDGE * turn / length
    return np.where(beyond, curved, size)


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
        self.edge = joint.slider_length if joint.edge_friction else 0.0  # L, or 0: no edges
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
        a pin, (FN, M', |FN|) of a slider (FN, M' on the slider; M' None without edges)."""
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
        return pressure(normal, tilt, self.edge), (normal, tilt, size)

    def pattern(self, parts: tuple) -> tuple:
        """A slider's pattern: the signs of FN and M', and whether the pressure changes
        sign over the block (a pin's direction is continuous)."""
        if self.revolute:
            return ()
        if parts[1] is None:
            return (parts[0] > 0.0,)
        return parts[0] > 0.0, parts[1] > 0.0, self.curved(parts)

    def curved(self, parts: tuple) -> FloatArray | None:
        """(n,) bool where a slider's gradient turns with its reactions: the pressure
        changes sign over the block, 6·|M'| > |FN|·L (None: a pin, or no edges)."""
        if self.revolute or parts[1] is None:
            return None
        return TILT * np.abs(parts[1]) > parts[2] * self.edge

    def choices(self) -> list[tuple[float, ...]]:
        """Every pattern a restart may force (``gradient``): the sense of a pin's force
        relative to the one measured; the signs of a slider's FN and, with edges, of M'
        in the bound |FN| + 3·|M'|/L (starts for Newton, which then follows the law's own
        gradient: a block whose pressure changes sign has no constant one)."""
        if self.revolute or not self.edge:
            return [(1.0,), (-1.0,)]
        return [(sn, st) for sn in (1.0, -1.0) for st in (1.0, -1.0)]

    def gradient(self, parts: tuple, forced: tuple | None = None, factor=1.0) -> tuple:
        """``factor``·a, with g = a·W_k at the pattern of ``parts``, or at the ``forced``
        one (``choices``): three (n,) arrays (or 0.0)."""
        if self.revolute:
            wx, wy, size = parts
            scale = factor * self.arm / np.maximum(size, 1e-300)  # |F| = 0: f = 0
            if forced is not None:
                scale *= forced[0]
            return wx * scale, wy * scale, 0.0
        normal, tilt, size = parts
        if tilt is None:
            sn = (np.sign(normal) if forced is None else forced[0]) * factor
            return -self.ay * sn, self.ax * sn, 0.0
        if forced is not None:
            sn, st = forced[0] * factor, forced[1] * (EDGE / self.edge * factor)
        else:  # ∂N/∂FN and ∂N/∂M' (module docstring), 1 and 0 at the bound
            turn = np.abs(tilt)
            beyond = TILT * turn > size * self.edge
            turn = np.where(beyond, turn, 1.0)
            sn = np.where(beyond, normal * (self.edge / TILT) / turn, np.sign(normal))
            ratio = normal / turn
            st = np.where(beyond, np.sign(tilt) * (EDGE / self.edge
                                                   - ratio * ratio * (self.edge / (2.0 * TILT))), 0.0)
            sn *= factor
            st *= factor
        gx = st * self.tx
        gx -= self.ay * sn
        gy = st * self.ty
        gy += self.ax * sn
        return gx, gy, st * self.zeta
