"""Variants of one topology stacked into one mechanism (``dyade.linkage.stack``): one
sweep over the flattened (variant, position) axis gives each variant's kinematics and
forces as its own sweep does (issue 26, "Speed")."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.linkage import kinematics, kinetostatics
from dyade.linkage.stack import NotStackable, stack
from tests.helpers import shipped

FOURBAR = [{"dyad.2.lengths.1": a, "dyad.2.lengths.2": b, "links.3.mass": m,
            "links.4.centre": [c, 5], "links.3.inertia": i, "frame.points.B0": [250, y]}
           for a, b, m, c, i, y in [(200, 150, 1.2, 75, 0.004, 0), (196, 148, 1.0, 70, 0.003, 2),
                                    (204, 153, 1.5, 80, 0.005, -3)]]
SLIDER = [{"dyad.2.length": a, "links.4.mass": m, "crank.length": r}
          for a, m, r in [(160, 0.5, 40), (150, 0.7, 38), (170, 0.4, 45)]]
DYADE16 = [{"dyad.2.lengths.2": b, "crank.length": r, "dyad.7.lengths.1": c,
            "frame.points.C0": [0, y], "links.8.mass": m}
           for b, r, c, y, m in [(150, 40, 160, -140, 1.0), (146, 39, 158, -136, 1.3),
                                 (154, 41, 163, -144, 0.8)]]
GUIDES = {  # guide points, angles and offsets of every prismatic kind
    "slotted-lever.toml": [{"dyad.2.B.offset": o, "frame.points.C0": [0, y]}
                           for o, y in ((0, -150), (5, -140), (-4, -160))],
    "scotch-yoke.toml": [{"dyad.2.A.angle": a, "dyad.2.B.angle": b, "dyad.2.A.point": [0, p]}
                         for a, b, p in ((0, 90, 0), (3, 85, 2), (-2, 95, -1))],
    "tangent-drive.toml": [{"dyad.2.A.angle": a} for a in (0, 3, -2)]}
MOTION = ("origin", "angle", "omega", "alpha", "velocity", "acceleration")


def _stacked(name, sets):
    variants = [dyade.read_mechanism(shipped(name), values) for values in sets]
    positions = variants[0].sweep.count
    together = stack(variants, positions)
    angle = np.tile(variants[0].sweep.angles(), len(variants))
    kin = kinematics.sweep(together, angle)
    return variants, positions, kin, kinetostatics.solve(together, kin)


@pytest.mark.parametrize(("name", "sets"), [("fourbar.toml", FOURBAR),
                                            ("slider-crank.toml", SLIDER),
                                            ("dyade-16.toml", DYADE16),
                                            *GUIDES.items()])
def test_stacked_sweep_is_each_variants_sweep(name, sets):
    variants, positions, kin, forces = _stacked(name, sets)
    assert np.all(kin.valid)
    for v, mechanism in enumerate(variants):
        part = slice(v * positions, (v + 1) * positions)
        alone = kinematics.sweep(mechanism)
        alone_forces = kinetostatics.solve(mechanism, alone)
        links = list(mechanism.moving_links)
        for array in MOTION:
            np.testing.assert_allclose(getattr(kin.motion, array)[part][:, links],
                                       getattr(alone.motion, array)[:, links],
                                       rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(kin.transmission[part], alone.transmission, rtol=1e-12)
        np.testing.assert_allclose(forces.drive_torque[part], alone_forces.drive_torque,
                                   rtol=1e-12, atol=1e-12)
        for kind in ("revolute", "normal", "moment"):
            for joint, reaction in getattr(alone_forces, kind).items():
                np.testing.assert_allclose(getattr(forces, kind)[joint][part], reaction,
                                           rtol=1e-12, atol=1e-12)
    # and the variants do differ (the test could not pass by broadcasting one of them)
    first, second = (kin.motion.origin[k * positions:(k + 1) * positions] for k in (0, 1))
    assert np.nanmax(np.abs(first - second)) > 1e-4


def test_a_variant_that_does_not_close_leaves_the_others_alone():
    sets = [FOURBAR[0], dict(FOURBAR[0], **{"dyad.2.lengths.2": 60}), FOURBAR[1]]
    variants, positions, kin, _ = _stacked("fourbar.toml", sets)
    bad = kin.valid.reshape(3, positions)
    assert bad[0].all() and bad[2].all() and not bad[1].all()
    alone = kinematics.sweep(variants[2])
    np.testing.assert_allclose(kin.motion.angle[2 * positions:, 4], alone.motion.angle[:, 4],
                               rtol=1e-12)


def test_variants_of_other_topologies_do_not_stack():
    fourbar = dyade.read_mechanism(shipped("fourbar.toml"))
    other = dyade.read_mechanism(shipped("fourbar.toml"), {"dyad.2.variant": -1})
    with pytest.raises(NotStackable, match="variant"):
        stack([fourbar, other], 361)
    with pytest.raises(NotStackable):
        stack([fourbar, dyade.read_mechanism(shipped("slider-crank.toml"))], 361)


@pytest.mark.parametrize("stop", [360.0, 359.0, 270.0])
def test_means_of_rows_are_each_rows_mean(stop):
    """``cycle.means``/``rmss``: one reduction over the variants' rows gives each row's
    ``cycle.mean``/``rms`` (whole revolutions, gaps, round-off, partial sweeps)."""
    from dyade import cycle

    angle = np.deg2rad(np.arange(0.0, stop + 0.5, 1.0))
    rng = np.random.default_rng(3)
    rows = (rng.uniform(-2, 2, (6, 1)) + np.cos(angle + rng.uniform(0, 6, (6, 1)))
            * rng.uniform(0.5, 3, (6, 1)))
    rows[2] = np.cos(angle)  # a mean that is round-off: 0
    rows[4, 17] = np.nan     # a gap: the trapezoid rule over the rest
    expected_mean = [cycle.mean(angle, row) for row in rows]
    expected_rms = [cycle.rms(angle, row) for row in rows]
    np.testing.assert_allclose(cycle.means(angle, rows), expected_mean, rtol=1e-14, atol=0)
    np.testing.assert_allclose(cycle.rmss(angle, rows), expected_rms, rtol=1e-14, atol=0)
    if stop == 360.0:
        assert cycle.means(angle, rows)[2] == 0.0
        assert abs(cycle.means(angle, rows)[0] - np.mean(rows[0, :-1])) < 1e-12


def test_spread_of_a_run_of_variants_is_spread_of_their_part():
    """``spread(m, n, first, last)`` (one walk, issue 41) = ``spread(part(m, first,
    last), n)`` = the stack of those variants taken out one by one (``pick``)."""
    import tomllib

    from dyade.arrays import Variants
    from dyade.files.mechanism import NUMBERING, build, set_dotted
    from dyade.linkage.stack import part, pick, same, spread

    path = shipped("fourbar.toml")
    with open(path, "rb") as file:
        data = tomllib.load(file)
    set_dotted(data, "dyad.2.lengths.1", Variants([196.0, 200.0, 203.0, 205.0]),
               "fourbar.toml", "parameter", NUMBERING)
    block = build(data, path)
    one_walk = spread(block, 3, 1, 3)
    assert not same(one_walk, spread(part(block, 1, 3), 3))
    assert not same(one_walk, stack([pick(block, 1), pick(block, 2)], 3))
    assert same(one_walk, spread(block, 3, 0, 2))  # (the test can fail)
