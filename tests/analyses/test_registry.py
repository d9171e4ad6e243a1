"""The registry walked entry by entry (issue 36): every analysis keeps one contract.

For every entry: its options map one documented way between the command line and the
API (``--step`` <-> ``step_deg``) and exist in its command; the command's ``--format
json`` is the API's ``Outcome.to_document()``; the document has the documented shape
(docs/reference/json.md) and every column and summary figure a unit; the command's
table shows no Python repr.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from dyade.registry import ENTRIES, REGISTRY
from dyade.analyses.base import SCHEMA_VERSION, UNIT_SUFFIX, api_name, flag_name, jsonable
from dyade.cli import main
from tests.helpers import shipped

TWO_STAGE = str(shipped("gears/two-stage.toml"))
DYADE_16 = str(shipped("dyade-16.toml"))
FOURBAR = str(shipped("fourbar.toml"))
CLEARANCE = {"stiffness": 1e8, "clearance": 1e-4}
STUDY = Path(__file__).with_name("small-study.toml")  # three variants of the four-bar
SYNTHESIS = Path(__file__).with_name("small-synthesis.toml")  # three precision points
RUNS = {
    # entry: (source for the API, its options, the command line)
    "coupling": (shipped("coupling/stiff-coupling.toml"), {"speed_rpm": (1450.0, 2900.0)},
                 ["coupling", str(shipped("coupling/stiff-coupling.toml")),
                  "--speed", "1450", "--speed-rpm", "2900"]),
    "accuracy": (FOURBAR, {"repeats": 1}, ["accuracy", FOURBAR, "--repeats", "1"]),
    "clearance-peak": (None, {"mass": 3.6, "stiffness": 1e7, "clearance": 1e-4,
                              "slope": 3.6e5},
                       ["clearance", "--mass", "3.6", "--stiffness", "1e7", "--clearance",
                        "1e-4", "--slope", "360000"]),
    "clearance-check": (DYADE_16, {**CLEARANCE, "joint": ("5,6",)},
                        ["clearance", DYADE_16, "--stiffness", "1e8", "--clearance", "1e-4",
                         "--joint", "5,6"]),
    "clearance-speeds": (DYADE_16, {**CLEARANCE, "joint": ("2,7",),
                                    "speed_range_rpm": "100:1000:300"},
                         ["clearance", DYADE_16, "--stiffness", "1e8", "--clearance", "1e-4",
                          "--joint", "2,7", "--speed-range", "100:1000:300"]),
    "gear-modes": (TWO_STAGE, {}, ["gears", TWO_STAGE]),
    "gear-campbell": (TWO_STAGE, {"speed_range_rpm": "0:3000:100"},
                      ["gears", TWO_STAGE, "--speed-range", "0:3000:100"]),
    "gear-response": (TWO_STAGE, {"frequency_range_hz": "10:1000:10"},
                      ["gears", TWO_STAGE, "--frequency-range", "10:1000:10"]),
    "flywheel": (DYADE_16, {"fluctuation": 0.02}, ["flywheel", DYADE_16, "--fluctuation",
                                                   "0.02"]),
    "balance": (FOURBAR, {}, ["balance", FOURBAR]),
    "study": (str(STUDY), {}, ["study", str(STUDY)]),
    "synthesis": (str(SYNTHESIS), {}, ["synthesise", str(SYNTHESIS)]),
    "sweep": (shipped("self-locking.toml"), {"step_deg": 2.0},
              ["analyse", str(shipped("self-locking.toml")), "--step", "2"]),
    "describe": (shipped("dyade-16.toml"), {}, ["describe", str(shipped("dyade-16.toml"))]),
    "profile": (shipped("profiles/conveyor.toml"), {"points": 121},
                ["profile", str(shipped("profiles/conveyor.toml")), "--points", "121"]),
    "cam": (shipped("cams/cam-linkage.toml"), {"step_deg": 2.0},
            ["cam", str(shipped("cams/cam-linkage.toml")), "--step", "2"]),
}
"""an invocation of each entry, from Python and from the command line"""
RUNS["servo"] = (shipped("servo/press.toml"), {"ratio_count": 3},
                 ["servo", str(shipped("servo/press.toml")), "--ratio-count", "3"])


def _drive_line_runs() -> None:
    """The drive-line entries' quick cases (tests/analyses/test_drive_line.py)."""
    from tests.analyses.test_drive_line import CASES, arguments

    for name, (source, options) in CASES.items():
        RUNS[name] = (source, options, arguments(name, "table")[:-2])


_drive_line_runs()

REPR = re.compile(r"np\.float64\(|np\.int64\(|np\.bool|array\(|\bTrue\b|\bFalse\b|\bNone\b"
                  r"|\bnan\b|\binf\b|Figure\(|Outcome\(")
"""what no table may show: a Python or numpy repr, or a missing value not shown as —"""


def command_of(entry) -> list[str]:
    """The words after ``dyade`` of the entry's command (``dyade driveline --analysis
    steady`` -> ["driveline"])."""
    return [word for word in entry.command.split()[1:] if not word.startswith("-")][:2]


def command_path(words: list[str]) -> list[str]:
    """The words of ``words`` that name commands (``plot mechanism``), not arguments."""
    import click

    ctx = click.Context(main)
    command, path = main, []
    for word in words:
        found = command.get_command(ctx, word) if isinstance(command, click.Group) else None
        if found is None:
            break
        command = found
        path.append(word)
    return path


def click_command(words: list[str]):
    import click

    ctx = click.Context(main)
    command = main
    for word in words:
        if not isinstance(command, click.Group):
            break
        found = command.get_command(ctx, word)
        if found is None:
            break
        command = found
    return command


def test_the_registry_lists_every_entry_and_each_loads():
    assert set(REGISTRY) == set(ENTRIES)
    for name in REGISTRY:
        entry = REGISTRY[name]
        assert entry.name == name and entry.title and entry.command.startswith("dyade ")


WRITERS = {"fmt", "output", "columns", "patterns", "show_all", "units", "save_as", "jobs", "resume",
           "mechanism_files", "mechanism_file", "file", "coupling_file", "gear_file",
           "study_file", "source", "save_path", "what", "plot_file", "synthesis_file", "folder",
           "figure", "cam_file", "points_file", "cutter_file", "outer_file",
           "dxf_file"}
"""a command's parameters that choose how its Outcome is written or where it runs (its
input files, --format, -o, --columns, --all, --units, --save-as, -j, --resume; driveline's
--analysis chooses the entry; synthesise's --write and --plot): the command's own"""
WRITERS |= {"controller"}  # dyade servo --controller: where the cam table is written
OWN = {("study", "journal"): "-o"}
"""an entry's option that its command gives by another of its flags: a study's journal
is the CSV it writes (-o)"""


@pytest.mark.parametrize("name", list(ENTRIES))
def test_every_option_maps_one_way_and_exists_in_its_command(name):
    entry = REGISTRY[name]
    command = click_command(command_of(entry))
    params = {param.name: param for param in command.params}
    for option in entry.every_option:
        assert api_name(option.name, option.unit) == option.api
        assert flag_name(option.api, option.unit) == option.flag
        suffix = UNIT_SUFFIX.get(option.unit)
        assert (suffix is None) or option.api.endswith("_" + suffix), option
        assert not any(option.flag.endswith("-" + s) for s in UNIT_SUFFIX.values()), \
            f"{option.flag}: a flag carries no unit (its help says it)"
        assert option.help and option.text.startswith(option.help)
        if (name, option.api) in OWN:
            assert any(OWN[name, option.api] in p.opts for p in command.params)
            continue
        assert option.api in params, f"{entry.command} has no {option.flag}"
        assert option.flag in params[option.api].opts


def test_every_option_of_a_command_is_an_option_of_its_entries():
    """The other way: what a command takes (but how it writes) its entries take, under the
    mapped name; a command of several entries (gears, clearance, driveline) takes the
    union of theirs."""
    commands: dict[str, set[str]] = {}
    for name in ENTRIES:
        entry = REGISTRY[name]
        words = tuple(command_path(command_of(entry)))
        commands.setdefault(words, set()).update(option.api for option in entry.every_option)
    for words, options in commands.items():
        command = click_command(list(words))
        extra = {param.name for param in command.params} - options - WRITERS
        assert not extra, f"dyade {' '.join(words)} has options no entry declares: {extra}"


def check_document(document: dict) -> None:
    """The documented shape of the JSON document (docs/reference/json.md)."""
    assert list(document) == ["columns", "units", "summary", "notes", "analysis", "options",
                              "meta", "schema"]
    assert document["schema"] == SCHEMA_VERSION
    assert document["analysis"] in ENTRIES
    columns = document["columns"]
    assert set(document["units"]) == set(columns)
    lengths = {len(values) for values in columns.values()}
    assert len(lengths) <= 1, "every column has one value per row"
    for name, values in columns.items():
        assert all(v is None or isinstance(v, (int, float, str)) for v in values), name
        per_row = "unit" in columns  # a long table: each row's unit in its own column
        if any(isinstance(v, float) for v in values) and not per_row:  # ids, texts: none
            assert document["units"][name], f"column {name} has no unit ('-' if none)"
    for name, figure in document["summary"].items():
        assert re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name), name
        assert set(figure) <= {"value", "unit", "where", "limit"} and "value" in figure
        assert figure["unit"], f"summary figure {name} has no unit ('-' if none)"
        value = figure["value"]
        assert value is None or isinstance(value, (int, float, str, bool, list)), name
        if isinstance(value, float):
            assert math.isfinite(value)
        if "where" in figure:
            assert isinstance(figure["where"], dict)
    assert all(isinstance(note, str) and note for note in document["notes"])
    assert isinstance(document["options"], dict) and isinstance(document["meta"], dict)


TIMES = ("time_ms",)
"""columns that hold wall-clock times (accuracy's): not compared"""


def untimed(document: dict) -> dict:
    for name in TIMES:
        document["columns"].pop(name, None)
        document["units"].pop(name, None)
    return document


@pytest.mark.parametrize("name", list(RUNS))
def test_the_commands_json_is_the_apis_document(name):
    source, options, argv = RUNS[name]
    api = json.loads(json.dumps(jsonable(REGISTRY[name](source, **options).to_document())))
    out = CliRunner().invoke(main, [*argv, "--format", "json"], catch_exceptions=False)
    assert out.exit_code == 0, out.output
    cli = json.loads(out.stdout)
    check_document(cli)
    assert untimed(cli) == untimed(api)


@pytest.mark.parametrize("name", list(RUNS))
def test_the_commands_table_shows_no_python_repr(name):
    _, _, argv = RUNS[name]
    out = CliRunner().invoke(main, argv, catch_exceptions=False)
    assert out.exit_code == 0, out.output
    found = REPR.findall(out.stdout)
    assert not found, f"{' '.join(argv)} shows {found[:5]}"


def test_every_entry_has_a_run():
    missing = sorted(set(ENTRIES) - set(RUNS))
    assert not missing, f"no invocation in RUNS for {missing}"


SHIPPED_MECHANISMS = sorted(str(p) for p in shipped("").glob("*.toml"))
SHIPPED_TABLES = [
    *[["analyse", path] for path in SHIPPED_MECHANISMS],
    *[["analyse", path, "--all"] for path in SHIPPED_MECHANISMS],
    *[["describe", path] for path in SHIPPED_MECHANISMS],
    *[["balance", path] for path in SHIPPED_MECHANISMS],
    *[["flywheel", path, "--fluctuation", "0.02"] for path in SHIPPED_MECHANISMS],
    *[["clearance", path, "--stiffness", "1e8", "--clearance", "1e-4"]
      for path in SHIPPED_MECHANISMS],
    *[["accuracy", path, "--repeats", "1"] for path in SHIPPED_MECHANISMS],
    *[["gears", str(path), *extra] for path in sorted(shipped("gears").glob("*.toml"))
      for extra in ([], ["--modes", "2"], ["--check"], ["--speed-range", "0:3000:500"])],
    ["coupling", str(shipped("coupling/stiff-coupling.toml"))],
    ["coupling", "--J", "1", "--c1", "1", "--c2", "1"],  # undamped: unbounded peaks
    ["flywheel", str(shipped("torque/engine.csv")), "--speed", "250", "--fluctuation", "0.01"],
    *[["driveline", DYADE_16, "--set", "drive_line.stiffness=1000", "--analysis", analysis]
      for analysis in ("frequency", "steady")],
]
"""every command's tables on the shipped files"""


@pytest.mark.slow
@pytest.mark.parametrize("argv", SHIPPED_TABLES, ids=lambda argv: " ".join(
    a.rsplit("/", 1)[-1] for a in argv))
def test_no_table_on_the_shipped_files_shows_a_python_repr(argv):
    out = CliRunner().invoke(main, argv, catch_exceptions=False)
    assert out.exit_code in (0, 1, 2), out.output  # a file without masses: said, exit 2
    found = REPR.findall(out.stdout)
    assert not found, f"{' '.join(argv)} shows {found[:5]}"
