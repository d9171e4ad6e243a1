"""Variants of one topology stacked into one mechanism whose numbers are per-position
arrays: the variants × positions flattened to one axis (variant-major), so that one
sweep of the engine computes them all (issue 26, "Speed").

``stack(mechanisms, positions)`` keeps every number the variants share as it is and
turns a number that differs into an (variants·positions,) array, each variant's value
repeated over its positions; what is not a number (the dyads' kinds, links, variants,
the names) must be the same in every variant, else ``NotStackable``.

A block of variants read at once (``dyade.arrays.Variants`` where the file has a
number, one per variant) becomes such a mechanism by ``spread``; ``pick`` takes one
variant out of it again, ``part`` a run of them, and ``same`` compares two mechanisms
number by number.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from dyade.arrays import Variants
from dyade.model.mechanism import Mechanism


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
    if where == "mechanism.cam":  # a cam's curves come from its profile, one cam a sweep
        if all(v == first for v in values):
            return first
        raise NotStackable(f"{where}: the cam differs between variants")
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


def spread(mechanism: Mechanism, positions: int, first: int = 0, last: int | None = None
           ) -> Mechanism:
    """The mechanism of a block of variants read at once (``Variants`` for the numbers
    that differ) as ``stack`` gives it: each ``Variants`` an array of one value per
    (variant, position), variant-major; of variants first..last−1 only where given
    (``spread(part(m, first, last), positions)`` in one walk)."""
    return _map(mechanism, lambda v: np.repeat(np.asarray(v)[first:last], positions))


def part(mechanism: Mechanism, first: int, last: int) -> Mechanism:
    """Variants first..last−1 of a block read at once (each ``Variants`` sliced)."""
    return _map(mechanism, lambda v: Variants(np.asarray(v)[first:last]))


def pick(mechanism: Mechanism, index: int) -> Mechanism:
    """Variant ``index`` of a block read at once: each ``Variants`` its number."""
    return _map(mechanism, lambda v: float(v[index]))


def _map(value, leaf):
    """``value`` with ``leaf(v)`` for every ``Variants`` v in it (the rest shared)."""
    if isinstance(value, Variants):
        return leaf(value)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        changes = {}
        for f in dataclasses.fields(value):
            part = getattr(value, f.name)
            mapped = _map(part, leaf)
            if mapped is not part:
                changes[f.name] = mapped
        return dataclasses.replace(value, **changes) if changes else value
    if isinstance(value, dict):
        items = {k: _map(v, leaf) for k, v in value.items()}
        return items if any(items[k] is not v for k, v in value.items()) else value
    if isinstance(value, tuple) and not hasattr(value, "_fields"):
        parts = tuple(_map(v, leaf) for v in value)
        return parts if any(p is not v for p, v in zip(parts, value)) else value
    return value


def same(a, b, rtol: float = 1e-14, where: str = "mechanism", index: int | None = None
         ) -> str:
    """"" when ``a`` and ``b`` hold the same structure and numbers (to ``rtol``:
    numpy's and Python's arithmetic may round a last bit apart), else where they differ.
    With ``index``: variant ``index`` of ``a``, a block read at once, against ``b``
    (``same(pick(a, index), b)`` in one walk)."""
    if index is not None and isinstance(a, Variants):
        a = float(a[index])
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        if type(a) is not type(b):
            return f"{where}: of different types"
        for f in dataclasses.fields(a):
            problem = same(getattr(a, f.name), getattr(b, f.name), rtol, f"{where}.{f.name}",
                           index)
            if problem:
                return problem
        return ""
    if isinstance(a, dict):
        if not isinstance(b, dict) or a.keys() != b.keys():
            return f"{where}: different keys"
        return next((p for k in a if (p := same(a[k], b[k], rtol, f"{where}[{k}]", index))),
                    "")
    if isinstance(a, tuple) and not hasattr(a, "_fields"):
        if not isinstance(b, tuple) or len(a) != len(b):
            return f"{where}: different lengths"
        return next((p for k, (x, y) in enumerate(zip(a, b))
                     if (p := same(x, y, rtol, f"{where}[{k}]", index))), "")
    if type(a) is float and type(b) is float:  # (most of a mechanism: fast)
        return "" if a == b or abs(a - b) <= rtol * max(abs(a), abs(b)) else \
            f"{where}: {a!r} against {b!r}"
    numbers = (float, int, np.floating, np.ndarray)
    if isinstance(a, numbers) and not isinstance(a, bool):
        if not isinstance(b, numbers) or isinstance(b, bool) or np.shape(a) != np.shape(b):
            return f"{where}: {a!r} against {b!r}"
        x, y = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
        ok = (x == y) | (np.abs(x - y) <= rtol * np.maximum(np.abs(x), np.abs(y)))
        return "" if np.all(ok | (np.isnan(x) & np.isnan(y))) else f"{where}: {a!r} against {b!r}"
    if callable(a) or a is b:
        return "" if a is b or a == b else f"{where}: differs"
    return "" if type(a) is type(b) and a == b else f"{where}: {a!r} against {b!r}"
