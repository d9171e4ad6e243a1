"""The search of a path synthesis: candidates drawn in blocks, each block traced through
dyade's positions-only stage (``dyade.linkage.positions``) as variants × positions,
filtered, matched to the target, its best kept; the best of all refined by a local
least-squares fit (scipy).

Block k draws its candidates from the generator seeded (seed, round, k): the same seed
gives the same candidates on any number of workers, and the best are merged by (error,
candidate number), so the result does not depend on how the blocks were spread.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from dyade.arrays import FloatArray, Variants
from dyade.synthesis.shape import (OPEN_SAMPLES, SAMPLES, closed_match, open_match,
                                   resample, timed_match)
from dyade.synthesis.topology import Placement, Topology


@dataclass(frozen=True, slots=True)
class Settings:
    """How candidates are drawn, filtered and matched."""

    bounds: dict[str, tuple[float, float]]
    """dimension -> (least, largest) [m] (canonical frame)"""
    candidates: int = 20_000
    block: int = 2_000
    method: str = "lhs"
    """"lhs" (Latin hypercube per block) or "random" """
    seed: int = 0
    positions: int = 100
    """crank angles per turn of the first pass"""
    min_transmission: float = 0.0
    """the least transmission angle over the turn [rad] a candidate may have"""
    regions: tuple = ()
    """(pivot index (0: A0, 1: B0), x least, x largest, y least, y largest) [m]: where
    the placed candidate's frame pivots must lie"""
    variants: tuple[int, ...] = (1, -1)
    scale: bool = True
    """the match is free in scale"""
    keep: int = 40
    """candidates each block hands back"""
    rounds: int = 2
    """rounds of drawing: each after the first draws around the best so far"""


@dataclass(slots=True, eq=False)
class Found:
    """The best candidates of a search, best first."""

    values: FloatArray
    """(k, dimensions) canonical dimensions [m]"""
    variant: np.ndarray
    """(k,) int assembly variant"""
    error: FloatArray
    """(k,) the first pass's shape distance [-]"""
    number: np.ndarray
    """(k,) the candidate's number (round·10⁹ + index)"""
    evaluated: int = 0
    """candidates traced"""
    assembled: int = 0
    """of these, those that assemble over the turn and pass the filters"""


def draw(settings: Settings, names: tuple[str, ...], block: int, round_: int = 0,
         around: Found | None = None, spread: float = 0.15) -> FloatArray:
    """The candidates of block ``block`` of round ``round_``: (block size, dimensions) [m]
    and a column of variants; a round after the first draws about ``around``'s best
    (a normal spread of ``spread`` of each bound's width)."""
    rng = np.random.default_rng([settings.seed, round_, block])
    n = settings.block
    lows = np.array([settings.bounds[k][0] for k in names])
    highs = np.array([settings.bounds[k][1] for k in names])
    if around is not None and len(around.values):
        pick = rng.integers(0, len(around.values), n)
        values = around.values[pick] + rng.normal(size=(n, len(names))) * spread * (highs - lows)
        values = np.clip(values, lows, highs)
        return np.column_stack([values, around.variant[pick]])
    if settings.method == "lhs":
        unit = (rng.permuted(np.tile(np.arange(n), (len(names), 1)), axis=1).T
                + rng.random((n, len(names)))) / n
    else:
        unit = rng.random((n, len(names)))
    variant = rng.choice(np.array(settings.variants), n)
    return np.column_stack([lows + unit * (highs - lows), variant])


SENTINEL = 0.7182818284590452
"""the template's stand-in for dimension k is SENTINEL + k/1024: numbers no reader
arithmetic on lengths in metres turns into another of them"""
_TEMPLATES: dict = {}
"""(topology, variant) -> the mechanism read once from stand-ins (per process)"""


def template(topology: Topology, variant: int):
    """The topology's mechanism read once (``dyade.files.mechanism.build``) with a
    stand-in number for each dimension: the candidates' mechanisms are this one with
    their numbers put in (``stacked``), without reading each block again."""
    key = (topology.name, variant)
    if key not in _TEMPLATES:
        from dyade.files.mechanism import build

        stand_ins = {name: SENTINEL + k / 1024 for k, name in enumerate(topology.names)}
        data = topology.data(stand_ins, variant)
        data["sweep"] = {"start": 0.0, "stop": 0.0, "step": 1.0}
        _TEMPLATES[key] = (build(data), {v: k for k, v in enumerate(stand_ins.values())})
    return _TEMPLATES[key]


def _substitute(value, index: dict, columns: list):
    """``value`` with every stand-in number replaced by its dimension's column."""
    import dataclasses

    if type(value) is float:
        k = index.get(value)
        return value if k is None else columns[k]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        changes = {}
        for f in dataclasses.fields(value):
            part = getattr(value, f.name)
            mapped = _substitute(part, index, columns)
            if mapped is not part:
                changes[f.name] = mapped
        return dataclasses.replace(value, **changes) if changes else value
    if isinstance(value, dict):
        items = {k: _substitute(v, index, columns) for k, v in value.items()}
        return items if any(items[k] is not v for k, v in value.items()) else value
    if isinstance(value, tuple) and not hasattr(value, "_fields"):
        parts = tuple(_substitute(v, index, columns) for v in value)
        return parts if any(p is not v for p, v in zip(parts, value)) else value
    return value


def traced(topology: Topology, values: FloatArray, variant: int, crank: FloatArray):
    """(curves (candidates, positions) complex [m], assembles (candidates,) bool, least
    transmission (candidates,) [rad]): the coupler point of each candidate through the
    positions-only stage, the candidates as one stacked mechanism (``stacked``), the
    crank angles ``crank`` the same for each."""
    from dyade.linkage.positions import positions

    count = len(values)
    template_, index = template(topology, variant)  # numbers one per candidate, unspread
    mechanism = _substitute(template_, index, [Variants(values[:, k])
                                               for k in range(values.shape[1])])
    point = mechanism.links[topology.coupler].points["P"]
    found = positions(mechanism, crank, [(topology.coupler, point)], repeat=count,
                      angles=False)
    # the (x, y) pairs read as complex numbers where they lie: x + iy without a copy
    z = np.ascontiguousarray(found.points[:, 0, :]).view(np.complex128)
    z = z.reshape(count, crank.size)
    closes = found.closes.reshape(count, crank.size).all(axis=1)
    with np.errstate(invalid="ignore"):
        least = np.arcsin(np.clip(np.nanmin(found.conditioning.reshape(count, -1), axis=1),
                                  0.0, 1.0))
    return z, closes, np.where(closes, least, 0.0)


@dataclass(eq=False)
class Block:
    """One block of a path search: a callable for any executor (it pickles)."""

    topology: Topology
    settings: Settings
    target: np.ndarray
    """the target resampled (``shape.resample``), or its points where ``crank`` is
    given, complex [m]"""
    round_: int = 0
    around: Found | None = None
    spread: float = 0.15
    crank: np.ndarray | None = None
    """the target points' crank angles [rad] (from an unknown zero); None: no timing"""
    closed: bool = True
    """without timing: the target is a closed curve (else a part of one, ``target``
    resampled as an open curve, matched to every window: ``shape.open_match``)"""

    def inside(self, values: FloatArray, match) -> np.ndarray:
        """(candidates,) bool: the placed frame pivots lie in the settings' regions."""
        if not self.settings.regions:
            return np.ones(len(values), dtype=bool)
        return within(pivots(values, match, complex(np.mean(self.target))),
                      self.settings.regions)

    def __call__(self, block: int) -> Found:
        s = self.settings

        def score(values: FloatArray, curves: np.ndarray) -> FloatArray:
            if self.crank is not None:
                match = timed_match(self.target, self.crank, curves, s.scale)
            elif not self.closed:
                match = open_match(self.target, curves, scale=s.scale)
            else:
                match = closed_match(self.target, resample(curves, SAMPLES), scale=s.scale)
            return np.where(self.inside(values, match), match.error, np.inf)

        return drawn_block(self.topology, s, block, self.round_, self.around, self.spread,
                           score)


def drawn_block(topology: Topology, s: Settings, block: int, round_: int,
                around: Found | None, spread: float,
                score: Callable[[FloatArray, np.ndarray], FloatArray]) -> Found:
    """Block ``block`` of round ``round_``: its candidates drawn, those whose crank turns
    traced through dyade's positions stage per assembly variant, the ones that close with
    the least transmission angle allowed scored by ``score(values, curves)`` (an error
    per candidate, inf: rejected), the best ``s.keep`` kept (every search's block)."""
    drawn = draw(s, topology.names, block, round_, around, spread)
    values, variant = drawn[:, :-1], drawn[:, -1].astype(int)
    error = np.full(len(values), np.inf)
    crank = np.linspace(0.0, 2.0 * np.pi, s.positions, endpoint=False)
    turns = topology.turns(values)
    kept = 0
    for sign in s.variants:
        rows = np.flatnonzero(turns & (variant == sign))
        if not rows.size:
            continue
        curves, closes, least = traced(topology, values[rows], sign, crank)
        ok = closes & (least >= s.min_transmission)
        kept += int(ok.sum())
        if ok.any():
            error[rows[ok]] = score(values[rows[ok]], curves[ok])
    order = np.argsort(error, kind="stable")[:s.keep]
    order = order[np.isfinite(error[order])]
    number = round_ * 10 ** 9 + block * s.block + order
    return Found(values[order], variant[order], error[order], number,
                 evaluated=len(values), assembled=kept)


def pivots(values: FloatArray, match, centre: complex) -> np.ndarray:
    """(candidates, 2) complex: the frame pivots A0 and B0 (canonical (0, 0) and (d, 0))
    placed by each candidate's best similarity onto a target of centroid ``centre``."""
    origin = centre - match.factor * match.centre
    return np.column_stack([origin, origin + match.factor * values[:, 3]]) \
        if values.shape[1] == 6 else np.column_stack([origin, origin])


def within(placed: np.ndarray, regions: tuple) -> np.ndarray:
    """(candidates,) bool: every placed pivot lies in its region."""
    ok = np.ones(len(placed), dtype=bool)
    for index, x0, x1, y0, y1 in regions:
        z = placed[:, index]
        ok &= (z.real >= x0) & (z.real <= x1) & (z.imag >= y0) & (z.imag <= y1)
    return ok


def merge(parts: list[Found], keep: int) -> Found:
    """The best ``keep`` of several blocks' bests, by (error, candidate number)."""
    values = np.concatenate([p.values for p in parts]) if parts else np.zeros((0, 0))
    variant = np.concatenate([p.variant for p in parts]) if parts else np.zeros(0, int)
    error = np.concatenate([p.error for p in parts]) if parts else np.zeros(0)
    number = np.concatenate([p.number for p in parts]) if parts else np.zeros(0, int)
    order = np.lexsort((number, error))[:keep]
    return Found(values[order], variant[order], error[order], number[order],
                 sum(p.evaluated for p in parts), sum(p.assembled for p in parts))


def run_blocks(function, blocks: list[int], jobs: int = 1, executor=None, progress=None):
    """``function(block)`` for every block: here, on ``jobs`` processes
    (``dyade.parallel``) or on ``executor`` (its ``map``), in the blocks' order;
    ``progress(result)`` hears each as it comes."""
    if executor is not None:
        results = executor.map(function, blocks)
    else:
        from dyade.parallel import ordered_map

        results = ordered_map(function, blocks, jobs)
    out = []
    for result in results:
        out.append(result)
        if progress is not None:
            progress(result)
    return out


def search(topology: Topology, target: np.ndarray, settings: Settings, jobs: int = 1,
           executor=None, progress=None, crank: np.ndarray | None = None,
           closed: bool = True) -> Found:
    """The best candidates for a path ``target`` (complex points [m], in order along the
    curve, start and timing unknown; ``closed``: a closed curve, else a part of one).

    Round 0 draws ``settings.candidates`` in blocks; each later round draws as many
    again about the best so far, closer each time. ``progress(evaluated, total, best)``
    hears every block.
    """
    if crank is not None:
        resampled = np.asarray(target)
    elif closed:
        resampled = resample(np.asarray(target)[None, :], SAMPLES)[0]
    else:
        resampled = resample(np.asarray(target)[None, :], OPEN_SAMPLES, closed=False)[0]
    blocks = max(1, math.ceil(settings.candidates / settings.block))
    total = blocks * settings.block * settings.rounds
    state = {"done": 0, "best": math.inf}

    def heard(found: Found) -> None:
        state["done"] += found.evaluated
        if len(found.error):
            state["best"] = min(state["best"], float(found.error[0]))
        if progress is not None:
            progress(state["done"], total, state["best"])

    best = None
    parts_all: list[Found] = []
    for round_ in range(settings.rounds):
        spread = 0.15 / (3.0 ** (round_ - 1)) if round_ else 0.0
        function = Block(topology, settings, resampled, round_, best, spread, crank, closed)
        parts = run_blocks(function, list(range(blocks)), jobs, executor, heard)
        parts_all += parts
        best = merge(parts_all, settings.keep)
    return best


# -- the local fit ---------------------------------------------------------------------
MAX_STEPS = 150
"""Levenberg–Marquardt steps of a local fit at most (an exact target converges in
tens; one the topology cannot reach stops here)"""

@dataclass(slots=True, eq=False)
class Fitted:
    """A candidate fitted to the target points by least squares."""

    values: FloatArray
    """canonical dimensions, scaled to the world [m]"""
    variant: int
    placement: Placement
    crank: FloatArray
    """(N,) the crank angle of each target point, canonical [rad]"""
    error: float
    """RMS distance to the target points over the target's RMS radius [-]"""
    rms: float
    """RMS distance to the target points [m]"""
    converged: bool
    notes: list[str] = field(default_factory=list)


def fit(topology: Topology, values: FloatArray, variant: int, target: np.ndarray,
        crank: FloatArray | None = None, tolerance: float = 1e-12,
        start: Placement | None = None) -> Fitted:
    """Fit one candidate to the target points by scipy's least squares: its dimensions,
    its placement (origin, angle; the scale is in the dimensions) and each point's crank
    angle (none given: timing unknown) or one crank offset (``crank`` given: the
    points' crank angles relative to an unknown zero).

    ``start``: the candidate's placement from the shape match (the best similarity);
    each point's crank angle starts at the nearest point of the placed curve.
    """
    least_squares = scipy_least_squares()
    target = np.asarray(target, dtype=complex)
    values = np.asarray(values, dtype=float)
    start = start or Placement()
    world = values * start.scale
    dims = world.size
    if crank is None:  # each point's crank angle from the nearest point of the curve
        dense = np.linspace(0.0, 2.0 * np.pi, 720, endpoint=False)
        curve = start.origin + np.exp(1j * start.angle) * topology.path(world, variant, dense)[0]
        nearest = np.nanargmin(np.abs(target[:, None] - curve[None, :]), axis=1)
        angles = np.unwrap(dense[nearest])
        x0 = np.concatenate([world, [start.origin.real, start.origin.imag, start.angle], angles])
    else:
        relative = np.asarray(crank, dtype=float)
        x0 = np.concatenate([world, [start.origin.real, start.origin.imag, start.angle], [0.0]])
    size = float(np.sqrt(np.mean(np.abs(target - target.mean()) ** 2)))

    def placed(x):
        dims_, (ox, oy, theta) = x[:dims], x[dims:dims + 3]
        phi = x[dims + 3:] if crank is None else x[dims + 3] + relative
        z = topology.path(dims_, variant, phi)[0]
        return complex(ox, oy) + np.exp(1j * theta) * z

    def residual(x):
        miss = placed(x) - target
        out = np.concatenate([miss.real, miss.imag]) / size
        return np.where(np.isfinite(out), out, 10.0)

    if crank is not None:  # the crank offset: the best of a coarse scan first
        offsets = np.linspace(0.0, 2.0 * np.pi, 72, endpoint=False)
        costs = []
        for offset in offsets:
            x0[dims + 3] = offset
            costs.append(float(np.sum(residual(x0) ** 2)))
        x0[dims + 3] = offsets[int(np.argmin(costs))]
    def jacobian(x):  # central differences: one column per dimension and placement
        columns = np.empty((2 * target.size, x.size))  # number, all φ_i at once (each
        for k in range(dims + 3 + (crank is not None)):  # residual pair has its own)
            h = 1e-7 * max(1.0, abs(x[k]))
            up, down = x.copy(), x.copy()
            up[k] += h
            down[k] -= h
            columns[:, k] = (residual(up) - residual(down)) / (2.0 * h)
        if crank is None:
            h = 1e-7
            up, down = x.copy(), x.copy()
            up[dims + 3:] += h
            down[dims + 3:] -= h
            change = (residual(up) - residual(down)) / (2.0 * h)
            columns[:, dims + 3:] = 0.0
            count = target.size
            columns[np.arange(count), dims + 3 + np.arange(count)] = change[:count]
            columns[count + np.arange(count), dims + 3 + np.arange(count)] = change[count:]
        return columns

    size_ = max(size, 1e-300)
    for _ in range(max(1, dims // 6) ** 2):  # more dimensions, more steps: in stages of
        solution = least_squares(residual, x0, jac=jacobian, method="lm", xtol=1e-15,
                                 ftol=1e-15, gtol=1e-15, max_nfev=MAX_STEPS)  # MAX_STEPS,
        x0 = solution.x  # stopped once the fit meets the target
        reached = np.sqrt(np.mean(np.abs(placed(x0) - target) ** 2)) / size_
        if solution.success or reached <= tolerance:
            break
    x = solution.x
    miss = np.abs(placed(x) - target)
    rms = float(np.sqrt(np.mean(miss ** 2))) if np.all(np.isfinite(miss)) else math.inf
    phi = x[dims + 3:] if crank is None else x[dims + 3] + relative
    placement = Placement(complex(x[dims], x[dims + 1]), 1.0, float(x[dims + 2]))
    fitted = x[:dims].copy()
    return Fitted(fitted, variant, placement, np.asarray(phi, dtype=float), rms / size, rms,
                  bool(solution.success) or rms / size <= tolerance)


def placement_of(match_factor: complex, candidate_centre: complex, target: np.ndarray
                 ) -> Placement:
    """The similarity of a shape match as a placement: x_world = mean(target) +
    α·(x − centre) = origin + α·x."""
    centre = complex(np.mean(resample(np.asarray(target)[None, :], SAMPLES)[0]))
    return Placement(centre - match_factor * candidate_centre, float(abs(match_factor)),
                     float(np.angle(match_factor)))


def scipy_least_squares():
    """scipy's least_squares, or a clear error when scipy (the study extra) is missing."""
    try:
        from scipy.optimize import least_squares
    except ImportError:
        from dyade.errors import MissingExtra

        raise MissingExtra("the local fit of a synthesis needs scipy, which is not "
                           "installed: pip install \"dyade[study]\".") from None
    return least_squares
