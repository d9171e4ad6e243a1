"""Round-off is zero: the rule by which every table, note, legend and title of dyade
prints a figure that floating point left behind as 0.

A figure x is round-off, and printed as 0, when

    |x| ≤ ROUNDOFF · S,

S being the scale of the same quantity in the same run: the largest magnitude of that
quantity (or of every column of its unit) over the sweep — the largest |M_drive| for a
mean drive torque, the largest joint force of the machine for a joint force, the
shaking force before balancing for the one after. ROUNDOFF = 1e-12, about 4500 machine
epsilons (2.2e-16): above the round-off that sums over a sweep of up to a million
positions and the closures' Newton steps leave, far below any figure a machine designer
reads (a mean drive torque of 1e-12 of its peak is no torque). Differences and errors that measure
round-off themselves (``dyade accuracy``'s relative errors, ``gears --check``'s
frequency differences, the friction residual) are shown as they are. CSV and JSON keep
every number as computed, except means over a revolution (``dyade.cycle.mean``), which
are 0 where they are round-off of their own values.

An eigen solution is accurate to the machine epsilon times its condition, not to the
epsilon: a mode shape's component is round-off below EIGEN_ROUNDOFF = 1e-9 of the
mode's largest component (as the modal mesh forces, ``dyade.report.gears.cleaned``) —
the rotations of a purely axial mode come out near 1e-11 of its translations.
"""

from __future__ import annotations

import math

ROUNDOFF = 1e-12  # [-] share of its quantity's scale below which a figure is round-off
EIGEN_ROUNDOFF = 1e-9  # [-] the same for a component of a mode shape (its largest: scale)


def is_roundoff(value: float, scale: float, share: float = ROUNDOFF) -> bool:
    """|value| ≤ share·|scale| (the module docstring); never for a non-finite value."""
    return math.isfinite(value) and abs(value) <= share * abs(scale)


def clean(value: float, scale: float, share: float = ROUNDOFF) -> float:
    """``value``, or 0.0 where it is round-off of ``scale``."""
    return 0.0 if is_roundoff(value, scale, share) else value + 0.0
