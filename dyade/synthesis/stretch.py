"""A straight-line or circular-arc stretch of a coupler curve over a given crank range:
the largest deviation from the best line (circle) over the stretch's length, for every
window of the crank turn at once, vectorised over the candidates.

Line: the principal axis of the window's points (the direction ½·arg Σ(z − z̄)²), the
deviation the distance from it, the length the extent along it. Arc: Kåsa's algebraic
circle, the deviation | |z − c| − R |, the length the arc R·Δ(angle about c).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.synthesis.search import Found, Settings, drawn_block
from dyade.synthesis.topology import Topology

PART = 256
"""candidates scored at once (their windows' points in memory together)"""


def deviation(points: np.ndarray, kind: str = "line") -> FloatArray:
    """(...,) the largest deviation over the length of each row of ``points`` (...,
    w) complex [-]; inf where a point is NaN or the stretch has no length."""
    z = np.asarray(points)
    u = z - z.mean(axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        if kind == "line":
            turn = np.exp(-0.5j * np.angle((u * u).sum(axis=-1)))
            v = u * turn[..., None]
            length = v.real.max(axis=-1) - v.real.min(axis=-1)
            out = np.abs(v.imag).max(axis=-1) / length
        else:
            x, y = u.real, u.imag
            a = np.stack([x, y, np.ones_like(x)], axis=-1)
            b = -(x * x + y * y)
            normal = np.einsum("...ki,...kj->...ij", a, a)
            right = np.einsum("...ki,...k->...i", a, b)
            solved = np.linalg.solve(normal + 1e-300, right[..., None])[..., 0]
            centre = -0.5 * (solved[..., 0] + 1j * solved[..., 1])
            radius = np.sqrt(np.abs(centre) ** 2 - solved[..., 2])
            rel = u - centre[..., None]
            swept = np.unwrap(np.angle(rel), axis=-1)
            length = radius * np.abs(swept[..., -1] - swept[..., 0])
            out = np.abs(np.abs(rel) - radius[..., None]).max(axis=-1) / length
    return np.where(np.isfinite(out), out, np.inf)


def circle(points: np.ndarray) -> tuple[complex, float]:
    """Kåsa's algebraic circle through the points (N,) complex: (centre, radius) [m]."""
    z = np.asarray(points)
    mean = z.mean()
    u = z - mean
    a = np.column_stack([u.real, u.imag, np.ones(u.size)])
    solved = np.linalg.lstsq(a, -(u.real ** 2 + u.imag ** 2), rcond=None)[0]
    centre = -0.5 * (solved[0] + 1j * solved[1])
    return complex(mean + centre), float(np.sqrt(abs(centre) ** 2 - solved[2]))


def best_window(curves: np.ndarray, window: int, kind: str = "line"
                ) -> tuple[FloatArray, np.ndarray]:
    """(score (C,), start (C,)): the best window of ``window`` consecutive samples of
    each closed curve (C, M) (wrapping around the turn)."""
    count, m = curves.shape
    index = (np.arange(m)[:, None] + np.arange(window)[None, :]) % m
    score = np.empty(count)
    start = np.empty(count, dtype=int)
    for lo in range(0, count, PART):
        part = curves[lo:lo + PART][:, index]  # (part, M, window)
        values = deviation(part, kind)
        start[lo:lo + PART] = np.argmin(values, axis=1)
        score[lo:lo + PART] = values[np.arange(len(values)), start[lo:lo + PART]]
    return score, start


@dataclass(eq=False)
class StretchBlock:
    """One block of a stretch search (a callable for any executor)."""

    topology: Topology
    settings: Settings
    stretch: float
    """the crank range [rad]"""
    kind: str = "line"
    round_: int = 0
    around: Found | None = None
    spread: float = 0.15

    def __call__(self, block: int) -> Found:
        s = self.settings
        window = int(math.ceil(self.stretch / (2.0 * np.pi / s.positions))) + 1

        def score(values: FloatArray, curves: np.ndarray) -> FloatArray:
            return best_window(curves, window, self.kind)[0]

        return drawn_block(self.topology, s, block, self.round_, self.around, self.spread,
                           score)


@dataclass(slots=True, eq=False)
class Refined:
    values: FloatArray
    variant: int
    start: float
    """the stretch's first crank angle [rad]"""
    error: float
    """largest deviation over the length [-]"""


def refine(topology: Topology, values: FloatArray, variant: int, stretch: float,
           bounds: dict[str, tuple[float, float]], kind: str = "line", least: float = 0.0,
           samples: int = 61) -> Refined:
    """Nelder–Mead on the dimensions (within ``bounds``) and the stretch's start, the
    stretch traced in closed form at ``samples`` crank angles; the linkage must close
    over the whole turn with a transmission angle of at least ``least`` [rad]."""
    from dyade.synthesis.search import scipy_least_squares

    scipy_least_squares()  # (scipy there, or a clear error)
    from scipy.optimize import minimize

    full = np.linspace(0.0, 2.0 * np.pi, 360, endpoint=False)
    along = np.linspace(0.0, stretch, samples)
    free = [k for k, name in enumerate(topology.names) if name != "d"]
    lows = np.array([bounds[topology.names[k]][0] for k in free])
    highs = np.array([bounds[topology.names[k]][1] for k in free])
    base = np.asarray(values, dtype=float).copy()
    curve = topology.path(base, variant, full)[0]
    window = int(round(stretch / (2 * np.pi / 360))) + 1
    _, first = best_window(curve[None, :], window, kind)

    def unpack(x):
        dims = base.copy()
        dims[free] = x[:-1]
        return dims, x[-1]

    def cost(x):
        dims, start = unpack(x)
        if np.any(x[:-1] < lows) or np.any(x[:-1] > highs):
            return 1e3
        if not topology.turns(dims[None, :])[0]:
            return 1e3
        if least > 0.0 and transmission(topology, dims, variant, full) < least:
            return 1e3
        return float(deviation(topology.path(dims, variant, start + along)[0], kind))

    x0 = np.concatenate([base[free], [full[first[0]]]])
    result = minimize(cost, x0, method="Nelder-Mead",
                      options={"xatol": 1e-10, "fatol": 1e-14, "maxiter": 2000,
                               "maxfev": 2500, "adaptive": True})
    dims, start = unpack(result.x)
    return Refined(dims, variant, float(start), float(result.fun))


def transmission(topology: Topology, dims: FloatArray, variant: int, crank: FloatArray
                 ) -> float:
    """The least transmission angle over ``crank`` [rad] (four-bar: at B between the
    coupler and the rocker; slider-crank: between the conrod and the guide's normal)."""
    from dyade.synthesis.closed import rrr

    if hasattr(topology, "chain"):  # a six-bar: the least of its two dyads'
        return sixbar_transmission(topology, dims, variant, crank)
    if topology.name != "fourbar":
        a, b, e = dims[0], dims[1], dims[2]
        return float(np.nanmin(np.arccos(np.clip(np.abs(e - a * np.sin(crank)) / b, 0, 1))))
    a, b, c, d = dims[:4]
    ax, ay = a * np.cos(crank), a * np.sin(crank)
    bx, by = rrr(ax, ay, d, 0.0, b, c, variant)
    sin = np.abs((bx - ax) * by - (by - ay) * (bx - d)) / (b * c)
    return float(np.nanmin(np.arcsin(np.clip(sin, 0.0, 1.0))))


def sixbar_transmission(topology: Topology, dims: FloatArray, variant: int,
                        crank: FloatArray) -> float:
    """A six-bar's least transmission angle over ``crank`` [rad]: of the four-bar's
    dyad at B and of the second dyad at F (between E–F and G–F)."""
    from dyade.synthesis.topology import FourBar

    first, second = topology.dyad_variants(variant)
    least = transmission(FourBar(), dims[:4], first, crank)
    f, g = dims[8], dims[9]
    # F from the path's coupler point with P at F: (p, q) = (f, 0)
    at_f = dims.copy()
    at_f[10], at_f[11] = f, 0.0
    at_e = dims.copy()
    at_e[10], at_e[11] = 0.0, 0.0
    z_f = topology.path(at_f, variant, crank)[0]
    z_e = topology.path(at_e, variant, crank)[0]
    z_g = _anchor(topology, dims, variant, crank)
    sin = np.abs(((z_f - z_e).conjugate() * (z_f - z_g)).imag) / (f * g)
    return float(min(least, np.nanmin(np.arcsin(np.clip(sin, 0.0, 1.0)))))


def _anchor(topology: Topology, dims: FloatArray, variant: int, crank: FloatArray):
    """G of a six-bar's second dyad at each crank angle (complex [m], canonical)."""
    from dyade.synthesis.closed import rrr

    a, b, c, d, _, _, gx, gy = dims[:8]
    first, _ = topology.dyad_variants(variant)
    ax, ay = a * np.cos(crank), a * np.sin(crank)
    bx, by = rrr(ax, ay, d, 0.0, b, c, first)
    g = complex(gx, gy)
    if topology.anchor == 1:
        return np.full(crank.shape, g)
    origin, toward = {2: (0j, ax + 1j * ay), 3: (ax + 1j * ay, bx + 1j * by),
                      4: (d + 0j, bx + 1j * by)}[topology.anchor]
    unit = (toward - origin) / np.abs(toward - origin)
    return origin + unit * g
