"""Function generation with a slider-crank: the slider's position s over the crank
angle φ, both in the frame of the crank's pivot A0 = (0, 0) with the guide along x
through (0, e); s is the x of the slider's pin B.

The loop (s − a·cos φ)² + (e − a·sin φ)² = b² is, expanded,

    s² = K1·s·cos φ + K2·sin φ + K3,   K1 = 2a, K2 = 2a·e, K3 = b² − a² − e²,

linear in (K1, K2, K3): three precision points give them by one 3×3 solve (the
slider-crank's Freudenstein equation), a table by linear least squares; a = K1/2,
e = K2/K1, b² = K3 + a² + e². The slider reaches each point on the branch
σ = sign(s − a·cos φ), the same at every point or the linkage cannot pass from one to
the next. A table or a motion law is then fitted by the least squares of the structural
error s_traced − s_target (scipy), a law's unknown start s0 (s = s0 + lift) with it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import DyadeError, InputError

LINK = 3
"""the conrod, which carries the slider's pin B at (b, 0) of its frame (point P)"""


@dataclass(frozen=True, slots=True)
class SliderCrank:
    """An in-frame slider-crank for function generation. ``a`` may be negative: the
    crank pin then lies at (a, 0) in the crank's frame, so that the crank angle stays
    the one asked for."""

    a: float
    """crank [m]"""
    b: float
    """conrod [m]"""
    e: float
    """the guide's offset [m] (through (0, e), along x)"""
    variant: int = 1
    """σ: the slider ahead of (+1) or behind (−1) the crank pin along x"""


def position(linkage: SliderCrank, crank: FloatArray) -> FloatArray:
    """s at the crank angles φ [rad] in closed form [m]; NaN where it does not close."""
    phi = np.asarray(crank, dtype=float)
    with np.errstate(invalid="ignore"):
        run = np.sqrt(linkage.b ** 2 - (linkage.e - linkage.a * np.sin(phi)) ** 2)
    return linkage.a * np.cos(phi) + linkage.variant * run


def turns(linkage: SliderCrank) -> bool:
    """The crank turns fully: b > |a| + |e|."""
    return linkage.b > abs(linkage.a) + abs(linkage.e)


def data(linkage: SliderCrank, speed_rpm: float = 60.0,
         sweep: tuple[float, float, float] = (0.0, 360.0, 1.0), name: str = "",
         masses: dict | None = None) -> dict:
    """The mechanism file (as data, lengths in m, angles in degrees); the slider's pin
    is the conrod's point P (what ``dyade analyse`` traces)."""
    from dyade.synthesis.topology import SliderCrank as Topology

    made = Topology().data({"a": abs(linkage.a), "b": linkage.b, "e": linkage.e,
                            "p": linkage.b, "q": 0.0}, linkage.variant, speed_rpm=speed_rpm,
                           masses=masses, sweep=sweep,
                           name=name or "Slider-crank function generator (synthesised)")
    if linkage.a < 0:  # the pin on the other side of the pivot: the crank angle kept
        made["crank"]["points"] = {"pin": [linkage.a, 0.0]}
        made["dyad"][0]["A"]["point"] = "pin"
    return made


def traced(linkage: SliderCrank, crank: FloatArray) -> FloatArray:
    """s at every crank angle φ [m], through dyade's positions-only stage (the file
    ``data`` writes); NaN where it does not close."""
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions

    mechanism = build(data(linkage))
    point = mechanism.links[LINK].points["P"]
    found = positions(mechanism, np.asarray(crank, dtype=float), [(LINK, point)])
    return np.where(found.closes, found.points[:, 0, 0], np.nan)


def precision(crank: FloatArray, output: FloatArray) -> SliderCrank:
    """The slider-crank through three precision points (φ_i [rad], s_i [m]) in closed
    form.

    Raises
    ------
    DyadeError
        The three points give no slider-crank (b² ≤ 0, a singular system) or reach
        them on both branches.
    """
    phi, s = np.asarray(crank, dtype=float), np.asarray(output, dtype=float)
    matrix = np.column_stack([s * np.cos(phi), np.sin(phi), np.ones(3)])
    if abs(np.linalg.det(matrix)) < 1e-12 * max(1.0, np.abs(matrix).max()) ** 3:
        raise DyadeError("the three precision points give no slider-crank: their equations "
                         "are dependent (two points coincide, or the positions do not "
                         "change); choose other points.")
    k1, k2, k3 = np.linalg.solve(matrix, s * s)
    return _from_k(k1, k2, k3, phi, s)


def _from_k(k1: float, k2: float, k3: float, phi: FloatArray, s: FloatArray) -> SliderCrank:
    a = 0.5 * k1
    if abs(a) < 1e-300:
        raise DyadeError("the precision points give a crank of no length: choose points "
                         "at which the slider moves.")
    e = k2 / k1
    square = k3 + a * a + e * e
    if not square > 0.0:
        raise DyadeError(f"no slider-crank passes through the precision points: they ask "
                         f"for a conrod of b² = {square:.6g} m² ≤ 0; choose other points "
                         f"or a wider range.")
    sides = np.sign(s - a * np.cos(phi))
    if np.any(sides != sides[0]):
        raise DyadeError("branch defect: the slider-crank through the precision points at "
                         f"φ = {', '.join(f'{v:.6g}°' for v in np.rad2deg(phi))} reaches "
                         "them on both sides of the crank pin (it cannot move from one to "
                         "the next); choose other points or ranges.")
    return SliderCrank(float(a), float(np.sqrt(square)), float(e), int(sides[0]) or 1)


@dataclass(slots=True, eq=False)
class Generated:
    """A slider-crank function generator and how well it follows the target."""

    linkage: SliderCrank
    crank: FloatArray
    """(N,) the target's crank angles [rad]"""
    target: FloatArray
    """(N,) the target's slider positions [m]"""
    traced: FloatArray
    """(N,) the positions the linkage gives, through dyade [m]"""
    precision: FloatArray
    """(k,) the precision points' crank angles [rad] (none for a fit)"""
    method: str
    start: float = 0.0
    """a motion law's s0: the position where its lift is zero [m] (found)"""

    @property
    def error(self) -> FloatArray:
        """(N,) the structural error s_traced − s_target [m]"""
        return self.traced - self.target


def generate(crank: FloatArray, output: FloatArray, method: str = "chebyshev") -> Generated:
    """Synthesise a slider-crank function generator.

    Parameters
    ----------
    crank, output : ndarray, shape (N,)
        The target: φ_i [rad] (ascending) and s_i [m].
    method : {"precision", "chebyshev", "fit"}
        "precision": through the three rows given (N = 3); "chebyshev": through three
        Chebyshev-spaced points of the table's range (s interpolated); "fit": the least
        squares of the structural error over every row, from the linear least squares
        of the loop equation.
    """
    from dyade.synthesis.function import three_points

    phi, s = np.asarray(crank, dtype=float), np.asarray(output, dtype=float)
    chosen, values = three_points(phi, s, method, "the slider-crank's equation")
    if method == "fit":
        linkage = _fit(_linear(phi, s), phi, s)
        chosen = np.zeros(0)
    else:
        linkage = precision(chosen, values)
    return Generated(linkage, phi, s, traced(linkage, phi), chosen, method)


def _linear(phi: FloatArray, s: FloatArray) -> SliderCrank:
    """The linear least squares of the loop equation over every row (a start)."""
    matrix = np.column_stack([s * np.cos(phi), np.sin(phi), np.ones_like(phi)])
    k1, k2, k3 = np.linalg.lstsq(matrix, s * s, rcond=None)[0]
    return _from_k(k1, k2, k3, phi, s)


def _fit(start: SliderCrank, phi: FloatArray, s: FloatArray, free_start: bool = False
         ) -> SliderCrank | tuple[SliderCrank, float]:
    """The least squares of the structural error over (a, b, e) (and s0, the
    target's unknown start, where ``free_start``: s_target = s0 + s)."""
    from dyade.synthesis.search import scipy_least_squares

    least_squares = scipy_least_squares()
    scale = float(np.ptp(s)) or 1.0

    def residual(x):
        trial = SliderCrank(x[0], x[1], x[2], start.variant)
        miss = (position(trial, phi) - s - (x[3] if free_start else 0.0)) / scale
        return np.where(np.isfinite(miss), miss, 10.0)

    x0 = [start.a, start.b, start.e] + ([0.0] if free_start else [])
    x = least_squares(residual, x0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15).x
    made = SliderCrank(float(x[0]), float(abs(x[1])), float(x[2]), start.variant)
    return (made, float(x[3])) if free_start else made


def from_law(crank: FloatArray, lift: FloatArray, method: str = "fit") -> Generated:
    """Synthesise a slider-crank whose slider follows a motion law over the crank
    angle: s(φ) = s0 + lift(φ), s0 unknown.

    s0 moves the positions, which the loop equation does not absorb: for each s0 of a
    scan over a few strokes, the linear least squares of the loop equation, the one of
    least largest structural error kept; "fit" then refines (a, b, e, s0) together,
    "precision"/"chebyshev" keep the three Chebyshev points' closed form at that s0.
    """
    from dyade.synthesis import closed

    phi, h = np.asarray(crank, dtype=float), np.asarray(lift, dtype=float)
    stroke = float(np.ptp(h))
    if not stroke > 0:
        raise InputError("the motion law does not move the slider over the range.",
                         key="target.profile")
    best, worst = None, np.inf
    for s0 in np.linspace(0.6, 8.0, 75) * stroke:  # the guide's foot behind the stroke
        for sign in (1.0, -1.0):
            s = sign * s0 + h
            try:
                linkage = _linear(phi, s)
            except DyadeError:
                continue
            miss = np.nanmax(np.abs(position(linkage, phi) - s)) if np.isfinite(
                position(linkage, phi)).all() else np.inf
            if not turns(linkage):  # a crank that cannot turn fully only after all others
                miss += 1e3 * stroke
            if miss < worst:
                best, worst = (linkage, sign * s0), miss
    if best is None:
        raise DyadeError("no slider-crank follows the motion law: the loop equation has no "
                         "solution for any start of the stroke tried.")
    linkage, s0 = best
    if method == "fit":
        linkage, shift = _fit(linkage, phi, h + s0, free_start=True)
        s0 += shift
        chosen = np.zeros(0)
    else:
        chosen = closed.chebyshev(phi[0], phi[-1], 3)
        linkage = precision(chosen, s0 + np.interp(chosen, phi, h))
    made = Generated(linkage, phi, s0 + h, traced(linkage, phi), chosen, method, s0)
    return made
