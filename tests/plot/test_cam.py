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


@pytest.mark.slow  # two panels of the linkage: about 1 s
def test_the_mechanism_figure_draws_the_cam_under_its_follower():
    """A cam-driven mechanism (`dyade plot mechanism`): at each cam angle the cam turned
    to it touches the roller on link 2, whose centre is the follower's at that angle."""
    from dyade.plot import mechanism as mechanism_plot

    result = dyade.analyse(dyade.read_mechanism("mechanisms/cams/cam-rocker.toml"))
    fig = mechanism_plot.figure(result, at_deg=[0.0, 60.0])
    for ax, lift in zip(fig.axes, (0.0, 0.0125)):  # the cycloid's lift at 60°: half of 25 mm
        cam = next(p for p in ax.patches if p.get_gid() == "cam").get_xy()
        roller = next(p for p in ax.patches if p.get_gid() == "roller")
        assert roller.center == pytest.approx((0.0, 0.038 + lift), abs=1e-12)
        gap = np.hypot(*(cam - np.asarray(roller.center)).T).min() - roller.radius
        assert abs(gap) < 2e-5  # the outline at 0.5°: within 20 µm
    assert [ax.get_title() for ax in fig.axes] == ["θ = 0°", "θ = 60°"]
