"""Six-bars (``dyade.synthesis.topology.SixBar``) for function and pose targets: no
closed form, so a search of many candidates (Latin hypercube over the bounds, each
assembly variant, traced in closed form as candidates × positions) and the least
squares (scipy) of the best few, each result checked through dyade's positions stage.

- function: the output angle ψ of link 6 (the second dyad's link at G) against the
  crank angle φ, both from the frame line (the crank's pivot at the origin, the frame
  pivot B0 at (d, 0) with d the problem's frame); unknowns a, b, c, E, G, f, g (nine;
  and ψ0 for a motion law whose output zero is not given);
- poses: link 5 (the second coupler) through poses (its point P, its angle); unknowns
  the twelve dimensions, the placement (origin, angle) and each pose's crank angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from dyade.errors import DyadeError, InputError
from dyade.synthesis.function import wrap

FUNCTION_DIMS = ("a", "b", "c", "ex", "ey", "gx", "gy", "f", "g")
"""the dimensions a function fit varies (d is the frame, P plays no part)"""
POSE_TOLERANCE = 1e-9
"""[-] a pose counts as reached within this times the poses' size (and this in rad)"""
STARTS = 6
POSE_STEPS = 600
"""least-squares steps of a pose fit at most"""
FIT_STAGES = ((60, STARTS), (1000, 2))
"""(least-squares steps, starts): every start a few steps, then the best two on"""
EXACT = 1e-13
"""[rad] a fit this close at every row ends the refinement of further starts"""
LENGTHS = ("a", "b", "c", "d", "f", "g")
"""the dimensions that are lengths (positive)"""
PENALTY = 10.0
"""[-] the weight of a fit's residual that holds the transmission angle above its limit
(the share below the limit, in rad)"""
MARGIN = 1e-3
"""[-] the penalty acts from (1 + MARGIN) times the limit: where a fit leans on it, its
balance with the misses stays above the limit itself (checked exactly afterwards)"""
TRIAL = 64
"""candidates of the timed trial that estimates a run before it starts"""
FIT_SHARE = {"function": 1.0, "poses": 0.5}
"""[-] the time of a target's least-squares fits over that of their step cap's worth of
timed trial steps, about (measured on the guide's and the templates' targets: a function
fit takes 0.6-0.8 of its steps, each dearer than the trial's; the pose fits end early)"""
STEP_OVERHEAD = 3e-4
"""[s] scipy's own work per least-squares step (trust region, its small SVD), about"""


@dataclass(eq=False)
class SixGenerated:
    """A six-bar function generator and how well it follows the target (the fields of
    ``dyade.synthesis.function.Generated`` the table and figure use)."""

    crank: np.ndarray
    """(N,) the target's crank angles [rad]"""
    target: np.ndarray
    """(N,) the target's output angles [rad]"""
    traced: np.ndarray
    """(N,) link 6's angle there, through dyade [rad]"""
    dense: tuple[np.ndarray, np.ndarray]
    """(crank angles, link 6's angle) over the range, through dyade [rad]"""
    precision: np.ndarray = field(default_factory=lambda: np.zeros(0))
    method: str = "fit"

    @property
    def error(self) -> np.ndarray:
        """(N,) the structural error ψ_traced − ψ_target [rad]"""
        return wrap(self.traced - self.target)


def _bounds(topology, problem, scale: float, fixed: dict) -> dict:
    bounds = {k: (lo * scale, hi * scale) for k, (lo, hi) in topology.defaults.items()}
    bounds.update(problem.bounds)
    bounds.update(fixed)
    return bounds


def _draw(problem, names, bounds, count: int, round_: int, around=None, spread=0.15):
    """(count, dimensions) candidates and a column of variants, seeded (seed, round)."""
    from dyade.synthesis.topology import SixBar

    rng = np.random.default_rng([problem.seed, 7, round_])
    lows = np.array([bounds[k][0] for k in names])
    highs = np.array([bounds[k][1] for k in names])
    if around is not None:
        values, variants = around
        pick = rng.integers(0, len(values), count)
        drawn = values[pick] + rng.normal(size=(count, len(names))) * spread * (highs - lows)
        return np.clip(drawn, lows, highs), variants[pick]
    unit = (rng.permuted(np.tile(np.arange(count), (len(names), 1)), axis=1).T
            + rng.random((count, len(names)))) / count
    return lows + unit * (highs - lows), rng.choice(np.array(SixBar.variants), count)


def _estimate(problem, names, bounds, score, step, steps: int) -> float:
    """The time of a six-bar search and its fits [s], from a timed trial: ``score`` of
    ``TRIAL`` candidates (per candidate, times the candidates of every round) and
    ``step(values)`` (one least-squares step of a fit: its residual and Jacobian)
    times its cap ``steps`` and the target's ``FIT_SHARE``."""
    from dyade.synthesis.cost import timed

    values, _ = _draw(problem, names, bounds, TRIAL, 0)
    per = timed(lambda: score(values, 1)) / TRIAL
    count = max(problem.candidates, 10) * problem.rounds
    share = FIT_SHARE[problem.target.kind]
    return per * count + (timed(lambda: step(values)) + STEP_OVERHEAD) * steps * share


def _search(problem, names, bounds, score, progress=None):
    """The best ``STARTS``·2 candidates by ``score(values, variant) -> (candidates,)``
    (inf: rejected) over the problem's rounds: (values, variants, errors, evaluated,
    assembled)."""
    count = max(problem.candidates, 10)
    best = None
    evaluated = assembled = 0
    pool_v, pool_s, pool_e = [], [], []
    total = count * problem.rounds
    for round_ in range(problem.rounds):
        spread = 0.15 / 3.0 ** (round_ - 1) if round_ else 0.0
        values, variants = _draw(problem, names, bounds, count, round_, best, spread)
        error = np.full(count, np.inf)
        for start in range(0, count, problem.block):  # blocks: a loop over candidates' blocks
            rows = np.arange(start, min(count, start + problem.block))
            for sign in np.unique(variants[rows]):
                picked = rows[variants[rows] == sign]
                error[picked] = score(values[picked], int(sign))
            evaluated += rows.size
            if progress is not None:
                progress(evaluated, total, float(np.min(error)) if np.isfinite(error).any()
                         else math.inf)
        assembled += int(np.isfinite(error).sum())
        pool_v.append(values)
        pool_s.append(variants)
        pool_e.append(error)
        every = np.concatenate(pool_e)
        order = np.argsort(every, kind="stable")[:40]
        order = order[np.isfinite(every[order])]
        if not order.size:
            continue
        best = (np.concatenate(pool_v)[order], np.concatenate(pool_s)[order])
    every = np.concatenate(pool_e)
    order = np.argsort(every, kind="stable")[:2 * STARTS]
    order = order[np.isfinite(every[order])]
    return (np.concatenate(pool_v)[order], np.concatenate(pool_s)[order], every[order],
            evaluated, assembled)


def jacobian(residuals):
    """The Jacobian of ``residual(x) = residuals(x[None])[0]`` by central differences,
    every column's two trials in one call of ``residuals`` (trials as candidates)."""
    def jac(x):
        h = 1e-7 * np.maximum(1.0, np.abs(x))
        step = np.diag(h)
        out = residuals(np.concatenate([x + step, x - step]))
        return ((out[:x.size] - out[x.size:]) / (2.0 * h[:, None])).T
    return jac


# -- function generation ---------------------------------------------------------------
def function(problem, progress=None, check_time=None):
    """The function target of a six-bar problem as its result (``dyade.synthesis``).

    ``check_time(seconds, what)`` hears the run's estimate (a timed trial) before the
    search; a candidate or fit whose smaller transmission angle (of both dyads) over the
    table's crank range falls below ``problem.min_transmission`` is rejected."""
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions
    from dyade.synthesis.designs import Design, Result, speed_rpm
    from dyade.synthesis.search import scipy_least_squares
    from dyade.synthesis.topology import TOPOLOGIES

    topology = TOPOLOGIES[problem.topology]
    target = problem.target
    free_zero = False
    if target.profile is not None:
        from dyade.motion.profile import evaluate

        master = np.linspace(target.crank[0], target.crank[-1], target.rows)
        crank = master + (target.zeros[0] or 0.0)
        output = evaluate(target.profile, master).s
        free_zero = target.zeros[1] is None
        output = output + (0.0 if free_zero else target.zeros[1])
    else:
        crank, output = np.asarray(target.crank), np.asarray(target.output)
    frame = problem.frame
    dense = np.linspace(crank.min(), crank.max(), 61)  # one branch over the whole range
    where = np.concatenate([crank, dense])
    bounds = _bounds(topology, problem, frame, {"d": (frame, frame)})
    names = topology.names
    index = [names.index(k) for k in FUNCTION_DIMS]

    least = problem.min_transmission

    def angle_of(values, variant, at, mu=False):
        """link 6's angle ψ (and with ``mu`` the smaller transmission angle) at ``at``."""
        with np.errstate(invalid="ignore", divide="ignore"):
            loops = topology.loops(values, variant, at)
        psi = np.angle(loops[3] - loops[4])
        return (psi, topology.transmission(values, variant, at, loops)) if mu else psi

    def misses(psi, zero=None):
        miss = wrap(psi - output)
        if free_zero:  # the best output zero: the circular mean of the misses
            zero = np.angle(np.mean(np.exp(1j * miss), axis=-1, keepdims=True)) \
                if zero is None else zero
            miss = wrap(miss - zero)
        return miss

    def score(values, variant):
        psi, mu = angle_of(values, variant, where, True) if least > 0.0 else (
            angle_of(values, variant, where), None)
        ok = np.isfinite(psi).all(axis=1)
        if mu is not None:
            with np.errstate(invalid="ignore"):
                ok &= np.min(mu, axis=1) >= least  # NaN: rejected
        miss = misses(psi[:, :crank.size])
        return np.where(ok, np.sqrt(np.mean(miss ** 2, axis=1)), np.inf)

    unknowns = len(index) + free_zero
    if check_time is not None:
        steps = sum(cap * going for cap, going in FIT_STAGES)
        check_time(_estimate(problem, names, bounds, score,
                             lambda v: (score(v[:1], 1), score(v[:1], 1),  # ~2 residuals a step
                                        score(v[:2 * unknowns], 1)), steps),
                   f"{problem.name}: {max(problem.candidates, 10) * problem.rounds:,} "
                   f"{topology.title} six-bars and the least squares of the best {STARTS}")
    values, variants, _, evaluated, assembled = _search(problem, names, bounds, score,
                                                        progress)
    if not len(values):
        raise _none_assembled(problem, topology, evaluated, "closes over the table's crank "
                                                            "range on one branch")
    least_squares = scipy_least_squares()  # only now: importing scipy takes a while
    def problem_of(full, variant):
        """(residual, its Jacobian, unpack) of a start's fit."""
        def residuals(xs):  # (trials, unknowns) -> (trials, rows)
            trial = np.tile(full, (len(xs), 1))
            trial[:, index] = xs[:, :len(index)]
            psi, mu = angle_of(trial, variant, where, True) if least > 0.0 else (
                angle_of(trial, variant, where), None)
            miss = wrap(psi[:, :crank.size] - output)
            if free_zero:
                miss = wrap(miss - xs[:, -1:])
            lost = ~np.isfinite(psi[:, crank.size:])  # held on the branch over the range
            parts = [np.where(np.isfinite(miss), miss, 1.0), lost * 1.0]
            if mu is not None:  # held above the transmission angle's limit over the range
                parts.append(PENALTY * np.where(np.isfinite(mu), np.maximum(
                    least * (1.0 + MARGIN) - mu, 0.0), 0.0))
            return np.concatenate(parts, axis=1)

        def unpack(x):
            trial = full.copy()
            trial[index] = x[:len(index)]
            return trial

        return (lambda x: residuals(x[None, :])[0]), jacobian(residuals), unpack

    fits = []  # (largest miss, x, variant, converged, the start's dimensions)
    for start, variant in zip(values[:STARTS], variants[:STARTS]):
        x0 = list(start[index])
        if free_zero:
            x0.append(float(np.angle(np.mean(np.exp(1j * misses(
                angle_of(start, int(variant), crank)[0], 0.0))))))
        fits.append((math.inf, np.array(x0), int(variant), False, start))
    for steps, going in FIT_STAGES:  # every start a few steps, the best ones on
        for k, (_, x0, variant, _, start) in enumerate(fits[:going]):
            residual, jac, unpack = problem_of(start, variant)
            solution = least_squares(residual, x0, jac=jac, method="trf", xtol=1e-15,
                                     ftol=1e-15, gtol=1e-15, max_nfev=steps)
            dims = unpack(solution.x)
            bad = np.any(dims[[names.index(n) for n in LENGTHS]] <= 0.0)
            if least > 0.0:  # within the limit itself (the penalty holds it above a margin)
                with np.errstate(invalid="ignore"):
                    bad |= not np.min(topology.transmission(dims, variant, where)) >= least
            fits[k] = (math.inf if bad else float(np.max(np.abs(residual(solution.x)))),
                       solution.x, variant, solution.status > 0 or bool(
                           np.max(np.abs(residual(solution.x))) <= EXACT), start)
            if fits[k][0] <= EXACT:
                break
        fits.sort(key=lambda f: f[0])
        if fits[0][0] <= EXACT:
            break
    fits = [f for f in fits if np.isfinite(f[0])]
    if not fits:
        limit = (f" or its transmission angle below search.min_transmission = "
                 f"{np.rad2deg(least):.3g}°" if least > 0.0 else "")
        raise DyadeError(f"{problem.name}: every least-squares fit of the best {STARTS} "
                         f"{topology.title} six-bars drove a length through zero{limit}: "
                         f"widen the [bounds], draw more candidates (search.candidates)"
                         + (" or lower search.min_transmission." if limit else "."))
    _, x, variant, converged, start = fits[0]
    dims = problem_of(start, variant)[2](x)
    zero = float(x[-1]) if free_zero else 0.0
    sweep = (float(np.rad2deg(crank.min())), float(np.rad2deg(crank.max())))
    step = (sweep[1] - sweep[0]) / max(1, round(sweep[1] - sweep[0]))
    data = topology.data(dims, variant, speed_rpm=speed_rpm(problem), masses=problem.masses,
                         sweep=(sweep[0], sweep[1], step or 1.0),
                         name=problem.name)
    mechanism = build(data)  # the design's output through dyade, not the closed form
    found = positions(mechanism, np.concatenate([crank, dense]), [(6, (0.0, 0.0))])
    traced = found.angles[:, 6]
    made = SixGenerated(crank, output + zero, traced[:crank.size],
                        (dense, traced[crank.size:]))
    notes = []
    if not np.isfinite(made.error).all():
        notes.append(f"the six-bar does not close at {np.count_nonzero(~np.isfinite(made.error))}"
                     f" of the table's {made.error.size} crank angles")
    if free_zero:
        notes.append(f"the law's output zero is link 6 at {np.rad2deg(zero):.6g}° from the "
                     f"frame line (found by the synthesis)")
    error = float(np.rad2deg(np.nanmax(np.abs(made.error)))) if np.isfinite(
        made.error).any() else math.inf
    converged = converged and bool(np.isfinite(made.error).all())
    if not converged:
        notes.append(f"the least squares stopped after {FIT_STAGES[-1][0]} steps, not converged to its "
                     f"tolerance (1e-15): the structural error is that of where it stopped")
    design = Design(problem.name, data, error, converged, crank, made.traced, notes=notes)
    result = Result(problem, [design], evaluated, assembled)
    result.function = made
    return result


def _none_assembled(problem, topology, evaluated: int, what: str) -> InputError:
    """No candidate of the bounds assembles (or keeps the transmission angle's limit): the
    bounds' fault, exit 2."""
    limit = (f" with a transmission angle of at least {np.rad2deg(problem.min_transmission):.3g}° "
             f"(both dyads)" if problem.min_transmission > 0.0 else "")
    return InputError(f"{problem.name}: none of the {evaluated:,} {topology.title} six-bars drawn "
                      f"{what}{limit}: widen the [bounds]"
                      + (" or lower search.min_transmission." if limit else "."),
                      source=problem.source, key="bounds")


# -- motion generation -----------------------------------------------------------------
def poses(problem, progress=None, check_time=None):
    """The poses target of a six-bar problem (link 5 through them) as its result.

    ``check_time(seconds, what)`` hears the run's estimate (a timed trial) before the
    search; a candidate or fit whose smaller transmission angle (of both dyads) over the
    crank's turn falls below ``problem.min_transmission`` is rejected."""
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions
    from dyade.synthesis.designs import Design, Result, speed_rpm
    from dyade.synthesis.search import scipy_least_squares
    from dyade.synthesis.topology import TOPOLOGIES, Placement

    topology = TOPOLOGIES[problem.topology]
    given = problem.target.poses
    z = given[:, 0] + 1j * given[:, 1]
    theta = given[:, 2]
    size = max(float(np.sqrt(np.mean(np.abs(z - z.mean()) ** 2))), 1e-9)
    n = len(given)
    names = topology.names
    bounds = _bounds(topology, problem, 2.0 * size, {})
    samples = 48
    grid = np.linspace(0.0, 2.0 * np.pi, samples, endpoint=False)
    relative = np.exp(-1j * theta[0]) * (z[1:] - z[0]) / size  # poses 2… seen from pose 1
    turned = theta[1:] - theta[0]

    def links(values, variant, at):
        with np.errstate(invalid="ignore", divide="ignore"):
            e, f, _, p = topology.joints(values, variant, at)
        return p, np.angle(f - e)

    least = problem.min_transmission

    def score(values, variant):
        p, angle = links(values, variant, grid)
        ok = np.isfinite(p).all(axis=1) & topology.turns(values)
        if least > 0.0:
            with np.errstate(invalid="ignore"):
                ok &= np.min(topology.transmission(values, variant, grid), axis=1) >= least
        cost = np.full(len(values), np.inf)
        for rows in np.array_split(np.flatnonzero(ok), max(1, ok.sum() // 256)):
            if not rows.size:
                continue
            pj, aj = p[rows], angle[rows]
            # seen from the link at crank sample j: where it is at sample l
            seen = np.exp(-1j * aj[:, :, None]) * (pj[:, None, :] - pj[:, :, None]) / size
            rot = aj[:, None, :] - aj[:, :, None]
            total = 0.0
            for k in range(n - 1):
                total = total + np.min(np.abs(seen - relative[k]) ** 2
                                       + wrap(rot - turned[k]) ** 2, axis=2)
            cost[rows] = np.sqrt(np.min(total, axis=1) / max(1, n - 1))
        return cost

    dims = len(names)
    if check_time is not None:
        width = 2 * (dims + 3 + n) + 1  # a Jacobian's trials, each at the n poses' angles

        def step(values):
            trials = np.repeat(values[:1], width * n, axis=0)
            links(trials, 1, np.resize(grid, (width * n, 1)))
            if least > 0.0:
                topology.transmission(values[:1], 1, grid)

        check_time(_estimate(problem, names, bounds, score, step, STARTS * POSE_STEPS),
                   f"{problem.name}: {max(problem.candidates, 10) * problem.rounds:,} "
                   f"{topology.title} six-bars and the least squares of the best {STARTS}")
    values, variants, _, evaluated, assembled = _search(problem, names, bounds, score,
                                                        progress)
    if not len(values):
        raise _none_assembled(problem, topology, evaluated, "turns its crank fully")
    least_squares = scipy_least_squares()  # only now: importing scipy takes a while
    low = np.array([1e-6 * size if k in LENGTHS else -np.inf for k in names])
    fits = []
    for start, variant in zip(values[:STARTS], variants[:STARTS]):
        variant = int(variant)
        p, angle = links(start, variant, grid)
        p, angle = p[0], angle[0]
        seen = np.exp(-1j * angle[:, None]) * (p[None, :] - p[:, None]) / size
        rot = angle[None, :] - angle[:, None]
        cost = sum(np.abs(seen - relative[k]) ** 2 + wrap(rot - turned[k]) ** 2
                   for k in range(n - 1))
        j = int(np.argmin(np.min(cost, axis=1)))
        picks = [j] + [int(np.argmin(np.abs(seen[j] - relative[k]) ** 2
                                     + wrap(rot[j] - turned[k]) ** 2)) for k in range(n - 1)]
        turn = theta[0] - angle[j]
        origin = z[0] - np.exp(1j * turn) * p[j]
        x0 = np.concatenate([start, [origin.real, origin.imag, turn], grid[picks]])

        def residuals(xs, variant=variant):  # each trial its own crank angles: a row each
            trial = np.repeat(xs[:, :dims], n, axis=0)
            pp, aa = links(trial, variant, xs[:, dims + 3:].reshape(-1, 1))
            pp, aa = pp.reshape(len(xs), n), aa.reshape(len(xs), n)
            turn = xs[:, dims + 2:dims + 3]
            placed = (xs[:, dims:dims + 1] + 1j * xs[:, dims + 1:dims + 2]
                      + np.exp(1j * turn) * pp)
            miss = (placed - z) / size
            out = np.concatenate([miss.real, miss.imag, wrap(aa + turn - theta)], axis=1)
            if least > 0.0:  # held above the transmission angle's limit over the turn
                mu = topology.transmission(xs[:, :dims], variant, grid)
                out = np.concatenate([out, PENALTY * np.maximum(least * (1.0 + MARGIN) - mu,
                                                                0.0)], axis=1)
            return np.where(np.isfinite(out), out, 10.0)

        def residual(x, residuals=residuals):
            return residuals(x[None, :])[0]

        lows = np.concatenate([low, [-np.inf] * (3 + n)])
        solution = least_squares(residual, np.maximum(x0, lows + 1e-12), method="trf",
                                 jac=jacobian(residuals), bounds=(lows, np.inf), xtol=1e-15,
                                 ftol=1e-15, gtol=1e-15, max_nfev=POSE_STEPS)
        fits.append((float(np.max(np.abs(residual(solution.x)))), solution.x, variant))
        if fits[-1][0] < 1e-12:
            break
    fits.sort(key=lambda f: f[0])
    designs = []
    for _, x, variant in fits:
        if len(designs) >= problem.keep:
            break
        rank = len(designs) + 1
        placement = Placement(complex(x[dims], x[dims + 1]), 1.0, float(x[dims + 2]))
        phi = x[dims + 3:]
        data = topology.data(x[:dims], variant, placement, speed_rpm(problem), problem.masses,
                             name=f"{problem.name}: design {rank}")
        mechanism = build(data)
        world = phi + placement.angle  # the crank angle from the world's x axis
        point = mechanism.links[5].points["P"]
        found = positions(mechanism, world, [(5, point)])
        reached = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
        miss = float(np.max(np.abs(reached - z)))
        off = float(np.max(np.abs(wrap(found.angles[:, 5] - theta))))
        dense = np.linspace(0.0, 2.0 * np.pi, 361) + placement.angle
        swept = positions(mechanism, dense, [(5, point)])
        between = swept.points[:, 0]
        converged = miss <= POSE_TOLERANCE * size and off <= POSE_TOLERANCE
        with np.errstate(invalid="ignore"):  # dyade's own transmission angles, both dyads
            mu = float(np.arcsin(np.clip(np.nanmin(swept.conditioning), 0.0, 1.0)))
        if least > 0.0 and not mu >= least:
            continue  # the fit left the limit
        at = np.rad2deg(np.mod(world, 2.0 * np.pi))
        notes = [f"the poses are reached at crank angles "
                 f"{', '.join(f'{v:.2f}°' for v in at)}; link 5's angle misses by at most "
                 f"{np.rad2deg(off):.3g}°"]
        steps = np.mod(np.diff(phi - phi[0]), 2.0 * np.pi)
        if np.mod(phi[-1] - phi[0], 2.0 * np.pi) < np.sum(steps) - 1e-9:
            notes.append("the crank reaches the poses out of their order (it passes them in "
                         "another sequence over its turn)")
        if not converged:
            notes.append(f"the local fit stopped {miss:.3g} m from the poses: not reached")
        opened = int(np.count_nonzero(~np.isfinite(between[:, 0])))
        if opened:
            notes.append(f"the six-bar does not close at {opened} of 361 crank angles over "
                         f"its turn (its crank does not turn fully): sweep it between the "
                         f"poses")
        design = Design(f"design {rank}", data, miss, converged, dense,
                        between[:, 0] + 1j * between[:, 1], notes=notes)
        designs.append(design)
    if not designs:
        raise DyadeError(f"{problem.name}: every least-squares fit of the best {len(fits)} "
                         f"{topology.title} six-bars through the {n} poses ends with a "
                         f"transmission angle below search.min_transmission = "
                         f"{np.rad2deg(least):.3g}° over the crank's turn: lower it, widen "
                         f"the [bounds] or draw more candidates.")
    if not designs[0].converged:
        raise DyadeError(f"{problem.name}: no {topology.title} six-bar within the bounds "
                         f"passes through the {n} poses: the best of {evaluated:,} candidates "
                         f"misses them by {designs[0].error:.3g} m after the local fit (at "
                         f"most {POSE_TOLERANCE:g} of their size counts): {n} poses are "
                         f"{3 * n} equations for its {15 + n} unknowns (12 dimensions, the "
                         f"placement, a crank angle per pose), and the search found no start "
                         f"from which the fit closes them. Draw more candidates, widen the "
                         f"bounds, give fewer poses, or try another topology.")
    designs = [d for d in designs if d.converged]
    return Result(problem, designs, evaluated, assembled)
