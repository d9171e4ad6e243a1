"""The ``accuracy`` entry (``dyade.analyses.accuracy``): the command line writes the
entry's Outcome (less the timings, which differ from run to run), every figure has its
unit, and the summary's settings are where the peaks stop moving."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from dyade.registry import REGISTRY
from dyade.analyses.accuracy import RTOL, converged
from dyade.analyses.base import jsonable
from dyade.cli import main
from tests.helpers import shipped


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def untimed(document: dict) -> dict:
    """A document without its timings (``time_ms``)."""
    document["columns"].pop("time_ms")
    document["units"].pop("time_ms")
    return document


@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml"])
def test_the_json_is_the_entrys_document(name):
    outcome = REGISTRY["accuracy"](shipped(name), repeats=1)
    out = cli("accuracy", shipped(name), "--repeats", 1, "--format", "json")
    assert out.exit_code == 0, out.output
    assert untimed(json.loads(out.stdout)) == untimed(
        json.loads(json.dumps(jsonable(outcome.to_document()))))
    assert outcome.summary and all(figure.unit for figure in outcome.summary.values())
    table = cli("accuracy", shipped(name), "--repeats", 1).stdout
    for text in ("np.float64(", "True", "False", "None", "nan"):
        assert text not in table, text


def test_every_compared_quantity_has_its_unit():
    outcome = REGISTRY["accuracy"](shipped("dyade-16.toml"), repeats=1)
    units = dict(zip(outcome.columns["quantity"], outcome.columns["unit"]))
    assert units["|M_drive| max"] == "N·m"
    assert units["F_1_2 max"] == units["FN_1_6 max"] == units["clearance F12max 2_7"] == "N"
    assert set(units.values()) <= {"N", "N·m"}
    kinematic = REGISTRY["accuracy"](shipped("watt-sixbar.toml"), repeats=1)  # no masses
    assert set(kinematic.columns["unit"]) == {"rad/s²"}


@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml", "self-locking.toml"])
def test_the_summary_names_where_the_peaks_stop_moving(name):
    # the coarsest setting from which on every peak lies within RTOL of the finest's, read
    # off the rows themselves: it and every finer setting within, the next coarser not
    outcome = REGISTRY["accuracy"](shipped(name), repeats=1)
    rows = outcome.result
    for study, figure in (("crank step", "crank_step_deg"), ("friction tol", "friction_tol")):
        mine = [r for r in rows if r["study"] == study]
        if not mine:
            assert figure not in outcome.summary
            continue
        settings = list(dict.fromkeys(r["setting"] for r in mine))
        worst = [max([r["rel_error"] for r in mine if r["setting"] == s
                      and r["rel_error"] == r["rel_error"]], default=0.0) for s in settings]
        value = outcome.value(figure)
        if value is None:
            assert worst[-2] > RTOL
            continue
        index = [float(s.rstrip("°")) for s in settings].index(value)
        assert all(w <= RTOL for w in worst[index:])
        assert index == 0 or worst[index - 1] > RTOL
        assert outcome.summary[figure].unit == ("°" if study == "crank step" else "-")


def test_converged_takes_the_run_of_settings_within_the_tolerance():
    def rows(*errors):
        return [{"setting": str(k), "rel_error": e} for k, e in enumerate(errors)]

    nan = float("nan")
    assert converged(rows(1e-2, 1e-4, 1e-5, nan)) == "1"
    assert converged(rows(1e-4, 1e-2, 1e-5, nan)) == "2"  # one coarser within does not count
    assert converged(rows(1e-2, 1e-2, nan)) is None


def test_the_bounds_of_a_run():
    out = cli("accuracy", shipped("fourbar.toml"), "--max-memory", 1)
    assert out.exit_code == 2 and "--max-memory is 1.05 MB, and this sweep of 7,201 positions" \
        in out.output
    out = cli("accuracy", shipped("dyade-16.toml"), "--max-time", 0.01)
    assert out.exit_code == 2 and "--max-time is 0.01 s, and DYADE-16 processing-machine " \
        "drive: the accuracy studies would take about" in out.output
