"""The drive line's entries (``dyade.analyses.drive_line``): ``dyade driveline --format
json`` is the entry's ``Outcome.to_document()``, every figure and column has its unit,
no table shows a Python repr, a scan where no speed has a periodic state exits 1, the
crank shaft (its line, tables and ω̄) is built once per analysis, and the report's
section runs its entry once."""

from __future__ import annotations

import io
import json
import re

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.registry import REGISTRY
from dyade.analyses.base import jsonable
from dyade.cli import main
from dyade.errors import DyadeError, InputError
from tests.helpers import shipped

SLIDER = str(shipped("slider-crank.toml"))
DYADE_16 = str(shipped("dyade-16.toml"))
LINE = ("drive_line.stiffness=1000", "drive_line.damping=0.05", "links.2.inertia=0.01",
        "drive_line.steps=360")
"""the shipped slider-crank with a flywheel on a shaft (ω̄ = 300.8 rad/s, Ω/ω̄ = 0.52),
integrated on 360 steps per revolution (quick)"""
MOTOR = ("drive_line.rotor_inertia=0.005", 'drive.motor="asynchronous"', "drive.rated_torque=5",
         "drive.rated_speed_rpm=1450", "drive.synchronous_speed_rpm=1500")
PARAMETRIC = ("drive_line.stiffness=1000", "drive_line.damping=0.04")
"""dyade-16 on a shaft: unstable near 2ω̄ = 3571 rpm (the issue's example)"""

CASES = {
    "driveline-frequency": (SLIDER, {"set": LINE}),
    "driveline-steady": (SLIDER, {"set": LINE}),
    "driveline-resonance": (SLIDER, {"set": LINE, "speed_range_rpm": "2000:2200:100"}),
    "driveline-stability": (DYADE_16, {"set": PARAMETRIC, "speed_range_rpm": "3450:3575:125"}),
    "driveline-map": (SLIDER, {"set": LINE, "speed_range_rpm": "1000:1500:500",
                               "map": "damping=0:0.1:0.1"}),
    "driveline-run-up": (SLIDER, {"set": LINE + MOTOR}),
}
"""entry -> a quick run of it (each well under 2 s)"""
FLAGS = {"speed_range_rpm": "--speed-range", "speed_rpm": "--speed", "map": "--map"}


def arguments(name: str, fmt: str) -> list[str]:
    """The command line of ``CASES[name]``."""
    source, options = CASES[name]
    args = ["driveline", source, "--analysis", name.removeprefix("driveline-")]
    for key, value in options.items():
        if key == "set":
            args += [part for assignment in value for part in ("--set", assignment)]
        else:
            args += [FLAGS[key], str(value)]
    return args + ["--format", fmt]


def invoke(args: list[str]):
    return CliRunner().invoke(main, args, catch_exceptions=False)


@pytest.fixture(scope="module")
def outcomes():
    """Each case's Outcome from the API, once."""
    return {name: REGISTRY[name](source, **options) for name, (source, options) in CASES.items()}


@pytest.mark.slow  # the registry walk (test_registry.py) runs these cases by default
@pytest.mark.parametrize("name", CASES)
def test_json_is_the_outcome_document(name, outcomes):
    result = invoke(arguments(name, "json"))
    assert result.exit_code == 0, result.output
    expected = json.loads(json.dumps(jsonable(outcomes[name].to_document()), ensure_ascii=False))
    assert json.loads(result.stdout) == expected
    assert expected["analysis"] == name and expected["schema"] == 2


@pytest.mark.parametrize("name", CASES)
def test_every_figure_and_column_has_its_unit(name, outcomes):
    outcome = outcomes[name]
    assert outcome.summary and outcome.columns
    for figure in outcome.summary.values():
        assert figure.unit, figure.name
        assert re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", figure.name), figure.name
    for column in outcome.columns:
        assert outcome.units[column], column
    # the natural frequency's figures in every entry, one name each
    assert {"omega_bar", "resonance_speed_rpm", "speed_ratio", "vdi_2149"} <= set(outcome.summary)


REPR = re.compile(r"np\.float64|np\.bool|\bTrue\b|\bFalse\b|\bNone\b|\bnan\b|\binf\b|\(\(|\[\[")


@pytest.mark.slow  # the registry walk (test_registry.py) runs these cases by default
@pytest.mark.parametrize("name", CASES)
def test_no_python_repr_in_the_tables(name):
    result = invoke(arguments(name, "table"))
    assert result.exit_code == 0, result.output
    assert not REPR.search(result.stdout), REPR.search(result.stdout)
    assert "Natural frequency, VDI 2149" in result.stdout


def test_the_issues_unstable_speeds_read_as_text():
    """Issue 36: `--analysis stability --speed-range 3400:3700:100` on dyade-16 printed
    `[(np.float64(3600.0), np.float64(3600.0))]` and True/False; now the range as text,
    yes/no flags, units beside the figures."""
    result = invoke(["driveline", DYADE_16, "--set", PARAMETRIC[0], "--set", PARAMETRIC[1],
                     "--analysis", "stability", "--speed-range", "3400:3700:100"])
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert not REPR.search(out), REPR.search(out)
    assert re.search(r"unstable_rpm\s+3600–3600 rpm", out)
    assert re.search(r"vdi_2149\s+no", out) and re.search(r"omega_bar\s+186\.978\s+rad/s", out)
    assert re.search(r"floquet\s", out) and re.search(r"unstable\s", out)  # a flag: yes/no
    assert re.search(r"3600 .* 1\.03396\s+yes\s+period", out)  # … and how: period doubling
    assert "exceeds 0.1 (VDI 2149 Part 1)" in result.stderr


def test_the_parametric_instability_lies_at_twice_the_natural_frequency(outcomes):
    """Mathieu (a J(φ) with its first harmonic): the unstable speeds lie at Ω ≈ 2ω̄, the
    parametric resonance the entry names; the summary's ranges and largest |μ| are the
    columns' (3575 rpm: |μ| = 1.039, the engine's doctest)."""
    outcome = outcomes["driveline-stability"]
    columns, summary = outcome.columns, outcome.summary
    parametric = summary["parametric_k1_rpm"].value
    assert parametric == pytest.approx(2 * summary["resonance_speed_rpm"].value, rel=1e-12)
    assert columns["unstable"].tolist() == [False, True]
    assert summary["unstable_rpm"].value == [[3575.0, 3575.0]]
    assert abs(3575.0 - parametric) < 125.0  # within a step of the scan
    assert summary["stability_max"].value == pytest.approx(1.039, abs=5e-4)
    assert summary["stability_max"].where == {"speed_rpm": 3575.0}


def test_the_steady_state_balances_and_is_stable(outcomes):
    """Over one period the motor's work is spent by loads, friction and damping; the
    flag `stable` is the largest |μ| within the unit circle."""
    s = outcomes["driveline-steady"].summary
    spent = s["work_load"].value + s["work_friction"].value + s["work_damping"].value
    # RK4 on 360 steps: the quadratures' error is 5e-8 here (∝ h⁴; tests/test_drive_line.py
    # checks 1e-8 on 1080 steps)
    assert abs(s["work_motor"].value - spent) <= 1e-6 * s["work_motor"].value
    assert s["stable"].value is (s["stability"].value <= 1.0)
    torque = outcomes["driveline-steady"].columns["shaft_torque"]
    assert s["peak_torque"].value == np.max(np.abs(torque))


def test_the_frequency_over_the_cycle(outcomes):
    """ω(φ) = √(k/J(φ)) of a shaft with an ideal motor: its extremes are the summary's
    ω_min, ω_max, where J(φ) is largest and smallest; ω̄ = √(k/J̄) lies between."""
    outcome = outcomes["driveline-frequency"]
    omega, angle = outcome.columns["natural_frequency"], outcome.columns["angle_deg"]
    s = outcome.summary
    assert s["omega_min"].value == omega.min() and s["omega_max"].value == omega.max()
    assert s["omega_min"].where == {"angle_deg": angle[np.argmin(omega)]}
    assert s["omega_bar"].value == pytest.approx(np.sqrt(1000.0 / s["inertia_mean"].value),
                                                 rel=1e-12)
    assert s["omega_min"].value < s["omega_bar"].value < s["omega_max"].value


def test_a_speed_sequence_at_the_api_is_the_range(outcomes):
    """`speed_range_rpm` takes the command line's text or a sequence of speeds [rpm]."""
    source, options = CASES["driveline-map"]
    listed = REGISTRY["driveline-map"](source, **(options | {"speed_range_rpm": [1000.0, 1500.0]}))
    for name, values in outcomes["driveline-map"].columns.items():
        np.testing.assert_array_equal(listed.columns[name], values)


def test_no_speed_with_a_periodic_state_exits_1():
    """A shaft of 10 N·m/rad at 10-20 rpm on dyade-16: the loads turn the crank back at
    every speed, so nothing is left to report (not a table of blanks)."""
    args = ["driveline", DYADE_16, "--set", "drive_line.stiffness=10", "--set",
            "drive_line.steps=36", "--analysis", "resonance", "--speed-range", "10:20:10"]
    result = invoke(args)
    assert result.exit_code == 1
    assert "no speed of the range has a periodic state" in result.output
    with pytest.raises(DyadeError, match="periodic state"):
        REGISTRY["driveline-stability"](DYADE_16, set=("drive_line.stiffness=10",
                                                       "drive_line.steps=36"),
                                        speed_range_rpm="10:20:10")


@pytest.mark.parametrize("args, words", [
    (["--analysis", "resonance", "--speed", "1000"], "--speed is for --analysis steady"),
    (["--map", "stiffness=500:600:100"], "--map is for --analysis map, not steady"),
    (["--analysis", "stability"], "--speed-range must be given"),
    (["--analysis", "map", "--speed-range", "1000:1500:500"], "--map must be stiffness="),
])
def test_options_of_another_analysis_are_refused(args, words):
    result = invoke(["driveline", SLIDER, "--set", LINE[0], *args])
    assert result.exit_code == 2 and words in result.output, result.output


def test_the_old_flag_still_works_and_the_api_names_carry_the_unit():
    result = invoke(["driveline", SLIDER, *sum((["--set", a] for a in LINE), []),
                     "--analysis", "map", "--speeds-rpm", "1000:1500:500", "--map",
                     "damping=0:0.1:0.1", "--format", "json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["options"]["speed_range_rpm"] == "1000:1500:500"
    with pytest.raises(InputError, match="speed_range_rpm"):
        REGISTRY["driveline-resonance"](SLIDER, set=LINE, speeds_rpm=[1000.0])


def test_a_long_run_is_bounded_before_it_starts_and_shows_progress(monkeypatch):
    """--max-time and --max-memory refuse on the estimates (nothing integrated); a run
    reports progress through its Newton iterations."""
    from dyade.linkage import drive_line as api

    source, options = CASES["driveline-resonance"]
    real = api.resonance_curve
    monkeypatch.setattr(api, "resonance_curve", lambda *a, **k: pytest.fail("it ran"))
    with pytest.raises(InputError, match="max_time_s"):
        REGISTRY["driveline-resonance"](source, **options, max_time_s=1e-3)
    with pytest.raises(InputError, match="max_memory_mb .* the orbits of 3 speeds"):
        REGISTRY["driveline-resonance"](source, **options, max_memory_mb=0.01)
    monkeypatch.setattr(api, "resonance_curve", real)
    ticks = []
    REGISTRY["driveline-resonance"](source, **options, progress=lambda done, total: ticks.append(
        (done, total)))
    assert ticks and [done for done, _ in ticks] == list(range(1, len(ticks) + 1))
    assert all(total > done for done, total in ticks)


def counting(monkeypatch, module, name: str) -> list:
    calls = []
    real = getattr(module, name)

    def counted(*args, **kwargs):
        calls.append(name)
        return real(*args, **kwargs)

    monkeypatch.setattr(module, name, counted)
    return calls


def test_the_crank_shaft_is_built_once_per_analysis(monkeypatch):
    """The steady state builds its line once (it built it three times), its tables once
    per grid (the coarse grid's serve the state, the natural frequency and the first
    guess: twice with the accuracy's half steps; it built them four times), the plan
    once and ω̄ once."""
    from dyade.linkage import drive, plan
    from dyade.machine import drive_line

    counts = {name: counting(monkeypatch, drive, name)
              for name in ("crank_tables", "natural_frequency")}
    counts["line_of"] = counting(monkeypatch, drive_line, "line_of")
    counts["plan"] = counting(monkeypatch, plan, "plan")
    REGISTRY["driveline-steady"](SLIDER, set=LINE[:3])  # 720 steps: the coarse grid's
    assert {name: len(calls) for name, calls in counts.items()} == {
        "line_of": 1, "crank_tables": 2, "natural_frequency": 1, "plan": 1}


def test_the_report_runs_the_entry_once(monkeypatch):
    """The report's drive-line section computes ω̄ once (it computed it twice, and the
    sweep a third time) and holds no analysis: the tables and notes of the entry."""
    pytest.importorskip("matplotlib")
    import dyade
    from dyade.linkage import drive as line_model
    from dyade.report import html

    mechanism = dyade.read_mechanism(SLIDER, {"drive_line.stiffness": 1000.0,
                                              "drive_line.damping": 0.05,
                                              "links.2.inertia": 0.01, "drive_line.steps": 360})
    calls = counting(monkeypatch, line_model, "natural_frequency")
    section = html.drive_line_html(mechanism)
    assert calls == ["natural_frequency"]
    assert "exceeds 0.1 (VDI 2149 Part 1)" in section and "Natural frequency, VDI 2149" in section
    assert "speed_mean_rpm" in section and '<figure id="figure-driveline">' in section
    assert not REPR.search(re.sub(r"<[^>]*>", " ", section.split("<figure")[0]))


def test_period_two_rows_follow_their_speed_in_table_json_and_csv(monkeypatch):
    """``--period-two``: at 3575 rpm (dyade-16 near 2ω̄) the only periodic motion flips
    (period doubling), so the scan asks ``period_two`` for that speed and lists its
    motion as a row with ``period`` 2 after the speed's row (its twist, |μ| over two
    revolutions, verdict), the speed's own row ``period`` 1; in the table, the JSON and
    the CSV. (``period_two`` itself, 10–20 s a speed, is replaced here by a stand-in: its
    physics is tests/linkage/test_drive_line_branches.py's.)"""
    from dyade.linkage import drive_line as api
    from dyade.units import RAD_PER_S_TO_RPM

    asked = []

    def stand_in(mechanism, speeds_rpm, **_):
        speeds = np.asarray(speeds_rpm, dtype=float) / RAD_PER_S_TO_RPM
        asked.append(list(speeds_rpm))
        n = speeds.size
        one = np.ones(n)
        return api.PeriodTwo(speeds, speeds / 187.0, np.ones(n, dtype=bool),
                             np.zeros((n, 2)), np.tile([0.5 + 0j, 0.1 + 0j], (n, 1)),
                             np.tile([-1.04 + 0j, 0.9 + 0j], (n, 1)), [""] * n,
                             np.full(n, 720), 0.01 * one, 0.02 * one, 3.0 * one, 0.1 * one,
                             1e-9 * one, 1e-9 * one, 0.5 * one)

    monkeypatch.setattr(api, "period_two", stand_in)
    args = ["driveline", DYADE_16, "--set", PARAMETRIC[0], "--set", PARAMETRIC[1],
            "--analysis", "stability", "--speed-range", "3575:3575:1", "--period-two"]
    outcome = REGISTRY["driveline-stability"](DYADE_16, set=PARAMETRIC,
                                              speed_range_rpm="3575:3575:1", period_two=True)
    document = json.loads(json.dumps(jsonable(outcome.to_document())))
    columns = document["columns"]
    assert asked == [[3575.0]]  # the flipping speed
    assert columns["speed_rpm"] == [3575.0, 3575.0]
    assert columns["period"] == [1, 2]
    assert columns["solution"] == [1, 2]
    assert columns["unstable"] == [True, False]
    assert columns["instability"] == ["period doubling", ""]
    assert columns["floquet"][1] == pytest.approx(0.5)
    assert columns["twist_max_deg"][1] == pytest.approx(np.degrees(0.02))
    assert document["units"]["period"] == "-"
    assert any("period-2 motions" in note for note in document["notes"])
    from dyade.report.outcome import write_csv

    csv = io.StringIO()
    write_csv(outcome, csv)
    header = next(line for line in csv.getvalue().splitlines() if "speed_rpm" in line)
    assert "period" in header.split(",")
    table = invoke(args)  # the command line: the table
    assert "period" in table.stdout and not REPR.search(table.stdout), REPR.search(table.stdout)
