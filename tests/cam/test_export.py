"""The profile to manufacture: points within the chord tolerance of the closed form."""

from __future__ import annotations

import numpy as np

from dyade.cam import export, geometry
from tests.cam.cycloid import cycle


def _working(n):
    theta = np.linspace(0.0, 2 * np.pi, n + 1)[:-1]
    s, ds, dds = cycle(theta, 0.02)
    return geometry.translating_roller(theta, s, ds, dds, base_radius=0.03, roller_radius=0.01,
                                       offset=0.005)


def _distance_to_chords(theta, points, keep_theta, polygon):
    """Distance [m] of each closed-form point (at cam angle θ) to the chord of the polygon
    that spans its angle."""
    k = np.searchsorted(keep_theta, theta, side="right") - 1
    a, b = polygon[k], np.roll(polygon, -1, axis=0)[k]
    ab, ap = b - a, points - a
    return np.abs(ab[:, 0] * ap[:, 1] - ab[:, 1] * ap[:, 0]) / np.hypot(*ab.T)


def test_working_curve_within_the_chord_tolerance():
    tolerance = 1e-5  # [m]
    cam = _working(export.dense_count(0.3, 0.02, tolerance))
    keep = export.chord_points(cam.working, cam.working_curvature_radius, tolerance)
    assert 20 < keep.size < cam.theta.size / 5
    # the closed form, 7 times denser and shifted (points the selection never saw)
    fine = _working(7 * cam.theta.size + 3)
    distance = _distance_to_chords(fine.theta, fine.working, cam.theta[keep], cam.working[keep])
    assert distance.max() <= tolerance
    assert distance.max() > 0.3 * tolerance  # not needlessly fine


def test_cutter_path_is_the_offset_of_the_pitch_curve():
    cam = _working(720)
    path = export.offset_curve(cam.working, cam.normal, 0.012)
    assert np.allclose(np.hypot(*(path - cam.pitch).T), 0.002, atol=1e-15)
