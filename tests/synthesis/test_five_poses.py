"""Motion generation through five poses: the Ball–Burmester points (moving pivots whose
five positions lie on one circle) include a known four-bar's own moving pivots, each is
on its circle to 1e-10, and the four-bar chosen reproduces the five poses through
dyade's engine."""

from __future__ import annotations

import numpy as np

from dyade.files.synthesis import parse
from dyade.synthesis import closed, synthesise

KNOWN = closed.FourBar(0.35, 0.9, 0.7, 1.0, 0.4, 0.3, variant=1)
PHI = np.deg2rad([20.0, 50.0, 85.0, 120.0, 150.0])


def _poses():
    rows = []
    for phi in PHI:
        at = closed.points(KNOWN, phi)
        rows.append([at["P"].real, at["P"].imag, np.angle(at["B"] - at["A"])])
    return np.array(rows)


def test_the_ball_burmester_points_hold_the_known_pivots():
    poses = _poses()
    centres, circles = closed.ball_burmester(poses)
    first = closed.points(KNOWN, PHI[0])
    for pivot, fixed in ((first["A"], 0j), (first["B"], complex(KNOWN.d))):
        k = int(np.argmin(np.abs(circles - pivot)))
        assert abs(circles[k] - pivot) < 1e-9 and abs(centres[k] - fixed) < 1e-9
    # every point found: its five positions on the circle about its centre
    at = closed.pose_points(poses, circles)
    radius = np.abs(at - centres[:, None])
    assert np.ptp(radius, axis=1).max() < 1e-10


def test_five_poses_are_reproduced_through_dyade():
    poses = _poses()
    problem = parse({"units": {"length": "m", "angle": "rad"},
                     "target": {"kind": "poses", "poses": poses.tolist()}})
    result = synthesise(problem)
    assert result.designs[0].error < 1e-9  # the largest miss of the five poses [m]
