"""An arc stretch with a prescribed radius: the design is scaled (a similarity, which
keeps the deviation over the length) so that the circle of its stretch, traced through
dyade's engine, has the radius asked."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.errors import InputError
from dyade.files.mechanism import build
from dyade.linkage.positions import positions
from dyade.files.synthesis import parse
from dyade.synthesis import synthesise
from dyade.synthesis.stretch import circle, deviation


@pytest.mark.slow
def test_an_arc_of_a_prescribed_radius():
    data = {"units": {"length": "mm", "angle": "deg"},
            "target": {"kind": "arc", "stretch": 90, "radius": 250},
            "search": {"candidates": 60, "block": 60, "rounds": 1, "seed": 2},
            "output": {"keep": 1}}
    sized = synthesise(parse(data))
    design = sized.designs[0]
    lo, hi = design.stretch
    mechanism = build(design.data)  # the design's file through dyade's positions stage
    along = lo + np.linspace(0.0, hi - lo, 121)  # the stretch as the synthesis samples it
    found = positions(mechanism, along, [(3, mechanism.links[3].points["P"])])
    centre, radius = circle(found.points[:, 0, 0] + 1j * found.points[:, 0, 1])
    assert radius == pytest.approx(0.25, rel=1e-9)
    crank = np.mod(design.crank - lo, 2 * np.pi) <= (hi - lo) + 1e-9
    # a similarity: the traced stretch's deviation over its length is the design's error
    # (found on the unscaled design; sampled here at dyade's 1° instead of the refine's)
    assert deviation(design.traced[crank], "arc") == pytest.approx(design.error, rel=0.05)


def test_a_radius_is_for_arcs_with_a_free_scale():
    for target, search in (({"kind": "line", "stretch": 90, "radius": 1}, {}),
                           ({"kind": "arc", "stretch": 90, "radius": 1}, {"scale": False})):
        with pytest.raises(InputError) as err:
            parse({"target": target, "search": search}, "s.toml")
        assert "target.radius" in str(err.value)
