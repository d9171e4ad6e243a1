"""The component forms of the closures and of the loop solve (issue 17) against what
they replaced: the vector closures of RRP, RPR, PRP and PPR (``tests/previous_closures``)
and the general 3×3 inverse of the loop matrix (``kinematics.inverse3``), to the bit;
the forces of each kind against one global solve per position.

Closure residuals and central differences of every kind are checked in test_dyads.py
(one dyad on the crank) and test_chains.py (dyads on moving links)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, reject
from hypothesis import strategies as st

from dyade.errors import InputError
from dyade.linkage import kinematics, kinetostatics
from dyade.linkage.motion import Motion
from tests import previous_closures
from tests.helpers import kinematics_at, mechanism_from, shipped
from tests.strategies import chained_files, dyad_files
from tests.test_kinetostatics import _compare, with_masses

SLIDING = ["RRP", "RPR", "PRP", "PPR"]
ANGLES = np.deg2rad(np.arange(0.0, 360.0, 15.0))


def _copy(motion: Motion) -> Motion:
    return Motion(*(np.array(getattr(motion, name)) for name in Motion.__slots__))


def _same_closures(mechanism) -> None:
    """Each sliding dyad closed again on the engine's motion, by the component form and
    by the vector form: the same poses, closures and transmission angles to the bit."""
    kin = kinematics_at(mechanism, ANGLES)
    for col, dyad in enumerate(mechanism.dyads):
        if dyad.kind.name not in SLIDING:
            continue
        new_motion, old_motion = _copy(kin.motion), _copy(kin.motion)
        new = dyad.kind.close(dyad, new_motion)
        old = previous_closures.CLOSE[dyad.kind.name](dyad, old_motion)
        np.testing.assert_array_equal(new.closes, old[0])
        closes = new.closes  # (elsewhere the engine sets the poses NaN)
        for name in ("origin", "angle", "cos", "sin"):
            for link in dyad.links:
                np.testing.assert_array_equal(getattr(new_motion, name)[closes, link],
                                              getattr(old_motion, name)[closes, link],
                                              err_msg=f"{dyad.kind.name} {name} {link}")
        np.testing.assert_array_equal(new.transmission[closes], old[1][closes])
        # |sin μ| from the closure's own numbers instead of the sine of μ: round-off
        np.testing.assert_allclose(new.conditioning[closes], old[2][closes], rtol=0, atol=1e-12)
        if dyad.kind.name == "RPR":
            np.testing.assert_array_equal(new.lever, old[3])


@pytest.mark.parametrize("kind", SLIDING)
def test_each_sliding_closure_is_the_vector_closure(kind):
    """One dyad of the kind on the crank and the frame, guides on either link."""
    given(data=dyad_files(kind=kind))(lambda data: _same_closures(mechanism_from(data)))()


def _built(data):
    """The mechanism of a drawn file (the chains' strategy may draw a bad one)."""
    try:
        return mechanism_from(data)
    except InputError:
        reject()


@given(data=chained_files())
def test_closures_on_moving_links_are_the_vector_closures(data):
    """Outer joints on any placed link: moving guides, guides carried by either link."""
    _same_closures(_built(data))


@pytest.mark.parametrize("name", ["slider-crank.toml", "self-locking.toml", "dyade-16.toml",
                                  "slotted-lever.toml", "tangent-drive.toml",
                                  "scotch-yoke.toml"])
def test_shipped_closures_are_the_vector_closures(name):
    from dyade.files import mechanism as toml_input

    _same_closures(toml_input.read_mechanism(shipped(name)))


@pytest.mark.parametrize("kind", ["RRP", "PRP"])
def test_middle_pin_off_the_origins_is_the_vector_closure(kind):
    """The readers put pin B at the origin of link j (RRP) or of both links (PRP); a
    mechanism built in Python may put it anywhere: the line through B moves with it."""
    from dataclasses import replace

    @given(data=dyad_files(kind=kind), shift=st.tuples(*[st.floats(-1.0, 1.0)] * 4))
    def check(data, shift):
        mechanism = mechanism_from(data)
        (dyad,) = mechanism.dyads
        joint_a, joint_b, joint_c = dyad.joints
        size = mechanism.crank.length
        (u_i, u_j) = joint_b.points
        points = ((u_i[0] + shift[0] * size, u_i[1] + shift[1] * size) if kind == "PRP" else u_i,
                  (shift[2] * size, shift[3] * size))
        moved = replace(dyad, joints=(joint_a, replace(joint_b, points=points), joint_c))
        _same_closures(replace(mechanism, dyads=(moved,)))

    check()


def _same_solves(mechanism) -> None:
    """Rates, the inverse and the force stage's solve of every dyad against the general
    inverse of its loop matrix: the same numbers to the bit."""
    kin = kinematics_at(mechanism, ANGLES)
    rng = np.random.default_rng(7)
    for group in kin.groups:
        with np.errstate(all="ignore"):  # a determinant below 1e-308 overflows there
            general = kinematics.inverse3(*group.screws, group.usable)
        # where the general inverse is not finite (|det M| < TINY_DET) the rows are NaN
        finite = np.isfinite(general).all(axis=(0, 1))
        assert np.isnan(group.inverse[:, :, ~finite]).all()
        np.testing.assert_array_equal(group.inverse[:, :, finite], general[:, :, finite])
        for k in range(3):
            np.testing.assert_array_equal(
                group.rate(k)[finite], kinematics.solve_rows(general, group.loop, (k,))[0][finite])
        rhs0, rhs2 = rng.normal(size=(2, ANGLES.size))
        np.testing.assert_array_equal(
            group.reaction(rhs0, rhs2)[:, finite],
            kinetostatics.solve_transposed(general, rhs0, rhs2)[:, finite])


@given(data=dyad_files())
def test_loop_solves_are_the_general_inverse(data):
    _same_solves(mechanism_from(data))


@given(data=chained_files())
def test_loop_solves_on_moving_links_are_the_general_inverse(data):
    _same_solves(_built(data))


@pytest.mark.parametrize("kind", SLIDING)
def test_each_sliding_kind_against_global_solve(kind):
    """Forces of one dyad of each kind on the crank, with masses and gravity everywhere,
    against one global linear solve per position (tests/global_solve.py)."""
    @given(data=dyad_files(kind=kind))
    def check(data):
        mechanism = with_masses(mechanism_from(data), gravity=(3.0, -9.81))
        kin = kinematics_at(mechanism, ANGLES)
        good = kin.valid & (kin.conditioning[:, 0] > 0.2)
        assume(good.any())
        kin = kinematics_at(mechanism, ANGLES[good])
        _compare(mechanism, kin, kinetostatics.solve(mechanism, kin))

    check()
