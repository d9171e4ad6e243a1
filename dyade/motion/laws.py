"""Motion laws of VDI 2143: closed forms of the normalised time z in [0, 1].

Each law is a ``Law``: called with z it returns the normalised position s (from 0 at
z = 0 to 1 at z = 1) and its derivatives with respect to z, v = s′, a = s″, j = s‴, all
in closed form and vectorised. A law is a list of pieces (``Piece``), each a polynomial
or a sine of the acceleration on its own interval of z with the integration constants
fixed when the law is built, so that s, v and a are continuous inside the law and exact
at its ends.

The characteristic values (VDI 2143 Blatt 1) are ``C_v = max|s′|``, ``C_a = max|s″|``,
``C_j = max|s‴|`` (inside the law: one-sided limits at the pieces' ends) and
``C_M = max|s′·s″|`` (the dynamic torque factor); they are found on each piece by a
zooming grid converged to ``PEAK_RTOL``.

The ends of a law are classed as in VDI 2143 (``boundary``): R rest (v = 0, a = 0),
U reversal (v = 0, a ≠ 0), G constant velocity (v ≠ 0, a = 0), B motion (v ≠ 0, a ≠ 0).

>>> from dyade.motion.laws import law
>>> cycloid = law("cycloid")
>>> round(cycloid.C_v, 12), round(cycloid.C_a, 4), cycloid.boundary
(2.0, 6.2832, 'R-R')
>>> law("cycloide")
Traceback (most recent call last):
...
dyade.errors.InputError: law = "cycloide" is not a motion law. Did you mean `cycloid`?
"""

from __future__ import annotations

import difflib
import math
import dataclasses
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable

import numpy as np

from dyade.errors import InputError

FloatArray = np.ndarray
PEAK_RTOL = 1e-13  # [-] relative change of a peak between two zooms of its grid
END_ATOL = 1e-12  # [-] |v| or |a| at a law's end below which it counts as zero (its class)
PI = math.pi


# --------------------------------------------------------------------------- pieces
@dataclass(frozen=True)
class Piece:
    """One closed-form piece of a law on z0 <= z <= z1.

    ``kind`` is ``"poly"`` (``coefficients`` of s in powers of (z - z0), lowest first) or
    ``"sine"`` (a = amplitude·sin(omega·(z - z0) + phase), with s(z0) = s0 and
    v(z0) = v0).
    """

    z0: float
    z1: float
    kind: str
    coefficients: tuple[float, ...] = ()
    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0
    s0: float = 0.0
    v0: float = 0.0

    def __call__(self, z: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        u = z - self.z0
        if self.kind == "poly":
            c = np.asarray(self.coefficients, dtype=float)
            out = []
            for _ in range(4):
                out.append(np.polynomial.polynomial.polyval(u, c) + 0.0 * u)
                c = np.polynomial.polynomial.polyder(c) if c.size > 1 else np.zeros(1)
            return out[0], out[1], out[2], out[3]
        amp, w, ph = self.amplitude, self.omega, self.phase
        arg = w * u + ph
        a = amp * np.sin(arg)
        j = amp * w * np.cos(arg)
        v = self.v0 + amp / w * (math.cos(ph) - np.cos(arg))
        s = (self.s0 + (self.v0 + amp / w * math.cos(ph)) * u
             - amp / w**2 * (np.sin(arg) - math.sin(ph)))
        return s, v, a, j

    def scaled(self, factor: float) -> Piece:
        """The same piece with s multiplied by ``factor``."""
        return Piece(self.z0, self.z1, self.kind, tuple(c * factor for c in self.coefficients),
                     self.amplitude * factor, self.omega, self.phase, self.s0 * factor,
                     self.v0 * factor)


def chain(specs: list[tuple[float, float, str, Any]]) -> list[Piece]:
    """Pieces of an acceleration given piece by piece, s and v carried across the joins,
    scaled so that s(1) = 1.

    ``specs``: (z0, z1, "poly", acceleration coefficients in powers of (z - z0)) or
    (z0, z1, "sine", (amplitude, omega, phase)). Starts at s = 0, v = 0.
    """
    pieces, s0, v0 = [], 0.0, 0.0
    for z0, z1, kind, data in specs:
        if z1 <= z0:
            continue
        if kind == "poly":
            acc = np.asarray(data, dtype=float)
            vel = np.polynomial.polynomial.polyint(acc, k=v0)
            pos = np.polynomial.polynomial.polyint(vel, k=s0)
            piece = Piece(z0, z1, "poly", tuple(float(c) for c in pos))
        else:
            amp, w, ph = data
            piece = Piece(z0, z1, "sine", amplitude=amp, omega=w, phase=ph, s0=s0, v0=v0)
        s_end, v_end, _, _ = piece(np.array(z1, dtype=float))
        s0, v0 = float(s_end), float(v_end)
        pieces.append(piece)
    return [piece.scaled(1.0 / s0) for piece in pieces]


def polynomial_piece(coefficients: list[float] | np.ndarray) -> list[Piece]:
    """One polynomial piece on [0, 1] with s = Σ c_k z^k."""
    return [Piece(0.0, 1.0, "poly", tuple(float(c) for c in coefficients))]


# --------------------------------------------------------------------------- the law
def peak(function: Callable[[FloatArray], FloatArray], z0: float, z1: float,
         points: int = 401) -> float:
    """max |function(z)| over z0 <= z <= z1, converged by zooming a grid around the
    largest sample until it changes by less than ``PEAK_RTOL`` (or the bracket is at
    the resolution of a float)."""
    lo, hi = z0, z1
    best = -1.0
    for _ in range(40):
        z = np.linspace(lo, hi, points)
        values = np.abs(function(z))
        k = int(np.argmax(values))
        new = float(values[k])
        step = (hi - lo) / (points - 1)
        if best >= 0 and abs(new - best) <= PEAK_RTOL * max(new, 1e-300) and step < 1e-6:
            return max(new, best)
        best = max(best, new)
        lo, hi = max(z0, z[k] - step), min(z1, z[k] + step)
        if hi - lo < 1e-15:
            break
    return best


def end_class(velocity: float, acceleration: float) -> str:
    """VDI 2143 class of a law's end from its normalised velocity and acceleration:
    R rest, U reversal, G constant velocity, B motion."""
    moving, accelerating = abs(velocity) > END_ATOL, abs(acceleration) > END_ATOL
    return {(False, False): "R", (False, True): "U", (True, False): "G",
            (True, True): "B"}[(moving, accelerating)]


@dataclass(frozen=True)
class Law:
    """A motion law: s(z) from s(0) = 0 to s(1) = 1 over the normalised time z in [0, 1].

    Call it with z (array) for ``(s, v, a, j)``: the position and its first three
    derivatives with respect to z [-]. Outside [0, 1] the end pieces are extrapolated.

    Examples
    --------
    >>> import numpy as np
    >>> from dyade.motion.laws import LAWS
    >>> s, v, a, j = LAWS["modified-sine"](np.array([0.0, 0.5, 1.0]))
    >>> s.round(12).tolist(), round(LAWS["modified-sine"].C_v, 4)
    ([0.0, 0.5, 1.0], 1.7596)
    """

    name: str
    """key of the law in ``LAWS`` (``"modified-sine"``)"""
    title: str
    """its name in words (``"modified sine"``)"""
    pieces: tuple[Piece, ...]
    """closed-form pieces covering [0, 1] in order"""
    params: dict[str, Any] = field(default_factory=dict)
    """the parameters it was built with (``law(name, **params)``)"""

    def __call__(self, z: Any) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        z = np.asarray(z, dtype=float)
        if len(self.pieces) == 1:
            s, v, a, j = self.pieces[0](z)
            return (np.broadcast_to(s, z.shape).copy(), np.broadcast_to(v, z.shape).copy(),
                    np.broadcast_to(a, z.shape).copy(), np.broadcast_to(j, z.shape).copy())
        starts = np.array([p.z0 for p in self.pieces[1:]])
        which = np.searchsorted(starts, z, side="right")
        out = [np.empty(z.shape) for _ in range(4)]
        for k, piece in enumerate(self.pieces):          # a loop over pieces, not over z
            mask = which == k
            if mask.any():
                for target, values in zip(out, piece(z[mask])):
                    target[mask] = values
        return out[0], out[1], out[2], out[3]

    def ends(self) -> tuple[tuple[float, float, float, float], tuple[float, float, float, float]]:
        """(s, v, a, j) at z = 0 (first piece) and at z = 1 (last piece)."""
        first = tuple(float(x) for x in self.pieces[0](np.array(0.0)))
        last = tuple(float(x) for x in self.pieces[-1](np.array(1.0)))
        return first, last  # type: ignore[return-value]

    @property
    def start_class(self) -> str:
        """VDI 2143 class of the start (R, U, G, B)."""
        (_, v, a, _), _ = self.ends()
        return end_class(v, a)

    @property
    def end_class(self) -> str:
        """VDI 2143 class of the end (R, U, G, B)."""
        _, (_, v, a, _) = self.ends()
        return end_class(v, a)

    @property
    def boundary(self) -> str:
        """The law's boundary class, start-end: ``"R-R"``, ``"R-U"``, ``"G-G"``, ..."""
        return f"{self.start_class}-{self.end_class}"

    def _peak(self, order: int) -> float:
        if order == 4:
            def f(piece: Piece) -> Callable[[FloatArray], FloatArray]:
                return lambda z: piece(z)[1] * piece(z)[2]
        else:
            def f(piece: Piece) -> Callable[[FloatArray], FloatArray]:
                return lambda z: piece(z)[order]
        return max(peak(f(p), p.z0, p.z1) for p in self.pieces)

    @cached_property
    def C_v(self) -> float:
        """Characteristic velocity C_v, the largest magnitude of s′ [-]."""
        return self._peak(1)

    @cached_property
    def C_a(self) -> float:
        """Characteristic acceleration C_a, the largest magnitude of s″ [-]."""
        return self._peak(2)

    @cached_property
    def C_j(self) -> float:
        """Characteristic jerk C_j, the largest magnitude of s‴ [-] (inside the law,
        one-sided at piece joins)."""
        return self._peak(3)

    @cached_property
    def C_M(self) -> float:
        """Characteristic torque factor C_M, the largest magnitude of s′·s″ [-]."""
        return self._peak(4)


# --------------------------------------------------------------------------- builders
def simple_harmonic() -> list[Piece]:
    """s = (1 − cos πz)/2: U-U (acceleration π²/2 at both ends)."""
    return chain([(0.0, 1.0, "sine", (1.0, PI, PI / 2))])


def cycloid() -> list[Piece]:
    """s = z − sin(2πz)/(2π): R-R."""
    return chain([(0.0, 1.0, "sine", (1.0, 2 * PI, 0.0))])


def inclined_sine(velocity: float = 0.0) -> list[Piece]:
    """Bestehorn's inclined sine: s = z − (1 − v_G)·sin(2πz)/(2π), a cycloid about an
    inclined line; the velocity at both ends is v_G (G-G; v_G = 0 is the cycloid)."""
    if not 0.0 <= velocity < 1.0:
        raise InputError.parameter("velocity", f"must be in [0, 1) [-] (the end velocity "
                                   f"s′ at both ends), got {velocity:g}.", value=velocity)
    amp = 2 * PI * (1.0 - velocity)
    return [Piece(0.0, 1.0, "sine", amplitude=amp, omega=2 * PI, phase=0.0, s0=0.0,
                  v0=velocity)]


def modified_sine() -> list[Piece]:
    """Quarter sines of the cycloid's frequency ×2 on the first and last eighth, a
    half sine of the simple harmonic in between: R-R."""
    return chain([(0.0, 1 / 8, "sine", (1.0, 4 * PI, 0.0)),
                  (1 / 8, 7 / 8, "sine", (1.0, 4 * PI / 3, PI / 2)),
                  (7 / 8, 1.0, "sine", (1.0, 4 * PI, -PI / 2))])


def modified_trapezoid() -> list[Piece]:
    """Acceleration trapezoid with quarter-sine ramps, eighths: R-R."""
    return chain([(0.0, 1 / 8, "sine", (1.0, 4 * PI, 0.0)),
                  (1 / 8, 3 / 8, "poly", [1.0]),
                  (3 / 8, 5 / 8, "sine", (1.0, 4 * PI, PI / 2)),
                  (5 / 8, 7 / 8, "poly", [-1.0]),
                  (7 / 8, 1.0, "sine", (1.0, 4 * PI, -PI / 2))])


def acceleration_trapezoid(ramp: float = 0.125) -> list[Piece]:
    """Acceleration trapezoid with straight ramps (constant jerk) of ``ramp`` of the
    segment each: R-R for ramp > 0 (ramp = 1/4 is the triangle), ramp = 0 the
    parabola (constant acceleration, U-U)."""
    r = float(ramp)
    if not 0.0 <= r <= 0.25:
        raise InputError.parameter("ramp", f"must be in [0, 0.25] [-] (each ramp's share "
                                   f"of the segment), got {r:g}.", value=r)
    specs: list[tuple[float, float, str, Any]] = [(0.0, r, "poly", [0.0, 1.0 / r] if r else [1.0]),
                                                  (r, 0.5 - r, "poly", [1.0])]
    specs.append((0.5 - r, 0.5 + r, "poly", [1.0, -1.0 / r] if r else [-1.0]))
    specs += [(0.5 + r, 1.0 - r, "poly", [-1.0]),
              (1.0 - r, 1.0, "poly", [-1.0, 1.0 / r] if r else [0.0])]
    return chain(specs)


@dataclass(frozen=True)
class DoubleHarmonic(Piece):
    """The double harmonic on [0, 1] (a sum of two sines: not one of Piece's kinds)."""

    z0: float = 0.0
    z1: float = 1.0
    kind: str = "double-harmonic"
    factor: float = 1.0
    """s (and its derivatives) multiplied by this"""

    def __call__(self, z: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        z = np.asarray(z, dtype=float)
        c1, c2 = np.cos(PI * z), np.cos(2 * PI * z)
        s1, s2 = np.sin(PI * z), np.sin(2 * PI * z)
        f = self.factor
        s = f * (0.5 * (1 - c1) - 0.125 * (1 - c2))
        v = f * (PI / 2 * s1 - PI / 4 * s2)
        a = f * PI**2 / 2 * (c1 - c2)
        j = f * PI**3 / 2 * (2 * s2 - s1)
        return s, v, a, j

    def scaled(self, factor: float) -> Piece:
        """The same piece with s multiplied by ``factor``."""
        return dataclasses.replace(self, factor=self.factor * factor)


def harmonic_combination() -> list[Piece]:
    """Double harmonic s = (1 − cos πz)/2 − (1 − cos 2πz)/8: starts at rest (R), ends
    at a reversal (U, s″(1) = −π²): a rise into a return without a dwell."""
    return [DoubleHarmonic()]


def polynomial_345() -> list[Piece]:
    """s = 10z³ − 15z⁴ + 6z⁵: R-R."""
    return polynomial_piece([0, 0, 0, 10, -15, 6])


def polynomial_4567() -> list[Piece]:
    """s = 35z⁴ − 84z⁵ + 70z⁶ − 20z⁷: R-R with zero jerk at both ends."""
    return polynomial_piece([0, 0, 0, 0, 35, -84, 70, -20])


def polynomial(v0: float = 0.0, a0: float = 0.0, v1: float = 0.0, a1: float = 0.0) -> list[Piece]:
    """The quintic with s(0) = 0, s(1) = 1 and the given normalised end velocities
    (v0, v1) and accelerations (a0, a1): any boundary class (R, U, G, B at each end)."""
    for name, value in (("v0", v0), ("a0", a0), ("v1", v1), ("a1", a1)):
        if not math.isfinite(float(value)):
            raise InputError.parameter(name, f"must be a finite number [-], got {value!r}.",
                                       value=value)
    # s = v0 z + a0/2 z² + c3 z³ + c4 z⁴ + c5 z⁵ with s(1) = 1, s′(1) = v1, s″(1) = a1
    rhs = np.array([1.0 - v0 - a0 / 2, v1 - v0 - a0, a1 - a0])
    matrix = np.array([[1.0, 1.0, 1.0], [3.0, 4.0, 5.0], [6.0, 12.0, 20.0]])
    c3, c4, c5 = np.linalg.solve(matrix, rhs)
    return polynomial_piece([0.0, v0, a0 / 2, c3, c4, c5])


def quintic_spline(points: Any = ((0.5, 0.5),)) -> list[Piece]:
    """The quintic spline through (0, 0), the given interior points (z, s) and (1, 1),
    continuous to the fourth derivative, at rest at both ends (v = a = 0: R-R)."""
    try:
        inner = np.asarray(points, dtype=float).reshape(-1, 2)
    except (TypeError, ValueError):
        raise InputError.parameter("points", f"must be a list of [z, s] pairs [-], got "
                                   f"{points!r}.", value=points) from None
    knots = np.concatenate([[0.0], inner[:, 0], [1.0]])
    values = np.concatenate([[0.0], inner[:, 1], [1.0]])
    if not np.all(np.isfinite(inner)) or np.any(np.diff(knots) <= 0):
        raise InputError.parameter("points", "must have z strictly increasing inside "
                                   f"(0, 1) [-], got {inner.tolist()}.", value=points)
    n = len(knots) - 1
    size = 6 * n
    matrix, rhs, row = np.zeros((size, size)), np.zeros(size), 0

    def derivative_row(k: int, h: float, order: int) -> np.ndarray:
        coeffs = np.zeros(6)
        for p in range(order, 6):
            coeffs[p] = math.factorial(p) / math.factorial(p - order) * h ** (p - order)
        return coeffs

    for k in range(n):
        h = knots[k + 1] - knots[k]
        matrix[row, 6 * k:6 * k + 6] = derivative_row(k, 0.0, 0)
        rhs[row] = values[k]
        row += 1
        matrix[row, 6 * k:6 * k + 6] = derivative_row(k, h, 0)
        rhs[row] = values[k + 1]
        row += 1
        if k < n - 1:
            for order in range(1, 5):
                matrix[row, 6 * k:6 * k + 6] = derivative_row(k, h, order)
                matrix[row, 6 * k + 6:6 * k + 12] = -derivative_row(k + 1, 0.0, order)
                row += 1
    for order in (1, 2):
        matrix[row, 0:6] = derivative_row(0, 0.0, order)
        row += 1
        matrix[row, 6 * (n - 1):] = derivative_row(n - 1, knots[-1] - knots[-2], order)
        row += 1
    coefficients = np.linalg.solve(matrix, rhs)
    return [Piece(float(knots[k]), float(knots[k + 1]), "poly",
                  tuple(float(c) for c in coefficients[6 * k:6 * k + 6])) for k in range(n)]


def constant_velocity() -> list[Piece]:
    """s = z: constant velocity (G-G), the law of a constant-velocity segment."""
    return polynomial_piece([0.0, 1.0])


BUILDERS: dict[str, tuple[str, Callable[..., list[Piece]]]] = {
    "simple-harmonic": ("simple harmonic", simple_harmonic),
    "cycloid": ("cycloid (sinusoid)", cycloid),
    "inclined-sine": ("inclined sine (Bestehorn)", inclined_sine),
    "modified-sine": ("modified sine", modified_sine),
    "modified-trapezoid": ("modified trapezoid", modified_trapezoid),
    "polynomial-345": ("polynomial 3-4-5", polynomial_345),
    "polynomial-4567": ("polynomial 4-5-6-7", polynomial_4567),
    "polynomial": ("polynomial of given end conditions (quintic)", polynomial),
    "harmonic-combination": ("harmonic combination (double harmonic)", harmonic_combination),
    "acceleration-trapezoid": ("acceleration trapezoid", acceleration_trapezoid),
    "quintic-spline": ("quintic spline through given points", quintic_spline),
    "constant-velocity": ("constant velocity", constant_velocity),
}
"""law name -> (title, builder of its pieces from its parameters)"""

ALIASES = {"sinusoid": "cycloid", "sine": "cycloid", "harmonic": "simple-harmonic",
           "bestehorn": "inclined-sine", "345": "polynomial-345", "3-4-5": "polynomial-345",
           "4567": "polynomial-4567", "4-5-6-7": "polynomial-4567",
           "polynomial-3-4-5": "polynomial-345", "polynomial-4-5-6-7": "polynomial-4567",
           "double-harmonic": "harmonic-combination", "trapezoid": "acceleration-trapezoid",
           "spline": "quintic-spline", "linear": "constant-velocity"}
"""other names users write -> the law's name"""


def canonical(name: str) -> str:
    """The law's name in ``LAWS`` for a name as a user writes it (case, ``_`` or spaces
    for ``-``, aliases); raises ``InputError`` with a did-you-mean for an unknown one."""
    key = "-".join(str(name).strip().lower().replace("_", " ").replace("-", " ").split())
    key = ALIASES.get(key, key)
    if key in BUILDERS:
        return key
    close = difflib.get_close_matches(key, [*BUILDERS, *ALIASES], n=1, cutoff=0.6)
    hint = (f" Did you mean `{ALIASES.get(close[0], close[0])}`?" if close
            else f" Known laws: {', '.join(BUILDERS)}.")
    raise InputError.parameter("law", f"= \"{name}\" is not a motion law.{hint}", value=name)


def law(name: str, **params: Any) -> Law:
    """The motion law ``name`` built with its parameters.

    Parameters
    ----------
    name : str
        A law of ``LAWS`` (case, ``_`` or spaces for ``-`` and a few other names such as
        ``"sinusoid"`` or ``"3-4-5"`` accepted).
    **params
        Its parameters: ``velocity`` (inclined-sine), ``ramp`` (acceleration-trapezoid),
        ``v0, a0, v1, a1`` (polynomial: normalised end conditions), ``points``
        (quintic-spline: interior [z, s] pairs).

    Returns
    -------
    Law
        Call it with z for (s, v, a, j); ``C_v``, ``C_a``, ``C_j``, ``C_M``,
        ``boundary``.

    Raises
    ------
    InputError
        An unknown name (with a did-you-mean), an unknown or bad parameter.

    Examples
    --------
    >>> from dyade.motion.laws import law
    >>> trapezoid = law("acceleration-trapezoid", ramp=0.25)   # the triangle
    >>> round(trapezoid.C_a, 6), trapezoid.boundary
    (8.0, 'R-R')
    >>> [round(float(x), 6) for x in law("3-4-5")([0.5])[1]]   # s′ at the middle
    [1.875]
    """
    key = canonical(name)
    title, builder = BUILDERS[key]
    import inspect
    allowed = list(inspect.signature(builder).parameters)
    for given in params:
        if given not in allowed:
            close = difflib.get_close_matches(given, allowed, n=1, cutoff=0.6)
            hint = (f" Did you mean `{close[0]}`?" if close else
                    f" It takes {', '.join(allowed)}." if allowed else " It takes none.")
            raise InputError.parameter(given, f"is not a parameter of the law {key}.{hint}",
                                       value=params[given])
    return Law(key, title, tuple(builder(**params)), dict(params))


LAWS: dict[str, Law] = {name: law(name) for name in BUILDERS}
"""law name -> the law with its default parameters"""
