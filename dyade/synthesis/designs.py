"""What a synthesis answers: its designs (``Design``), the whole answer (``Result``),
the units and words of a match error by target kind, and the Pareto set."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from dyade.model.synthesis import Synthesis

ERROR_UNITS = {"function": "°", "path": "-", "line": "-", "arc": "-", "poses": "m"}
"""the unit of a design's match error, by target kind"""
ERROR_WORDS = {"function": "largest structural error |ψ − ψ_target|",
               "path": "RMS distance to the target points over the target's RMS radius",
               "line": "largest deviation from a straight line over the stretch's length",
               "arc": "largest deviation from a circular arc over the arc's length",
               "poses": "largest distance of the coupler point from the poses"}
SLIDER_UNIT = "m"
"""the match error's unit of a slider-crank's function (the slider's position)"""
SLIDER_WORDS = "largest structural error |s − s_target| of the slider's position"


def error_unit(problem: Synthesis) -> tuple[str, str]:
    """(unit, words) of a problem's match error."""
    kind = problem.target.kind
    if kind == "function" and problem.topology == "slider-crank":
        return SLIDER_UNIT, SLIDER_WORDS
    return ERROR_UNITS[kind], ERROR_WORDS[kind]


REACH = 0.02
"""[-] a path whose best match is worse than this (RMS over the target's size) is
not reached: an error, not a result"""
HOPELESS = 10 * REACH
"""[-] a first pass this far from the target is not refined: no local fit closes it"""
FIGURES = ("M_drive_max", "M_drive_rms", "F_joint_peak", "mu_min_deg", "F_shake_max",
           "locks")
"""the sweep figures of every design (with masses): peak and RMS drive torque, the
largest joint force, the least transmission angle, the peak shaking force, self-locking"""


@dataclass(eq=False)
class Design:
    """One synthesised mechanism."""

    name: str
    data: dict
    """the mechanism file's data (lengths in m, angles in degrees)"""
    error: float
    """the match error, in ``ERROR_UNITS`` of the target's kind"""
    converged: bool
    """the local fit converged (its tolerances met)"""
    crank: np.ndarray
    """(n,) the crank angles of ``traced`` [rad] (world)"""
    traced: np.ndarray
    """(n,) what the mechanism does there, through dyade's engine: the coupler point
    (complex [m]) or the output angle [rad]"""
    figures: dict[str, float] = field(default_factory=dict)
    """the sweep's figures (``FIGURES``), with masses"""
    notes: list[str] = field(default_factory=list)


@dataclass(eq=False)
class Result:
    """The answer of a synthesis: its designs, best first."""

    problem: Synthesis
    designs: list[Design]
    evaluated: int = 0
    """candidates traced by the search"""
    assembled: int = 0
    """of these, those that assembled over the range and passed the filters"""
    seconds: float = 0.0
    pareto: np.ndarray | None = None
    """(designs,) bool: non-dominated in (error, the problem's figure), with masses"""
    notes: list[str] = field(default_factory=list)

    @property
    def rate(self) -> float:
        """candidates per second of the search"""
        return self.evaluated / self.seconds if self.seconds > 0 else 0.0


def speed_rpm(problem: Synthesis) -> float:
    """The problem's operating speed [rpm]."""
    from dyade.units import RAD_PER_S_TO_RPM

    return problem.speed * RAD_PER_S_TO_RPM


def pareto(objectives: np.ndarray) -> np.ndarray:
    """(n,) bool: the rows no other row dominates (every objective as low or lower, one
    lower); a row with a NaN is not in the set."""
    objectives = np.asarray(objectives, dtype=float)
    ok = ~np.isnan(objectives).any(axis=1)
    front = np.zeros(len(objectives), dtype=bool)
    for i in np.flatnonzero(ok):
        other = objectives[ok]
        dominated = np.any(np.all(other <= objectives[i], axis=1)
                           & np.any(other < objectives[i], axis=1))
        front[i] = not dominated
    return front
