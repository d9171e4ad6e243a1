"""Array types shared by every analysis (for annotations; numpy.typing is loaded only
by a type checker, it costs start-up time)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

    FloatArray = npt.NDArray[np.float64]
else:
    FloatArray = np.ndarray
Vec = tuple[float, float]
"""A point or vector (x, y) or (ξ, η) [m]."""


def plain(value):
    """numpy scalars and arrays inside dicts, lists and tuples -> plain Python values
    (float, int, bool, lists), for results a person reads or a notebook prints.

    >>> plain({"a": np.float64(1.5), "b": [np.int64(2), np.bool_(True)], "c": np.arange(2.0)})
    {'a': 1.5, 'b': [2, True], 'c': [0.0, 1.0]}
    """
    if isinstance(value, dict):
        return {key: plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(plain(item) for item in value)
    if isinstance(value, (np.ndarray, np.generic)):
        return value.tolist()
    return value


def resolution(angle_deg) -> int:
    """The decimals [°] that write every angle of a sweep exactly (at most 9: below,
    the angles differ by float noise only): 0 for whole degrees, 1 for 0.5°, 2 for 0.25°.

    >>> resolution(np.arange(721) * 0.5), resolution([0.0, 0.25, 359.50000000000006])
    (1, 2)
    """
    angle = np.asarray(angle_deg, dtype=np.float64)
    angle = angle[np.isfinite(angle)]
    for digits in range(9):
        if np.all(np.abs(np.round(angle, digits) - angle) <= 1e-9 * np.maximum(1.0, np.abs(angle))):
            return digits
    return 9


class Variants(np.ndarray):
    """One number per variant of a study, where a mechanism file has one number: a
    (variants,) float array the file reader takes through its arithmetic, so that a
    block of variants is read at once (``dyade.study``; ``dyade.linkage.stack.spread``
    turns each into one value per variant and position). Arithmetic keeps the type;
    a check the reader cannot make on an array raises, and the block is read variant by
    variant instead."""

    def __new__(cls, values) -> Variants:
        return np.asarray(values, dtype=np.float64).reshape(-1).view(cls)
