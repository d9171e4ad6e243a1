"""How long a synthesis will take, estimated before it starts (``synthesise``'s
``check_time``, the contract's ``Budget.time``: ``--max-time``).

- path, line and arc searches: a cost per candidate and position traced (and per
  window matched), over the workers; the least squares of the best (a stretch's
  refinement);
- the six-bars' function and pose searches: a timed trial of their own scores and of
  one least-squares step (``dyade.synthesis.sixbar``);
- the closed forms and fits of four-bars and slider-cranks (function, poses): a timed
  trial of one trace of a stand-in linkage through dyade's positions stage at the
  target's rows, times the traces' worth of work each method was measured to take
  (``TRACES``), plus the sweep of every design with masses.
"""

from __future__ import annotations

import math
import time

import numpy as np

from dyade.model.synthesis import Synthesis

PATH_SECONDS = 4e-7
"""[s] per candidate and crank position of a path search's first pass"""
WINDOW_SECONDS = 3e-4
"""[s] per candidate of a part of a curve (every window's match)"""
FIT_SECONDS = 0.03
"""[s] per target point of each path design's least-squares fit, in one process
(measured: the closed-curve template's 24 points 0.6-0.8 s a fit)"""
REFINE_SECONDS = 1.0
"""[s] per refined design of a line or arc stretch (Nelder–Mead, at most 2500 steps:
measured 0.9-1.4 s), in one process"""
TRACES = {("fourbar", "precision"): 20, ("fourbar", "chebyshev"): 20,
          ("fourbar", "fit"): 2500, ("fourbar", "profile"): 1500,
          ("slider-crank", "precision"): 20, ("slider-crank", "chebyshev"): 20,
          ("slider-crank", "fit"): 60, ("slider-crank", "profile"): 150,
          ("fourbar", 3): 150, ("fourbar", 4): 3500, ("fourbar", 5): 60}
"""(topology, method or poses) -> the run's work in traces of the timed trial (measured
on the guide's and the tests' targets: 3-20 for the closed forms, up to ~2500 for a
four-bar's least squares that runs to its step cap, ~3500 for four poses' Burmester
pairs)"""
SCORE_TRACES = 300
"""a design's sweep with masses, in traces of the timed trial (measured ~260)"""


def estimate(problem: Synthesis, workers: int = 1) -> tuple[float, str] | None:
    """(seconds, what) of a run of ``problem`` on ``workers`` processes, or None where the
    run estimates itself (a six-bar's function or poses: ``dyade.synthesis.sixbar``)."""
    kind = problem.target.kind
    if kind in ("path", "line", "arc"):
        seconds = PATH_SECONDS * problem.positions * problem.candidates * problem.rounds
        if not problem.target.closed and problem.target.crank is None:
            seconds += WINDOW_SECONDS * problem.candidates * problem.rounds
        seconds /= max(1, workers)
        if kind in ("line", "arc"):  # the best keep + 1 refined one after another
            seconds += REFINE_SECONDS * (problem.keep + 1)
        else:  # the best keep fitted one after another
            seconds += FIT_SECONDS * problem.target.points.size * problem.keep
        return (seconds,
                f"{problem.name}: {problem.candidates * problem.rounds:,} candidates")
    if problem.topology.endswith("sixbar"):
        return None
    trace, rows = _trial(problem)
    if kind == "poses":
        work = TRACES[("fourbar", len(problem.target.poses))]
        what = f"{problem.name}: a four-bar through {len(problem.target.poses)} poses"
    else:
        method = "profile" if problem.target.profile is not None else problem.target.method
        work = TRACES[(problem.topology, method)]
        what = (f"{problem.name}: a {problem.topology.replace('fourbar', 'four-bar')} "
                f"function generator "
                f"({method}, {rows} rows)")
    designs = 1 if problem.masses else 0
    return trace * (work + SCORE_TRACES * designs), what


def timed(call, repeat: int = 3) -> float:
    """The shortest of ``repeat`` runs of ``call()`` [s]: a timed trial."""
    best = math.inf
    for _ in range(repeat):
        started = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - started)
    return best


def _trial(problem: Synthesis) -> tuple[float, int]:
    """(seconds, rows): one trace of a stand-in linkage of the problem's topology through
    dyade's positions stage at as many crank angles as the target has rows, timed."""
    from dyade.synthesis import closed, function, slider

    target = problem.target
    rows = (target.rows if target.profile is not None else
            len(target.poses) if target.kind == "poses" else len(target.crank))
    crank = np.linspace(0.0, math.pi / 2, max(rows, 3))
    if problem.topology == "slider-crank":
        stand_in = slider.SliderCrank(0.1, 0.35, 0.02, 1)
        return timed(lambda: slider.traced(stand_in, crank)), rows
    stand_in = closed.FourBar(0.35, 0.9, 0.7, 1.0, variant=1)
    return timed(lambda: function.traced(stand_in, crank)), rows
