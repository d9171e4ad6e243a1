"""The cam figure (issue 40): the cam drawn turned to the angle asked, touching its
roller; the pressure angle and curvature panels are the Outcome's columns."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("matplotlib")

import dyade  # noqa: E402
from dyade.plot import cam as cam_plot  # noqa: E402


@pytest.mark.slow  # a figure of five panels: about 1 s
def test_the_cam_touches_its_roller_at_the_angle_asked():
    outcome = dyade.run("cam", "mechanisms/cams/translating-roller.toml", step_deg=2.0)
    fig = cam_plot.figure(outcome, angles_deg=(100.0,))
    drawing, motion, *_ = fig.axes
    shape = drawing.patches[0].get_xy()  # the cam turned to 100°, in mm
    roller = next(p for p in drawing.patches if type(p).__name__ == "Circle")
    gap = np.hypot(*(shape - np.asarray(roller.center)).T).min() - roller.radius
    assert abs(gap) < 0.01  # the polygon of the curve sampled at 2°: within 10 µm
    cam = outcome.result.cam
    assert roller.radius == pytest.approx(cam.roller_radius * 1e3)
    pressure = next(ax for ax in fig.axes if ax.get_ylabel() == "pressure angle α [°]")
    assert np.allclose(pressure.lines[0].get_ydata(), outcome.columns["pressure_angle_deg"])
    assert math.isclose(abs(pressure.lines[1].get_ydata()[0]), 30.0)
