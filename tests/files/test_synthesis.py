"""The synthesis file reader: units to SI, every key checked, the file and key named."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.errors import InputError
from dyade.files.synthesis import parse


def test_units_become_si():
    problem = parse({"units": {"length": "mm", "angle": "deg"},
                     "target": {"kind": "path", "points": [[100 * np.cos(t), 50 * np.sin(t)]
                                                           for t in np.linspace(0, 6, 12)]},
                     "bounds": {"a": [10, 40]},
                     "search": {"min_transmission": 30, "seed": 3},
                     "scores": {"speed_rpm": 60, "mass_per_length": 2}})
    assert problem.target.points[0] == pytest.approx(0.1)
    assert problem.bounds["a"] == pytest.approx((0.01, 0.04))
    assert problem.min_transmission == pytest.approx(np.pi / 6)
    assert problem.speed == pytest.approx(2 * np.pi) and problem.seed == 3
    assert problem.masses == {"per_length": 2.0, "each": None}


@pytest.mark.parametrize("data, key, words", [
    ({"target": {"kind": "pth"}}, "target.kind", "Did you mean"),
    ({"target": {"kind": "path", "points": [[0, 0]] * 5}}, "target.points", "at least 8"),
    ({"target": {"kind": "path", "points": [[0, 0], [1, 0], [1, 1], [0, 1]], "closed": False,
                 }}, "target.points", "a part of a curve without crank angles"),
    ({"target": {"kind": "function", "crank": [1, 2], "output": [1, 2, 3]}}, "target.output",
     "3 angles for 2"),
    ({"target": {"kind": "poses", "poses": [[0, 0, 0], [1, 0, 10]]}}, "target.poses", "three"),
    ({"target": {"kind": "line", "stretch": 400}}, "target.stretch", "360"),
    ({"target": {"kind": "line", "stretch": 120}, "bounds": {"z": [1, 2]}}, "bounds.z", ""),
    ({"target": {"kind": "line", "stretch": 120}, "bounds": {"a": [2, 1]}}, "bounds.a",
     "least, largest"),
    ({"target": {"kind": "line", "stretch": 120}, "topology": "fivebar"}, "topology", ""),
    ({"target": {"kind": "line", "stretch": 120}, "search": {"candidates": 0}},
     "candidates", "at least 1"),
])
def test_bad_input_names_the_key(data, key, words):
    with pytest.raises(InputError) as err:
        parse(data, "s.toml")
    assert key in str(err.value) and words in str(err.value) and "s.toml" in str(err.value)
