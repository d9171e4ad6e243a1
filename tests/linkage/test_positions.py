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
