"""Statics of a gear stage: the mesh force from the torque, the helical axial share, the
support reactions in equilibrium with the applied torques; the plane-of-action normal."""

from __future__ import annotations

import math

import numpy as np
import pytest

import dyade
from dyade.model.gears import mesh_frame, plane_of_action
from dyade.vibration.gears.assembly import assemble
from tests.gears.drives import build, single_stage
from tests.helpers import shipped

T_OUT = 800.0  # [N·m] the load's braking torque


def _balanced(drive):
    """The motor drives right-handed with T_OUT·z_p/z_r; the load, which turns
    left-handed (one external mesh), brakes with T_OUT about +x."""
    p, w = drive.gears
    return {"load": T_OUT, "motor": T_OUT * p.teeth / w.teeth}


@pytest.mark.parametrize("alpha", [14.5, 20.0, 25.0])
def test_spur_mesh_force_is_the_torque_over_the_base_radius(alpha):
    drive = build(single_stage(alpha=alpha))
    statics = dyade.gear_statics(drive, _balanced(drive))
    wheel = drive.gears[1]
    assert statics.mesh_forces[0] == pytest.approx(T_OUT / wheel.base_radius, rel=1e-9)


@pytest.mark.parametrize("beta, hand", [(15.0, "right"), (25.0, "left")])
def test_helical_mesh_force_and_its_axial_share(beta, hand):
    data = single_stage(beta=beta)
    data["gear"][0]["hand"], data["gear"][1]["hand"] = hand, {"right": "left",
                                                              "left": "right"}[hand]
    drive = build(data)
    statics = dyade.gear_statics(drive, _balanced(drive))
    wheel = drive.gears[1]
    alpha_n, b = wheel.pressure_angle, math.radians(beta)
    # the tangential force T/r (pitch radius), the normal force T/(r·cos α_n·cos β)
    normal = T_OUT / (wheel.pitch_radius * math.cos(alpha_n) * math.cos(b))
    assert statics.mesh_forces[0] == pytest.approx(normal, rel=1e-9)
    axial = T_OUT * math.tan(b) / wheel.pitch_radius  # = F_t·tan β
    # each shaft's axial bearing takes the thrust: on the driving pinion along +x for a
    # right-hand gear turning right-handed (the hand rule), so the frame pushes along −x
    by_support = dict(zip(statics.supports, statics.forces))
    motor_axial, wheel_axial = by_support["bearing5"][0], by_support["bearing6"][0]
    sign = 1.0 if hand == "right" else -1.0
    assert motor_axial == pytest.approx(-sign * axial, rel=1e-9)
    assert wheel_axial == pytest.approx(sign * axial, rel=1e-9)


@pytest.mark.parametrize("name", ["gears/two-stage.toml", None])
def test_support_reactions_balance_the_applied_torques(name):
    drive = (dyade.read_gears(shipped(name)) if name
             else build(single_stage(beta=20.0) | {"element": [
                 {"bodies": ["wheel", "frame"], "stiffness": [1e7, 2e7, 3e7, 0, 4e5, 5e5],
                  "at": [0.25, 0.15, 0.05]}]}))
    if name:
        torques = {"load": -1000.0, "motor": 1000.0 * 20 / 60 * 20 / 70}  # two reversals
    else:
        torques = _balanced(drive)
    statics = dyade.gear_statics(drive, torques)
    assert np.all(statics.mesh_forces > 0)  # the driving torque loads every mesh in compression
    applied = sum(t * np.asarray(drive.body(b).axis) for b, t in torques.items())
    forces = statics.forces.sum(axis=0)
    moments = (np.cross(statics.points, statics.forces) + statics.moments).sum(axis=0)
    scale = max(abs(t) for t in torques.values())
    assert np.max(np.abs(forces)) < 1e-9 * scale
    assert np.max(np.abs(moments + applied)) < 1e-9 * scale


def test_unbalanced_torques_on_a_free_drive_are_refused():
    drive = build(single_stage())
    with pytest.raises(dyade.InputError, match="torques do not balance"):
        dyade.gear_statics(drive, {"load": -100.0})


@pytest.mark.parametrize("hand, rotation", [(1, 1), (1, -1), (-1, 1), (-1, -1)])
def test_the_plane_of_action_normal_is_unit_and_normal_to_the_tooth(hand, rotation):
    from dyade.model.gears import Gear, Mesh

    beta, alpha = math.radians(22.0), math.radians(20.0)
    gear = Gear("p", "b", 20, 0.004, alpha, beta, hand)
    mesh = Mesh("m", "p", "r", rotation, math.radians(40.0))
    axis = (0.0, 0.6, 0.8)
    normal, pitch = plane_of_action(gear, mesh, axis)
    z1, z2, z3 = mesh_frame(mesh, axis)
    assert np.linalg.norm(normal) == pytest.approx(1.0, abs=1e-15)
    # the tooth line of a right-hand (left-hand) helix at the pitch point
    tooth = np.cos(beta) * np.array(z1) + hand * np.sin(beta) * np.array(z3)
    assert abs(np.dot(normal, tooth)) < 1e-15
    # the paper's components: B = (−1)^i sin α_n, C = cos α_n cos β
    assert np.dot(normal, z2) == pytest.approx(rotation * np.sin(alpha), abs=1e-15)
    assert np.dot(normal, z3) == pytest.approx(np.cos(alpha) * np.cos(beta), abs=1e-15)
    assert np.allclose(pitch, gear.pitch_radius * np.array(z2))


def test_every_assembled_normal_is_unit():
    system = assemble(dyade.read_gears(shipped("gears/two-stage.toml")))
    assert np.allclose(np.linalg.norm(system.normals, axis=1), 1.0, atol=1e-15)
