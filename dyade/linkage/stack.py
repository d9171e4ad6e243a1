"""Variants of one topology stacked into one mechanism whose numbers are per-position
arrays: the variants × positions flattened to one axis (variant-major), so that one
sweep of the engine computes them all (issue 26, "Speed").

``stack(mechanisms, positions)`` keeps every number the variants share as it is and
turns a number that differs into an (variants·positions,) array, each variant's value
repeated over its positions; what is not a number (the dyads' kinds, links, variants,
the names) must be the same in every variant, else ``NotStackable``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from dyade.linkage.model import Mechanism


class NotStackable(ValueError):
    """The variants differ in more than numbers (their topology, kinds or assembly)."""


def stack(mechanisms: Sequence[Mechanism], positions: int) -> Mechanism:
    """One mechanism for ``mechanisms`` (variants of one topology) whose differing
    numbers are arrays of one value per (variant, position), variant-major."""
    if not mechanisms:
        raise NotStackable("no variants")
    return _stack(list(mechanisms), positions, "mechanism")


def _stack(values: list, positions: int, where: str):
    first = values[0]
    if all(v is first for v in values):
        return first
    if dataclasses.is_dataclass(first) and not isinstance(first, type):
        if any(type(v) is not type(first) for v in values):
            raise NotStackable(f"{where}: of different types")
        changes = {}
        for f in dataclasses.fields(first):
            parts = [getattr(v, f.name) for v in values]
            merged = _stack(parts, positions, f"{where}.{f.name}")
            if merged is not parts[0]:
                changes[f.name] = merged
        return dataclasses.replace(first, **changes) if changes else first
    if isinstance(first, bool) or isinstance(first, (int, str)) or first is None:
        if any(type(v) is not type(first) or v != first for v in values):
            raise NotStackable(f"{where}: differs ({first!r}, …)")
        return first
    if isinstance(first, float):
        if any(type(v) is not float and not isinstance(v, np.floating) for v in values):
            raise NotStackable(f"{where}: not a number in every variant")
        numbers = np.array(values, dtype=np.float64)
        if (numbers == numbers[0]).all() and np.all(np.signbit(numbers) == np.signbit(first)):
            return first
        return np.repeat(numbers, positions)
    if isinstance(first, dict):
        if any(v.keys() != first.keys() for v in values):
            raise NotStackable(f"{where}: different keys")
        return {k: _stack([v[k] for v in values], positions, f"{where}[{k}]") for k in first}
    if isinstance(first, tuple) and not hasattr(first, "_fields"):
        if any(not isinstance(v, tuple) or len(v) != len(first) for v in values):
            raise NotStackable(f"{where}: different lengths")
        parts = [_stack([v[k] for v in values], positions, f"{where}[{k}]")
                 for k in range(len(first))]
        return tuple(parts)
    if isinstance(first, np.ndarray):  # a table (a load over the crank angle): shared
        if all(isinstance(v, np.ndarray) and np.array_equal(v, first) for v in values):
            return first
        raise NotStackable(f"{where}: a table that differs between variants")
    raise NotStackable(f"{where}: {type(first).__name__} differs between variants")
