"""Function generation with a four-bar: the output angle ψ over the crank angle φ, both
from the frame line A0→B0 (``dyade.synthesis.closed``), through three precision points
(Freudenstein), three Chebyshev-spaced points of a table, or a least-squares fit of the
whole table started from them; the structural error ψ_traced − ψ_target at every row,
traced through dyade's positions-only stage.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.errors import InputError
from dyade.synthesis import closed

OUTPUT = 4
"""the output link (the rocker)"""


def data(linkage: closed.FourBar, speed_rpm: float = 60.0,
         sweep: tuple[float, float, float] = (0.0, 360.0, 1.0), name: str = "",
         masses: dict | None = None) -> dict:
    """The mechanism file (as data, lengths in m, angles in degrees) of a function
    generator in the frame A0 = (0, 0), B0 = (d, 0): a negative ``a`` puts the crank pin
    at (a, 0) of the crank's frame (the point ``pin``), so that the crank angle is the
    one of the target; a negative ``c`` turns the output link's frame by 180° (its
    angle is then ψ + 180°: ``output_offset``)."""
    crank: dict = {"pivot": "A0", "length": abs(linkage.a), "speed_rpm": speed_rpm}
    pin = "tip"
    if linkage.a < 0:
        crank["points"] = {"pin": [linkage.a, 0.0]}
        pin = "pin"
    out = {"name": name or "Function generator (synthesised)",
           "units": {"length": "m", "angle": "deg"},
           "sweep": {"start": sweep[0], "stop": sweep[1], "step": sweep[2]},
           "frame": {"points": {"A0": [0.0, 0.0], "B0": [linkage.d, 0.0]}},
           "crank": crank,
           "dyad": [{"kind": "RRR", "links": [3, 4], "A": {"link": 2, "point": pin},
                     "C": {"link": 1, "point": "B0"},
                     "lengths": [linkage.b, abs(linkage.c)], "variant": linkage.variant}]}
    if masses:
        from dyade.synthesis.topology import bar

        per, each = masses.get("per_length"), masses.get("each")
        out["links"] = {"2": bar(abs(linkage.a), per, each), "3": bar(linkage.b, per, each),
                        "4": bar(abs(linkage.c), per, each)}
    return out


def output_offset(linkage: closed.FourBar) -> float:
    """ψ − the output link's angle in dyade [rad]: 0, or π for a negative ``c``."""
    return 0.0 if linkage.c > 0 else -np.pi


def traced(linkage: closed.FourBar, crank: FloatArray) -> FloatArray:
    """ψ at every crank angle φ [rad], through dyade's positions-only stage; NaN where
    the linkage does not close."""
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions

    mechanism = build(data(linkage))
    found = positions(mechanism, np.asarray(crank, dtype=float), [(OUTPUT, (1.0, 0.0))])
    b = found.points[:, 0, 0] - linkage.d + 1j * found.points[:, 0, 1]
    return np.angle(b) - output_offset(linkage)


def wrap(angle: FloatArray) -> FloatArray:
    """An angle difference in (−π, π] [rad]."""
    return np.angle(np.exp(1j * np.asarray(angle)))


@dataclass(slots=True, eq=False)
class Generated:
    """A function generator and how well it follows the target."""

    linkage: closed.FourBar
    crank: FloatArray
    """(N,) the target's crank angles [rad]"""
    target: FloatArray
    """(N,) the target's output angles [rad]"""
    traced: FloatArray
    """(N,) the output angles the linkage gives, through dyade [rad]"""
    precision: FloatArray
    """(k,) the precision points' crank angles [rad] (none for a fit)"""
    method: str

    @property
    def error(self) -> FloatArray:
        """(N,) the structural error ψ_traced − ψ_target [rad]"""
        return wrap(self.traced - self.target)


def generate(crank: FloatArray, output: FloatArray, method: str = "chebyshev",
             frame: float = 1.0) -> Generated:
    """Synthesise a four-bar function generator.

    Parameters
    ----------
    crank, output : ndarray, shape (N,)
        The target: φ_i and ψ_i [rad], from the frame line; φ ascending.
    method : {"precision", "chebyshev", "fit"}
        "precision": through the three rows given (N = 3); "chebyshev": through three
        Chebyshev-spaced points of the table's range (ψ interpolated); "fit": the least
        squares of the structural error over every row, from the Chebyshev solution.
    frame : float
        d [m].
    """
    phi, psi = np.asarray(crank, dtype=float), np.asarray(output, dtype=float)
    if method == "precision":
        if phi.size != 3:
            raise InputError(f"precision points: Freudenstein's equation needs exactly "
                             f"three, got {phi.size} (for more, use method = \"chebyshev\" "
                             f"or \"fit\").", key="target.method")
        chosen, values = phi, psi
    else:
        if phi.size < 3:
            raise InputError(f"a function table needs at least three rows, got {phi.size}.",
                             key="target.crank_deg")
        if np.any(np.diff(phi) <= 0):
            raise InputError("the table's crank angles must ascend.", key="target.crank_deg")
        chosen = closed.chebyshev(phi[0], phi[-1], 3)
        values = np.interp(chosen, phi, np.unwrap(psi))
    linkage = closed.freudenstein(chosen, values, frame)
    miss = np.abs(wrap(traced(linkage, chosen) - values))
    if not np.all(miss < 1e-9):  # (NaN: it does not close there)
        from dyade.errors import DyadeError

        raise DyadeError("branch defect: Freudenstein's four-bar through the precision points "
                         f"at φ = {', '.join(f'{v:.6g}°' for v in np.rad2deg(chosen))} reaches "
                         "them on different assembly branches (it cannot move from one to "
                         "the next); choose other points or angle ranges.")
    if method == "fit":
        linkage = _fit(linkage, phi, psi)
        chosen = np.zeros(0)
    return Generated(linkage, phi, psi, traced(linkage, phi), chosen, method)


def _fit(start: closed.FourBar, phi: FloatArray, psi: FloatArray) -> closed.FourBar:
    """The least squares of the structural error over (a, b, c), d fixed."""
    from dyade.synthesis.search import scipy_least_squares

    least_squares = scipy_least_squares()

    def residual(x):
        trial = closed.FourBar(x[0], x[1], x[2], start.d, variant=start.variant)
        miss = wrap(closed.output_angle(trial, phi) - psi)
        return np.where(np.isfinite(miss), miss, 1.0)

    x = least_squares(residual, [start.a, start.b, start.c], method="lm", xtol=1e-14,
                      ftol=1e-14).x
    return closed.FourBar(float(x[0]), float(abs(x[1])), float(x[2]), start.d,
                          variant=start.variant)
