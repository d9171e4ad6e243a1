"""A block of a study's variants read at once (``dyade.arrays.Variants``): the reader's
checks take all variants in one go and refuse exactly where each variant alone is
refused, with that variant's own message (issue 41: the checks were a loop per variant)."""

from __future__ import annotations

import math

import pytest

from dyade.arrays import Variants
from dyade.errors import InputError
from dyade.files.schema import UnitReader

GOOD = [0.0, 1.0, 2.5]
CASES = [  # (check, its arguments after (value, key), a bad value)
    ("number", ("kg",), math.inf),
    ("number", ("kg", True), 0.0),            # positive
    ("number", ("kg", False, True), -1.0),    # non-negative
    ("number", ("kg",), 1e12),                # above what a machine has
    ("within", ("mass", "kg"), 1e12),
    ("within", ("mass", "kg"), 1e-12),        # below, with the floor
    ("below_top", ("mass", "kg"), -1e12),
    ("length_of", (), 1e9),
]


def _message(check, args, value):
    try:
        getattr(UnitReader("m.toml"), check)(value, "link.mass", *args)
    except InputError as err:
        return str(err)
    return ""


@pytest.mark.parametrize("check, args, bad", CASES)
def test_variants_are_refused_as_each_alone(check, args, bad):
    alone = _message(check, args, bad)
    assert alone  # the bad value alone is refused
    assert all(not _message(check, args, good) for good in GOOD[1:])
    assert _message(check, args, Variants(GOOD[1:] + [bad, 3.0])) == alone
    assert not _message(check, args, Variants(GOOD[1:] + [3.0]))


def test_within_without_floor_takes_tiny_values():
    reader = UnitReader("m.toml")
    assert reader.within(Variants([1e-12, 1.0]), "link.mass", "mass", "kg", floor=False) \
        is not None
    with pytest.raises(InputError):
        reader.within(Variants([1e-12, 1.0]), "link.mass", "mass", "kg")
