"""The bounds every command shares, in one place.

**Size.** Anything that grows with an input (positions, segments, frequencies, speeds,
harmonics, steps, revolutions, frames) is estimated before it is allocated or looped
over, and refused when the estimate exceeds ``max_memory`` [B] (default ``MAX_MEMORY``,
4 GiB; the command line's ``--max-memory`` in MB): ``check_memory`` says the figure, the
estimate and how to raise the bound. Tables cost ``BYTES_PER_VALUE`` per value (the
arrays, the table and its text), dense matrices 8 B per entry each.

**Plausibility.** A value outside what any machine has (``PLAUSIBLE``: quantity ->
range in SI) is refused where it is read, naming the key or flag and the range
(``check_plausible``), so that no result is computed from it and no absurd number is
printed.
"""

from __future__ import annotations

import math

from dyade.errors import InputError

MAX_MEMORY = 4 << 30  # [B] default bound on what one run may take (overridable)
BYTES_PER_VALUE = 90  # [B] per value of a result table: arrays, the table and its text
"""measured: dyade-16 (269 columns) and the four-bar (59) at 3 600 and 36 000 positions
peak at 84-86 B per column and position in `dyade analyse --format csv`"""

MAX_STEPS = 100_000  # integration steps per revolution at most (drive lines)

PLAUSIBLE: dict[str, tuple[float, float, str]] = {
    # quantity: (lowest, highest, unit), SI; 0 is a lower bound only where 0 is allowed
    "speed_rpm": (1e-2, 1e6, "rpm"),
    "frequency": (0.0, 1e6, "Hz"),
    "torque": (-1e9, 1e9, "N·m"),
    "mass": (1e-9, 1e7, "kg"),
    "inertia": (1e-12, 1e7, "kg·m²"),
    "stiffness": (1e-6, 1e13, "N/m or N·m/rad"),  # 0 (no spring) passes: the bound is for the rest
    "damping": (0.0, 1e10, "N·s/m or N·m·s/rad"),
    "length": (1e-7, 1e3, "m"),
    "modulus": (1e5, 1e13, "Pa"),
    "density": (1.0, 1e5, "kg/m³"),
    "time_constant": (0.0, 10.0, "s"),
    "fluctuation": (1e-6, 1.0, "-"),
    "order": (0.0, 1e4, "-"),
    "teeth": (1, 10_000, "-"),
    "ratio": (1e-4, 1e4, "-"),  # a gear ratio
    "force": (-1e10, 1e10, "N"),
    "acceleration": (0.0, 1e4, "m/s²"),  # a gravity field: a thousand g at most
    "friction_coefficient": (0.0, 10.0, "-"),
}
"""quantity -> (lowest, highest, unit): what any machine dyade models has"""


def size(nbytes: float) -> str:
    """A byte count for people: 3 significant digits, kB … PB."""
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if nbytes < 1000 or unit == "PB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1000
    return f"{nbytes:.3g} PB"  # pragma: no cover - the loop returns


def check_memory(need: float, what: str, max_memory: float | None = None,
                 advice: str = "Ask for less", parameter: str = "max_memory") -> None:
    """Refuse, before anything is allocated, ``what`` (e.g. "this sweep of 3,600
    positions") that would take ``need`` [B] beyond ``max_memory`` [B] (default
    ``MAX_MEMORY``): an InputError on ``parameter`` (the command line names its flag)
    with the figure, the estimate and ``advice``."""
    bound = MAX_MEMORY if max_memory is None else max_memory
    if not need <= bound:  # NaN and inf refused too
        raise InputError.parameter(
            parameter, f"is {size(bound)}, and {what} would take about {size(need)}. "
                       f"{advice}, or raise the bound.", value=bound, unit="B")


def plausible_range(quantity: str) -> str:
    """"1e-06…1000 m": the range of ``quantity`` for messages."""
    low, high, unit = PLAUSIBLE[quantity]
    return f"{low:g}…{high:g} {unit}"


def implausible(quantity: str, value: float, scale: float = 1.0) -> bool:
    """Whether ``value`` [SI / ``scale``] lies outside the plausible range of
    ``quantity``, or is not finite."""
    low, high, _ = PLAUSIBLE[quantity]
    value = value * scale
    if not math.isfinite(value):
        return True
    return not low <= value <= high


def check_plausible(name: str, value: float, quantity: str, scale: float = 1.0) -> float:
    """``value`` when plausible for ``quantity`` (``value * scale`` in SI), else an
    InputError on parameter ``name`` naming the range."""
    if implausible(quantity, value, scale):
        raise InputError.parameter(name, f"must lie in {plausible_range(quantity)} (what a "
                                         f"machine has), got {value:g}.", value=value,
                                   unit=PLAUSIBLE[quantity][2])
    return value
