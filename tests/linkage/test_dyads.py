"""Every dyad kind, both variants, guide/slider swapped or not, any scale."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from dyade.linkage import motion as joints
from tests.helpers import kinematics_at, mechanism_from
from tests.strategies import KINDS, dyad_files

ANGLES = np.deg2rad(np.arange(0.0, 360.0, 7.5))
H = 1e-5  # [rad]
WELL_CONDITIONED = np.sin(np.deg2rad(10.0))  # FD checks away from dead centres


def _good_positions(mechanism):
    """Crank angles away from dead centres, and the kinematics there."""
    kin = kinematics_at(mechanism, ANGLES)
    good = kin.valid & (kin.conditioning[:, 0] > WELL_CONDITIONED)
    assume(good.sum() >= 2)
    return ANGLES[good], kinematics_at(mechanism, ANGLES[good])


def _single_dyad(data):
    """Mechanism, its one dyad, the kinematics at good positions and the crank tip A."""
    mechanism = mechanism_from(data)
    _, kin = _good_positions(mechanism)
    (dyad,) = mechanism.dyads
    return mechanism, dyad, kin, kin.motion.point(2, (mechanism.crank.length, 0.0))


def _check_closure_and_derivatives(data):
    mechanism = mechanism_from(data)
    angles, kin = _good_positions(mechanism)
    scale = mechanism.crank.length
    omega = mechanism.crank.speed
    for joint in mechanism.joints:
        res = joints.residual(joint, kin.motion)
        limit = 1e-12 * scale * 10
        if joint.kind == "P":
            assert np.max(np.abs(res[:, 0])) < 1e-12
            assert np.max(np.abs(res[:, 1])) < limit
        else:
            assert np.max(np.abs(res)) < limit
    ahead = kinematics_at(mechanism, angles + H).motion
    behind = kinematics_at(mechanism, angles - H).motion
    here = kin.motion
    for link in (3, 4):
        fd_v = (ahead.point(link, (scale, 0)) - behind.point(link, (scale, 0))) / (2 * H) * omega
        fd_a = ((ahead.point_velocity(link, (scale, 0)) - behind.point_velocity(link, (scale, 0)))
                / (2 * H) * omega)
        v = here.point_velocity(link, (scale, 0))
        a = here.point_acceleration(link, (scale, 0))
        assert np.allclose(fd_v, v, rtol=0, atol=1e-5 * max(np.max(np.abs(v)), scale * abs(omega)))
        assert np.allclose(fd_a, a, rtol=0,
                           atol=1e-4 * max(np.max(np.abs(a)), scale * omega ** 2))


@pytest.mark.parametrize("kind", KINDS)
@given(draw=st.data())
def test_closes_and_differentiates(kind, draw):
    _check_closure_and_derivatives(draw.draw(dyad_files(kind=kind), label="mechanism"))


@given(data=dyad_files(kind="RRR"))
def test_rrr_variant_picks_the_side_of_ac(data):
    _, dyad, kin, a = _single_dyad(data)
    c = np.array(dyad.joints[2].points[0])
    b = kin.motion.point(3, dyad.joints[1].points[0])
    side = np.sign((c - a)[:, 0] * (b - a)[:, 1] - (c - a)[:, 1] * (b - a)[:, 0])
    assert np.all(side == dyad.variant)


@given(data=dyad_files(kind="RRP"))
def test_rrp_variant_puts_b_ahead_or_behind_along_the_guide(data):
    _, dyad, kin, a = _single_dyad(data)
    guide = dyad.joints[2]
    d = kin.motion.direction(guide.carrier, guide.guide_angle)
    b = kin.motion.origin[:, 4]
    assert np.all(np.sign(joints.dot(b - a, d)) == dyad.variant)


@given(data=dyad_files(kind="RPR"))
def test_rpr_variant_orients_the_guide(data):
    _, dyad, kin, a = _single_dyad(data)
    guide = dyad.joints[1]
    d = kin.motion.direction(guide.carrier, guide.guide_angle)
    pivots = {3: a,
              4: np.broadcast_to(dyad.joints[2].points[0], d.shape)}
    towards = pivots[guide.slider] - pivots[guide.carrier]
    assert np.all(np.sign(joints.dot(towards, d)) == dyad.variant)


def test_rrr_dead_centre_is_flagged_not_solved():
    # coupler + rocker exactly stretched at φ21 = 0: |AC| = l_i + l_j
    data = {"crank": {"length": 1.0, "speed_rpm": 60},
            "dyad": [{"kind": "RRR", "links": [3, 4], "A": {"link": 2, "point": "tip"},
                      "C": {"link": 1, "point": [4.0, 0.0]}, "lengths": [2.0, 1.0]}]}
    kin = kinematics_at(mechanism_from(data), [0.0, np.pi / 2])
    assert kin.closes[0, 0] and kin.singular[0, 0]
    assert np.isnan(kin.motion.omega[0, 3])           # no huge number posing as a result
    assert np.rad2deg(kin.transmission[0, 0]) == pytest.approx(180.0)
    assert not kin.closes[1, 0]                          # beyond the dead centre: no closure
