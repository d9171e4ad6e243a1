"""The key figures' shortcuts (issue 41, the study's speed) give numpy's plain forms to
the bit: the rocker's unwrap where nothing wraps, the peak and the least transmission
angle without a NaN mask where no value is NaN, the cycle's integrals in place."""

from __future__ import annotations

import numpy as np
import pytest

from dyade import cycle
from dyade.linkage.summary import least_transmission, peaks, swings


def _curves(seed: int, infinite: bool = False) -> list[np.ndarray]:
    """(rows, positions) angle curves [°]: rockers, cranks that wrap, gaps, ±0 (and,
    ``infinite``, ±inf)."""
    rng = np.random.default_rng(seed)
    out = []
    for case in range(24):
        v = np.cumsum(rng.normal(size=(6, 37)) * rng.choice([0.1, 5.0, 90.0]), axis=1)
        v += rng.uniform(-180.0, 180.0, (6, 1))
        if case % 2:
            v = np.remainder(v + 180.0, 360.0) - 180.0
        if case % 3 == 0:
            v[1, 4] = np.nan
        if case % 4 == 0:
            v[2] = -0.0
        if infinite and case % 5 == 0:
            v[3, 7], v[4, 9] = np.inf, -np.inf
        out.append(v)
    return out


def test_swings_unwrap_as_numpy():
    for v in _curves(1):
        expected = np.rad2deg(np.unwrap(np.deg2rad(v), axis=1))
        _, turned = swings(v.copy())
        assert np.array_equal(turned, expected, equal_nan=True)
        assert np.array_equal(np.signbit(turned), np.signbit(expected))  # the zeros too


def test_peaks_and_least_transmission_as_with_the_mask():
    for v in _curves(2, infinite=True):
        k = np.argmax(np.where(np.isnan(v), -np.inf, np.abs(v)), axis=1)
        value, where = peaks(v)
        assert np.array_equal(where, k)
        assert np.array_equal(value, np.take_along_axis(v, k[:, None], axis=1)[:, 0],
                              equal_nan=True)
        with np.errstate(invalid="ignore"):
            mu = np.abs(np.remainder(v, 180.0))
        off = np.minimum(mu, 180.0 - mu)
        k = np.argmin(np.where(np.isnan(off), np.inf, off), axis=1)
        least, where = least_transmission(mu)
        assert np.array_equal(where, k)
        assert np.array_equal(least, np.take_along_axis(off, k[:, None], axis=1)[:, 0],
                              equal_nan=True)


@pytest.mark.parametrize("angle", [np.arange(0.0, 360.0, 5.0),
                                   np.r_[0:180:3.0, 180:360:5.0]])
def test_cycle_integrals_as_written_out(angle):
    """The Hermite integrals over each interval: the formula written out, with its
    temporaries, against the in-place one; the mean over a revolution their sum over
    2π, or for equal steps (the first sweep) the plain mean of the distinct positions
    (what the Hermite sum is up to round-off: the slopes' terms cancel)."""
    angle = np.deg2rad(angle)
    rng = np.random.default_rng(3)
    values = rng.normal(size=(9, angle.size)) * 10.0 ** rng.integers(-6, 6, (9, 1))
    values[4, 2] = np.nan
    h = np.diff(np.append(angle, angle[0] + 2.0 * np.pi))
    left = np.roll(h, 1)
    step = np.roll(values, -1, axis=-1) - values
    slope = (left * left * step + h * h * np.roll(step, 1, axis=-1)) / (left * h * (left + h))
    expected = (0.5 * h * (values + np.roll(values, -1, axis=-1))
                + h * h / 12.0 * (slope - np.roll(slope, -1, axis=-1)))
    assert np.array_equal(cycle.integrals(angle, values), expected, equal_nan=True)
    means = cycle.means(np.append(angle, 2.0 * np.pi), np.column_stack([values, values[:, 0]]))
    assert np.isnan(means[4]) == np.isnan(values[4]).all()  # a gap: the rows it has
    hermite = np.sum(expected[[0, 1, 2]], axis=1) / (2 * np.pi)
    if cycle.equal_steps(angle):
        assert np.array_equal(means[[0, 1, 2]], np.sum(values[[0, 1, 2]], axis=1) / angle.size)
        assert np.allclose(means[[0, 1, 2]], hermite, rtol=1e-12, atol=0)
    else:
        assert np.array_equal(means[[0, 1, 2]], hermite)
    assert cycle.equal_steps(angle) == (angle.size == 72)
