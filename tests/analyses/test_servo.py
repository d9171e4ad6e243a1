"""The servo entry in a design study (``[outputs] extra = ["servo"]``): the gear ratio and
a segment's boundary as parameters."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from tests.helpers import shipped


@pytest.mark.slow
def test_a_study_varies_the_gear_ratio_and_a_segments_end(tmp_path):
    study = tmp_path / "study.toml"
    study.write_text(f'mechanism = "{shipped("servo/fourbar.toml").as_posix()}"\n\n'
                     '[plan]\nkind = "grid"\n\n[parameters]\n"servo.ratio" = [4, 8]\n'
                     '"profile.segment.1.end" = [0.25, 0.3]\n\n[outputs]\nextra = ["servo"]\n')
    outcome = dyade.run("study", study)
    columns = outcome.columns
    assert outcome.units["motor_torque_rms"] == "N·m"
    # each variant's figures are those of dyade servo with its values set
    for row in range(len(columns["servo.ratio"])):
        alone = dyade.run("servo", shipped("servo/fourbar.toml"), set=(
            f"servo.ratio={columns['servo.ratio'][row]:g}",
            f"profile.segment.1.end={columns['profile.segment.1.end'][row]:g}"))
        assert columns["motor_torque_rms"][row] == pytest.approx(
            alone.value("motor_torque_rms"), rel=1e-12)
    # a faster rise asks more torque
    fast = (columns["profile.segment.1.end"] == 0.25) & (columns["servo.ratio"] == 8)
    slow = (columns["profile.segment.1.end"] == 0.3) & (columns["servo.ratio"] == 8)
    assert np.all(columns["motor_torque_peak"][fast] > columns["motor_torque_peak"][slow])
