"""The servo's inversion (issue 39): a profile on the slider of the offset slider-crank
inverted to the crank's motion by dyade (Newton's method on the sweep, all instants at
once, ``dyade.linkage.servo.crank_motion``) beside the closed form of that one linkage,
in one run:

    pytest tests/benchmarks/test_servo_speed.py -m benchmark --benchmark-enable \\
        --benchmark-columns=min,median,rounds

The closed form: (x − r·cos φ)² + (e − r·sin φ)² = l² gives cos(φ − δ) =
(x² + r² + e² − l²)/(2·r·√(x² + e²)), δ = atan2(e, x); dyade must find the same angles
(to 1e-10 rad) at every instant.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

import dyade
from dyade.linkage import servo
from tests.benchmarks.yardstick import SE, SL3, SR2
from tests.helpers import shipped

COUNT = 720 if os.environ.get("CI") == "true" else 72_000
START = math.radians(30.0)


def _target(count: int) -> servo.Target:
    t = np.linspace(0.0, 0.3, count + 1)
    z, w, h = t / 0.3, 2 * math.pi, -0.05
    return servo.Target(t, h * (z - np.sin(w * z) / w), h / 0.3 * (1 - np.cos(w * z)),
                        w * h / 0.09 * np.sin(w * z), w * w * h / 0.027 * np.cos(w * z))


def closed_form(travel: np.ndarray) -> np.ndarray:
    """The crank angles of the slider positions x0 + travel on the branch through START."""
    x0 = SR2 * math.cos(START) + math.sqrt(SL3 ** 2 - (SE - SR2 * math.sin(START)) ** 2)
    x = x0 + travel
    delta = np.arctan2(SE, x)
    turn = np.arccos((x * x + SR2 ** 2 + SE ** 2 - SL3 ** 2) / (2 * SR2 * np.hypot(x, SE)))
    return delta + turn


@pytest.fixture(scope="module")
def slider_crank():
    return dyade.read_mechanism(shipped("slider-crank.toml"))


def test_inversion_dyade(benchmark, slider_crank):
    target = _target(COUNT)
    motion = benchmark(servo.crank_motion, slider_crank, "s_1_4", START, target)
    assert np.max(np.abs(motion.angle - closed_form(target.position))) < 1e-10


def test_inversion_closed_form(benchmark):
    target = _target(COUNT)
    angles = benchmark(closed_form, target.position)
    assert angles[0] == pytest.approx(START, abs=1e-12)
