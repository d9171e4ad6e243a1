"""The ``cam`` entry (issue 40): the checks over the turn, the notes, the profile to
manufacture, and the bad inputs."""

from __future__ import annotations

import dataclasses
import io
import math
from pathlib import Path

import numpy as np
import pytest

import dyade
from dyade.errors import DyadeError, InputError
from dyade.files.cam import read_cam

FILE = "mechanisms/cams/translating-roller.toml"


@pytest.fixture(scope="module")
def cam():
    return read_cam(FILE)


@pytest.fixture(scope="module")
def outcome(cam):
    return dyade.run("cam", cam)


def test_checks_of_the_example(outcome, cam):
    result = outcome.result
    s, v = result.s, result.v
    e, d = cam.offset, math.sqrt(cam.pitch_radius ** 2 - cam.offset ** 2)
    alpha = np.radians(outcome.columns["pressure_angle_deg"])
    assert np.max(np.abs(np.tan(alpha) - (v - e) / (s + d))) < 1e-10
    assert outcome.value("pressure_angle_max_deg") < 30.0 and not outcome.value("undercut")
    assert outcome.units["rho_pitch"] == "m" and outcome.units["contact_force"] == "N"
    # lift-off: the closed form of the balance at the angle that sets it
    k = int(np.argmin(np.abs(outcome.columns["angle_deg"]
                             - outcome.summary["lift_off_speed_rpm"].where["angle_deg"])))
    omega = math.sqrt((cam.stiffness * (s[k] + cam.preload) + cam.load) / (cam.mass * -result.a[k]))
    assert outcome.value("lift_off_speed_rpm") == pytest.approx(omega * 30 / math.pi, rel=1e-12)
    assert any("up to 492.7 rpm" in note for note in outcome.notes)
    document = outcome.to_document()
    assert document["analysis"] == "cam" and document["summary"]["undercut"]["value"] is False


def test_above_the_lift_off_speed_the_force_is_withheld(cam):
    outcome = dyade.run("cam", cam, speed_rpm=700.0)
    force = outcome.columns["contact_force"]
    assert np.isnan(force).any() and np.isfinite(force).any()
    assert np.all(np.isnan(force) == outcome.result.lifted)
    assert any(note.startswith("warning: at 700 rpm the follower lifts off") for note in outcome.notes)
    # a grooved cam holds it: the other flank carries a negative force
    grooved = dyade.run("cam", dataclasses.replace(cam, closure="groove"), speed_rpm=700.0)
    assert np.isfinite(grooved.columns["contact_force"]).all()
    assert grooved.value("contact_force_min") < 0.0


def test_a_roller_larger_than_the_base_circle_is_a_warning_with_the_undercut_range(cam):
    from dyade.model.profile import Profile, Segment

    r = math.radians
    steep = Profile((Segment("rise", 0.0, r(60), 0.0, 0.03, law="cycloid"),
                     Segment("dwell", r(60), r(180), 0.03, 0.03),
                     Segment("return", r(180), r(240), 0.03, 0.0, law="cycloid"),
                     Segment("dwell", r(240), r(360), 0.0, 0.0)), period=2 * math.pi)
    big = dataclasses.replace(cam, base_radius=0.005, roller_radius=0.025, offset=0.0,
                              cutter_radius=None, profile=steep)
    outcome = dyade.run("cam", big)
    assert outcome.value("undercut") is True
    cut = outcome.columns["undercut"]
    angles = outcome.columns["angle_deg"][cut]
    # the undercut lies where the rise's and return's convex humps are sharper than the roller
    rho = outcome.columns["rho_pitch"]
    assert np.array_equal(cut, (rho > 0) & (rho < 0.025))
    warning = next(n for n in outcome.notes if n.startswith("warning: undercut at cam angles"))
    assert f"{angles[0]:.1f}°" in warning
    assert any("larger than the base circle" in n for n in outcome.notes)


def test_a_follower_that_can_never_keep_contact(cam):
    pulled = dataclasses.replace(cam, preload=-0.05, load=0.0)
    with pytest.raises(DyadeError, match="can never keep contact") as err:
        dyade.run("cam", pulled)
    assert not isinstance(err.value, InputError)  # exit 1: an analysis problem


def test_a_law_that_does_not_close(tmp_path):
    text = Path(FILE).read_text(encoding="utf-8").replace("law = \"polynomial-345\"\nend = 320\nto = 0",
                                                        "law = \"polynomial-345\"\nend = 320\nto = 5")
    text = text.replace("kind = \"dwell\"\nend = 360", "kind = \"dwell\"\nend = 360\nto = 5")
    path = tmp_path / "open.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(InputError, match=r"open.toml: `profile.segment.5.to` = 5 mm does not "
                                         r"come back .* the law does not close over the cycle"):
        read_cam(path)


def test_the_exported_curve_and_its_dxf(outcome, cam, tmp_path):
    from dyade.cam import checks
    from dyade.report import cam as report

    made = report.curve(outcome.result, "working")
    assert made.deviation <= cam.chord_tolerance
    # the closed form between the exported points: every point within the tolerance
    theta = np.linspace(0.0, 2 * np.pi, 40_001)[:-1]  # points the export never saw
    fine, _ = checks.curves(cam, theta)
    k = np.searchsorted(made.theta, theta, side="right") - 1
    a, b = made.points[k], np.roll(made.points, -1, axis=0)[k]
    ab, ap = b - a, fine.working - a
    distance = np.abs(ab[:, 0] * ap[:, 1] - ab[:, 1] * ap[:, 0]) / np.hypot(*ab.T)
    assert distance.max() <= cam.chord_tolerance
    handle = io.StringIO()
    report.write_points(made, handle, "mm")
    rows = np.loadtxt(io.StringIO(handle.getvalue()), delimiter=",", skiprows=1)
    assert handle.getvalue().startswith("angle_deg,x_mm,y_mm\n")
    assert np.allclose(rows[:, 1:] * 1e-3, made.points, rtol=0, atol=1e-15)


@pytest.mark.slow  # ezdxf's import alone takes 0.6 s
def test_the_dxf_reads_back_to_the_same_points(outcome, grooved, tmp_path):
    from dyade.report import cam as report

    ezdxf = pytest.importorskip("ezdxf")
    made = report.curve(outcome.result, "working")
    path = tmp_path / "cam.dxf"
    report.write_dxf(outcome.result, path, "mm")
    document = ezdxf.readfile(path)
    assert document.header["$INSUNITS"] == 4
    lines = {e.dxf.layer: e for e in document.modelspace().query("LWPOLYLINE")}
    assert set(lines) == {"CAM-WORKING", "CAM-CUTTER"} and lines["CAM-WORKING"].closed
    back = np.array([p[:2] for p in lines["CAM-WORKING"].get_points("xy")])
    assert np.allclose(back * 1e-3, made.points, rtol=0, atol=1e-12)
    # a grooved cam: both flanks, the outer on its own layer
    report.write_dxf(grooved.result, tmp_path / "groove.dxf", "mm")
    lines = {e.dxf.layer: e for e in ezdxf.readfile(tmp_path / "groove.dxf").modelspace()
             .query("LWPOLYLINE")}
    assert set(lines) == {"CAM-WORKING", "CAM-OUTER"} and lines["CAM-OUTER"].closed
    back = np.array([p[:2] for p in lines["CAM-OUTER"].get_points("xy")])
    assert np.allclose(back * 1e-3, report.curve(grooved.result, "outer").points, rtol=0,
                       atol=1e-12)


def test_a_cam_linkage_chain_from_its_file():
    outcome = dyade.run("cam", "mechanisms/cams/cam-linkage.toml")
    result = outcome.result
    assert outcome.meta["chain"] == "Lever and slider of a cam drive"
    assert result.chain is not None and result.chain.valid.all()
    # the cam's power is the chain's: drive torque · ω = lever torque · φ̇
    assert np.allclose(result.drive_torque * result.cam.speed,
                       result.chain.lever_torque * result.chain.lever_speed, rtol=0,
                       atol=1e-9 * np.max(np.abs(result.chain.lever_torque * result.chain.lever_speed)))
    # at the lift-off speed the least contact force is zero (N = N0 + ω²·N2)
    lift = outcome.value("lift_off_speed_rpm")
    at = dyade.run("cam", "mechanisms/cams/cam-linkage.toml", speed_rpm=lift, step_deg=1.0)
    force = at.result.chain.contact_force  # as solved (a value a hair below 0 is lifted off)
    assert force.min() == pytest.approx(0.0, abs=1e-9 * force.max())


@pytest.fixture(scope="module")
def grooved(cam):
    return dyade.run("cam", dataclasses.replace(cam, closure="groove", width=0.012,
                                                chord_tolerance=2e-5, cutter_radius=None),
                     speed_rpm=700.0)


def test_a_grooved_cam_carries_the_load_on_the_flank_the_force_says(grooved, cam):
    result, columns = grooved.result, grooved.columns
    omega = 700.0 * math.pi / 30.0
    alpha = result.geometry.pressure_angle
    # the balance along the follower, both signs: N = (m·s″·ω² + k·(s + s0) + F)/cos α
    expected = (cam.mass * result.a * omega ** 2 + cam.stiffness * (result.s + cam.preload)
                + cam.load) / np.cos(alpha)
    assert np.allclose(columns["contact_force"], expected, rtol=1e-12, atol=0)
    outer = columns["outer_flank"]
    assert np.array_equal(outer, expected < 0) and 0 < outer.sum() < outer.size
    assert grooved.value("outer_flank_share") == pytest.approx(outer.mean(), rel=1e-12)
    assert grooved.summary.get("lift_off_speed_rpm") is None  # a groove never lifts off
    note = next(n for n in grooved.notes if "switches flanks" in n)
    switches = np.flatnonzero(outer != np.roll(outer, 1))
    assert all(f"{columns['angle_deg'][k]:.1f}°" in note for k in switches)
    # Hertz: the roller inside the outer wall (concave, ρ_p + r_r), outside the inner one
    modulus = 1 / (2 * (1 - 0.3 ** 2) / 210e9)
    rho_p, r_r = columns["rho_pitch"], cam.roller_radius
    curvature = np.where(outer, 1 / r_r - 1 / (rho_p + r_r), 1 / r_r + 1 / (rho_p - r_r))
    p0 = np.sqrt(np.abs(expected) * modulus * curvature / (np.pi * 0.012))
    assert np.allclose(columns["hertz_stress"], p0, rtol=1e-12, atol=0)


def test_the_groove_s_outer_flank_is_the_roller_s_envelope(grooved, outcome, cam):
    from dyade.cam import checks
    from dyade.report import cam as report

    outer = report.curve(grooved.result, "outer")
    assert outer is not None and outer.deviation <= grooved.result.cam.chord_tolerance
    # every exported point of the outer flank lies r_r from the pitch curve (the roller's
    # centre path, a dense closed-form sampling), on its far side from the working curve
    fine, _ = checks.curves(grooved.result.cam, np.linspace(0, 2 * np.pi, 10_001)[:-1])
    near = (np.searchsorted(fine.theta, outer.theta)[:, None] + np.arange(-200, 201)) % 10_000
    distance = np.min(np.hypot(*np.moveaxis(outer.points[:, None, :] - fine.pitch[near], -1, 0)),
                      axis=1)
    # (a sampled curve only overestimates the distance: by h²/(8·r_r) ≈ 2e-8 m here)
    assert cam.roller_radius - 1e-12 < distance.min() and distance.max() < cam.roller_radius + 5e-8
    assert np.all(np.hypot(*outer.points.T) > np.interp(
        outer.theta, fine.theta, np.hypot(*fine.pitch.T)) - 1e-12)
    # the plain spring cam makes no outer flank
    assert report.curve(outcome.result, "outer") is None


@pytest.mark.parametrize("clockwise", [False, True])
def test_a_flat_face_s_width_and_its_cusp(clockwise):
    flat = dataclasses.replace(read_cam("mechanisms/cams/flat-faced.toml"), offset=0.003,
                               clockwise=clockwise, chord_tolerance=1e-4)
    outcome = dyade.run("cam", flat, step_deg=2.0)
    v = outcome.result.v
    # the face touches the cam at x = s′ and the stem runs along x = e; a clockwise cam
    # is the mirror image of the counter-clockwise one with −e: the contact at x = −s′
    across = -v - 0.003 if clockwise else v - 0.003
    assert outcome.value("face_contact_min") == pytest.approx(across.min(), rel=1e-12)
    assert outcome.value("face_contact_max") == pytest.approx(across.max(), rel=1e-12)
    assert outcome.value("face_width") == pytest.approx(np.ptp(v), rel=1e-12)
    # below the smallest base circle r_b + s + s″ > 0 fails: a cusp, named with its angles
    smallest = outcome.value("base_radius_min")
    assert smallest == pytest.approx(np.max(-outcome.result.s - outcome.result.a), rel=1e-12)
    cusped = dyade.run("cam", dataclasses.replace(flat, base_radius=0.8 * smallest),
                       step_deg=2.0)
    radius = cusped.columns["rho_working"]
    assert np.array_equal(cusped.columns["undercut"], radius <= 0) and (radius < 0).any()
    note = next(n for n in cusped.notes if n.startswith("warning: undercut at cam angles"))
    assert "cannot follow the motion (cusp)" in note and f"{smallest * 1e3:.4g} mm" in note


def test_the_oscillating_follower_s_smallest_base_circle_is_reported():
    lever = dataclasses.replace(read_cam("mechanisms/cams/oscillating-roller.toml"),
                                chord_tolerance=1e-4, cutter_radius=None)  # (quick)
    outcome = dyade.run("cam", lever, step_deg=2.0)
    smallest = outcome.value("base_radius_min")
    document = outcome.to_document()["summary"]["base_radius_min"]
    assert document["unit"] == "m" and document["value"] == pytest.approx(smallest, rel=1e-12)
    assert 0 < smallest < lever.base_radius and "limit" not in document
    # that cam meets the 45° of an oscillating follower just: its largest |α| is the limit
    at = dyade.run("cam", dataclasses.replace(lever, base_radius=smallest), step_deg=2.0)
    assert at.value("pressure_angle_max_deg") == pytest.approx(45.0, abs=1e-7)
