"""The positions-only stage gives the full sweep's positions, to the bit, for every
shipped kind of linkage; stacked variants over one turn give each variant's own."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.linkage import kinematics
from dyade.linkage.positions import positions
from dyade.linkage.stack import stack
from tests.helpers import shipped


@pytest.mark.parametrize("name", ["fourbar.toml", "slider-crank.toml", "watt-sixbar.toml",
                                  "slotted-lever.toml", "scotch-yoke.toml"])
def test_the_points_are_the_full_sweeps(name):
    mechanism = dyade.read_mechanism(shipped(name))
    angle = mechanism.sweep.angles()
    full = kinematics.sweep(mechanism, angle)
    asked = [(link, point) for _, link, point in mechanism.named_points]
    asked += [(kinematics.joint_anchor(j)) for j in mechanism.joints
              if hasattr(j, "points")]
    found = positions(mechanism, angle, asked)
    for k, (link, local) in enumerate(asked):
        assert np.array_equal(found.points[:, k], full.motion.point(link, local),
                              equal_nan=True), (link, local)
    assert np.array_equal(found.closes, full.closes.all(axis=1))
    assert np.array_equal(found.transmission, full.transmission, equal_nan=True)


def test_stacked_variants_give_each_variants_own_points():
    base = shipped("fourbar.toml")
    variants = [dyade.read_mechanism(base, {"dyad.2.lengths": [200 + 5 * k, 150 - 3 * k]})
                for k in range(3)]
    angle = np.deg2rad(np.arange(0.0, 360.0, 10.0))
    stacked = stack(variants, angle.size)
    point = (3, (0.1, 0.04))
    together = positions(stacked, angle, [point], repeat=3).points[:, 0]
    for k, mechanism in enumerate(variants):
        alone = positions(mechanism, angle, [point]).points[:, 0]
        assert np.allclose(together[k * angle.size:(k + 1) * angle.size], alone,
                           rtol=0, atol=1e-15)


@pytest.mark.parametrize("name", ["fourbar.toml", "slider-crank.toml", "watt-sixbar.toml",
                                  "slotted-lever.toml", "scotch-yoke.toml"])
def test_only_the_points_are_the_same_points(name):
    """angles=False (the angle-free path for RRR dyads, the generic one otherwise): the
    points, where it closes and the conditioning to the bit; no angles."""
    mechanism = dyade.read_mechanism(shipped(name))
    angle = mechanism.sweep.angles()
    asked = [(link, point) for _, link, point in mechanism.named_points]
    asked += [(kinematics.joint_anchor(j)) for j in mechanism.joints
              if hasattr(j, "points")]
    full = positions(mechanism, angle, asked)
    fast = positions(mechanism, angle, asked, angles=False)
    assert np.array_equal(fast.points, full.points, equal_nan=True)
    assert np.array_equal(fast.closes, full.closes)
    assert np.array_equal(fast.conditioning, full.conditioning, equal_nan=True)
    assert fast.angles is None and fast.transmission is None


@pytest.mark.parametrize("kind", ["four-bar", "slider-crank"])
def test_only_the_points_of_variants_that_do_not_always_close(monkeypatch, kind):
    """Candidates read at once (Variants), some of which lock up part of the turn (a
    crank longer than the Grashof limit), more than one chunk of the angle-free path:
    the generic path's points, NaN included, to the bit."""
    from dyade.arrays import Variants
    from dyade.linkage import positions as stage
    from dyade.linkage.stack import spread
    from dyade.synthesis.search import _substitute, template
    from dyade.synthesis.topology import COUPLER, FourBar, SliderCrank

    monkeypatch.setattr(stage, "CACHE_ELEMENTS", 360)  # chunks of 10 candidates
    rng = np.random.default_rng(5)
    count = 47
    topology = FourBar() if kind == "four-bar" else SliderCrank()
    values = np.column_stack([rng.uniform(0.1, 0.9, count), rng.uniform(0.5, 1.5, count),
                              rng.uniform(0.5, 1.5, count), np.ones(count),
                              rng.uniform(-1, 1, count), rng.uniform(-1, 1, count)])
    if kind == "slider-crank":  # a, b, offset e, p, q
        values = np.column_stack([values[:, 0], values[:, 1] * 0.7, values[:, 4] * 0.5,
                                  values[:, 4], values[:, 5]])
    angle = np.deg2rad(np.arange(0.0, 360.0, 10.0))
    for variant in (1, -1):
        mechanism, index = template(topology, variant)
        read = _substitute(mechanism, index, [Variants(v) for v in values.T])
        point = read.links[COUPLER].points["P"]
        fast = positions(read, angle, [(COUPLER, point)], repeat=count, angles=False)
        spread_point = tuple(np.repeat(np.asarray(v), angle.size) for v in point)
        full = positions(spread(read, angle.size), np.tile(angle, count),
                         [(COUPLER, spread_point)])
        assert 0 < fast.closes.sum() < fast.closes.size  # some lock up
        assert np.array_equal(fast.points, full.points, equal_nan=True)
        assert np.array_equal(fast.closes, full.closes)
        assert np.array_equal(fast.conditioning, full.conditioning, equal_nan=True)
