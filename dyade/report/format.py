"""The one number formatter and the one cell rule of every writer (issue 36).

Tables (``number``): 6 significant digits, round-off of the run's scale as 0, a value
not given as ``MISSING`` (—), flags as yes/no, never a Python repr. CSV and JSON
(``cell``): 15 significant digits, a value not given as an empty cell (JSON: null),
flags 1/0. Units: ``display`` turns an SI unit into the one a table shows (lengths in
the mechanism file's length unit unless ``--units si``).
"""

from __future__ import annotations

import math
from typing import Any

from dyade.analyses.base import MISSING, cell  # noqa: F401 (the one cell rule, re-exported)
from dyade.roundoff import is_roundoff
from dyade.units import LENGTH_FACTORS

FLAG = "1/0"
"""the CSV/JSON unit of a flag column; tables say yes or no"""


def number(value: Any, scale: float = 0.0, spec: str = ".6g") -> str:
    """A value as a table shows it: ``spec`` (6 significant digits), round-off of
    ``scale`` as 0 (``dyade.roundoff``), not given (None, NaN) as ``MISSING``, ±inf as
    ∞, flags yes/no, text as it is.

    >>> import numpy as np
    >>> [number(v) for v in (np.float64(3600.0), 0.1 + 0.2, None, float("nan"), True, -0.0)]
    ['3600', '0.3', '—', '—', 'yes', '0']
    """
    if value is None:
        return MISSING
    if isinstance(value, str):
        return value
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return flag(value)
    value = float(value)
    if math.isnan(value):
        return MISSING
    if math.isinf(value):
        return "∞" if value > 0 else "−∞"
    if is_roundoff(value, scale):
        return "0"
    return f"{value + 0.0:{spec}}"


def flag(value: Any) -> str:
    """A flag in a table: yes or no."""
    return "yes" if value else "no"


def display(unit: str, length_unit: str = "m") -> tuple[float, str]:
    """Factor and unit to show a value of SI ``unit`` with lengths in ``length_unit``
    (m, m/s, m/s², m/rad … become mm, mm/s, mm/s², mm/rad … for "mm")."""
    if length_unit == "m" or unit not in ("m", "m/s", "m/s²", "m/rad", "m/rad²", "m/rad³"):
        return 1.0, unit
    return 1.0 / LENGTH_FACTORS[length_unit], length_unit + unit[1:]


def with_unit(value: Any, unit: str, scale: float = 0.0) -> str:
    """``"3600 rpm"``: a figure and its unit for a sentence; a value not given alone."""
    text = number(value, scale)
    return text if text == MISSING or not unit or unit == "-" else f"{text} {unit}"


def where(place: Any) -> str:
    """Where a figure occurs, for a table: ``{"angle_deg": 37.0}`` -> ``"37°"``."""
    if not place:
        return ""
    parts = []
    for key, value in dict(place).items():
        unit = {"deg": "°", "rpm": " rpm", "hz": " Hz", "s": " s"}.get(key.rpartition("_")[2], "")
        name = key.rpartition("_")[0] if unit else key
        shown = number(value)
        parts.append(f"{shown}{unit}" if name in ("angle", "") else f"{name} {shown}{unit}")
    return ", ".join(parts)


def ordinal(n: int) -> str:
    """1st, 2nd, 3rd, 4th, …, 11th, 12th, 13th, 21st, 32nd: "every 32nd row shown".

    >>> [ordinal(n) for n in (1, 2, 3, 11, 12, 21, 32)]
    ['1st', '2nd', '3rd', '11th', '12th', '21st', '32nd']
    """
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"
