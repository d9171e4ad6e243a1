"""Texts right (issue 28): what dyade says about a file matches the file and the numbers."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from tests.helpers import shipped


@pytest.mark.parametrize("variant", [1, -1])
def test_describe_prints_the_rule_of_each_variant_and_the_geometry_obeys_it(variant):
    out = CliRunner(env={"COLUMNS": "250"}).invoke(
        main, ["describe", str(shipped("fourbar.toml")), "--set", f"dyad.2.variant={variant}"],
        catch_exceptions=False)
    assert out.exit_code == 0, out.output
    side = "left" if variant > 0 else "right"
    assert (f"assembly variant {variant:+d} (B {side} of the directed line A→C)"
            in " ".join(out.stdout.split()))
    # and B is on that side of A→C at every position
    cols = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), overrides={
        "dyad.2.variant": variant})).columns()
    a = np.array([cols["x_2_3"], cols["y_2_3"]])
    b = np.array([cols["x_3_4"], cols["y_3_4"]])
    c = np.array([cols["x_1_4"], cols["y_1_4"]])
    cross = (c[0] - a[0]) * (b[1] - a[1]) - (c[1] - a[1]) * (b[0] - a[0])
    assert np.all(np.sign(cross) == variant)
