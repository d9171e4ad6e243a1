"""`dyade accuracy`: the studies run, errors shrink with the step, references are marked."""

import csv
import io
import math

from click.testing import CliRunner

from dyade.linkage import accuracy
from dyade.files import mechanism as toml_input
from dyade.cli import main
from tests.helpers import shipped


def test_crank_step_errors_shrink():
    mechanism = toml_input.read_mechanism(shipped("fourbar.toml"))
    rows = [r for r in accuracy.crank_step(mechanism, steps=(5.0, 1.0, 0.1), repeats=1)
            if r.quantity == "|M_drive| max"]
    errors = [r.error for r in rows]
    assert math.isnan(errors[-1])  # the reference
    assert errors[0] > errors[1] > 0


def test_cli_csv_has_every_study(tmp_path):
    out = CliRunner().invoke(main, ["accuracy", str(shipped("dyade-16.toml")), "--repeats", "1",
                                    "--format", "csv"], catch_exceptions=False)
    assert out.exit_code == 0
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    assert {r["study"] for r in rows} == {"crank step", "clearance"}
    assert any(r["quantity"] == "clearance F12max 2_7" for r in rows)
    sims = [r for r in rows if r["setting"].startswith("RK4")]
    assert float(sims[-1]["rel_error"]) < 1e-9


def test_friction_study_when_the_file_has_friction():
    mechanism = toml_input.read_mechanism(shipped("self-locking.toml"))
    rows = accuracy.friction_tol(mechanism, tols=(1e-3, 1e-9), repeats=1)
    assert {r.setting for r in rows} == {"0.001", "1e-09"}
    assert all("passes" in r.extra for r in rows)
