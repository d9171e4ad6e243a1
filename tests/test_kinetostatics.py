"""Kinetostatics: global solve, power balance, statics, shaking force, dead centres."""

from __future__ import annotations

import tomllib
from dataclasses import replace

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import assume, given

import dyade
from dyade.linkage import sweep as analysis, kinematics, kinetostatics
from dyade.files import mechanism as toml_input
from dyade.cli import main
from dyade.model.mechanism import FRAME, Link, Load, Revolute
from tests.conftest import SHIPPED
from tests.global_solve import global_forces
from tests.helpers import kinematics_at, mechanism_from, read_csv, shipped
from tests.strategies import dyad_files


def with_masses(mechanism, gravity=(0.0, 0.0), seed=1):
    """Give every moving link a mass, centre and inertia (deterministic, plausible)."""
    rng = np.random.default_rng(seed)
    size = mechanism.crank.length
    links = dict(mechanism.links)
    for number in mechanism.moving_links:
        old = links[number]
        links[number] = Link(number, old.points, mass=float(rng.uniform(0.2, 2.0)),
                             centre=tuple(rng.uniform(-1, 1, 2) * size),
                             inertia=float(rng.uniform(0.1, 1.0)) * size ** 2)
    return replace(mechanism, links=links, gravity=gravity)


def kinetic_energy_rate(mechanism, motion):
    """dE_kin/dt = Σ m v_S·a_S + J_S ω α, from the kinematics alone."""
    rate = 0.0
    for number, link in mechanism.links.items():
        if number == FRAME:
            continue
        v = motion.point_velocity(number, link.centre)
        a = motion.point_acceleration(number, link.centre)
        rate = rate + link.mass * np.sum(v * a, axis=1) + link.inertia * motion.omega[:, number] * motion.alpha[:, number]
    return rate


def applied_power(mechanism, motion, crank_angle):
    """Power of gravity, applied loads and springs, from the kinematics alone."""
    power = np.zeros(crank_angle.shape[0])
    g = np.asarray(mechanism.gravity)
    for number, link in mechanism.links.items():
        if number != FRAME:
            power += link.mass * motion.point_velocity(number, link.centre) @ g
    for load in mechanism.loads:
        fx, fy, moment = kinetostatics.load_values(load, crank_angle)
        v = motion.point_velocity(load.link, load.point)
        power += fx * v[:, 0] + fy * v[:, 1] + moment * motion.omega[:, load.link]
    for spring in mechanism.springs:
        (a, b), (u_a, u_b) = spring.links, spring.points
        d = motion.point(b, u_b) - motion.point(a, u_a)
        dd = motion.point_velocity(b, u_b) - motion.point_velocity(a, u_a)
        length = np.hypot(d[:, 0], d[:, 1])
        power -= spring.stiffness * (length - spring.free_length) * np.sum(d * dd, 1) / length
    return power


def _compare(mechanism, kin, forces, loads=()):
    reference = global_forces(mechanism, kin, loads)
    scale = max(np.nanmax(np.abs(f)) for f in forces.revolute.values())
    for joint in mechanism.joints:
        if isinstance(joint, Revolute):
            mine = forces.revolute[joint.name]
        else:
            mine = np.stack((forces.normal[joint.name], forces.moment[joint.name]), axis=-1)
        # 1e-9 of the largest joint force: both solve well-conditioned systems
        assert np.allclose(mine, reference[joint.name], rtol=1e-9, atol=1e-9 * scale), joint.name
    torque_scale = max(np.max(np.abs(reference["drive"])), 1e-300)
    assert np.allclose(forces.drive_torque, reference["drive"], rtol=1e-9, atol=1e-9 * torque_scale)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_dyad_by_dyad_equals_global_solve(path):
    mechanism = with_masses(toml_input.read_mechanism(path), gravity=(0.0, -9.81))
    loads = ((mechanism.moving_links[-1], (0.01, 0.02), (30.0, -40.0)),)
    mechanism = replace(mechanism, springs=(), loads=tuple(
        Load(link, point, None, np.array([f[0]]), np.array([f[1]]), np.array([0.0]))
        for link, point, f in loads))
    angles = np.linspace(mechanism.sweep.start, mechanism.sweep.stop, 13)
    kin = kinematics_at(mechanism, angles)
    _compare(mechanism, kin, kinetostatics.solve(mechanism, kin), loads)


def _assert_power_balance(mechanism):
    kin = kinematics.sweep(mechanism)
    forces = kinetostatics.solve(mechanism, kin)
    lhs = forces.drive_torque * mechanism.crank.speed
    rhs = kinetic_energy_rate(mechanism, kin.motion) - applied_power(mechanism, kin.motion,
                                                                      kin.crank_angle)
    assert np.allclose(lhs, rhs, rtol=0, atol=1e-10 * np.max(np.abs(rhs)))


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_power_balance(path):
    _assert_power_balance(with_masses(toml_input.read_mechanism(path), gravity=(0.0, -9.81)))


def test_power_balance_with_load_table_and_spring():
    mechanism = toml_input.read_mechanism(shipped("dyade-16.toml"))
    assert mechanism.loads and mechanism.springs and any(l.angles is not None for l in mechanism.loads)
    _assert_power_balance(mechanism)


def test_dyade16_against_global_solve():
    mechanism = toml_input.read_mechanism(shipped("dyade-16.toml"))
    mechanism = replace(mechanism, loads=(), springs=())  # loads/springs: power balance above
    angles = np.deg2rad(np.arange(0, 360, 30.0))
    kin = kinematics_at(mechanism, angles)
    _compare(mechanism, kin, kinetostatics.solve(mechanism, kin))


@given(data=dyad_files())
def test_every_kind_against_global_solve(data):
    mechanism = with_masses(mechanism_from(data), gravity=(3.0, -9.81))
    angles = np.deg2rad(np.arange(0.0, 360.0, 30.0))
    kin = kinematics_at(mechanism, angles)
    good = kin.valid & (kin.conditioning[:, 0] > 0.2)
    assume(good.any())
    kin = kinematics_at(mechanism, angles[good])
    _compare(mechanism, kin, kinetostatics.solve(mechanism, kin))


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_slow_crank_with_gravity_is_static_equilibrium(path):
    # Ω → 0: inertia vanishes (∝ Ω²), and M_drive must balance gravity by virtual work:
    # M_drive = −Σ m g·∂r_S/∂φ21 with ∂r_S/∂φ21 = v_S/Ω from the velocity analysis
    mechanism = with_masses(toml_input.read_mechanism(path), gravity=(0.0, -9.81))
    crank = replace(mechanism.crank, speed=1e-6)
    mechanism = replace(mechanism, crank=crank, loads=(), springs=())
    kin = kinematics.sweep(mechanism)
    forces = kinetostatics.solve(mechanism, kin)
    virtual = np.zeros(kin.crank_angle.size)
    for number in mechanism.moving_links:
        link = mechanism.links[number]
        virtual -= link.mass * (kin.motion.point_velocity(number, link.centre) / 1e-6) @ np.array([0.0, -9.81])
    assert np.allclose(forces.drive_torque, virtual, rtol=1e-9, atol=1e-9 * np.max(np.abs(virtual)))


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_shaking_force_is_the_resultant_of_inertia_forces(path):
    mechanism = with_masses(toml_input.read_mechanism(path))
    mechanism = replace(mechanism, loads=(), springs=())
    kin = kinematics.sweep(mechanism)
    forces = kinetostatics.solve(mechanism, kin)
    force = np.zeros((kin.crank_angle.size, 2))
    moment = np.zeros(kin.crank_angle.size)
    for number in mechanism.moving_links:
        link = mechanism.links[number]
        f = -link.mass * kin.motion.point_acceleration(number, link.centre)
        s = kin.motion.point(number, link.centre)
        force += f
        moment += s[:, 0] * f[:, 1] - s[:, 1] * f[:, 0] - link.inertia * kin.motion.alpha[:, number]
    scale = np.max(np.abs(force))
    assert np.allclose(forces.shaking[:, :2], force, rtol=0, atol=1e-10 * scale)
    assert np.allclose(forces.shaking[:, 2], moment, rtol=0, atol=1e-10 * np.max(np.abs(moment)))


def test_fourbar_and_slider_crank_csv_against_global_solve():
    for name in ("fourbar.toml", "slider-crank.toml"):
        out = CliRunner().invoke(main, ["analyse", str(shipped(name)), "--format", "csv"],
                                 catch_exceptions=False)
        cols = read_csv(out.stdout)
        mechanism = toml_input.read_mechanism(shipped(name))
        kin = kinematics_at(mechanism, np.deg2rad(cols["angle_deg"]))
        reference = global_forces(mechanism, kin)
        # 1e-6 relative (the bar; the CSV carries 15 significant digits)
        assert np.allclose(cols["M_drive"], reference["drive"], rtol=1e-6,
                           atol=1e-6 * np.max(np.abs(reference["drive"])))
        for joint in mechanism.joints:
            a, b = joint.name
            if isinstance(joint, Revolute):
                got = np.stack((cols[f"Fx_{a}_{b}"], cols[f"Fy_{a}_{b}"]), axis=-1)
            else:
                got = np.stack((cols[f"FN_{a}_{b}"], cols[f"M_{a}_{b}"]), axis=-1)
            ref = reference[joint.name]
            assert np.allclose(got, ref, rtol=1e-6, atol=1e-6 * np.max(np.abs(ref))), joint.name


def test_slider_crank_piston_force_by_hand():
    # slider: m4·a = FN-free x equilibrium: the conrod pushes the piston, F_34x = m4 a_x
    mechanism = toml_input.read_mechanism(shipped("slider-crank.toml"))
    kin = kinematics.sweep(mechanism)
    forces = kinetostatics.solve(mechanism, kin)
    a_x = kin.motion.acceleration[:, 4, 0]
    assert np.allclose(forces.revolute[(3, 4)][:, 0], 0.5 * a_x, rtol=1e-12, atol=1e-9)


def test_no_masses_no_force_stage(monkeypatch):
    def must_not_run(*args, **kwargs):
        raise AssertionError("the force stage ran for a file without masses or loads")

    monkeypatch.setattr(kinetostatics, "solve", must_not_run)
    mechanism = toml_input.read_mechanism(shipped("watt-sixbar.toml"))
    assert not mechanism.has_dynamics
    result = analysis.analyse(mechanism)
    assert result.forces is None
    out = CliRunner().invoke(main, ["analyse", str(shipped("watt-sixbar.toml")), "--format", "csv"],
                             catch_exceptions=False)
    assert "M_drive" not in out.stdout.splitlines()[0]


def test_dead_centre_forces_are_flagged_not_printed(tmp_path):
    # |AC| runs from 3 to 5 and l_i + l_j = 5: coupler and rocker stretched at φ21 = 180°
    path = tmp_path / "dead.toml"
    path.write_text("""
        [crank]
        length = 1.0
        speed_rpm = 60
        [[dyad]]
        kind = "RRR"
        links = [3, 4]
        A = { link = 2, point = "tip" }
        C = { link = 1, point = [4.0, 0.0] }
        lengths = [3.0, 2.0]
        [links.3]
        mass = 1.0
        [sweep]
        start = 150
        stop = 210
        step = 0.5
        """.replace("\n        ", "\n"))
    out = CliRunner().invoke(main, ["analyse", str(path), "--format", "csv"],
                             catch_exceptions=False)
    assert out.exit_code == 0
    cols = read_csv(out.stdout)
    assert cols["angle_deg"].size == 121
    near = cols["mu_2_deg"] > 178
    assert near.any()
    assert np.all(np.isnan(cols["M_drive"][near])) and np.all(cols["forces_valid"][near] == 0)
    assert np.all(np.isfinite(cols["M_drive"][~near]))
    # the validity policy: nothing of such a row is given, not even its kinematics
    assert np.all(np.isnan(cols["omega_3"][near])) and np.all(cols["kinematics_valid"][near] == 0)
    assert np.all(np.isfinite(cols["omega_3"][~near])) and np.all(cols["kinematics_valid"][~near] == 1)
    assert "within 2° of a dead centre" in out.stderr and "nothing is given" in out.stderr


@pytest.mark.parametrize("link, point", [(3, "K"), (4, "R")], ids=["coupler", "rocker"])
def test_load_in_the_link_frame_turns_with_the_link(link, point):
    # No masses: the only load is a constant force (ξ, η) in link k's frame at point P.
    # Virtual power: M_drive·Ω + F·v_P = 0, with F = R(φ_k)·(ξ, η) rotated here from the
    # CSV's phi_k_deg, and Ω, v_P from its columns (a sign slip in the rotation breaks it)
    data = tomllib.loads(shipped("fourbar.toml").read_text())
    data["links"] = {"3": {"points": {"K": [100, 40]}}, "4": {"points": {"R": [120, 25]}}}
    data["load"] = [{"link": link, "point": point, "force": [30.0, -70.0], "frame": "link"}]
    result = dyade.analyse(mechanism_from(data))
    cols = result.columns()
    valid = cols["forces_valid"] == 1
    assert valid.sum() > 300
    phi = np.deg2rad(cols[f"phi_{link}_deg"][valid])
    assert np.ptp(phi) > np.deg2rad(10)  # the link turns, so the frames differ
    xi, eta = 30.0, -70.0
    fx, fy = np.cos(phi) * xi - np.sin(phi) * eta, np.sin(phi) * xi + np.cos(phi) * eta
    load_power = fx * cols[f"vx_{point}"][valid] + fy * cols[f"vy_{point}"][valid]
    drive_power = cols["M_drive"][valid] * cols["omega_2"][valid]
    # 1e-9 of the largest load power: one dyad solve, no iteration
    assert np.allclose(drive_power, -load_power, rtol=0, atol=1e-9 * np.max(np.abs(load_power)))
