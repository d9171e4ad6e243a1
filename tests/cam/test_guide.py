"""The translating follower's guide (dyade.cam.guide) against the classic two-point
guide in closed form: the stem bears at the guide's two ends, L apart, the contact force
N at the pressure angle α through the roller centre b' = b − s below the near end. The
reactions sum to μ·N·|sin α|·(1 + 2·b'/L), so the balance along the guide is

    N·(cos α − μ·|sin α|·(1 + 2·b'/L)·σ) = m·s″·ω² + k·(s + s0) + F     (σ = sign ṡ)

and the cam cannot push the follower up where tan |α| ≥ L/(μ·(L + 2·b')): it jams."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.cam import geometry, guide
from tests.cam.cycloid import cycle

THETA = np.linspace(0.0, 2 * np.pi, 721)[:-1]
M, K, S0, F = 0.5, 2000.0, 0.01, 5.0  # [kg], [N/m], [m], [N]
L, B, OMEGA = 0.02, 0.04, 30.0  # [m], [m], [rad/s]


def _roller(clockwise=False):
    s, ds, dds = cycle(THETA, 0.02)
    cam = geometry.translating_roller(THETA, s, ds, dds, base_radius=0.025,
                                      roller_radius=0.008, offset=0.006, clockwise=clockwise)
    return cam, s, ds, dds


@pytest.mark.parametrize("clockwise", [False, True])
@pytest.mark.parametrize("mu", [0.3, 0.9])
def test_roller_follower_in_a_two_point_guide(clockwise, mu):
    cam, s, ds, dds = _roller(clockwise)
    guided = guide.guide(cam, s, ds, friction=mu, length=L, overhang=B)
    alpha = cam.pressure_angle
    lever = 1.0 + 2.0 * (B - s) / L
    assert np.max(np.abs(guided.pressure - np.abs(np.sin(alpha)) * lever)) < 1e-12
    margin = 1.0 - mu * np.abs(np.tan(alpha)) * lever
    assert np.max(np.abs(guided.margin - margin)) < 1e-12
    along = M * dds * OMEGA ** 2 + K * (s + S0) + F
    force, jammed = guide.contact_force(along, np.cos(alpha), guided, mu)
    sigma = np.sign(ds) * (np.abs(ds) > 1e-12)
    expected = along / (np.cos(alpha) - mu * np.abs(np.sin(alpha)) * lever * sigma)
    classic = (sigma > 0) & (np.abs(np.tan(alpha)) >= L / (mu * (L + 2.0 * (B - s))))
    assert np.array_equal(jammed, classic)
    free = ~classic
    assert np.max(np.abs(force[free] / expected[free] - 1.0)) < 1e-9
    assert np.isnan(force[classic]).all()
    assert classic.any() == (mu == 0.9)  # the steeper guide friction jams the rise
    # the friction takes power: the cam's (N·n·contact velocity) exceeds the follower's
    # useful power on the rise by the guide's loss μ·N·p·|ṡ|
    rise = free & (sigma > 0)
    loss = mu * force * guided.pressure * ds * OMEGA
    cam_power = force * np.cos(alpha) * ds * OMEGA
    assert np.allclose(cam_power[rise] - loss[rise], along[rise] * ds[rise] * OMEGA,
                       rtol=1e-9, atol=1e-12)


def test_flat_face_tilts_the_stem():
    s, ds, dds = cycle(THETA, 0.01)
    cam = geometry.translating_flat(THETA, s, ds, dds, base_radius=0.04, offset=0.003)
    guided = guide.guide(cam, s, ds, friction=0.2, length=L, overhang=B)
    d = ds - 0.003  # the contact's distance from the stem's line of motion
    assert np.max(np.abs(guided.pressure - 2.0 * np.abs(d) / L)) < 1e-12
    assert np.max(np.abs(guided.margin - (1.0 - 0.4 * np.abs(d) / L))) < 1e-12


CAM = """name = "Guided cam"
units = {{ length = "mm", angle = "deg" }}
[cam]
follower = "{follower}"
base_radius = 25
speed_rpm = 300
[follower]
{roller}
mass = 0.5
stiffness = 2000
preload = 10
guide_friction = {mu}
{guide}
[manufacture]
chord_tolerance = 0.05
[profile]
unit = "mm"
period = 360
[[profile.segment]]
kind = "rise"
law = "cycloid"
end = 120
to = 20
[[profile.segment]]
kind = "dwell"
end = 180
[[profile.segment]]
kind = "return"
law = "cycloid"
end = 300
to = 0
[[profile.segment]]
kind = "dwell"
end = 360
"""


def _file(tmp_path, mu=0.6, follower="translating-roller", roller="roller_radius = 8",
          guide="guide_length = 20\nguide_overhang = 40"):
    path = tmp_path / "guided.toml"
    path.write_text(CAM.format(follower=follower, roller=roller, mu=mu, guide=guide))
    return str(path)


def test_the_cam_entry_says_where_the_follower_jams(tmp_path):
    import dyade

    outcome = dyade.run("cam", _file(tmp_path), step_deg=1.0)
    jammed = outcome.columns["jammed"]
    assert jammed.any() and np.isnan(outcome.columns["contact_force"][jammed]).all()
    assert np.isnan(outcome.columns["drive_torque"][jammed]).all()
    margin = outcome.columns["guide_margin"]
    assert (margin[jammed] <= 0).all() and outcome.summary["guide_margin_min"].value < 0
    angles = outcome.columns["angle_deg"][jammed]
    assert any(f"jams in its guide at cam angles {angles[0]:.1f}°–{angles[-1]:.1f}°" in n
               for n in outcome.notes)
    free = dyade.run("cam", _file(tmp_path, mu=0.2), step_deg=1.0)
    assert not free.columns["jammed"].any() and free.summary["guide_margin_min"].value > 0
    assert not any("jams" in n for n in free.notes)


@pytest.mark.parametrize("follower, roller, guide, key", [
    ("oscillating-roller", "roller_radius = 8\npivot_distance = 60\narm_length = 45", "",
     "follower.guide_friction"),
    ("translating-roller", "roller_radius = 8", "guide_overhang = 40",
     "follower.guide_length")])
def test_guide_friction_needs_a_translating_follower_and_a_guide_length(
        tmp_path, follower, roller, guide, key):
    from dyade.errors import InputError
    from dyade.files.cam import read_cam

    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        read_cam(_file(tmp_path, 0.3, follower, roller, guide))
