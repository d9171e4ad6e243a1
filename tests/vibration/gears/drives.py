"""Gear drives for the tests, written as the data of a gear-drive file (SI, degrees)."""

from __future__ import annotations

import copy
import math
from typing import Any

from hypothesis import strategies as st

import dyade


def single_stage(*, alpha: float = 20.0, beta: float = 0.0, module: float = 0.004,
                 base_radii: bool = False, radial: float = 2e8, tilt: float = 0.0,
                 mesh: dict[str, Any] | None = None, segments: int = 1,
                 model: str = "rfe", damping: float = 0.0) -> dict[str, Any]:
    """Motor — shaft — pinion (z 20) | wheel (z 50) — shaft — load, every body in an
    isotropic radial bearing, one axial bearing per shaft. With ``base_radii`` the module
    follows α_n so that the base radii stay those of α_n = 20° and m_n = 4 mm."""
    if base_radii:
        module = 0.004 * math.cos(math.radians(20.0)) / math.cos(math.radians(alpha))
    hands = ({"hand": "right"}, {"hand": "left"}) if beta else ({}, {})
    data: dict[str, Any] = {
        "model": model,
        "speed": {"body": "motor", "rotation": "right", "rpm": 1500.0},
        "body": [
            {"name": "motor", "mass": 10.0, "J_x": 0.02, "J_y": 0.05, "J_z": 0.05},
            {"name": "pinion", "diameter": 0.08, "width": 0.04, "bore": 0.03},
            {"name": "wheel", "diameter": 0.2, "width": 0.04, "bore": 0.04},
            {"name": "load", "mass": 20.0, "J_x": 0.5, "J_y": 0.4, "J_z": 0.4},
        ],
        "shaft": [
            {"name": "in", "bodies": ["motor", "pinion"], "length": 0.2, "diameter": 0.03,
             "segments": segments, "damping": damping},
            {"name": "out", "bodies": ["wheel", "load"], "length": 0.3, "diameter": 0.04,
             "segments": segments, "damping": damping},
        ],
        "gear": [
            {"name": "p", "body": "pinion", "teeth": 20, "module": module,
             "pressure_angle": alpha, "helix_angle": beta} | hands[0],
            {"name": "w", "body": "wheel", "teeth": 50, "module": module,
             "pressure_angle": alpha, "helix_angle": beta} | hands[1],
        ],
        "mesh": [{"name": "m", "driving": "p", "driven": "w", "angle": 30.0} | (mesh or {})],
        "bearing": [{"body": name, "radial": radial, "tilt": tilt,
                     "radial_damping": 2e3 * (damping > 0)}
                    for name in ("motor", "pinion", "wheel", "load")]
                   + [{"body": "motor", "axial": 1e8}, {"body": "wheel", "axial": 1e8}],
    }
    return data


def two_stage_data() -> dict[str, Any]:
    from dyade.files.gears import load_data
    from tests.helpers import shipped

    return load_data(shipped("gears/two-stage.toml"))


def with_pressure_angle(data: dict[str, Any], alpha: float) -> dict[str, Any]:
    """``data`` with every gear at pressure angle ``alpha`` [°] and the module changed so
    that the base radii stay (r_b = z·m_n·cos α_n / 2 for spur gears)."""
    out = copy.deepcopy(data)
    for gear in out["gear"]:
        old = math.radians(gear.get("pressure_angle", 20.0))
        gear["module"] = gear["module"] * math.cos(old) / math.cos(math.radians(alpha))
        gear["pressure_angle"] = alpha
    return out


def build(data: dict[str, Any]):
    return dyade.build_gears(data)


@st.composite
def random_drives(draw, ideal_only: bool = False) -> dict[str, Any]:
    """1–3 stages on parallel shafts (x), spur or helical, random sizes, shaft divisions,
    line-of-centres angles, bearings, gear offsets; RFE or torsional model."""
    stages = draw(st.integers(1, 3))
    model = draw(st.sampled_from(["rfe", "rfe", "torsional"]))
    bodies: list[dict[str, Any]] = [
        {"name": "motor", "mass": draw(st.floats(2.0, 40.0)), "J_x": draw(st.floats(0.005, 0.2)),
         "J_y": draw(st.floats(0.01, 0.3)), "J_z": draw(st.floats(0.01, 0.3))}]
    shafts, gears, meshes, bearings = [], [], [], []
    previous = "motor"
    for s in range(stages):
        z_p, z_r = draw(st.integers(12, 40)), draw(st.integers(20, 90))
        module = draw(st.sampled_from([0.002, 0.003, 0.004, 0.005]))
        alpha = draw(st.floats(14.5, 25.0))
        beta = draw(st.sampled_from([0.0, 0.0, 12.0, 20.0, 30.0]))
        hand = draw(st.sampled_from(["right", "left"]))
        other = "left" if hand == "right" else "right"
        pinion, wheel = f"p{s}", f"w{s}"
        for name, z in ((pinion, z_p), (wheel, z_r)):
            diameter = z * module / math.cos(math.radians(beta))
            bodies.append({"name": name, "diameter": diameter,
                           "width": draw(st.floats(0.02, 0.06)),
                           "bore": draw(st.floats(0.2, 0.6)) * diameter})
        shafts.append({"bodies": [previous, pinion], "length": draw(st.floats(0.08, 0.4)),
                       "diameter": draw(st.floats(0.032, 0.06)),
                       "segments": draw(st.integers(0, 2))})
        helix = {"helix_angle": beta} if beta else {}
        gears.append({"name": f"g{pinion}", "body": pinion, "teeth": z_p, "module": module,
                      "pressure_angle": alpha, "offset": draw(st.floats(-0.01, 0.01))}
                     | helix | ({"hand": hand} if beta else {}))
        gears.append({"name": f"g{wheel}", "body": wheel, "teeth": z_r, "module": module,
                      "pressure_angle": alpha} | helix | ({"hand": other} if beta else {}))
        mesh = {"driving": f"g{pinion}", "driven": f"g{wheel}", "angle": draw(st.floats(-180, 180))}
        if not ideal_only and draw(st.booleans()) and draw(st.booleans()):
            mesh["stiffness"] = draw(st.floats(1e8, 1e10))
        meshes.append(mesh)
        previous = wheel
    bodies.append({"name": "load", "mass": draw(st.floats(5.0, 80.0)),
                   "J_x": draw(st.floats(0.05, 3.0)), "J_y": draw(st.floats(0.05, 3.0)),
                   "J_z": draw(st.floats(0.05, 3.0))})
    shafts.append({"bodies": [previous, "load"], "length": draw(st.floats(0.1, 0.5)),
                   "diameter": draw(st.floats(0.04, 0.08)), "segments": draw(st.integers(0, 2))})
    for body in bodies:
        bearings.append({"body": body["name"], "radial": draw(st.floats(5e7, 5e8))})
    for name in ["motor"] + [f"w{s}" for s in range(stages)]:
        bearings.append({"body": name, "axial": draw(st.floats(5e7, 5e8))})
    if model == "torsional":
        for body in bodies:
            body.pop("J_y", None), body.pop("J_z", None)
    return {"model": model, "speed": {"body": "motor", "rotation": draw(
        st.sampled_from(["right", "left"]))}, "body": bodies, "shaft": shafts, "gear": gears,
            "mesh": meshes, "bearing": bearings}
