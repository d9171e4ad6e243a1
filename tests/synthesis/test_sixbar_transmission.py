"""The smallest transmission angle as a filter of six-bar function and pose targets: both
dyads' angles, in closed form as dyade's engine gives them; a limit above a known
six-bar's rejects it, one below finds it."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.errors import InputError
from dyade.files.synthesis import parse
from dyade.synthesis.topology import TOPOLOGIES

STEPHENSON = np.array([0.3, 1.0, 0.9, 1.0, 0.5, 0.4, 0.6, 1.4, 1.2, 1.0, 0.4, -0.2])
"""a Stephenson III six-bar (m); over 0°-120° of crank its smaller transmission angle is
30.10° (the second dyad's, assembly variants 1 and 2) or 42.83° (variants 3 and 4)"""
CRANK = np.deg2rad(np.linspace(0.0, 120.0, 9))


def function_file(least_deg: float, pinned: bool, candidates: int = 10) -> dict:
    """The synthesis file's data of the six-bar's own function over 0°-120° (pinned: its
    bounds hold every dimension at the known six-bar's)."""
    topology = TOPOLOGIES["stephenson-sixbar"]
    _, f, g, _ = topology.joints(STEPHENSON, 1, CRANK)
    bounds = {k: [float(v), float(v)] for k, v in zip(topology.names, STEPHENSON)
              if pinned and k != "d"}
    return {"topology": "stephenson-sixbar", "units": {"length": "m", "angle": "deg"},
            "target": {"kind": "function", "crank": list(np.rad2deg(CRANK)),
                       "output": list(np.rad2deg(np.angle(f - g)[0]))},
            "bounds": bounds, "search": {"candidates": candidates, "seed": 1,
                                         "min_transmission": least_deg}}


@pytest.mark.parametrize("name", ["stephenson-sixbar", "watt-sixbar", "watt1-sixbar",
                                  "stephenson1-sixbar"])
def test_both_dyads_transmission_angles_are_dyades(name):
    from dyade.files.mechanism import build
    from dyade.linkage.positions import positions

    topology = TOPOLOGIES[name]
    crank = np.linspace(0.0, 2.0 * np.pi, 37)
    for variant in topology.variants:
        mu = topology.transmission(STEPHENSON, variant, crank)[0]
        found = positions(build(topology.data(STEPHENSON, variant)), crank, [(5, (0.0, 0.0))])
        engine = np.arcsin(np.clip(np.min(found.conditioning, axis=1), 0.0, 1.0))
        closes = np.isfinite(mu)
        assert closes.sum() >= 16
        assert np.abs(mu[closes] - engine[closes]).max() < 1e-12  # [rad]


def test_a_limit_below_the_known_six_bar_finds_it_one_above_every_variant_refuses_all():
    from dyade.synthesis import synthesise

    found = synthesise(parse(function_file(25.0, pinned=True)))
    assert found.designs[0].error < 1e-9  # [°] the known six-bar, through dyade
    with pytest.raises(InputError) as err:  # 45° > 42.83°: no variant of it passes
        synthesise(parse(function_file(45.0, pinned=True)))
    assert err.value.key == "bounds" and "at least 45°" in str(err.value)
    assert "search.min_transmission" in str(err.value)


# The design reported obeys the limit through `dyade analyse` of its written file: the
# six-bar templates (min_transmission = 20°), tests/cli/test_synthesis_templates.py.
