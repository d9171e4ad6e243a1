"""Scores beyond kinematics: the three cognates of a drag-link trace one curve with
different drive torques; the synthesis ranks them by RMS drive torque, and each one's
figure is what `dyade analyse` gives for its written file."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.cli import main
from dyade.files.synthesis import parse
from dyade.report.synthesis import mechanism_text
from dyade.synthesis import Design, Result, closed, pareto, score
from dyade.synthesis.topology import FourBar, fourbar_from_points


def test_pareto_keeps_the_non_dominated_rows():
    rows = np.array([[1.0, 5.0], [2.0, 1.0], [2.0, 6.0], [0.5, 9.0], [np.nan, 0.1]])
    assert pareto(rows).tolist() == [True, True, False, True, False]


@pytest.mark.slow
def test_the_cognates_rank_by_rms_drive_torque_as_dyade_analyse_gives_it(tmp_path):
    # a drag-link (the frame the shortest): all three cognates are double cranks
    linkage = closed.FourBar(a=1.0, b=1.4, c=1.2, d=0.5, p=0.6, q=0.5, variant=1)
    problem = parse({"units": {"length": "m"}, "target": {"kind": "line", "stretch": 90},
                     "scores": {"speed_rpm": 300, "mass_per_length": 3.0}})
    designs = []
    for k, cognate in enumerate(closed.cognates(linkage), start=1):
        (f0, f1), (m0, m1), p = cognate.fixed, cognate.moving, cognate.point
        values, variant, placement, _ = fourbar_from_points(f0, m0, m1, f1, p)
        data = FourBar().data(values, variant, placement, 300.0, problem.masses,
                              name=f"cognate {k}")
        designs.append(Design(f"cognate {k}", data, 0.0, True, np.zeros(0), np.zeros(0)))
    result = Result(problem, designs)
    score(result)
    rms = np.array([d.figures["M_drive_rms"] for d in designs])
    assert np.all(np.isfinite(rms))
    ranked = np.sort(rms)
    assert np.all(np.diff(ranked) > 0.01 * ranked[-1])  # three different torques
    assert result.pareto.tolist() == (rms == rms.min()).tolist()  # equal curves: the least
    runner = CliRunner()
    for k, design in enumerate(designs, start=1):
        path = tmp_path / f"design-{k}.toml"
        path.write_text(mechanism_text(design), encoding="utf-8")
        written = tmp_path / f"design-{k}.json"
        out = runner.invoke(main, ["analyse", str(path), "--format", "json", "-o", str(written)])
        assert out.exit_code == 0, out.output
        document = json.loads(written.read_text(encoding="utf-8"))
        assert document["summary"]["M_drive_rms"]["value"] == pytest.approx(rms[k - 1],
                                                                             rel=1e-12)
