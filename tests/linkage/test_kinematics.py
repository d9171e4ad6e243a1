"""Kinematics: closure residuals, finite differences, independent closed forms."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.linkage import motion as joints, kinematics
from dyade.files import mechanism as toml_input
from dyade.cli import main
from tests.conftest import SHIPPED
from tests.helpers import kinematics_at, read_csv, shipped

H = 1e-5  # [rad] crank-angle step of the central differences


def _valid_angles(mechanism, count=37):
    angles = np.linspace(mechanism.sweep.start, mechanism.sweep.stop, count)
    kin = kinematics_at(mechanism, angles)
    return angles[kin.valid]


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_joint_closes_to_round_off(path):
    mechanism = toml_input.read_mechanism(path)
    kin = kinematics.sweep(mechanism)
    assert kin.valid.all()
    size = np.nanmax(np.abs(kin.motion.origin))  # [m] the mechanism's extent
    for joint in mechanism.joints:
        res = joints.residual(joint, kin.motion)
        if joint.kind == "R":
            assert np.max(np.abs(res)) < 1e-14 * size * 100, joint   # metres, ~100 ulp
        else:
            assert np.max(np.abs(res[:, 0])) < 1e-13, joint           # relative angle [rad]
            assert np.max(np.abs(res[:, 1])) < 1e-14 * size * 100, joint


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_velocities_and_accelerations_match_central_differences(path):
    mechanism = toml_input.read_mechanism(path)
    angles = _valid_angles(mechanism)
    omega = mechanism.crank.speed
    here = kinematics_at(mechanism, angles).motion
    ahead = kinematics_at(mechanism, angles + H).motion
    behind = kinematics_at(mechanism, angles - H).motion
    length = mechanism.crank.length
    for link in mechanism.moving_links:
        d_angle = np.angle(np.exp(1j * (ahead.angle[:, link] - behind.angle[:, link])))
        checks = (
            (d_angle / (2 * H) * omega, here.omega[:, link], abs(omega)),
            ((ahead.omega[:, link] - behind.omega[:, link]) / (2 * H) * omega,
             here.alpha[:, link], omega ** 2),
            ((ahead.origin[:, link] - behind.origin[:, link]) / (2 * H) * omega,
             here.velocity[:, link], length * abs(omega)),
            ((ahead.velocity[:, link] - behind.velocity[:, link]) / (2 * H) * omega,
             here.acceleration[:, link], length * omega ** 2),
        )
        for fd, exact, typical in checks:
            # truncation O(H²) and round-off O(eps/H): 1e-6 of the larger of the
            # quantity's own peak and the mechanism's typical value (L·Ω, L·Ω², ...)
            scale = max(np.max(np.abs(exact)), typical)
            assert np.max(np.abs(fd - exact)) <= 1e-6 * scale, (link, scale)


def _fourbar_closed_form(phi, a0, b0, r2, r3, r4, omega):
    """Independent vector-loop solution of the four-bar (Freudenstein-style)."""
    a = a0 + r2 * np.stack((np.cos(phi), np.sin(phi)), -1)
    d = b0 - a
    dist = np.hypot(d[:, 0], d[:, 1])
    # angle at A between AB0 and AB (law of cosines); B above the line A->B0
    gamma = np.arccos((r3 ** 2 + dist ** 2 - r4 ** 2) / (2 * r3 * dist))
    phi3 = np.arctan2(d[:, 1], d[:, 0]) + gamma
    b = a + r3 * np.stack((np.cos(phi3), np.sin(phi3)), -1)
    phi4 = np.arctan2(b[:, 1] - b0[1], b[:, 0] - b0[0])
    # velocity loop: r2 ω2 e⊥2 + r3 ω3 e⊥3 = r4 ω4 e⊥4 -> ω3, ω4 by Cramer's rule
    w3 = omega * r2 * np.sin(phi4 - phi) / (r3 * np.sin(phi3 - phi4))
    w4 = omega * r2 * np.sin(phi3 - phi) / (r4 * np.sin(phi3 - phi4))
    # acceleration loop
    rhs = (r2 * omega ** 2 * np.cos(phi) + r3 * w3 ** 2 * np.cos(phi3) - r4 * w4 ** 2 * np.cos(phi4),
           r2 * omega ** 2 * np.sin(phi) + r3 * w3 ** 2 * np.sin(phi3) - r4 * w4 ** 2 * np.sin(phi4))
    # unknowns α3, α4:  -r3 sin3 α3 + r4 sin4 α4 = rhs_x ; r3 cos3 α3 - r4 cos4 α4 = rhs_y
    det = -r3 * np.sin(phi3) * (-r4 * np.cos(phi4)) - r4 * np.sin(phi4) * r3 * np.cos(phi3)
    al3 = (rhs[0] * (-r4 * np.cos(phi4)) - r4 * np.sin(phi4) * rhs[1]) / det
    al4 = (-r3 * np.sin(phi3) * rhs[1] - r3 * np.cos(phi3) * rhs[0]) / det
    return b, phi3, phi4, w3, w4, al3, al4


def _rel(a, b):
    return np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300)


def test_fourbar_csv_matches_independent_closed_form():
    out = CliRunner().invoke(main, ["analyse", str(shipped("fourbar.toml")), "--format", "csv"],
                             catch_exceptions=False)
    assert out.exit_code == 0, out.output
    cols = read_csv(out.stdout)
    phi = np.deg2rad(cols["angle_deg"])
    omega = 300 * 2 * np.pi / 60
    b, phi3, phi4, w3, w4, al3, al4 = _fourbar_closed_form(
        phi, np.zeros(2), np.array([0.25, 0.0]), 0.05, 0.2, 0.15, omega)
    assert _rel(cols["x_3_4"], b[:, 0]) < 1e-9
    assert _rel(cols["y_3_4"], b[:, 1]) < 1e-9
    assert _rel(np.deg2rad(cols["phi_3_deg"]), np.unwrap(phi3)) < 1e-9
    assert _rel(cols["omega_3"], w3) < 1e-9
    assert _rel(cols["omega_4"], w4) < 1e-9
    assert _rel(cols["alpha_3"], al3) < 1e-9
    assert _rel(cols["alpha_4"], al4) < 1e-9
    assert (cols["y_3_4"][0] > 0)  # joint (3,4) above the ground line at φ21 = 0


def test_slider_crank_csv_matches_independent_closed_form():
    out = CliRunner().invoke(main, ["analyse", str(shipped("slider-crank.toml")), "--format",
                                    "csv"], catch_exceptions=False)
    cols = read_csv(out.stdout)
    phi = np.deg2rad(cols["angle_deg"])
    r, l, e = 0.04, 0.16, 0.01
    omega = 1500 * 2 * np.pi / 60
    # x = r cos φ + sqrt(l² − (e − r sin φ)²) and its time derivatives
    h = e - r * np.sin(phi)
    root = np.sqrt(l ** 2 - h ** 2)
    x = r * np.cos(phi) + root
    hd = -r * omega * np.cos(phi)
    hdd = r * omega ** 2 * np.sin(phi)
    xd = -r * omega * np.sin(phi) - h * hd / root
    xdd = -r * omega ** 2 * np.cos(phi) - (hd ** 2 + h * hdd) / root - (h * hd) ** 2 / root ** 3
    assert _rel(cols["s_1_4"], x) < 1e-9
    assert _rel(cols["v_1_4"], xd) < 1e-9
    assert _rel(cols["a_1_4"], xdd) < 1e-9
    assert np.allclose(cols["y_3_4"], e, rtol=0, atol=1e-15)
    assert _rel(cols["x_3_4"], x) < 1e-9


def test_scotch_yoke_is_harmonic():
    mechanism = toml_input.read_mechanism(shipped("scotch-yoke.toml"))
    kin = kinematics.sweep(mechanism)
    phi, omega = kin.crank_angle, mechanism.crank.speed
    motion = kin.motion
    assert np.allclose(motion.origin[:, 3, 0], 0.05 * np.cos(phi), rtol=0, atol=1e-15)
    assert np.allclose(motion.velocity[:, 3, 0], -0.05 * omega * np.sin(phi), rtol=0, atol=1e-12)
    assert np.allclose(motion.acceleration[:, 3, 0], -0.05 * omega ** 2 * np.cos(phi), rtol=0,
                       atol=1e-10)


def test_tangent_drive_height_is_tangent():
    mechanism = toml_input.read_mechanism(shipped("tangent-drive.toml"))
    kin = kinematics.sweep(mechanism)
    (prism,) = [j for j in mechanism.joints if j.name == (1, 4)]
    s, v, _ = joints.travel(prism, kin.motion)
    phi, omega = kin.crank_angle, mechanism.crank.speed
    assert np.allclose(s, 0.08 * np.tan(phi), rtol=1e-12, atol=1e-15)
    assert np.allclose(v, 0.08 * omega / np.cos(phi) ** 2, rtol=1e-12)


def test_slotted_lever_follows_the_block():
    mechanism = toml_input.read_mechanism(shipped("slotted-lever.toml"))
    kin = kinematics.sweep(mechanism)
    phi = kin.crank_angle
    block = 0.06 * np.stack((np.cos(phi), np.sin(phi)), -1)
    lever = np.arctan2(block[:, 1] + 0.15, block[:, 0])
    assert np.allclose(np.angle(np.exp(1j * (kin.motion.angle[:, 4] - lever))), 0, atol=1e-13)


def test_crank_cos_sin_from_one_complex_exponential():
    """``cos_sin`` (e^{iφ}) gives np.cos and np.sin to the last bit or so, over many turns
    either way, and NaN for a NaN angle without a warning (pytest turns warnings into
    errors), as np.cos does."""
    angle = np.concatenate((np.linspace(-40.0, 40.0, 10_001), [np.nan, 0.0, -0.0]))
    cos, sin = np.empty_like(angle), np.empty_like(angle)
    kinematics.cos_sin(angle, cos, sin)
    finite = np.isfinite(angle)
    np.testing.assert_array_max_ulp(cos[finite], np.cos(angle[finite]), maxulp=1)
    np.testing.assert_array_max_ulp(sin[finite], np.sin(angle[finite]), maxulp=1)
    assert np.isnan(cos[~finite]).all() and np.isnan(sin[~finite]).all()
    assert cos[-1] == 1.0 and sin[-2] == 0.0
