"""The closed forms of dimensional synthesis, each checked through dyade's own engine
(``dyade.linkage.positions``): the precision points and poses are reproduced by the
mechanism dyade builds from the file data, not only by the formulas that made them."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.files.mechanism import build
from dyade.linkage.positions import positions
from dyade.synthesis import closed, function
from dyade.synthesis.topology import FourBar, fourbar_from_points


def test_freudenstein_passes_through_three_precision_points_exactly():
    phi = np.deg2rad([40.0, 75.0, 110.0])
    psi = np.deg2rad([70.0, 95.0, 128.0])
    linkage = closed.freudenstein(phi, psi, frame=1.0)
    traced = function.traced(linkage, phi)  # through dyade's engine
    assert np.abs(function.wrap(traced - psi)).max() < 1e-12
    # Freudenstein's equation itself (K1 = d/a, K2 = d/c, K3 from the lengths)
    a, b, c, d = linkage.a, linkage.b, linkage.c, linkage.d
    k3 = (a * a - b * b + c * c + d * d) / (2 * a * c)
    assert np.allclose(d / a * np.cos(psi) - d / c * np.cos(phi) + k3, np.cos(phi - psi),
                       rtol=0, atol=1e-13)


def test_a_negative_crank_is_built_with_its_pin_on_the_other_side():
    # points whose solution has a < 0 (the crank pin opposite the crank's ξ axis)
    phi = np.deg2rad([200.0, 230.0, 260.0])
    psi = np.deg2rad([60.0, 80.0, 105.0])
    linkage = closed.freudenstein(phi, psi)
    traced = function.traced(linkage, phi)
    assert np.abs(function.wrap(traced - psi)).max() < 1e-12


def test_chebyshev_spacing_and_the_structural_error_at_every_row():
    assert np.allclose(closed.chebyshev(0.0, 2.0, 3), [1 - np.cos(np.pi / 6), 1.0,
                                                       1 + np.cos(np.pi / 6)])
    # y = log10(x), x in [1, 10] -> φ over 200°..290°, ψ over 300°..360°
    x = np.linspace(1.0, 10.0, 46)
    phi = np.deg2rad(200.0 + 90.0 * (x - 1.0) / 9.0)
    psi = np.deg2rad(300.0 + 60.0 * np.log10(x))
    result = function.generate(phi, psi, method="chebyshev")
    assert result.error.shape == phi.shape and np.isfinite(result.error).all()
    # zero at the precision points (ψ there interpolated from the table: the linear
    # interpolation's error), nonzero between, alternating in sign between them
    at = function.traced(result.linkage, result.precision)
    wanted = np.interp(result.precision, phi, psi)
    assert np.abs(function.wrap(at - wanted)).max() < 1e-12
    assert np.abs(result.error).max() > 1e-3
    signs = np.sign(result.error[np.abs(result.error) > 1e-6])
    assert np.count_nonzero(np.diff(signs)) >= 2


@pytest.mark.slow
def test_the_least_squares_fit_of_a_table_beats_its_chebyshev_start():
    x = np.linspace(1.0, 10.0, 46)
    phi = np.deg2rad(200.0 + 90.0 * (x - 1.0) / 9.0)
    psi = np.deg2rad(300.0 + 60.0 * np.log10(x))
    start = function.generate(phi, psi, method="chebyshev")
    fitted = function.generate(phi, psi, method="fit")
    assert np.abs(fitted.error).max() < np.abs(start.error).max()


def test_too_few_precision_points_are_refused():
    with pytest.raises(ValueError, match="exactly three"):
        function.generate(np.deg2rad([10.0, 20.0]), np.deg2rad([1.0, 2.0]), method="precision")


def test_three_poses_are_reproduced_by_the_engine():
    poses = np.array([[0.0, 0.0, 0.0], [0.6, 0.25, np.deg2rad(25.0)],
                      [1.1, 0.2, np.deg2rad(55.0)]])
    a0, a, b0, b = closed.three_poses(poses, (-0.3 + -0.5j, 0.5 - 0.4j))
    values, variant, placement, crank0 = fourbar_from_points(a0, a, b, b0, 0j)
    mechanism = build(FourBar().data(values, variant, placement))
    # the crank angle of each pose: the moving pivot's direction from its fixed pivot
    moving = closed.pose_points(poses, a)
    crank = np.angle(moving - a0)
    found = positions(mechanism, crank, [(3, (values[4], values[5]))])
    point = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
    assert np.abs(point - (poses[:, 0] + 1j * poses[:, 1])).max() < 1e-12
    turned = found.angles[:, 3] - found.angles[0, 3]
    assert np.abs(function.wrap(turned - (poses[:, 2] - poses[0, 2]))).max() < 1e-12


def test_every_burmester_pair_reproduces_the_four_poses():
    poses = np.array([[0.0, 0.0, 0.0], [0.5, 0.2, np.deg2rad(20.0)],
                      [0.9, 0.1, np.deg2rad(45.0)], [1.2, -0.2, np.deg2rad(80.0)]])
    curves = closed.burmester(poses, samples=360)
    assert curves.centre.size > 100
    for centre, circle in zip(curves.centre, curves.circle):
        radii = np.abs(closed.pose_points(poses, circle) - centre)
        assert radii.max() - radii.min() < 1e-9 * max(1.0, radii.max())
    # the pole of poses 0 and 1 lies on the centre-point curve (a degenerate dyad)
    z = poses[:, 0] + 1j * poses[:, 1]
    turn = np.exp(1j * (poses[1, 2] - poses[0, 2]))
    pole = (z[1] - turn * z[0]) / (1 - turn)
    assert np.abs(curves.centre - pole).min() < 0.05


def on_the_coupler_curve(linkage: closed.FourBar, point: complex) -> float:
    """How far P is from being a position of the four-bar's coupler point: the crank
    pin A on both circles |A − A0| = a and |A − P| = |AP|, then B = A + (P − A)/ρ must
    lie at c from B0 (the smaller miss of the two intersections) [m]."""
    rho = complex(linkage.p, linkage.q) / linkage.b
    ring = abs(rho) * linkage.b
    d = abs(point)
    along = (d * d + linkage.a ** 2 - ring ** 2) / (2 * d)
    height = np.sqrt(max(linkage.a ** 2 - along ** 2, 0.0))
    unit = point / d
    misses = []
    for side in (1, -1):
        a = unit * (along + 1j * side * height)
        b = a + (point - a) / rho
        misses.append(abs(abs(b - linkage.d) - linkage.c))
    return min(misses)


def test_the_cognates_trace_the_same_curve_through_the_engine():
    linkage = closed.FourBar(a=0.4, b=1.2, c=1.1, d=1.0, p=0.5, q=0.6, variant=1)
    for cognate in closed.cognates(linkage):
        (f0, f1), (m0, m1), p = cognate.fixed, cognate.moving, cognate.point
        values, variant, placement, crank0 = fourbar_from_points(f0, m0, m1, f1, p)
        mechanism = build(FourBar().data(values, variant, placement))
        # swing the driven link ±10° about the given position: it moves there
        crank = crank0 + placement.angle + np.deg2rad(np.linspace(-10.0, 10.0, 21))
        found = positions(mechanism, crank, [(3, (values[4], values[5]))])
        traced = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
        assert found.closes.all()
        assert np.abs(traced[10] - p) < 1e-12
        assert max(on_the_coupler_curve(linkage, z) for z in traced) < 1e-12
        assert np.ptp(np.abs(traced - p)) > 0.01  # it moved
