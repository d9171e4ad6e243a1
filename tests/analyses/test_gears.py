"""The gear entries (``gear-modes``, ``gear-campbell``, ``gear-response``): the command
line writes the entries' Outcomes, the figures have units, the tables no Python repr,
and what the entries compute is the physics of the drive."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.registry import REGISTRY
from dyade.analyses.base import jsonable
from dyade.analyses.inputs import Text
from dyade.cli import main
from dyade.errors import DyadeError, InputError
from tests.helpers import shipped

GEARS = sorted(str(p) for p in shipped("gears").glob("*.toml"))
TWO_STAGE = str(shipped("gears/two-stage.toml"))
FRISWELL = str(shipped("gears/friswell-geared.toml"))

RUNS = [  # (command line after the file, entry, its API options)
    ([], "gear-modes", {}),
    (["--modes", "3"], "gear-modes", {"modes": 3}),
    (["--check"], "gear-modes", {"check": True}),
    (["--set", "shaft.1.segments=4"], "gear-modes", {"set": ("shaft.1.segments=4",)}),
    (["--speed-range", "0:3000:10"], "gear-campbell", {"speed_range_rpm": "0:3000:10"}),
    (["--speed-range", "0:3000:10", "--harmonics", "2"], "gear-campbell",
     {"speed_range_rpm": "0:3000:10", "harmonics": 2}),
    (["--frequency-range", "10:1000:1", "--dof", "gear1.uy"], "gear-response",
     {"frequency_range_hz": "10:1000:1", "dof": ("gear1.uy",)}),
]
REPR = re.compile(r"np\.float64\(|\bnan\b|\bTrue\b|\bFalse\b|\bNone\b|\(np\.|array\(")


def run(*args, code: int = 0):
    result = CliRunner().invoke(main, ["gears", *map(str, args)], catch_exceptions=False)
    assert result.exit_code == code, result.output
    return result


def cases():
    for path in GEARS:
        for args, name, options in RUNS:
            if name == "gear-campbell" and dyade.read_gears(path).speed is None:
                continue  # friswell: no [speed], no Campbell diagram
            if "shaft.1.segments=4" in args and "two-stage" not in path:
                continue
            if name == "gear-response" and "two-stage" not in path:
                continue
            yield pytest.param(path, args, name, options,
                               id=f"{path.rsplit('/', 1)[1]} {' '.join(args) or name}")


@pytest.mark.parametrize("path, args, name, options", list(cases()))
def test_the_json_is_the_entrys_document(path, args, name, options):
    written = json.loads(run(path, *args, "--format", "json").stdout)
    outcome = REGISTRY[name](path, **options)
    assert written == json.loads(json.dumps(jsonable(outcome.to_document())))
    assert written["analysis"] == name
    for figure in outcome.summary.values():  # every figure has its unit ("-": none)
        assert figure.unit, figure.name
        assert re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", figure.name), figure.name
    for column, unit in outcome.units.items():
        text = np.asarray(outcome.columns[column]).dtype.kind == "O"
        assert bool(unit) != text, column  # numbers have a unit, text has none
    csv_head = run(path, *args, "--format", "csv").stdout.splitlines()[0]
    assert csv_head.split(",") == list(outcome.columns)


@pytest.mark.parametrize("path, args, name, options", list(cases()))
def test_tables_show_no_python_repr(path, args, name, options):
    text = run(path, *args).stdout
    assert not REPR.search(text), REPR.search(text)


def test_the_sources_agree_file_text_drive_and_modes():
    """A path, its text, a GearDrive and its Modes give one analysis; --set only on a file."""
    by_path = REGISTRY["gear-campbell"](TWO_STAGE, speed_range_rpm="0:3000:100")
    drive = dyade.read_gears(TWO_STAGE)
    modes = REGISTRY["gear-modes"](drive).result.modes
    for source in (Text(shipped("gears/two-stage.toml").read_text()), drive, modes):
        other = REGISTRY["gear-campbell"](source, speed_range_rpm="0:3000:100")
        assert other.to_document()["summary"] == by_path.to_document()["summary"]
        assert np.array_equal(other.columns["speed_rpm"], by_path.columns["speed_rpm"])
    with pytest.raises(InputError, match="set needs a gear-drive file"):
        REGISTRY["gear-modes"](drive, set=("shaft.1.segments=4",))


def test_friswell_frequencies_of_the_paper():
    # Friswell et al. (2010), the geared rotor: 425.4, 634.1 and 3247.2 Hz (printed to 0.1 Hz)
    outcome = REGISTRY["gear-modes"](FRISWELL)
    assert np.round(outcome.columns["f_Hz"], 1).tolist() == [425.4, 634.1, 3247.2]
    assert outcome.value("f_1") == outcome.columns["f_Hz"][0]
    assert outcome.value("rigid_modes") == 1 and outcome.value("elastic_modes") == 3


def test_the_response_peaks_at_natural_frequencies():
    """Lightly damped: each amplitude peaks within a step (1 Hz) of a natural frequency,
    and the peaks are where the summary says."""
    outcome = REGISTRY["gear-response"](TWO_STAGE, frequency_range_hz="10:1000:1")
    natural = REGISTRY["gear-modes"](TWO_STAGE).columns["f_Hz"]
    for name in ("F_stage1_N", "F_stage2_N", "bearing5_radial_N"):
        values = outcome.columns[name]
        k = int(np.nanargmax(values))
        figure = outcome.summary[name[:-2] + "_peak"]
        assert figure.value == values[k] and figure.unit == "N"
        assert figure.where == {"f_hz": outcome.columns["f_Hz"][k]}
        assert np.min(np.abs(natural - outcome.columns["f_Hz"][k])) <= 1.0, name


def test_a_response_with_no_finite_value_is_refused():
    """A drive that turns freely has no finite response at 0 Hz: a range of that one
    frequency is all withheld, and says so (exit 1), never a table of blanks."""
    with pytest.raises(DyadeError, match="no frequency of the range has a finite response"):
        REGISTRY["gear-response"](TWO_STAGE, frequency_range_hz="0:0:1")
    assert "finite response" in run(TWO_STAGE, "--frequency-range", "0:0:1", code=1).output
    outcome = REGISTRY["gear-response"](TWO_STAGE, frequency_range_hz="0:20:10")  # partly: fine
    assert np.isnan(outcome.columns["F_stage1_N"][0]) and "no finite response at 0" in \
        outcome.notes[0]


def test_long_runs_are_estimated_before_they_start():
    """The time bound refuses, before anything is solved, a response estimated above it;
    the estimate grows with the frequencies and the size of the drive."""
    told = []
    with pytest.raises(InputError, match=r"max_time_s is 0.1 s, and the response at 99,991 "):
        REGISTRY["gear-response"](TWO_STAGE, frequency_range_hz="0:9999:0.1", max_time_s=0.1)
    REGISTRY["gear-response"](TWO_STAGE, frequency_range_hz="10:20:1", told=told.append)
    assert told == []  # a short run is not announced
    result = run(TWO_STAGE, "--set", "shaft.1.segments=400", "--max-time", "1", code=2)
    assert "--max-time is 1 s, and the modes of" in result.output


def test_the_report_runs_each_entry_once(monkeypatch):
    """The design report of a gear drive composes the entries' Outcomes: the modes are
    computed once (the Campbell diagram reuses them)."""
    pytest.importorskip("matplotlib")
    from dyade.report.html import report
    from dyade.vibration.gears import modes as engine

    calls = []
    solve = engine.gear_modes
    monkeypatch.setattr(engine, "gear_modes", lambda *a, **k: calls.append(1) or solve(*a, **k))
    page = report(TWO_STAGE)
    assert len(calls) == 1
    assert "Campbell diagram" in page and "Natural frequencies and energy shares" in page
    assert not REPR.search(re.sub(r"<[^>]+>", " ", page.split("<svg")[0]))
