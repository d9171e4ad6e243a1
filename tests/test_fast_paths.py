"""The component forms of the closures and of the loop solve (issue 17) against what
they replaced: the vector closures of RRP, RPR, PRP and PPR (``tests/previous_closures``)
and the general 3×3 inverse of the loop matrix (``inverse3`` below), to the bit;
the forces of each kind against one global solve per position.

Closure residuals and central differences of every kind are checked in test_dyads.py
(one dyad on the crank) and test_chains.py (dyads on moving links)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, reject
from hypothesis import strategies as st

from dyade.errors import InputError
from dyade.linkage import dyads, kinetostatics
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
        new = dyads.close(dyad, new_motion)
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


# -- the general inverse of the loop matrix the components replaced (issue 17) -------
def _comb(p, a, q, b):
    """p·a − q·b for constants p, q (the ω parts of screws, mostly 0 or ±1)."""
    if q == 0.0:
        return 0.0 if p == 0.0 else (a if p == 1.0 else p * a)
    if p == 0.0:
        return -b if q == 1.0 else -q * b
    if p == 1.0 and q == 1.0:
        return a - b
    return p * a - q * b


def inverse3(c0, c1, c2, usable):
    """Rows (3, 3, n) of the inverse of the loop matrix [c0, c1, −c2] of three screws;
    NaN where not ``usable``. The rows of [c0, c1, c2]⁻¹ are c1×c2, c2×c0, c0×c1 over
    the determinant; the sign of c2 flips the last row."""
    (x0, y0, w0), (x1, y1, w1), (x2, y2, w2) = c0, c1, c2
    rows = np.empty((3, 3, x0.shape[0]))
    rows[0, 0], rows[0, 1] = _comb(w2, y1, w1, y2), _comb(w1, x2, w2, x1)
    rows[1, 0], rows[1, 1] = _comb(w0, y2, w2, y0), _comb(w2, x0, w0, x2)
    rows[2, 0], rows[2, 1] = _comb(w1, y0, w0, y1), _comb(w0, x1, w1, x0)
    rows[0, 2] = x1 * y2 - y1 * x2
    rows[1, 2] = x2 * y0 - y2 * x0
    rows[2, 2] = x0 * y1 - y0 * x1
    det = x0 * rows[0, 0] + y0 * rows[0, 1]
    if w0 != 0.0:
        det += w0 * rows[0, 2]
    # singular rows become NaN below; a determinant below 1e-308 overflows to inf
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        scale = 1.0 / det
    if not usable.all():
        scale[~usable] = np.nan
    rows[:2] *= scale
    rows[2] *= -scale
    return rows


def solve_rows(inverse, rhs, rows=(0, 1, 2)):
    """Rows of M⁻¹·rhs; ``rhs`` has three components, a plain 0.0 for a zero one."""
    out = []
    for k in rows:
        total = None
        for col in range(3):
            if isinstance(rhs[col], float) and rhs[col] == 0.0:
                continue
            term = inverse[k, col] * rhs[col]
            total = term if total is None else np.add(total, term, out=total)
        out.append(np.zeros_like(inverse[k, 0]) if total is None else total)
    return out


def solve_transposed(inverse, rhs0, rhs2):
    """M⁻ᵀ·(rhs0, 0, rhs2) with the rows (3, 3, n) of M⁻¹."""
    out = inverse[0] * rhs0
    out += inverse[2] * rhs2
    return out


def _same_solves(mechanism) -> None:
    """Rates, the inverse and the force stage's solve of every dyad against the general
    inverse of its loop matrix: the same numbers to the bit."""
    kin = kinematics_at(mechanism, ANGLES)
    rng = np.random.default_rng(7)
    for group in kin.groups:
        with np.errstate(all="ignore"):  # a determinant below 1e-308 overflows there
            general = inverse3(*group.screws, group.usable)
        # where the general inverse is not finite (|det M| < TINY_DET) the rows are NaN
        finite = np.isfinite(general).all(axis=(0, 1))
        assert np.isnan(group.inverse[:, :, ~finite]).all()
        np.testing.assert_array_equal(group.inverse[:, :, finite], general[:, :, finite])
        for k in range(3):
            np.testing.assert_array_equal(
                group.rate(k)[finite], solve_rows(general, group.loop, (k,))[0][finite])
        rhs0, rhs2 = rng.normal(size=(2, ANGLES.size))
        np.testing.assert_array_equal(
            group.reaction(rhs0, rhs2)[:, finite],
            solve_transposed(general, rhs0, rhs2)[:, finite])


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
