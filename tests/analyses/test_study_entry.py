"""The ``study`` entry (``dyade.study.entry``): the command line writes the entry's
Outcome, its summary is the study's answers with units, its CSV and journal follow the
one cell rule of every CSV, and the bounds of a run hold."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.registry import REGISTRY
from dyade.analyses.base import cell, jsonable
from dyade.cli import main
from tests.helpers import shipped


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def study_file(tmp_path, parameters: str, rest: str = "", mechanism="fourbar.toml"):
    path = tmp_path / "study.toml"
    path.write_text(f"mechanism = {json.dumps(str(shipped(mechanism)))}\n{rest}\n"
                    f"[parameters]\n{parameters}\n", encoding="utf-8")
    return path


GRID = '"dyad.2.lengths.1" = [190, 80, 210]'
TOLERANCE = ('"links.4.mass" = { nominal = 0.9, sd = 0.05 }',
             '[plan]\nkind = "monte-carlo"\nsamples = 6\nseed = 1\n'
             '[tolerance]\ntransmission_deg = 63\njoint_force = 90\n')
SENSITIVITY = ('"links.4.mass" = { nominal = 0.9, step = 0.01 }\n"dyad.2.lengths.1" = 200',
               '[plan]\nkind = "sensitivity"\nrel_step = 0.002\n')


@pytest.mark.parametrize("kind", ["grid", "tolerance", "sensitivity"])
def test_the_json_is_the_entrys_document(tmp_path, kind):
    path = {"grid": lambda: study_file(tmp_path, GRID),
            "tolerance": lambda: study_file(tmp_path, *TOLERANCE),
            "sensitivity": lambda: study_file(tmp_path, *SENSITIVITY)}[kind]()
    outcome = REGISTRY["study"](path)
    out = cli("study", path, "--format", "json")  # without -o: the document on stdout
    assert out.exit_code == 0, out.output
    assert json.loads(out.stdout) == json.loads(json.dumps(jsonable(outcome.to_document())))
    assert all(figure.unit for figure in outcome.summary.values())
    assert set(outcome.units) == set(outcome.columns)
    table = cli("study", path).stdout.replace("allow_partial=True", "")  # (a reason's words)
    for text in ("np.float64(", "True", "False", "None", "nan"):
        assert text not in table, text


def test_the_summary_is_the_studys_answers(tmp_path):
    grid = REGISTRY["study"](study_file(tmp_path, GRID))
    cols = grid.columns
    assert grid.value("variants") == 3 and grid.value("variants_not_closing") == 1
    assert grid.notes == [f"1 of 3 variants do not close (the first, variant 1: "
                          f"{cols['reason'][1].rstrip('.')})."]
    values = cols["M_drive_rms"]
    assert grid.value("max_M_drive_rms") == np.nanmax(values)
    assert grid.summary["max_M_drive_rms"].where == {"variant": int(np.nanargmax(values))}
    assert grid.summary["min_mu_2_min_deg"].unit == "°"
    assert grid.units["dyad.2.lengths.1"] == "mm" and grid.units["F_1_2_peak"] == "N"
    tolerance = REGISTRY["study"](study_file(tmp_path, *TOLERANCE))
    force = tolerance.columns["F_1_2_peak"]
    assert tolerance.value("mean_F_1_2_peak") == pytest.approx(np.mean(force), rel=1e-12)
    assert tolerance.value("sd_F_1_2_peak") == pytest.approx(np.std(force, ddof=1), rel=1e-12)
    assert tolerance.value("probability_transmission_below") == np.mean(
        tolerance.columns["mu_2_min_deg"] < 63)
    sensitivity = REGISTRY["study"](study_file(tmp_path, *SENSITIVITY))
    figure = sensitivity.summary["d_M_drive_rms_d_dyad_2_lengths_1"]
    assert figure.unit == "N·m/m" and figure.where["parameter"] == "dyad.2.lengths.1"
    assert sensitivity.summary["d_M_drive_rms_d_links_4_mass"].unit == "N·m/kg"
    # central differences from the table's own rows: the plan's ±h rows of the parameter
    cols, h = sensitivity.columns, figure.where["step"]
    lengths = cols["dyad.2.lengths.1"]
    plus, minus = np.flatnonzero(lengths == 200 + h)[0], np.flatnonzero(lengths == 200 - h)[0]
    assert figure.value == pytest.approx((cols["M_drive_rms"][plus] - cols["M_drive_rms"][minus])
                                         / (2 * h * 1e-3), rel=1e-12)  # h in mm, per m


def test_the_csv_follows_the_one_cell_rule(tmp_path):
    path = study_file(tmp_path, GRID)
    outcome = REGISTRY["study"](path)
    text = cli("study", path, "--format", "csv").stdout
    lines = text.splitlines()
    assert lines[0].split(",") == list(outcome.columns)
    assert "nan" not in text and "0.0," not in text
    closed = lines[2].split(",")  # the variant that does not close: empty outputs
    assert closed[:3] == ["1", "80", "does not close"] and closed[-1] == ""
    first = lines[1].split(",")
    assert first[4] == cell(outcome.columns["mu_2_min_deg"][0])  # 15 digits
    written = tmp_path / "out.csv"
    assert cli("study", path, "-o", written).exit_code == 0
    assert written.read_text() == text  # the journal that streamed there, rewritten alike


def test_a_journal_of_flags_and_gaps_resumes(tmp_path):
    # self-locking variants write their flags 1/0 and their lock angles empty where they do
    # not lock: the journal reads back and resumes at once
    path = study_file(tmp_path, '"friction.coefficient" = [0.05, 0.2, 0.3]',
                      mechanism="self-locking.toml")
    out = tmp_path / "out.csv"
    first = cli("study", path, "-o", out)
    assert first.exit_code == 0, first.output
    text = out.read_text()
    header, *rows = csv.reader(io.StringIO(text))
    flags, start = header.index("locks_1_4"), header.index("lock_start_1_4_deg")
    assert sorted({row[flags] for row in rows}) == ["0", "1"]
    assert {row[start] == "" for row in rows if row[flags] == "0"} == {True}
    assert {row[header.index("reason")] for row in rows if row[flags] == "1"} == {
        "self-locks at joint (1,4)"}
    again = cli("study", path, "-o", out, "--resume")
    assert again.exit_code == 0 and "already complete, none computed" in again.output
    assert out.read_text() == text


def test_the_bounds_of_a_run(tmp_path):
    from dyade.errors import InputError

    path = study_file(tmp_path, GRID)
    with pytest.raises(InputError, match="max_time_s is 1e-06 s, and study.toml: 3 variants"):
        REGISTRY["study"](path, max_time_s=1e-6)
    out = cli("study", path, "--max-time", 1e-6)
    assert out.exit_code == 2 and "--max-time is 1e-06 s" in out.output
    out = cli("study", path, "--max-memory", 1)
    assert out.exit_code == 2 and "--max-memory is 1.05 MB, and this study of 3 variants" \
        in out.output
    told = []
    REGISTRY["study"](path, told=told.append)
    assert told == []  # a short run is not announced


def test_the_journal_streams_by_the_one_cell_rule(tmp_path):
    # the CSV a study streams to as it runs (the API's journal, not rewritten at the end)
    # is the command's CSV: flags 1/0, empty cells, 15 digits
    path = study_file(tmp_path, '"friction.coefficient" = [0.05, 0.2, 0.3]',
                      mechanism="self-locking.toml")
    journal = tmp_path / "journal.csv"
    REGISTRY["study"](path, journal=str(journal))
    assert journal.read_text() == cli("study", path, "--format", "csv").stdout


def test_progress_and_its_note_as_every_entry_gives_them():
    """The study tells its rate through the budget's note, the synthesis its rate and
    best error: one signature each, progress(done, total) and note(text)."""
    from pathlib import Path

    heard, notes = [], []
    REGISTRY["study"](Path(__file__).parent / "small-study.toml",
                      progress=lambda done, total: heard.append((done, total)),
                      note=notes.append)
    assert heard and heard[-1] == (3, 3)
    assert len(notes) == len(heard) and all(n.endswith("variants/s") for n in notes)
