"""Six-bar topologies of two dyads (Watt II, Stephenson III) for path generation: the
closed-form coupler curve the local fit uses equals dyade's own positions stage for
every assembly variant (and the shipped Watt six-bar's), and a search recovers a
Stephenson six-bar from its own coupler curve."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.files.mechanism import read_mechanism
from dyade.files.synthesis import parse
from dyade.linkage.positions import positions
from dyade.synthesis.search import traced
from dyade.synthesis.topology import TOPOLOGIES

STEPHENSON = np.array([0.3, 1.0, 0.9, 1.0, 0.5, 0.4, 0.6, 1.4, 1.2, 1.0, 0.4, -0.2])
CRANK = np.linspace(0.0, 2.0 * np.pi, 48, endpoint=False)
SAMPLES = {"stephenson-sixbar": STEPHENSON,
           "watt-sixbar": np.array([0.2, 0.8, 0.6, 1.0, 0.4, -0.24, 1.8, 1.0, 0.72, 0.48, 0.36,
                                    0.12]),
           "watt1-sixbar": np.array([0.2, 0.8, 0.6, 1.0, 0.58, 0.03, 0.21, -0.46, 0.98, 0.78,
                                     0.36, 0.12]),  # E on the coupler, G on the rocker
           "stephenson1-sixbar": np.array([0.2, 0.8, 0.6, 1.0, 0.27, -0.16, 0.59, 0.16, 0.76,
                                           0.98, 0.36, 0.12])}  # E on the crank, G on the rocker
"""six-bars whose second dyad closes over the whole turn on both of its branches"""


def test_the_shipped_watt_sixbar_is_the_watt_topology():
    mechanism = read_mechanism("mechanisms/watt-sixbar.toml")
    found = positions(mechanism, CRANK, [(5, mechanism.links[5].points["P"])])
    dyade_path = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
    # the file's numbers [mm -> m]: a b c d, E on the rocker, D0, f g, P on link 5
    values = np.array([50, 200, 150, 250, 100, -60, 450, 250, 180, 120, 90, 30]) * 1e-3
    closed_form = TOPOLOGIES["watt-sixbar"].path(values, 2, CRANK)[0]  # variants (+1, −1)
    assert np.abs(closed_form - dyade_path).max() < 1e-12
    assert np.abs(TOPOLOGIES["watt-sixbar"].path(values, 1, CRANK)[0] - dyade_path).max() > 1e-3


@pytest.mark.parametrize("name", ["watt-sixbar", "stephenson-sixbar", "watt1-sixbar",
                                  "stephenson1-sixbar"])
def test_the_closed_form_curve_is_dyades_for_every_variant(name):
    topology = TOPOLOGIES[name]
    values = SAMPLES[name]
    checked = 0
    for variant in topology.variants:
        expected = topology.path(values, variant, CRANK)[0]
        curves, closes, _ = traced(topology, values[None, :], variant, CRANK)
        assert closes[0] == np.isfinite(expected).all()
        if closes[0]:
            assert np.abs(curves[0] - expected).max() < 1e-12
            checked += 1
    assert checked >= 2


def test_a_six_bar_sizes_paths_stretches_and_poses():
    assert parse({"topology": "watt-sixbar", "target": {"kind": "line", "stretch": 120}},
                 "s.toml").target.kind == "line"
    made = parse({"topology": "watt1-sixbar",
                  "target": {"kind": "poses", "poses": [[0, 0, 0], [1, 0, 10], [1, 1, 20]]}},
                 "s.toml")  # tests/synthesis/test_sixbar_targets.py: function and poses
    assert made.target.kind == "poses"


@pytest.mark.parametrize("name", list(SAMPLES))
def test_the_least_transmission_angle_is_dyades(name):
    """The stretch refinement's closed-form transmission angle of a six-bar (the least
    of its two dyads') against the one dyade's positions stage reports."""
    from dyade.synthesis.stretch import transmission

    topology = TOPOLOGIES[name]
    checked = 0
    for variant in topology.variants:
        _, closes, least = traced(topology, SAMPLES[name][None, :], variant, CRANK)
        if closes[0]:
            assert transmission(topology, SAMPLES[name], variant, CRANK) == pytest.approx(
                least[0], abs=1e-12)
            checked += 1
    assert checked >= 2


@pytest.mark.slow
def test_a_search_recovers_a_stephenson_sixbar_from_its_own_coupler_curve():
    from dyade.synthesis import synthesise

    topology = TOPOLOGIES["stephenson-sixbar"]
    crank = np.linspace(0.0, 2.0 * np.pi, 20, endpoint=False)
    points = topology.path(STEPHENSON, 1, crank + 0.7)[0] * 0.1 + (0.3 + 0.2j)  # moved
    bounds = {k: sorted([0.85 * x, 1.15 * x]) for k, x in zip(topology.names, STEPHENSON)}
    bounds["d"] = [1.0, 1.0]
    problem = parse({"topology": "stephenson-sixbar",
                     "target": {"kind": "path", "points": [[z.real, z.imag] for z in points]},
                     "bounds": bounds, "output": {"keep": 1},
                     "search": {"candidates": 300, "block": 300, "rounds": 1, "seed": 1}})
    result = synthesise(problem)
    best = result.designs[0]
    assert best.error < 1e-9 and best.converged
    # the generating six-bar's own proportions (its error is 0: none can do better)
    fitted = best.fitted
    assert fitted.values / fitted.values[3] == pytest.approx(STEPHENSON, rel=1e-6)
    # the written mechanism traces the target through dyade
    traced_path = best.traced
    assert np.min(np.abs(traced_path[:, None] - points[None, :]), axis=0).max() < 2e-3 * 0.1


@pytest.mark.parametrize("name", ["watt1-sixbar", "stephenson1-sixbar"])
def test_the_written_mechanism_file_traces_the_closed_form(tmp_path, name):
    """Watt I and Stephenson I as files: written as ``dyade synthesise --write`` writes
    them, read back, their coupler point through dyade's engine is the closed form's."""
    from dyade.report.synthesis import mechanism_text
    from dyade.synthesis import Design
    from dyade.synthesis.topology import Placement

    topology = TOPOLOGIES[name]
    placement = Placement(0.1 - 0.2j, 0.25, 0.4)
    data = topology.data(SAMPLES[name], 3, placement)
    path = tmp_path / "design-1.toml"
    path.write_text(mechanism_text(Design("design 1", data, 0.0, True, CRANK, CRANK)))
    mechanism = read_mechanism(path)
    found = positions(mechanism, CRANK + placement.angle, [(5, mechanism.links[5].points["P"])])
    traced_path = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
    expected = placement.apply(topology.path(SAMPLES[name], 3, CRANK)[0])
    assert np.abs(traced_path - expected).max() < 1e-12
