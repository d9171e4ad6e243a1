"""Limits the model must reach: the torsional model for stiff bearings and shafts, the
ideal mesh for a stiff elastic one, beam theory for finely divided shafts; and what the
pressure angle may and may not change."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import dyade
from dyade.vibration.gears.modes import gear_modes
from tests.vibration.gears.drives import build, single_stage, two_stage_data, with_pressure_angle


def _stiffened(data, scale):
    """Bearings (radial, axial) and the shafts' bending, shear and axial stiffness times
    ``scale``; torsion (G·I_p) unchanged."""
    out = copy.deepcopy(data)
    for bearing in out["bearing"]:
        for key in ("radial", "axial"):
            if key in bearing:
                bearing[key] *= scale
    for shaft in out["shaft"]:
        shaft["material"] = {"E": 2.1e11 * scale}
        shaft["shear_factor"] = 0.9 * scale
    return out


def test_stiff_bearings_and_shafts_converge_to_the_torsional_model():
    """As bearings and shaft bending/shear/axial stiffness grow by s, the six-coordinate
    drive's torsional frequencies reach the torsional model's with an error ∝ 1/s (static
    condensation of the lateral coordinates)."""
    data = two_stage_data()
    torsional = copy.deepcopy(data)
    torsional["model"] = "torsional"
    limit = gear_modes(build(torsional)).frequencies
    assert limit.size == 6  # 6 bodies + 3 shaft segments - 2 meshes - 1 rigid-body mode
    errors = []
    for scale in (1e2, 1e3, 1e4):
        modes = gear_modes(dyade.build_gears(_stiffened(data, scale), plausible=False))
        torsion = modes.totals("kinetic")["torsion"] > 0.5
        f = modes.frequencies[torsion][:limit.size]
        errors.append(np.abs(f - limit) / limit)
    # per mode, e.g. mode 1: 7.6e-4, 7.6e-5, 7.6e-6; mode 6 (still reaching it): 1.1e-2,
    # 8.3e-4, 6.7e-5. (Beyond s = 1e4 the round-off eps·ω²_max/ω², which grows with s,
    # reaches these errors.)
    rate = np.log10(errors[1] / errors[2])
    assert np.all((rate > 0.97) & (rate < 1.12)), (errors, rate)  # error ∝ 1/s
    assert np.all(errors[2] < 1e-4) and np.all(errors[1] < 1e-3)


def test_one_mesh_on_isotropic_bearings_is_independent_of_the_pressure_angle():
    """Rotating a line of action about isotropically supported shafts changes nothing:
    at fixed base radii the frequencies do not depend on α_n (the centre distance does)."""
    reference = gear_modes(build(single_stage(alpha=20.0, base_radii=True))).frequencies
    for alpha in (14.5, 25.0, 30.0):
        f = gear_modes(build(single_stage(alpha=alpha, base_radii=True))).frequencies
        assert np.allclose(f, reference, rtol=1e-9), alpha


def test_two_meshes_on_a_shaft_or_anisotropic_bearings_depend_on_the_pressure_angle():
    """Never assert invariance where it does not hold: the two-stage drive's intermediate
    shaft carries two meshes whose lines of action cannot both be turned away; and one
    mesh with a bearing stiffer along y than along z."""
    f20 = gear_modes(build(with_pressure_angle(two_stage_data(), 20.0))).frequencies
    f25 = gear_modes(build(with_pressure_angle(two_stage_data(), 25.0))).frequencies
    assert np.max(np.abs(f25 - f20) / f20) > 1e-3
    spring = [{"bodies": ["pinion", "frame"], "stiffness": [0, 3e8, 0, 0, 0, 0]}]
    a = gear_modes(build(single_stage(base_radii=True) | {"element": spring})).frequencies
    b = gear_modes(build(single_stage(alpha=25.0, base_radii=True) | {"element": spring}))
    assert np.max(np.abs(b.frequencies - a) / a) > 1e-3


def test_an_elastic_mesh_tends_to_the_ideal_constraint_as_one_over_k():
    ideal = gear_modes(build(single_stage())).frequencies[:8]
    errors = []
    for k in (1e10, 1e11, 1e12):
        f = gear_modes(build(single_stage(mesh={"stiffness": k}))).frequencies[:8]
        errors.append(np.max(np.abs(f - ideal) / ideal))
    assert errors[0] / errors[1] == pytest.approx(10.0, rel=0.05)
    assert errors[1] / errors[2] == pytest.approx(10.0, rel=0.05)


# -- shafts by the RFE method ------------------------------------------------------------
STEEL = {"E": 2.1e11, "G": 8.1e10, "density": 7850.0}


def _shaft(segments, length=1.0, diameter=0.05):
    """A shaft clamped to the frame at one end, a disk of its own section and 1/100 of its
    length at the other (fixed end, end inertia 1 % of the shaft's)."""
    return {
        "body": [{"name": "tip", "diameter": diameter, "width": length / 100}],
        "shaft": [{"name": "s", "bodies": ["tip", "frame"], "length": length,
                   "diameter": diameter, "segments": segments}],
    }


def _pinned_shaft(segments, length=1.0, diameter=0.05):
    """A shaft between two thin disks in stiff radial bearings (simply supported), free to
    turn, axially held at one end."""
    return {
        "body": [{"name": "a", "diameter": diameter, "width": 0.01},
                 {"name": "b", "diameter": diameter, "width": 0.01}],
        "shaft": [{"name": "s", "bodies": ["a", "b"], "length": length, "diameter": diameter,
                   "segments": segments}],
        "bearing": [{"body": "a", "radial": 1e11, "axial": 1e11}, {"body": "b", "radial": 1e11}],
    }


def _rates(values):
    """Observed orders of each halving of the segment length, from successive differences
    (constant offsets, such as the supports' own compliance, cancel)."""
    steps = np.abs(np.diff(values))
    return np.log2(steps[:-1] / steps[1:])


def _rod(wave_speed):
    """First frequency [Hz] of a fixed-free rod with an end inertia 1/100 of its own:
    x·tan x = 100, f = x·c/(2π·L)."""
    x = brentq(lambda x: x * math.tan(x) - 100.0, 1e-9, math.pi / 2 - 1e-12)
    return x * wave_speed / (2 * math.pi)


def test_shaft_torsion_and_axial_converge_to_the_rod_at_second_order():
    """The RFE division of a fixed-free shaft with an end disk against the exact rod
    (c = √(G/ρ) in torsion, √(E/ρ) axially): second order, 9.5e-5 at 32 segments."""
    counts = [4, 8, 16, 32]
    torsion, axial = [], []
    for n in counts:
        modes = gear_modes(build(_shaft(n)))
        kinetic = modes.totals("kinetic")
        torsion.append(modes.frequencies[kinetic["torsion"] > 0.99][0])
        axial.append(modes.frequencies[kinetic["axial"] > 0.99][0])
    for values, modulus in ((torsion, STEEL["G"]), (axial, STEEL["E"])):
        exact = _rod(math.sqrt(modulus / STEEL["density"]))
        errors = np.abs(np.array(values) - exact) / exact
        assert np.allclose(np.log2(errors[:-1] / errors[1:]), 2.0, atol=0.01), errors
        assert errors[-1] < 1e-4


def _timoshenko_pinned(length, diameter, mode=1):
    """First bending frequency of a simply supported Timoshenko beam [Hz] (shear factor
    0.9 as the shafts use): the smaller root of
    (κGA·k² − ρAω²)(EI·k² + κGA − ρIω²) = (κGA·k)², k = mode·π/L."""
    e, g, rho, kappa = STEEL["E"], STEEL["G"], STEEL["density"], 0.9
    area, inertia = math.pi * diameter ** 2 / 4, math.pi * diameter ** 4 / 64
    k = mode * math.pi / length
    a = rho * area * rho * inertia
    b = -(rho * area * (e * inertia * k ** 2 + kappa * g * area)
          + rho * inertia * kappa * g * area * k ** 2)
    c = kappa * g * area * k ** 2 * e * inertia * k ** 2
    omega2 = (-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)
    return math.sqrt(omega2) / (2 * math.pi)


def test_shaft_bending_converges_to_the_timoshenko_beam_at_third_order():
    """Simply supported shaft, L/d = 20: the first bending frequency converges at third
    order (observed 2.98–3.00 from 4 to 64 segments, 2.92 by 256); extrapolated, it is the
    Timoshenko beam's within the supports' own effect (bearings of 1e11 N/m and the end
    disks' inertia: 4.5e-5)."""
    values = []
    for n in (4, 8, 16, 32, 64):
        modes = gear_modes(build(_pinned_shaft(n)))
        lateral = modes.totals("kinetic")["lateral"] > 0.99
        values.append(modes.frequencies[lateral][0])
    assert np.allclose(_rates(values), 3.0, atol=0.05), _rates(values)
    limit = values[-1] + (values[-1] - values[-2]) / 7  # Richardson, third order
    exact = _timoshenko_pinned(1.0, 0.05)
    assert abs(limit - exact) / exact < 1e-4
    assert abs(values[3] - exact) / exact < 1e-4  # 32 segments
