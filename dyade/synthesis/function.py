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


def three_points(phi: FloatArray, output: FloatArray, method: str,
                 equation: str) -> tuple[FloatArray, FloatArray]:
    """The three crank angles [rad] and outputs a closed form is solved through: the
    table's own three rows (``method`` "precision"), else three Chebyshev-spaced angles of
    the table's range with the output interpolated; refused with an ``InputError`` on the
    file's key where the table cannot give them."""
    if method == "precision":
        if phi.size != 3:
            raise InputError(f"precision points: {equation} needs exactly three, got "
                             f"{phi.size} (for more, use method = \"chebyshev\" or "
                             f"\"fit\").", key="target.method")
        return phi, output
    if phi.size < 3:
        raise InputError(f"a function table needs at least three rows, got {phi.size}.",
                         key="target.crank")
    if np.any(np.diff(phi) <= 0):
        raise InputError("the table's crank angles must ascend.", key="target.crank")
    chosen = closed.chebyshev(phi[0], phi[-1], 3)
    return chosen, np.interp(chosen, phi, output)


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
    chosen, values = three_points(phi, np.unwrap(psi), method, "Freudenstein's equation")
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


# -- a motion profile as the target ------------------------------------------------------
RATIO = (0.2, 5.0)
"""a profile's four-bar: each of a, b, c between these multiples of the frame d"""
MIN_TRANSMISSION = np.radians(20.0)
"""a profile's four-bar: the least transmission angle over the range when the problem
states none [rad] (a fit would otherwise use a near-dead-centre's sharp turn)"""
OFFSET_GRID = 36
"""the starting offsets tried per axis (every 10°): the crank angle of the profile's
master zero and the output angle of its zero"""


@dataclass(slots=True, eq=False)
class Offsets:
    """Where a profile sits on the four-bar: ψ = output + s(φ − crank) [rad]."""

    crank: float
    """the crank angle φ (from the frame line) at the profile's master zero [rad]"""
    output: float
    """the output angle ψ (from the frame line) where the profile's s = 0 [rad]"""
    fitted: bool
    """found by the synthesis (else given in the file)"""


def _batched(phi: FloatArray, psi: FloatArray, frame: float):
    """Freudenstein's four-bars of many triples at once: (G, 3) φ and ψ [rad] ->
    a, b, c (G,) [m] and the variant (G,) (NaN where the triple gives none)."""
    matrix = np.stack([np.cos(psi), -np.cos(phi), np.ones_like(phi)], axis=-1)
    det = np.linalg.det(matrix)
    good = np.abs(det) > 1e-9
    matrix[~good] = np.eye(3)
    k = np.linalg.solve(matrix, np.cos(phi - psi)[..., None])[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        a, c = frame / k[:, 0], frame / k[:, 1]
        square = a * a + c * c + frame * frame - 2.0 * a * c * k[:, 2]
        b = np.where(good & (square > 0.0) & np.isfinite(a) & np.isfinite(c),
                     np.sqrt(np.abs(square)), np.nan)
    ax, ay = a * np.cos(phi[:, 0]), a * np.sin(phi[:, 0])
    bx, by = frame + c * np.cos(psi[:, 0]), c * np.sin(psi[:, 0])
    variant = np.where((bx - ax) * (0.0 - ay) - (by - ay) * (frame - ax) < 0.0, 1, -1)
    return a, b, c, variant


def transmission(a, b, c, d, phi):
    """The transmission angle μ between coupler and rocker folded to [0, π/2] [rad]
    at crank angles φ (broadcast; NaN where the four-bar does not close)."""
    with np.errstate(invalid="ignore"):
        cosine = (b * b + c * c - (a * a + d * d - 2.0 * a * d * np.cos(phi))) / (
            2.0 * b * np.abs(c))
        mu = np.arccos(np.where(np.abs(cosine) <= 1.0, cosine, np.nan))
    return np.minimum(mu, np.pi - mu)


def _batched_output(a, b, c, d, variant, phi):
    """ψ (G, N) [rad] of the four-bars (G,) at crank angles (G, N) (NaN: open)."""
    ax, ay = a[:, None] * np.cos(phi), a[:, None] * np.sin(phi)
    up = closed.rrr(ax, ay, d, 0.0, b[:, None], np.abs(c)[:, None], 1)
    down = closed.rrr(ax, ay, d, 0.0, b[:, None], np.abs(c)[:, None], -1)
    x = np.where(variant[:, None] > 0, up[0], down[0])
    y = np.where(variant[:, None] > 0, up[1], down[1])
    return np.arctan2(y, x - d) + np.where(c > 0, 0.0, np.pi)[:, None]


def from_profile(master: FloatArray, lift: FloatArray, method: str = "fit",
                 frame: float = 1.0, crank_zero: float | None = None,
                 output_zero: float | None = None, lift_at=None,
                 min_transmission: float = MIN_TRANSMISSION) -> tuple[Generated, Offsets]:
    """Synthesise a four-bar whose output angle follows a motion profile s(x) over
    the crank angle: ψ(φ0 + x) = ψ0 + s(x).

    Parameters
    ----------
    master, lift : ndarray, shape (N,)
        The profile's master angles x [rad], ascending, and its output s(x) [rad]
        (``dyade.motion.profile.evaluate``).
    method : {"precision", "chebyshev", "fit"}
        "precision" and "chebyshev": through three Chebyshev-spaced points of the
        range; "fit": then the least squares of the structural error over every row,
        the offsets included where they are free.
    crank_zero, output_zero : float, optional
        φ0 and ψ0 [rad]; None: found (a grid of starts every 10°, the one of least
        largest structural error, then fitted).
    lift_at : callable, optional
        s at any master angles [rad] (the profile itself): the precision points' values;
        None: interpolated in the rows.
    min_transmission : float
        The least transmission angle over the range [rad]: starts below it are not
        tried, the fit is held above it.

    Returns
    -------
    (Generated, Offsets)
        Its crank angles are φ0 + x, its target ψ0 + s.
    """
    x, s = np.asarray(master, dtype=float), np.asarray(lift, dtype=float)
    if x.size < 3:
        raise InputError(f"a profile target needs at least three rows, got {x.size}.",
                         key="target.rows")
    grid = np.arange(OFFSET_GRID) * (2.0 * np.pi / OFFSET_GRID)
    phi0 = grid if crank_zero is None else np.array([crank_zero])
    psi0 = grid if output_zero is None else np.array([output_zero])
    phi0, psi0 = (v.ravel() for v in np.meshgrid(phi0, psi0, indexing="ij"))
    chosen = closed.chebyshev(x[0], x[-1], 3)
    values = np.interp(chosen, x, s) if lift_at is None else np.asarray(lift_at(chosen))
    a, b, c, variant = _batched(phi0[:, None] + chosen, psi0[:, None] + values, frame)
    psi = _batched_output(a, b, c, frame, variant, phi0[:, None] + x)
    worst = np.max(np.abs(wrap(psi - psi0[:, None] - s)), axis=1)
    lengths = np.stack([np.abs(a), b, np.abs(c)]) / frame
    usable = np.all((lengths >= RATIO[0]) & (lengths <= RATIO[1]), axis=0)  # NaN: False
    mu = transmission(a[:, None], b[:, None], c[:, None], frame, phi0[:, None] + x)
    usable &= np.min(mu, axis=1) >= min_transmission  # NaN: False
    worst = np.where(np.isfinite(worst) & usable, worst, np.inf)
    if not np.isfinite(worst).any():
        from dyade.errors import DyadeError

        raise DyadeError("no four-bar through three Chebyshev points of the profile moves "
                         "over its whole range on one assembly branch, for any placement "
                         "tried (every 10° of crank and output angle, links between "
                         f"{RATIO[0]:g} and {RATIO[1]:g} times the frame, a transmission angle "
                         f"of at least {np.degrees(min_transmission):.4g}°): a range this long "
                         "or a motion this large is beyond a four-bar; shorten target.range "
                         "(or leave target.crank_zero and output_zero to the synthesis).")
    starts = np.argsort(worst)[:3 if method == "fit" else 1]
    best = None
    for k in starts:  # a few local fits: a loop over candidates, each vectorised
        linkage = closed.FourBar(float(a[k]), float(b[k]), float(c[k]), frame,
                                 variant=int(variant[k]))
        zero = (float(phi0[k]), float(psi0[k]))
        if method == "fit":
            linkage, zero = _fit_offsets(linkage, zero, x, s, crank_zero is None,
                                         output_zero is None, min_transmission)
        miss = np.abs(wrap(closed.output_angle(linkage, zero[0] + x) - zero[1] - s))
        least = np.min(transmission(linkage.a, linkage.b, linkage.c, frame, zero[0] + x))
        score = float(np.max(miss)) if np.isfinite(miss).all() else np.inf
        score = score if least >= min_transmission * (1 - 1e-6) else np.inf
        if best is None or score < best[0]:
            best = (score, linkage, zero)
    if not np.isfinite(best[0]):  # every fit left the transmission bound: the best start
        k = starts[0]
        linkage = closed.FourBar(float(a[k]), float(b[k]), float(c[k]), frame,
                                 variant=int(variant[k]))
        best = (None, linkage, (float(phi0[k]), float(psi0[k])))
    _, linkage, zero = best
    crank, target = x + zero[0], s + zero[1]
    precision = chosen + zero[0] if method != "fit" else np.zeros(0)
    made = Generated(linkage, crank, target, traced(linkage, crank), precision, method)
    return made, Offsets(zero[0], zero[1], crank_zero is None or output_zero is None)


def _fit_offsets(start: closed.FourBar, zero: tuple[float, float], x: FloatArray,
                 s: FloatArray, free_crank: bool, free_output: bool,
                 min_transmission: float = 0.0):
    """The least squares of the structural error over (a, b, c) and the free offsets,
    d fixed, the transmission angle held above ``min_transmission`` by a penalty."""
    from dyade.synthesis.search import scipy_least_squares

    least_squares = scipy_least_squares()

    signs = np.sign([start.a, 1.0, start.c])

    def unpack(v):  # lengths by their logarithms within RATIO, their signs kept
        a, b, c = signs * np.exp(v[:3]) * start.d
        phi0 = v[3] if free_crank else zero[0]
        psi0 = v[3 + free_crank] if free_output else zero[1]
        return closed.FourBar(a, b, c, start.d, variant=start.variant), phi0, psi0

    def residual(v):
        trial, phi0, psi0 = unpack(v)
        miss = wrap(closed.output_angle(trial, phi0 + x) - psi0 - s)
        mu = transmission(trial.a, trial.b, trial.c, trial.d, phi0 + x)
        below = np.where(np.isfinite(mu), np.maximum(min_transmission - mu, 0.0), 1.0)
        return np.concatenate([np.where(np.isfinite(miss), miss, 1.0), 10.0 * below])

    low, high = np.log(RATIO)
    v0 = list(np.clip(np.log(np.abs([start.a, start.b, start.c]) / start.d), low, high))
    v0 += [zero[0]] * free_crank + [zero[1]] * free_output
    n = len(v0)
    v = least_squares(residual, v0, method="trf", bounds=([low] * 3 + [-np.inf] * (n - 3),
                                                          [high] * 3 + [np.inf] * (n - 3)),
                      xtol=1e-13, ftol=1e-13, gtol=1e-13, max_nfev=150).x
    trial, phi0, psi0 = unpack(v)
    linkage = closed.FourBar(float(trial.a), float(trial.b), float(trial.c), start.d,
                             variant=start.variant)
    return linkage, (float(phi0), float(psi0))
