"""A synthesis problem as a synthesis file describes it (``dyade.files.synthesis``), SI:
which topology, what it must do (the target), the bounds of its dimensions, how to
search and how to score (``dyade.synthesis`` solves it)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dyade.arrays import FloatArray

TARGETS = ("function", "path", "line", "arc", "poses")
"""the kinds of target: function generation, path generation (a curve, a straight-line
or circular-arc stretch), motion generation"""


@dataclass(frozen=True, slots=True, eq=False)  # holds arrays: no meaningful ==
class Target:
    """What the mechanism must do."""

    kind: str
    """one of ``TARGETS``"""
    crank: FloatArray | None = None
    """(N,) crank angles φ [rad]: a function's table, or a path's timing (from an
    unknown zero); None: no timing"""
    output: FloatArray | None = None
    """(N,) a function's output angles ψ [rad], from the frame line"""
    points: np.ndarray | None = None
    """(N,) complex: a path's points x + iy [m], in order along it"""
    closed: bool = True
    """a path is a closed curve (else an open one: needs its crank angles)"""
    poses: FloatArray | None = None
    """(N, 3) a link's poses (x [m], y [m], θ [rad]) for motion generation"""
    method: str = "chebyshev"
    """function generation: "precision" (three rows), "chebyshev", "fit" """
    stretch: float = 0.0
    """a straight-line or arc stretch's crank range [rad]"""
    radius: float | None = None
    """an arc stretch's prescribed radius [m] (the design scaled to it); None: any"""
    moving: tuple[complex, complex] | None = None
    """three poses: the moving pivots in pose 1 (complex [m]); None: chosen"""
    profile: Any = None
    """function generation: a motion profile (``dyade.model.profile.Profile``, master
    and output angles) instead of the table; ``crank`` is then its master range"""
    rows: int = 61
    """a profile's rows over its range"""
    zeros: tuple[float | None, float | None] = (None, None)
    """a profile: the crank angle at its master zero and the output angle where s = 0
    [rad]; None: found by the synthesis"""


@dataclass(frozen=True, slots=True, eq=False)
class Synthesis:
    """A synthesis file, read and checked (SI)."""

    name: str
    source: str | None
    topology: str
    """"fourbar" or "slider-crank" """
    target: Target
    bounds: dict[str, tuple[float, float]] = field(default_factory=dict)
    """canonical dimension -> (least, largest) [m]; missing: the topology's defaults
    scaled to the target"""
    candidates: int = 20_000
    block: int = 2_000
    method: str = "lhs"
    seed: int = 0
    positions: int = 100
    rounds: int = 2
    min_transmission: float = 0.0
    """[rad]"""
    regions: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    """frame pivot ("A0", "B0") -> (x least, x largest, y least, y largest) [m]: where a
    path's design may put it"""
    scale: bool = True
    """path: the match is free in scale (the bounds then only shape the linkage)"""
    keep: int = 3
    """the best mechanisms to report and write"""
    speed: float = 2.0 * np.pi
    """the crank's operating speed [rad/s]"""
    mass_per_length: float | None = None
    """[kg/m] links as slender bars of this mass per length"""
    mass_each: float | None = None
    """[kg] or each link of this mass (a bar's inertia about its middle)"""
    figure: str = "M_drive_rms"
    """the sweep's figure to rank by beside the match error (with masses)"""
    frame: float = 1.0
    """function generation: the frame length d [m]"""
    length_unit: str = "m"
    """the file's length unit (for writing mechanisms in it)"""

    @property
    def masses(self) -> dict | None:
        if self.mass_per_length is None and self.mass_each is None:
            return None
        return {"per_length": self.mass_per_length, "each": self.mass_each}
