"""Dimensional synthesis (``dyade synthesise``): which mechanism moves like this.

A synthesis problem (``dyade.model.synthesis``, read from a synthesis file by
``dyade.files.synthesis``) names a topology (four-bar, slider-crank), a target and the
bounds of the dimensions; ``synthesise`` answers with the best mechanisms, each as the
data of a mechanism file ready for ``dyade analyse``:

- function generation: Freudenstein's closed form through three precision points
  (given, or Chebyshev-spaced over the table), or the least squares of the whole table
  (``dyade.synthesis.function``);
- motion generation: three poses in closed form, four by the Burmester curves
  (``dyade.synthesis.closed``, ``dyade.synthesis.motion``);
- path generation: many candidates (Latin hypercube or random, seeded per block) traced
  in blocks of variants × positions through dyade's positions-only stage
  (``dyade.linkage.positions``), filtered (the crank turns fully, the least
  transmission angle), matched by a start-point-free Fourier shape distance
  (``dyade.synthesis.shape``) or by a straight-line / circular-arc stretch's deviation
  (``dyade.synthesis.stretch``), the best refined by least squares (scipy);
- with masses (links as bars), each result's sweep figures (drive torque, joint forces,
  transmission angle, shaking force) from ``dyade.linkage.sweep.analyse`` and the
  Pareto set of the match error against one of them.

The package sits above the engine (``dyade.linkage``) and the readers (it builds the
candidates' mechanisms from file data, ``dyade.files.mechanism.build``) and below the
analyses (the ``synthesis`` entry, ``dyade.analyses.synthesis``).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from dyade.errors import DyadeError, InputError
from dyade.model.synthesis import Synthesis

from dyade.synthesis.designs import (ERROR_UNITS, ERROR_WORDS, FIGURES, HOPELESS, REACH,
                                     Design, Result, error_unit, pareto, speed_rpm)

__all__ = ["ERROR_UNITS", "ERROR_WORDS", "FIGURES", "Design", "Result", "error_unit", "pareto",
           "score", "synthesise", "trace"]


def synthesise(problem: Synthesis, jobs: int = 1, executor=None, progress=None,
               check_time=None) -> Result:
    """Solve a synthesis problem.

    Parameters
    ----------
    problem : Synthesis
        From ``dyade.files.synthesis.read_synthesis`` or ``parse``.
    jobs : int
        Processes for the search's blocks (``dyade.parallel``); the same candidates
        and result on any number.
    executor : concurrent.futures.Executor, optional
        Runs the blocks instead (a Dask cluster's ``Client.get_executor()``).
    progress : callable, optional
        ``progress(evaluated, total, best_error)`` as the blocks come.
    check_time : callable, optional
        ``check_time(seconds, what)`` hears the run's estimate [s] before the work
        (``dyade.synthesis.cost``; a six-bar's function or poses: from a timed trial of
        its own score), e.g. the contract's ``Budget.time``, which refuses a run over
        ``--max-time``.

    Returns
    -------
    Result

    Raises
    ------
    InputError
        The bounds let no candidate assemble; too few points for the method.
    DyadeError
        The topology cannot reach the target (the message gives the best error found).
    """
    started = time.perf_counter()
    kind = problem.target.kind
    if check_time is not None:
        from dyade.synthesis.cost import estimate

        told = estimate(problem, jobs)
        if told is not None:
            check_time(*told)
    if kind in ("function", "poses") and problem.topology.endswith("sixbar"):
        from dyade.synthesis import sixbar

        result = (sixbar.function if kind == "function" else sixbar.poses)(problem, progress,
                                                                            check_time)
    elif kind == "function":
        result = _function(problem)
    elif kind == "poses":
        from dyade.synthesis.motion import poses

        result = poses(problem)
    elif kind in ("line", "arc"):
        result = _stretch(problem, jobs, executor, progress)
    else:
        result = _path(problem, jobs, executor, progress)
    result.seconds = time.perf_counter() - started
    if problem.masses:
        score(result)
    return result


def topology_of(problem: Synthesis):
    from dyade.synthesis.topology import TOPOLOGIES

    return TOPOLOGIES[problem.topology]


def _function(problem: Synthesis) -> Result:
    from dyade.synthesis import function

    target = problem.target
    if problem.topology == "slider-crank":
        return _slider(problem)
    offsets = None
    if target.profile is not None:
        from dyade.motion.profile import evaluate

        master = np.linspace(target.crank[0], target.crank[-1], target.rows)
        lift = evaluate(target.profile, master).s
        made, offsets = function.from_profile(
            master, lift, target.method, problem.frame, *target.zeros,
            lift_at=lambda x: evaluate(target.profile, x).s,
            min_transmission=problem.min_transmission or function.MIN_TRANSMISSION)
    else:
        made = function.generate(target.crank, target.output, target.method, problem.frame)
    sweep = (float(np.rad2deg(made.crank[0])), float(np.rad2deg(made.crank[-1])),
             _step(made.crank))
    data = function.data(made.linkage, speed_rpm(problem), sweep, problem.name,
                         problem.masses)
    if offsets is None:  # (a profile's fit holds the limit itself)
        _transmission_kept(problem, data, made.crank, "four-bar")
    error = float(np.rad2deg(np.nanmax(np.abs(made.error)))) if np.isfinite(
        made.error).any() else math.inf
    notes = []
    if not np.isfinite(made.error).all():
        notes.append(f"the four-bar does not close at {np.count_nonzero(~np.isfinite(made.error))}"
                     f" of the table's {made.error.size} crank angles")
    if offsets is not None:
        notes.append(f"the profile's master {np.rad2deg(target.crank[0]):.6g}° … "
                     f"{np.rad2deg(target.crank[-1]):.6g}° is the crank angle "
                     f"{np.rad2deg(made.crank[0]):.6g}° … {np.rad2deg(made.crank[-1]):.6g}° "
                     f"from the frame line; its output s = 0 is the output angle "
                     f"{np.rad2deg(offsets.output):.6g}°"
                     + (" (both found by the synthesis)" if offsets.fitted else ""))
    design = Design(problem.name, data, error, True, made.crank, made.traced, notes=notes)
    result = Result(problem, [design])
    result.offsets = offsets
    result.function = made  # the structural error at every row, for the table
    return result


def _slider(problem: Synthesis) -> Result:
    """Function generation with a slider-crank: its slider's position s(φ)."""
    from dyade.synthesis import slider

    target = problem.target
    notes = []
    if target.profile is not None:
        from dyade.motion.profile import evaluate

        master = np.linspace(target.crank[0], target.crank[-1], target.rows)
        lift = evaluate(target.profile, master).s
        zero = target.zeros[0] or 0.0
        made = slider.from_law(master + zero, lift, target.method)
        notes.append(f"the law's master {np.rad2deg(master[0]):.6g}° … "
                     f"{np.rad2deg(master[-1]):.6g}° is the crank angle "
                     f"{np.rad2deg(master[0] + zero):.6g}° … {np.rad2deg(master[-1] + zero):.6g}° "
                     f"from the guide; its lift 0 is the slider at s0 = {made.start:.6g} m "
                     f"(found by the synthesis)")
    else:
        made = slider.generate(target.crank, target.output, target.method)
    sweep = (float(np.rad2deg(made.crank[0])), float(np.rad2deg(made.crank[-1])),
             _step(made.crank))
    data = slider.data(made.linkage, speed_rpm(problem), sweep, problem.name, problem.masses)
    _transmission_kept(problem, data, made.crank, "slider-crank")
    error = float(np.nanmax(np.abs(made.error))) if np.isfinite(made.error).any() else math.inf
    if not np.isfinite(made.error).all():
        notes.append(f"the slider-crank does not close at "
                     f"{np.count_nonzero(~np.isfinite(made.error))} of the table's "
                     f"{made.error.size} crank angles")
    design = Design(problem.name, data, error, True, made.crank, made.traced, notes=notes)
    result = Result(problem, [design])
    result.function = made  # the structural error at every row, for the table
    return result


TRANSMISSION_SAMPLES = 361  # [-] crank angles over a table's range the limit is checked at


def _transmission_kept(problem: Synthesis, data: dict, crank: np.ndarray, what: str) -> None:
    """A function generator solved in closed form or fitted to a table (one answer, no
    candidates to choose from) whose transmission angle (through dyade's positions
    stage, as ``dyade analyse`` reports it) falls below ``search.min_transmission``
    somewhere over the table's crank range: a ``DyadeError`` that says where and by how
    much (exit 1), not a design."""
    limit = problem.min_transmission
    if not limit > 0.0:
        return
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions

    at = np.linspace(crank[0], crank[-1], TRANSMISSION_SAMPLES)
    mu = positions(build(data), at, []).transmission
    off = np.min(np.minimum(mu, np.pi - mu), axis=1)  # the dyads' nearer dead centre
    if np.isnan(off).all() or np.nanmin(off) >= limit:
        return
    k = int(np.nanargmin(off))
    raise DyadeError(
        f"the {what} through the table has a transmission angle of only "
        f"{np.rad2deg(off[k]):.3g}° at the crank angle {np.rad2deg(at[k]):.6g}°, below "
        f"search.min_transmission = {np.rad2deg(limit):.3g}° (a table has one "
        f"{problem.target.method} solution, no candidates to choose from): choose other precision "
        f"points, a shorter crank range or another output range, or lower "
        f"search.min_transmission.")


def _step(crank: np.ndarray) -> float:
    """A sweep step [°] that covers a table's range in about a degree."""
    span = float(np.rad2deg(crank[-1] - crank[0]))
    return span / max(1, round(span)) if span > 0 else 1.0


def settings_of(problem: Synthesis, scale: bool | None = None):
    """The search's settings of a problem, the bounds completed from the topology's
    defaults (scaled to the target's size where the match is not free in scale)."""
    from dyade.synthesis.search import Settings

    topology = topology_of(problem)
    bounds = dict(topology.defaults)
    size = 1.0
    points = problem.target.points
    if points is not None and not problem.scale:
        size = float(np.sqrt(np.mean(np.abs(points - points.mean()) ** 2))) or 1.0
        bounds = {k: (lo * size, hi * size) for k, (lo, hi) in bounds.items()}
    bounds.update(problem.bounds)
    if problem.scale and "d" in bounds and "d" not in problem.bounds:
        bounds["d"] = (1.0, 1.0)
    return Settings(bounds=bounds, candidates=problem.candidates, block=problem.block,
                    method=problem.method, seed=problem.seed, positions=problem.positions,
                    min_transmission=problem.min_transmission, scale=problem.scale,
                    rounds=problem.rounds, keep=max(40, 4 * problem.keep),
                    variants=topology.variants,
                    regions=tuple((0 if name == "A0" else 1, *box)
                                  for name, box in problem.regions.items()))


def _no_candidate(problem: Synthesis, evaluated: int) -> InputError:
    return InputError(
        f"{problem.name}: none of the {evaluated:,} candidates assembles over the whole crank "
        f"turn with a transmission angle of at least "
        f"{np.rad2deg(problem.min_transmission):.3g}° within the [bounds]: widen the bounds "
        f"(a crank that turns fully needs Grashof's s + l ≤ p + q with the crank or the frame "
        f"the shortest) or lower search.min_transmission.", source=problem.source,
        key="bounds")


def _path(problem: Synthesis, jobs, executor, progress) -> Result:
    from dyade.synthesis.search import fit, placement_of, search, traced
    from dyade.synthesis.shape import (FINE_FRACTIONS, FINE_SAMPLES, SAMPLES, closed_match,
                                       open_match, resample, timed_match)
    from dyade.synthesis.topology import Placement
    topology = topology_of(problem)
    target = problem.target
    settings = settings_of(problem)
    found = search(topology, target.points, settings, jobs, executor, progress, target.crank,
                   target.closed)
    if not len(found.error):
        if settings.regions:
            raise DyadeError(
                f"{problem.name}: of {found.evaluated:,} candidates ({found.assembled:,} "
                f"assembled), none matched to the path puts its frame pivots within the "
                f"[regions]: widen them, or the bounds.")
        raise _no_candidate(problem, found.evaluated)
    crank = np.linspace(0.0, 2.0 * np.pi, settings.positions, endpoint=False)
    if target.closed:
        resampled = resample(target.points[None, :], SAMPLES)[0]
    else:  # a part of a curve: its window on each kept candidate's, finer than the search
        resampled = resample(target.points[None, :], FINE_SAMPLES, closed=False)[0]
    fits: list = []
    tried = 0
    best_error = math.inf
    if found.error[0] > HOPELESS:  # no local fit closes such a gap: say so at once
        raise _unreached(problem, topology, found, float(found.error[0]), "the search")
    for values, variant in zip(found.values, found.variant):
        if len(fits) >= problem.keep or tried >= 2 * problem.keep + 4:
            break
        tried += 1
        curve, _, _ = traced(topology, values[None, :], int(variant), crank)
        if target.crank is not None:
            match = timed_match(target.points, target.crank, curve, settings.scale)
            centre = complex(np.mean(target.points))
            start = Placement(centre - match.factor[0] * match.centre[0],
                              float(abs(match.factor[0])), float(np.angle(match.factor[0])))
        elif not target.closed:
            match = open_match(resampled, curve, scale=settings.scale,
                               fractions=FINE_FRACTIONS)
            factor = match.factor[0]
            start = Placement(complex(resampled.mean()) - factor * match.centre[0],
                              float(abs(factor)), float(np.angle(factor)))
        else:
            match = closed_match(resampled, resample(curve, SAMPLES), scale=settings.scale)
            start = placement_of(match.factor[0], match.centre[0], target.points)
        fitted = fit(topology, values, int(variant), target.points, target.crank,
                     start=start)
        best_error = min(best_error, fitted.error)
        if settings.regions and not _placed_within(fitted, settings.regions):
            continue  # the fit moved a pivot out of its region
        if np.isfinite(fitted.error) and not any(_same(fitted, other) for other in fits):
            fits.append(fitted)
    fits.sort(key=lambda f: f.error)
    if not target.closed and target.crank is None:  # a part of a curve: a flat valley
        from dyade.synthesis.partial import polish

        fits = sorted((polish(topology, f, target.points) if not f.converged else f
                       for f in fits[:problem.keep]), key=lambda f: f.error)
    designs = [_design(problem, topology, fitted, rank)
               for rank, fitted in enumerate(fits, start=1)]
    if not designs or designs[0].error > REACH:
        raise _unreached(problem, topology, found, min(best_error, float(found.error[0])),
                         "the local fit")
    return Result(problem, designs, found.evaluated, found.assembled)


def _unreached(problem: Synthesis, topology, found, error: float, after: str) -> DyadeError:
    return DyadeError(
        f"{problem.name}: no {topology.name} within the bounds traces this path: the best of "
        f"{found.evaluated:,} candidates ({found.assembled:,} assembled) deviates by "
        f"{100 * error:.3g} % RMS of the path's size after {after} (at most {100 * REACH:g} % "
        f"counts as reached). A {topology.name}'s coupler curve cannot follow every shape "
        f"(a four-bar's is of degree six, without sharp corners): widen the bounds, draw more "
        f"candidates, or try another topology.")


def _placed_within(fitted, regions: tuple) -> bool:
    """A fit's frame pivots lie in their regions."""
    from dyade.synthesis.search import within

    a0 = fitted.placement.origin
    b0 = a0 + fitted.values[3] * np.exp(1j * fitted.placement.angle) \
        if fitted.values.size == 6 else a0
    return bool(within(np.array([[a0, b0]]), regions)[0])


def _same(fitted, other) -> bool:
    """Two fits found the same mechanism (within 1e-6 relative)."""
    return (other.variant == fitted.variant
            and np.allclose(other.values, fitted.values, rtol=1e-6, atol=1e-9)
            and abs(other.placement.origin - fitted.placement.origin) < 1e-6)


def _design(problem: Synthesis, topology, fitted, rank: int) -> Design:
    """A fitted candidate as a design: its mechanism data and its path through dyade."""
    from dyade.synthesis.topology import Placement

    placement = Placement(fitted.placement.origin, 1.0, fitted.placement.angle)
    data = topology.data(fitted.values, fitted.variant, placement, speed_rpm(problem),
                         problem.masses, name=f"{problem.name}: design {rank}")
    crank, path = trace(data, placement.angle)
    notes = [] if fitted.converged else [
        f"the local fit stopped {fitted.error:.3g} from the target (RMS over its size)"]
    design = Design(f"design {rank}", data, fitted.error, fitted.converged, crank, path,
                    notes=notes)
    design.fitted = fitted  # the target points' crank angles, for checks and figures
    return design


def trace(data: dict, offset: float = 0.0, count: int = 361) -> tuple[np.ndarray, np.ndarray]:
    """(crank angles [rad], coupler point P (complex [m])) of a mechanism's data over a
    turn, through dyade's positions-only stage."""
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions
    mechanism = build(data)
    crank = offset + np.linspace(0.0, 2.0 * np.pi, count)
    link = next(k for k, body in sorted(mechanism.links.items()) if "P" in body.points)
    found = positions(mechanism, crank, [(link, mechanism.links[link].points["P"])])
    return crank, found.points[:, 0, 0] + 1j * found.points[:, 0, 1]


def _stretch(problem: Synthesis, jobs, executor, progress) -> Result:
    from dyade.synthesis.search import merge, run_blocks
    from dyade.synthesis.stretch import StretchBlock, refine
    from dyade.synthesis.topology import Placement

    topology = topology_of(problem)
    target = problem.target
    settings = settings_of(problem)
    blocks = max(1, math.ceil(settings.candidates / settings.block))
    total = blocks * settings.block * settings.rounds
    state = {"done": 0, "best": math.inf}

    def heard(part):
        state["done"] += part.evaluated
        if len(part.error):
            state["best"] = min(state["best"], float(part.error[0]))
        if progress is not None:
            progress(state["done"], total, state["best"])

    best, parts_all = None, []
    for round_ in range(settings.rounds):
        spread = 0.15 / (3.0 ** (round_ - 1)) if round_ else 0.0
        function = StretchBlock(topology, settings, target.stretch, target.kind, round_, best,
                                spread)
        parts_all += run_blocks(function, list(range(blocks)), jobs, executor, heard)
        best = merge(parts_all, settings.keep)
    if not len(best.error):
        raise _no_candidate(problem, best.evaluated)
    designs = []
    for values, variant in zip(best.values[:problem.keep + 1], best.variant):
        refined = refine(topology, values, int(variant), target.stretch, settings.bounds,
                         target.kind, problem.min_transmission)
        if any(np.allclose(refined.values, d.values, rtol=1e-4) for d in designs):
            continue
        designs.append(refined)
    designs.sort(key=lambda r: r.error)
    if designs[0].error > REACH:
        raise DyadeError(
            f"{problem.name}: no {topology.name} within the bounds keeps to a "
            f"{'straight line' if target.kind == 'line' else 'circular arc'} over "
            f"{np.rad2deg(target.stretch):.4g}° of crank: the best of {best.evaluated:,} "
            f"candidates ({best.assembled:,} assembled) deviates by "
            f"{100 * designs[0].error:.3g} % of the stretch's length after the local fit (at "
            f"most {100 * REACH:g} % counts as reached): shorten the stretch, widen the "
            f"bounds, draw more candidates, or try a six-bar.")
    out = []
    for rank, refined in enumerate(designs[:problem.keep], start=1):
        scaled = None
        if target.kind == "arc" and target.radius is not None:  # a similarity: the same
            from dyade.synthesis.stretch import circle  # deviation over length, to R

            along = refined.start + np.linspace(0.0, target.stretch, 121)
            _, radius = circle(topology.path(refined.values, refined.variant, along)[0])
            refined.values = refined.values * (target.radius / radius)
            scaled = target.radius / radius
        data = topology.data(refined.values, refined.variant, Placement(), speed_rpm(problem),
                             problem.masses, name=f"{problem.name}: design {rank}")
        crank, path = trace(data)
        design = Design(f"design {rank}", data, refined.error, True, crank, path)
        design.stretch = (refined.start, refined.start + target.stretch)
        design.notes.append(f"the stretch runs from crank angle {np.rad2deg(refined.start) % 360:.2f}° "
                            f"to {np.rad2deg(refined.start + target.stretch) % 360:.2f}°")
        if scaled is not None:
            design.notes.append(f"scaled by {scaled:.6g} so that the arc's circle has the "
                                f"radius asked, {target.radius:.6g} m")
        out.append(design)
    return Result(problem, out, best.evaluated, best.assembled)


def score(result: Result) -> None:
    """Each design's sweep figures (``FIGURES``) with its masses, by dyade's sweep of its
    mechanism data (as ``dyade analyse`` of its written file gives them), and the Pareto
    set of (error, the problem's figure)."""
    from dyade.files.mechanism import build
    from dyade.linkage.summary import summary
    from dyade.linkage.sweep import analyse

    for design in result.designs:
        try:
            swept = analyse(build(design.data))
        except DyadeError as err:
            design.notes.append(f"no sweep figures: {err}")
            continue
        figures = summary(swept, swept.columns(), extremes=False)
        joints = [v for k, v in figures.items() if k.startswith("F_") and k.endswith("_peak")
                  and not k.startswith("F_shake") and v is not None]
        mus = [v for k, v in figures.items() if k.startswith("mu_") and v is not None]
        locks = [v for k, v in figures.items() if k.startswith("locks_") and v is not None]
        design.figures.update({
            "M_drive_max": _abs_max(figures.get("M_drive_max"), figures.get("M_drive_min")),
            "M_drive_rms": figures.get("M_drive_rms"),
            "F_joint_peak": max(joints) if joints else None,
            "mu_min_deg": min(mus) if mus else None,
            "F_shake_max": figures.get("F_shake_max"),
            "locks": float(any(locks)) if locks else 0.0})
        design.all_figures = figures
    name = result.problem.figure
    values = np.array([_number(d.figures.get(name, d.all_figures.get(name) if hasattr(
        d, "all_figures") else None)) for d in result.designs])
    errors = np.array([d.error for d in result.designs])
    result.pareto = pareto(np.column_stack([errors, values]))


def _abs_max(top, bottom):
    if top is None or bottom is None:
        return None
    return max(abs(top), abs(bottom))


def _number(value: Any) -> float:
    return math.nan if value is None else float(value)
