"""The machine in motion (issue 18): reduced inertia and load torque, non-constant crank
speed, the equation of motion with a motor, the flywheel and the counterweights."""

from __future__ import annotations

import json
import math
import tomllib
from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.linkage.sweep import analyse_si
from dyade.cli import main
from dyade.errors import DyadeError, InputError
from dyade.files import mechanism as toml_input
from dyade.linkage import kinematics, kinetostatics
from dyade.model.mechanism import Load
from tests.conftest import SHIPPED
from tests.global_solve import global_forces
from tests.helpers import mechanism_from, read_csv, shipped
from tests.test_kinetostatics import applied_power, with_masses

RPM = math.pi / 30.0


def _figures(document: str) -> dict:
    """The summary figures' values of a JSON document (``Outcome.to_document``)."""
    return {name: figure["value"] for name, figure in json.loads(document)["summary"].items()}


def _invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def _massive(path):
    """A shipped mechanism, with masses where the file has none."""
    mechanism = toml_input.read_mechanism(path)
    if not any(link.mass for link in mechanism.links.values()):
        mechanism = with_masses(mechanism, gravity=(0.0, -9.81))
    return mechanism


def _frictionless(mechanism, drive=None):
    """The mechanism with μ = 0 in every joint (and the given drive)."""
    def smooth(joint):
        return replace(joint, friction=0.0)

    return replace(mechanism, drive=drive, crank=replace(
        mechanism.crank, joint=smooth(mechanism.crank.joint)),
        dyads=tuple(replace(d, joints=tuple(smooth(j) for j in d.joints))
                    for d in mechanism.dyads))


# -- 1. reduced inertia and load torque ---------------------------------------------------
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_drive_torque_is_half_the_inertia_slope_times_speed_squared_less_the_load(path):
    # M_drive = ½·dJ_red·Ω² − M_load without friction: the power balance of the machine
    # reduced to its crank, at every position of every shipped mechanism
    mechanism = _frictionless(_massive(path))
    # loads that turn with the links and push across them too: gravity with an x part,
    # a force and a moment on the last link (besides the file's own loads and springs)
    last = mechanism.moving_links[-1]
    mechanism = replace(mechanism, gravity=(3.0, -9.81), loads=mechanism.loads + (
        Load(last, (0.01, 0.02), None, np.array([30.0]), np.array([-40.0]), np.array([0.7])),))
    cols = dyade.analyse(mechanism, allow_partial=True).columns()
    omega = mechanism.crank.speed
    expected = 0.5 * cols["dJ_red"] * omega ** 2 - cols["M_load"]
    valid = cols["forces_valid"] == 1
    scale = np.max(np.abs(cols["M_drive"][valid]))
    assert np.allclose(cols["M_drive"][valid], expected[valid], rtol=0, atol=1e-10 * scale)


@pytest.mark.parametrize("name", ["fourbar.toml", "slider-crank.toml", "dyade-16.toml",
                                  "slotted-lever.toml"])
def test_inertia_slope_is_the_derivative_of_the_inertia(name):
    mechanism = _massive(shipped(name))
    angles = np.deg2rad(np.arange(3.0, 360.0, 7.0))
    h = 1e-5  # central differences: error ~h²·J''' ~ 1e-10 of J
    result = analyse_si(mechanism, crank_angle=angles).columns()
    ahead = analyse_si(mechanism, crank_angle=angles + h).columns()["J_red"]
    behind = analyse_si(mechanism, crank_angle=angles - h).columns()["J_red"]
    slope = (ahead - behind) / (2 * h)
    assert np.allclose(result["dJ_red"], slope, rtol=0,
                       atol=1e-7 * np.max(np.abs(result["dJ_red"])))


def test_inertia_and_load_of_the_slider_crank_by_hand():
    # centric slider-crank, crank r, rod l, only a slider mass m and a constant force F
    # on it: J = m·(dx/dφ)², M_L = F·dx/dφ, x = r·cos φ + √(l² − r² sin² φ)
    r, length, mass, force = 0.05, 0.2, 0.7, -120.0
    mechanism = mechanism_from({
        "crank": {"length": r, "speed_rpm": 400},
        "dyad": [{"kind": "RRP", "links": [3, 4], "length": length,
                  "A": {"link": 2, "point": "tip"}, "C": {"link": 1, "angle": 0}}],
        "links": {"4": {"mass": mass}},
        "load": [{"link": 4, "force": [force, 0.0]}]})
    phi = np.deg2rad(np.arange(0.0, 360.0, 10.0))
    cols = analyse_si(mechanism, crank_angle=phi).columns()
    root = np.sqrt(length ** 2 - (r * np.sin(phi)) ** 2)
    dx = -r * np.sin(phi) - r ** 2 * np.sin(phi) * np.cos(phi) / root
    assert np.allclose(cols["J_red"], mass * dx ** 2, rtol=1e-12, atol=1e-15)
    assert np.allclose(cols["M_load"], force * dx, rtol=1e-12, atol=1e-12)


def test_new_columns_close_the_force_block():
    cols = list(dyade.analyse(dyade.read_mechanism(shipped("dyade-16.toml"))).columns())
    assert cols[-4:] == ["forces_valid", "J_red", "dJ_red", "M_load"]
    mechanism = toml_input.read_mechanism(shipped("watt-sixbar.toml"))  # no force stage
    assert "J_red" not in dyade.analyse(mechanism).columns()


# -- 3. non-constant crank speed -------------------------------------------------------
def _positions(mechanism, count):
    angles = np.linspace(mechanism.sweep.start, mechanism.sweep.stop, count)
    speed = mechanism.crank.speed * (1.0 + 0.3 * np.sin(angles))
    acceleration = 400.0 * np.cos(2 * angles) - 150.0
    return angles, speed, acceleration


def _compare_to_global(mechanism, angles, speed, acceleration):
    kin = kinematics.sweep(mechanism, angles, crank_speed=speed, crank_acceleration=acceleration)
    forces = kinetostatics.solve(mechanism, kin)
    reference = global_forces(mechanism, kinematics.sweep(mechanism, angles), (), speed,
                              acceleration)
    for name, mine in forces.revolute.items():
        assert np.allclose(mine, reference[name], rtol=1e-7,
                           atol=1e-7 * np.max(np.abs(reference[name]))), name
    for name, normal in forces.normal.items():
        mine = np.stack((normal, forces.moment[name]), axis=-1)
        assert np.allclose(mine, reference[name], rtol=1e-7,
                           atol=1e-7 * np.max(np.abs(reference[name]))), name
    scale = np.max(np.abs(reference["drive"]))
    assert np.allclose(forces.drive_torque, reference["drive"], rtol=1e-7, atol=1e-7 * scale)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_speed_and_acceleration_of_the_crank_against_a_global_solve(path):
    # the global solve finds velocities and accelerations itself, from the constraints,
    # with the same crank speed and acceleration (the dyad twists take them as input)
    mechanism = replace(_massive(path), loads=(), springs=())
    angles, speed, acceleration = _positions(mechanism, 13)
    keep = kinematics.sweep(mechanism, angles).valid
    _compare_to_global(mechanism, angles[keep], speed[keep], acceleration[keep])


def test_crank_acceleration_adds_the_reduced_inertia_times_it():
    # frictionless: M_drive(φ̇, φ̈) − M_drive(φ̇, 0) = J_red·φ̈ at one position
    mechanism = toml_input.read_mechanism(shipped("dyade-16.toml"))
    at = analyse_si(mechanism, crank_angle=[1.0], crank_speed=25.0).columns()
    sped = analyse_si(mechanism, crank_angle=[1.0], crank_speed=25.0,
                         crank_acceleration=80.0).columns()
    assert sped["alpha_2"][0] == 80.0 and at["alpha_2"][0] == 0.0
    assert sped["M_drive"][0] - at["M_drive"][0] == pytest.approx(at["J_red"][0] * 80.0,
                                                                   rel=1e-12)


def test_speed_of_the_crank_cannot_be_given_with_a_drive():
    mechanism = _driven({"motor": "constant"})
    with pytest.raises(InputError, match="crank_speed"):
        dyade.analyse(mechanism, crank_speed=3.0)


# -- 3. the equation of motion ----------------------------------------------------------
def _driven(drive, name="dyade-16.toml", **overrides):
    data = tomllib.loads(shipped(name).read_text())
    data["drive"] = drive
    for key, value in overrides.items():
        toml_input.set_dotted(data, key, value, first=toml_input.NUMBERING)
    return mechanism_from(data)


FLYWHEEL_ONLY = """
[crank]
length = 0.05
speed_rpm = 300
[links.2]
inertia = 0.5
[[dyad]]
kind = "RRR"
links = [3, 4]
A = { link = 2, point = "tip" }
C = { link = 1, point = [0.25, 0] }
lengths = [0.2, 0.15]
[[load]]
link = 2
moment = -5.0
[drive]
motor = "asynchronous"
rated_torque = 10
rated_speed_rpm = 1440
synchronous_speed_rpm = 1500
tol = 1e-12
"""


@pytest.mark.parametrize("sense", [1, -1], ids=["ccw", "cw"])
def test_constant_inertia_and_linear_motor_reach_the_analytic_speed(sense):
    # J = 0.5 kg·m² (massless linkage), load 5 N·m: k·(ω_s − ω) = 5 with
    # k = M_N/(ω_s − ω_N) gives ω = 1470 rpm, constant (clockwise: all signs turn)
    data = tomllib.loads(FLYWHEEL_ONLY)
    data["crank"]["direction"] = "ccw" if sense > 0 else "cw"
    data["load"][0]["moment"] *= sense
    mechanism = mechanism_from(data)
    cols = dyade.analyse(mechanism).columns()
    assert np.allclose(cols["omega_2"], sense * 1470 * RPM, rtol=1e-12)
    assert np.allclose(cols["alpha_2"], 0.0, atol=1e-9)
    assert np.allclose(cols["M_motor"], sense * 5.0, rtol=1e-10)
    # the run-up from rest: J·ω̇ = k·(ω_s − ω) − 5, so ω = ω∞·(1 − exp(−t/τ)), τ = J/k
    result = dyade.analyse(mechanism, run_up=True)
    cols = result.columns()
    assert np.all(np.diff(cols["angle_deg"]) * sense > 0)
    k = 10.0 / (60 * RPM)
    expected = sense * 1470 * RPM * (1.0 - np.exp(-cols["t"] * k / 0.5))
    assert np.allclose(cols["omega_2"], expected, rtol=0, atol=1e-9 * 1470 * RPM)
    motion = result.summary()
    assert motion["settled"]
    assert motion["W_motor"] == pytest.approx(motion["E_kinetic"] + motion["W_load"],
                                              rel=1e-10)


@pytest.mark.parametrize("flywheel", [20.0, 200.0])
def test_a_heavy_flywheel_gives_the_flywheel_estimate_and_constant_speed_forces(flywheel):
    # a constant-torque motor holds the nominal mean speed; as J grows the speed becomes
    # constant: δ → ΔE/(J·Ω²) (ΔE from the constant-speed torque curve) and the forces
    # tend to the constant-speed ones, both with errors of the order of δ
    mechanism = _driven({"motor": "constant", "flywheel_inertia": flywheel})
    result = dyade.analyse(mechanism)
    motion = dyade.run("sweep", mechanism).summary  # its figures, with where they occur
    assert motion["speed_mean_rpm"].value == pytest.approx(300, rel=1e-9)
    curve = dyade.mechanism_torque_curve(mechanism)
    estimate = dyade.speed_fluctuation(curve, 0.0)  # the flywheel is in the machine's inertia
    delta = estimate.fluctuation
    assert delta < 1e-3
    assert motion["fluctuation"].value == pytest.approx(delta, rel=3 * delta)
    fixed = dyade.analyse(mechanism, constant_speed=True).columns()
    real = result.columns()
    for name in ("F_2_5", "F_1_2", "FN_7_8", "F_15_16"):
        scale = np.max(np.abs(fixed[name]))
        assert np.max(np.abs(real[name] - fixed[name])) < 20 * delta * scale, name
    # while the flywheel (on the crank) takes up the swings of the drive torque (1e-6 of
    # them: the two cycle means integrate the load table's kinks differently)
    assert np.allclose(real["M_drive"], curve.mean_torque, rtol=0,
                       atol=1e-6 * np.max(np.abs(fixed["M_drive"])))
    # the speed is highest and lowest where the curve says
    assert math.degrees(estimate.angle_max_speed) == pytest.approx(
        motion["speed_max_rpm"].where["angle_deg"], abs=1.0)
    assert math.degrees(estimate.angle_min_speed) == pytest.approx(
        motion["speed_min_rpm"].where["angle_deg"], abs=1.0)


def test_drive_and_kinetostatics_agree_at_the_real_speed():
    # the motor torque balances the kinetostatic drive torque at every position, with
    # friction too (found by passes)
    mechanism = _driven({"motor": "asynchronous", "rated_torque": 1.5, "rated_speed_rpm": 288,
                         "synchronous_speed_rpm": 300, "flywheel_inertia": 0.3},
                        **{"friction.coefficient": 0.1, "friction.pin_radius": 5,
                           "friction.slider_length": 40, "friction.slider_height": 20})
    cols = dyade.analyse(mechanism).columns()
    assert np.max(np.abs(cols["M_drive"] - cols["M_motor"])) < 1e-8 * np.max(
        np.abs(cols["M_drive"]))
    assert np.ptp(cols["omega_2"]) > 0.01 * np.mean(cols["omega_2"])


def test_real_speed_kinetostatics_against_a_global_solve():
    # the forces of a steady state with a motor: the global solve gets the same crank
    # speed and acceleration at every position (and finds the rest itself)
    mechanism = _driven({"motor": "asynchronous", "rated_torque": 4.0, "rated_speed_rpm": 290,
                         "synchronous_speed_rpm": 302})
    mechanism = replace(mechanism, loads=(), springs=())
    result = dyade.analyse(mechanism, step_deg=10.0)
    speed, acceleration = result.drive.speed, result.drive.acceleration
    assert np.ptp(speed) > 0.05 * np.mean(speed)
    _compare_to_global(mechanism, result.crank_angle, speed, acceleration)


def _run_up_balance(mechanism, count=8000):
    """Motor work, kinetic energy, work on the loads and friction work of a run-up, each
    by its own route: the motor law at the crank speed, the links' velocities, the
    loads' power at unit crank speed, and the friction torque as the difference of two
    kinetostatic runs, with and without friction, at the same crank motion. The works
    are integrated over σ = √φ by Simpson's rule: from rest the speed grows like √φ,
    which no rule in φ integrates well, but every integrand is smooth in σ."""
    result = dyade.analyse(mechanism, run_up=True)
    end = np.deg2rad(result.columns()["angle_deg"][-1])
    sigma = np.linspace(0.0, math.sqrt(end), count + 1)
    phi = sigma ** 2
    cols = analyse_si(mechanism, run_up=True, crank_angle=phi).columns()
    speed, acceleration = cols["omega_2"], cols["alpha_2"]
    motor = mechanism.drive.motor.torques(speed)
    unit = kinematics.sweep(mechanism, phi, crank_speed=1.0)
    load = applied_power(mechanism, unit.motion, phi)
    frictionless = analyse_si(_frictionless(mechanism), crank_angle=phi, crank_speed=speed,
                                 crank_acceleration=acceleration).columns()["M_drive"]
    rub = cols["M_drive"] - frictionless
    kin = result.kinematics
    kinetic = 0.0
    for number in mechanism.moving_links:
        link = mechanism.links[number]
        v = kin.motion.point_velocity(number, link.centre)[-1]
        kinetic += 0.5 * (link.mass * v @ v + link.inertia * kin.motion.omega[-1, number] ** 2)

    def work(torque):  # ∫ torque dφ = ∫ torque·2σ dσ
        values, step = torque * 2.0 * sigma, sigma[1] - sigma[0]
        return step / 3 * (values[0] + values[-1] + 4 * values[1:-1:2].sum()
                           + 2 * values[2:-1:2].sum())

    return work(motor), kinetic, -work(load), work(rub), result


RUN_UP = ({"motor": "asynchronous", "rated_torque": 4.0, "rated_speed_rpm": 280,
           "synchronous_speed_rpm": 300, "flywheel_inertia": 0.02},
          {"crank.friction": 0.1, "crank.pin_radius": 5, "dyad.2.A.friction": 0.1,
           "dyad.2.A.pin_radius": 5, "gravity": True, "load": [{"link": 2, "moment": -1.0}]})
"""a four-bar run up by an asynchronous motor, friction in the crank's joints"""


def test_run_up_energy_balance():
    # motor work = kinetic energy + work on the loads + friction work, 1e-8 relative: a
    # four-bar with gravity, a resisting moment on the crank and friction in the two
    # crank joints (whose relative rotation never reverses: a friction torque that jumps
    # would leave a first-order quadrature error), run up by an asynchronous motor
    mechanism = _driven(RUN_UP[0] | {"tol": 1e-9}, name="fourbar.toml", **RUN_UP[1])
    motor, kinetic, load, rub, result = _run_up_balance(mechanism)
    summary = result.summary()
    assert summary["revolutions"] >= 3 and rub > 0.02 * motor and load > 0.2 * motor
    assert motor == pytest.approx(kinetic + load + rub, rel=1e-8)
    # and the run-up's own account of it
    for key, value in (("W_motor", motor), ("E_kinetic", kinetic),
                       ("W_load", load), ("W_friction", rub)):
        assert summary[key] == pytest.approx(value, rel=1e-7, abs=1e-8 * motor), key


def test_steady_state_shooting_equals_a_long_run_up():
    mechanism = _driven({"motor": "asynchronous", "rated_torque": 4.0, "rated_speed_rpm": 290,
                         "synchronous_speed_rpm": 302, "flywheel_inertia": 0.01,
                         "tol": 1e-12})
    steady = dyade.analyse(mechanism).summary()
    run = dyade.analyse(mechanism, run_up=True).summary()
    assert run["settled"]
    for key in ("speed_mean_rpm", "speed_min_rpm", "speed_max_rpm", "fluctuation"):
        assert run[key] == pytest.approx(steady[key], rel=1e-8), key


def test_torque_speed_table_motor_equals_the_same_line():
    line = {"motor": "asynchronous", "rated_torque": 4.0, "rated_speed_rpm": 290,
            "synchronous_speed_rpm": 302}
    table = {"motor": "table", "table": [[0, 4.0 * 302 / 12], [302, 0.0], [400, -4.0 * 98 / 12]]}
    a = dyade.analyse(_driven(line)).columns()
    b = dyade.analyse(_driven(table)).columns()
    assert np.allclose(a["omega_2"], b["omega_2"], rtol=1e-12)


def test_motor_problems_are_named():
    weak = _driven({"motor": "constant", "torque": 0.5}, name="fourbar.toml",
                   **{"load": [{"link": 2, "moment": -1.0}]})
    with pytest.raises(DyadeError, match="cannot start the machine from rest"):
        dyade.analyse(weak, run_up=True)
    with pytest.raises(DyadeError, match="does not balance"):
        dyade.analyse(weak)
    # the rocker's load reaches the crank only once it moves: it starts, then stops
    stalls = _driven({"motor": "constant", "torque": 0.01}, name="fourbar.toml",
                     **{"load": [{"link": 4, "moment": -1.0}]})
    with pytest.raises(DyadeError, match="stops during the run-up"):
        dyade.analyse(stalls, run_up=True)
    with pytest.raises(InputError, match="drive.torque"):
        dyade.analyse(_driven({"motor": "constant"}), run_up=True)
    with pytest.raises(InputError, match="run_up"):
        dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml")), run_up=True)


@pytest.mark.parametrize("drive, message", [
    ({"motor": "diesel"}, "drive.motor"),
    ({"motor": "asynchronous", "rated_torque": 1, "rated_speed_rpm": 300,
      "synchronous_speed_rpm": 290}, "drive.synchronous_speed_rpm"),
    ({"motor": "asynchronous", "rated_torque": 1, "rated_speed_rpm": 300}, "synchronous_speed"),
    ({"motor": "table", "table": [[0, 1], [0, 2]]}, "drive.table"),
    ({"motor": "constant", "rated_torque": 2}, "drive.rated_torque"),
    ({"motor": "constant", "flywheel_inertia": -1}, "drive.flywheel_inertia"),
    ({"motor": "constant", "steps": 10}, "drive.steps"),
])
def test_drive_table_errors_name_the_key(drive, message):
    with pytest.raises(InputError, match=message):
        _driven(drive)


def test_a_drive_needs_inertia():
    with pytest.raises(InputError, match="flywheel_inertia"):
        _driven({"motor": "constant"}, name="watt-sixbar.toml")


# -- the command line -------------------------------------------------------------------
def _drive_file(tmp_path, drive, name="dyade-16.toml"):
    data = tomllib.loads(shipped(name).read_text())
    data["drive"] = drive
    path = tmp_path / "driven.toml"
    path.write_text(toml_input.dumps(data))
    return path


def test_describe_plans_the_equation_of_motion(tmp_path):
    path = _drive_file(tmp_path, {"motor": "asynchronous", "rated_torque": 4.0,
                                  "rated_speed_rpm": 290, "synchronous_speed_rpm": 302})
    out = _invoke("describe", path)
    assert out.exit_code == 0
    assert "equation of motion" in out.stdout and "asynchronous" in out.stdout
    plain = _invoke("describe", shipped("dyade-16.toml"))
    assert "equation of motion" not in plain.stdout


def test_analyse_with_a_drive_from_the_command_line(tmp_path):
    path = _drive_file(tmp_path, {"motor": "asynchronous", "rated_torque": 4.0,
                                  "rated_speed_rpm": 290, "synchronous_speed_rpm": 302,
                                  "flywheel_inertia": 0.05})
    table = _invoke("analyse", path)
    assert table.exit_code == 0 and "speed fluctuation δ" in table.stdout
    cols = read_csv(_invoke("analyse", path, "--format", "csv").stdout)
    assert list(cols)[-5:] == ["J_red", "dJ_red", "M_load", "t", "M_motor"]
    assert np.ptp(cols["omega_2"]) > 0
    steady = json.loads(_invoke("analyse", path, "--format", "json").stdout)["summary"]
    assert steady["motion_state"]["value"] == "steady"
    assert 0 < steady["fluctuation"]["value"] < 0.2 and steady["fluctuation"]["unit"] == "-"
    fixed = read_csv(_invoke("analyse", path, "--constant-speed", "--format", "csv").stdout)
    assert np.allclose(fixed["omega_2"], 300 * RPM, rtol=1e-15) and "t" not in fixed
    run = read_csv(_invoke("analyse", path, "--run-up", "--format", "csv").stdout)
    assert run["omega_2"][0] == 0 and run["t"][0] == 0 and run["angle_deg"][-1] > 360
    bad = _invoke("analyse", shipped("fourbar.toml"), "--run-up")
    assert bad.exit_code == 2 and "--run-up" in bad.stderr


# -- 2. the flywheel --------------------------------------------------------------------
def test_flywheel_of_the_textbook_engine():
    # T = 10000 + 2000·sin 2θ − 1800·cos 2θ N·m against a constant load at 250 rpm,
    # δ = 0.005: P = 261.799 kW, ΔE = 2690.725 J, J_F = 785.17 kg·m² (the issue's
    # numbers, to their printed digits), from the integration of the curve sampled every
    # degree (the shipped mechanisms/torque/engine.csv of the README)
    path = shipped("torque/engine.csv")
    cols = read_csv(path.read_text())
    theta = np.deg2rad(cols["angle_deg"])
    assert np.allclose(cols["M_drive"], 10000 + 2000 * np.sin(2 * theta)
                       - 1800 * np.cos(2 * theta), rtol=0, atol=1e-9)
    out = _invoke("flywheel", path, "--fluctuation", 0.005, "--speed-rpm", 250, "--format", "json")
    assert out.exit_code == 0, out.stderr
    result = _figures(out.stdout)
    assert result["P_mean"] / 1e3 == pytest.approx(261.799, abs=5e-4)
    assert result["delta_E"] == pytest.approx(2690.725, abs=5e-4)
    assert result["J_flywheel"] == pytest.approx(785.17, abs=5e-3)
    # ΔE = 2·√(1000² + 900²) exactly (the integral in closed form, here only as a check)
    assert result["delta_E"] == pytest.approx(2 * math.hypot(1000, 900), rel=1e-7)
    back = _figures(_invoke("flywheel", path, "--inertia", result["J_flywheel"],
                            "--speed-rpm", 250, "--format", "json").stdout)
    assert back["fluctuation"] == pytest.approx(0.005, rel=1e-12)
    csv = read_csv(_invoke("flywheel", path, "--fluctuation", 0.005, "--speed-rpm", 250,
                           "--format", "csv").stdout)
    assert list(csv) == ["speed_rpm", "P_mean", "M_mean", "delta_E", "J_machine",
                         "J_flywheel", "fluctuation", "angle_max_speed_deg",
                         "angle_min_speed_deg"]
    table = _invoke("flywheel", path, "--fluctuation", 0.005, "--speed-rpm", 250)
    assert "785.167" in table.stdout


def test_flywheel_of_a_mechanism_against_a_fine_integration():
    # ΔE = max − min of ∫(M_mean − M_drive)dφ, here by the trapezoid rule on a 0.02° grid
    from scipy.integrate import cumulative_trapezoid

    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"))
    result = dyade.size_flywheel(dyade.mechanism_torque_curve(mechanism), 0.02)
    fine = np.deg2rad(np.arange(0.0, 360.0 + 1e-9, 0.02))
    torque = analyse_si(mechanism, crank_angle=fine).columns()["M_drive"]
    energy = cumulative_trapezoid(np.mean(torque[:-1]) - torque, fine, initial=0.0)
    assert result.delta_energy == pytest.approx(np.ptp(energy), rel=1e-5)
    assert math.degrees(result.angle_max_speed) == pytest.approx(
        np.rad2deg(fine[np.argmax(energy)]), abs=0.05)
    omega = 300 * RPM
    inertia = analyse_si(mechanism, crank_angle=fine[:-1]).columns()["J_red"].mean()
    assert result.flywheel == pytest.approx(np.ptp(energy) / (0.02 * omega ** 2) - inertia,
                                            rel=1e-5)


def test_flywheel_from_dyades_own_csv_equals_the_mechanism(tmp_path):
    out = tmp_path / "d16.csv"
    assert _invoke("analyse", shipped("dyade-16.toml"), "-o", out).exit_code == 0
    from_csv = _figures(_invoke("flywheel", out, "--fluctuation", 0.02, "--format",
                                "json").stdout)
    direct = _figures(_invoke("flywheel", shipped("dyade-16.toml"), "--fluctuation", 0.02,
                              "--step", 1, "--format", "json").stdout)
    for key in ("delta_E", "J_flywheel", "J_machine", "P_mean", "angle_max_speed_deg"):
        assert from_csv[key] == pytest.approx(direct[key], rel=1e-9), key


def test_flywheel_with_a_load_column(tmp_path):
    theta = np.arange(0.0, 360.0, 2.0)
    drive = 50 + 20 * np.sin(np.deg2rad(theta))
    load = -50 - 20 * np.sin(np.deg2rad(theta)) + 10 * np.cos(np.deg2rad(3 * theta))
    path = tmp_path / "curve.csv"
    path.write_text("angle_deg,M_drive,M_load\n"
                    + "".join(f"{a:g},{d:.17g},{m:.17g}\n" for a, d, m in zip(theta, drive, load)))
    result = _figures(_invoke("flywheel", path, "--inertia", 2, "--speed-rpm", 100,
                              "--format", "json").stdout)
    # net torque 10·cos 3θ: ΔE = 2·10/3 J (fourth order: 2e-6 at a 2° step)
    assert result["delta_E"] == pytest.approx(20 / 3, rel=1e-5)
    assert result["fluctuation"] == pytest.approx(20 / 3 / (2 * (100 * RPM) ** 2), rel=1e-5)
    path.write_text("angle_deg,M_drive,M_load\n"
                    + "".join(f"{a:g},{d:.17g},{-m:.17g}\n" for a, d, m in zip(theta, drive, load)))
    wrong = _invoke("flywheel", path, "--inertia", 2, "--speed-rpm", 100)
    assert wrong.exit_code == 2 and "resisting load is negative" in wrong.stderr


@pytest.mark.parametrize("args, message", [
    (["--fluctuation", 0.02], "--speed"),
    (["--speed-rpm", 100], "--fluctuation and --inertia are missing: give either"),
    (["--fluctuation", -1, "--speed-rpm", 100], "--fluctuation"),
])
def test_flywheel_errors(tmp_path, args, message):
    path = tmp_path / "curve.csv"
    path.write_text("angle_deg,M_drive\n" + "".join(f"{a},{5 + math.sin(a)}\n"
                                                   for a in range(0, 360, 10)))
    out = _invoke("flywheel", path, *args)
    assert out.exit_code == 2 and message in out.stderr


def test_flywheel_needs_a_torque(tmp_path):
    out = _invoke("flywheel", shipped("watt-sixbar.toml"), "--fluctuation", 0.02)
    assert out.exit_code == 2 and "no masses" in out.stderr
    path = tmp_path / "bad.csv"
    path.write_text("angle_deg,torque\n0,1\n90,2\n180,3\n270,4\n")
    out = _invoke("flywheel", path, "--fluctuation", 0.02, "--speed-rpm", 100)
    assert out.exit_code == 2 and "M_drive" in out.stderr


# -- 4. balancing -----------------------------------------------------------------------
def test_four_bar_is_fully_force_balanced(tmp_path):
    # Berkof & Lowen: counterweights on crank and rocker cancel the shaking force at every
    # position; the saved mechanism, analysed again, shows it
    saved = tmp_path / "balanced.toml"
    out = _invoke("balance", shipped("fourbar.toml"), "--save-as", saved, "--format", "json")
    assert out.exit_code == 0, out.stderr
    document = json.loads(out.stdout)
    report = _figures(out.stdout)
    assert document["columns"]["link"] == [2, 4]
    assert set(document["columns"]) >= {"link", "first_moment", "angle_deg"}
    before = read_csv(_invoke("analyse", shipped("fourbar.toml"), "--format", "csv").stdout)
    after = read_csv(_invoke("analyse", saved, "--format", "csv").stdout)
    unbalanced = np.max(np.hypot(before["Fx_shake"], before["Fy_shake"]))
    assert np.max(np.hypot(after["Fx_shake"], after["Fy_shake"])) < 1e-12 * unbalanced
    # the report's before and after are those of the two analyses
    assert report["M_drive_peak_after"] == pytest.approx(
        np.max(np.abs(after["M_drive"])), rel=1e-12)
    assert report["M_shake_max_before"] == pytest.approx(
        np.max(np.abs(before["M_shake"])), rel=1e-12)
    assert report["F_1_4_peak_after"] == pytest.approx(np.max(after["F_1_4"]), rel=1e-12)
    assert report["F_inertia_ratio"] < 1e-12


def test_six_bar_counterweights_equal_an_independent_least_squares_solve():
    from scipy.linalg import lstsq

    mechanism = with_masses(toml_input.read_mechanism(shipped("watt-sixbar.toml")), seed=3)
    result = dyade.balance(mechanism)
    cols = dyade.analyse(mechanism).columns()
    # the shaking force and the counterweights' effect written out here: a first moment
    # (b_ξ, b_η) on link k about its pivot adds −m·a of the point, with
    # a = (α·E − ω²)·R(φ_k)·b (the pivot is fixed)
    kin = kinematics.sweep(mechanism)
    force = np.zeros((kin.crank_angle.size, 2))
    for number in mechanism.moving_links:
        link = mechanism.links[number]
        force -= link.mass * kin.motion.point_acceleration(number, link.centre)
    columns = []
    for k in (2, 4, 6):
        phi = np.deg2rad(cols[f"phi_{k}_deg"])
        omega, alpha = cols[f"omega_{k}"], cols[f"alpha_{k}"]
        c, s = np.cos(phi), np.sin(phi)
        for ex, ey in ((c, s), (-s, c)):  # R·e_ξ, R·e_η
            columns.append(-np.stack((-alpha * ey - omega ** 2 * ex,
                                      alpha * ex - omega ** 2 * ey), axis=1).ravel())
    solution = lstsq(np.stack(columns, axis=1), -force.ravel())[0]
    mine = [(w.first_moment * math.cos(w.angle), w.first_moment * math.sin(w.angle))
            for w in result.counterweights]
    assert [w.link for w in result.counterweights] == [2, 4, 6]
    assert np.allclose(np.ravel(mine), solution, rtol=1e-9, atol=1e-12)


def test_balance_options_and_errors(tmp_path):
    out = _invoke("balance", shipped("fourbar.toml"), "--link", 2, "--radius", 0.1,
                  "--format", "json").stdout
    only = json.loads(out)["columns"]
    assert only["link"] == [2]
    assert only["radius"] == [0.1]
    assert 0 < _figures(out)["F_inertia_ratio"] < 1
    csv = read_csv(_invoke("balance", shipped("fourbar.toml"), "--format", "csv").stdout)
    assert list(csv) == ["link", "first_moment", "angle_deg", "radius", "mass"]
    bad = _invoke("balance", shipped("fourbar.toml"), "--link", 3)
    assert bad.exit_code == 2 and "--link" in bad.stderr and "frame pivot" in bad.stderr
    none = _invoke("balance", shipped("watt-sixbar.toml"))
    assert none.exit_code == 2 and "no link has a mass" in none.stderr


def test_balanced_file_keeps_a_drive_flywheel_apart(tmp_path):
    path = _drive_file(tmp_path, {"motor": "constant", "flywheel_inertia": 0.5},
                       name="fourbar.toml")
    saved = tmp_path / "balanced.toml"
    assert _invoke("balance", path, "--save-as", saved).exit_code == 0
    data = tomllib.loads(saved.read_text())
    assert data["drive"]["flywheel_inertia"] == 0.5
    assert data["links"]["2"]["inertia"] < 0.01  # the counterweight's, not the flywheel's
    before = dyade.read_mechanism(path).links[2]
    assert dyade.read_mechanism(saved).links[2].inertia == pytest.approx(
        before.inertia + data["links"]["2"]["inertia"], rel=1e-12)


@pytest.mark.parametrize("run_up", [False, True], ids=["steady", "run-up"])
def test_the_integration_grid_in_blocks_is_the_whole_grid(run_up, monkeypatch):
    """The equation of motion's grid (J, J′, M_L and the friction torque at every half
    step: 1440 points a revolution here, 720 000 for a 0.001° sweep) computed in blocks
    of positions gives the same motion to the bit as in one block (the friction solved
    as within the whole grid: ``friction.Coupling``, checked block by block)."""
    from dyade.linkage import blocks, drive

    if run_up:
        mechanism = _driven(RUN_UP[0], name="fourbar.toml", **RUN_UP[1])
    else:
        mechanism = _driven({"motor": "asynchronous", "rated_torque": 1.5,
                             "rated_speed_rpm": 288, "synchronous_speed_rpm": 300,
                             "flywheel_inertia": 0.3},
                            **{"friction.coefficient": 0.1, "friction.pin_radius": 5,
                               "friction.slider_length": 40, "friction.slider_height": 20})
    from dyade.linkage import friction

    solve, couplings = friction.solve, []

    def recorded(*args, **kw):  # the coupling each solution took (its own: None)
        result = solve(*args, **kw)
        couplings.append((kw.get("coupling"), result.coupling))
        return result

    monkeypatch.setattr(friction, "solve", recorded)
    monkeypatch.setattr(drive, "BLOCK_SIZE", 10 ** 9)  # the whole grid in one block
    whole = drive.solve(mechanism, run_up=run_up, friction=True)
    own = [mine for given, mine in couplings]  # the whole grid's, pass by pass
    assert all(given is None for given, _ in couplings)
    couplings.clear()
    monkeypatch.setattr(drive, "BLOCK_SIZE", 97)
    assert len(list(blocks.spans(1440, drive.BLOCK_SIZE))) == 15
    parts = drive.solve(mechanism, run_up=run_up, friction=True)
    for name in ("speed", "acceleration", "time", "motor_torque", "friction_torque"):
        np.testing.assert_array_equal(getattr(parts, name), getattr(whole, name), err_msg=name)
    assert parts.figures == whole.figures
    # every block of a pass was solved with that pass's whole-grid coupling (the force
    # floors and the top speed hardly ever change a bit here: checked directly)
    given = [coupling for coupling, _ in couplings]
    assert None not in given and len(given) == len(own) * (len(given) // len(own))
    per_pass = len(given) // len(own)
    assert given == [coupling for coupling in own for _ in range(per_pass)]
