"""Design studies (issue 26): every row equals a single run of its variant, the plans'
rows do not depend on the workers, the questions equal what single runs give, failing
variants are rows, a study resumes without recomputing, and bad input is refused."""

from __future__ import annotations

import json
import math
import re
import time

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.study import tables
from tests.helpers import shipped

FRICTION = {"friction.coefficient": 0.1, "friction.pin_radius": 10,
            "friction.slider_length": 40, "friction.slider_height": 20}
"""dyade-16 with friction in every joint"""


def same_in_csv(values, expected) -> bool:
    """Whether two columns are equal as the study's CSV writes them (the one cell rule:
    15 significant digits, an empty cell for NaN)."""
    from dyade.analyses.base import cell

    values, expected = np.asarray(values), np.asarray(expected)
    return values.shape == expected.shape and all(
        cell(a) == cell(b) for a, b in zip(values.tolist(), expected.tolist()))

def write(tmp_path, text: str, name: str = "study.toml") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def toml_value(value) -> str:
    return json.dumps(value)


def study_file(tmp_path, mechanism: str, parameters: dict, plan: str = "", fixed=None,
               extra: str = "") -> str:
    lines = [f"mechanism = {json.dumps(str(shipped(mechanism)))}"]
    if fixed:
        lines.append("set = { " + ", ".join(f"{json.dumps(k)} = {toml_value(v)}"
                                           for k, v in fixed.items()) + " }")
    lines.append("[parameters]")
    lines += [f"{json.dumps(k)} = {v}" for k, v in parameters.items()]
    if plan:
        lines += ["[plan]", plan]
    return write(tmp_path, "\n".join(lines) + "\n" + extra)


def single_run(path, overrides: dict) -> dict:
    """``dyade analyse FILE --set ... --format json``: its summary and columns."""
    args = ["analyse", str(path), "--format", "json"]
    for key, value in overrides.items():
        args += ["--set", f"{key}={value}"]
    out = CliRunner().invoke(main, args)
    assert out.exit_code == 0, out.output
    return json.loads(out.stdout)


KEY_RESULTS = re.compile(r"mu_\d+_min_deg|stroke_\d+_\d+|time_ratio_\d+(_\d+)?|swing_\d+_deg"
                         r"|M_drive_(max|min|rms)|P_drive_mean|FN?_\d+_\d+_peak"
                         r"|P_friction_mean|locks_\d+_\d+")


def expected(document: dict) -> dict[str, float]:
    """The key results as `dyade analyse`'s JSON gives them, under the summary's names
    (a flag as 1.0 or 0.0); the shaking force's peak and RMS from its columns by the
    trapezoid rule over the sweep."""
    s, cols = document["summary"], document["columns"]
    out = {name: float(figure["value"]) if isinstance(figure["value"], bool) else figure["value"]
           for name, figure in s.items() if KEY_RESULTS.fullmatch(name)}
    angle = np.deg2rad(np.array(cols["angle_deg"], dtype=float))
    force2 = (np.array(cols["Fx_shake"], dtype=float) ** 2
              + np.array(cols["Fy_shake"], dtype=float) ** 2)
    out["F_shake_rms"] = math.sqrt(np.trapezoid(force2, angle) / (angle[-1] - angle[0]))
    out["F_shake_max"] = float(np.sqrt(force2.max()))
    assert out["F_shake_max"] == pytest.approx(s["F_shake_max"]["value"], rel=1e-12)
    return out


def close(a: float, b: float, rel: float = 1e-12) -> bool:
    if a is None or b is None:
        return (a is None or np.isnan(a)) and (b is None or np.isnan(b))
    return abs(a - b) <= rel * max(abs(a), abs(b)) + 1e-300 or abs(a - b) < 1e-12 * 1e-3


@pytest.mark.parametrize("mechanism, parameters, fixed", [
    ("fourbar.toml", {"dyad.2.lengths.1": "[190, 210]", "crank.speed_rpm": "[250, 400]"}, None),
    ("dyade-16.toml", {"dyad.2.lengths.2": "[145, 155]"}, FRICTION),
])
def test_grid_rows_equal_single_runs(tmp_path, mechanism, parameters, fixed):
    path = study_file(tmp_path, mechanism, parameters, fixed=fixed)
    result = dyade.study(path)
    cols = result.columns()
    assert list(cols)[:1 + len(parameters)] == ["variant", *parameters]  # parameters first
    for i in range(len(cols["variant"])):
        overrides = {**(fixed or {}), **{k: cols[k][i] for k in parameters}}
        want = expected(single_run(shipped(mechanism), overrides))
        for name, value in want.items():
            assert close(cols[name][i], value), (i, name, cols[name][i], value)
        assert cols["status"][i] == "ok"


def test_monte_carlo_with_no_scatter_gives_the_nominal_row(tmp_path):
    nominal = dyade.study(study_file(tmp_path, "fourbar.toml",
                                     {"dyad.2.lengths.1": "[200]", "links.3.mass": "[1.2]"}))
    path = study_file(tmp_path, "fourbar.toml",
                      {"dyad.2.lengths.1": "{ nominal = 200, sd = 0 }",
                       "links.3.mass": "{ nominal = 1.2, tol = 0 }"},
                      "kind = \"monte-carlo\"\nsamples = 3\nseed = 4")
    cols, row = dyade.study(path).columns(), nominal.columns()
    for name in nominal.outputs:
        assert np.all(cols[name] == row[name][0]), name


def test_same_seed_same_table_on_any_number_of_processes(tmp_path):
    path = study_file(tmp_path, "fourbar.toml",
                      {"dyad.2.lengths.1": "{ nominal = 200, sd = 2 }",
                       "links.4.mass": "{ uniform = [0.8, 1.0] }"},
                      "kind = \"latin-hypercube\"\nsamples = 12\nseed = 7")
    from concurrent.futures import ThreadPoolExecutor

    one = dyade.study(path, jobs=1).columns()
    two = dyade.study(path, jobs=2, block_size=2).columns()
    with ThreadPoolExecutor(3) as executor:  # any concurrent.futures.Executor
        threads = dyade.study(path, executor=executor, block_size=5).columns()
    for name in one:
        assert np.array_equal(one[name], two[name]) and np.array_equal(one[name], threads[name])
    assert len(np.unique(one["dyad.2.lengths.1"])) == 12


def test_latin_hypercube_has_one_sample_per_stratum(tmp_path):
    path = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "{ uniform = [0.5, 1.5] }"},
                      "kind = \"latin-hypercube\"\nsamples = 10\nseed = 1")
    values = dyade.study(path).columns()["links.4.mass"]
    assert sorted(np.floor((values - 0.5) * 10).astype(int)) == list(range(10))


def test_sensitivity_equals_central_differences_of_single_runs(tmp_path):
    path = study_file(tmp_path, "fourbar.toml",
                      {"dyad.2.lengths.1": "200", "links.4.mass": "{ nominal = 0.9, step = 0.01 }"},
                      "kind = \"sensitivity\"\nrel_step = 0.002")
    result = dyade.study(path)
    rows = {(r["parameter"], r["output"]): r for r in result.sensitivity}
    for key, h in (("dyad.2.lengths.1", 0.4), ("links.4.mass", 0.01)):
        nominal = {"dyad.2.lengths.1": 200, "links.4.mass": 0.9}
        runs = {}
        for sign in (-1, 1):
            values = dict(nominal, **{key: nominal[key] + sign * h})
            runs[sign] = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), values)
                                       ).summary()["M_drive_rms"]
        centre = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"))).summary()
        derivative = (runs[1] - runs[-1]) / (2 * h)
        row = rows[(key, "M_drive_rms")]
        per = 1e-3 if key == "dyad.2.lengths.1" else 1.0  # [m per mm]: N·m per m (issue 42)
        assert row["step"] == pytest.approx(h, rel=1e-12)
        assert row["derivative"] == pytest.approx(derivative / per, rel=1e-9)
        assert row["normalised"] == pytest.approx(
            derivative * nominal[key] / centre["M_drive_rms"], rel=1e-9)
    assert rows[("links.4.mass", "M_drive_rms")]["derivative"] != 0.0
    # the mean drive power of a machine without losses is 0 (1e-16 W): no % per %
    assert math.isnan(rows[("links.4.mass", "P_drive_mean")]["normalised"])


def test_failing_variants_are_rows_and_the_study_goes_on(tmp_path):
    # a coupler of 80 mm cannot reach the rocker: the four-bar does not close;
    # a negative friction coefficient is refused by the reader
    path = study_file(tmp_path, "fourbar.toml", {"dyad.2.lengths.1": "[80, 200]",
                                                 "friction.coefficient": "[0, -0.1]"})
    cols = dyade.study(path).columns()
    assert list(cols["status"]) == ["does not close", "refused", "ok", "refused"]
    assert "dyad 2" in cols["reason"][0] and np.isnan(cols["M_drive_max"][0])
    assert "friction.coefficient" in cols["reason"][1]
    assert np.isfinite(cols["M_drive_max"][2])


def test_self_locking_probability_equals_the_single_runs(tmp_path):
    path = study_file(tmp_path, "self-locking.toml",
                      {"friction.coefficient": "{ uniform = [0.05, 0.3] }",
                       "dyad.2.C.slider_length": "{ nominal = 48, tol = 4 }"},
                      "kind = \"monte-carlo\"\nsamples = 8\nseed = 3",
                      extra="[tolerance]\njoint_force = 5000\n")
    result = dyade.study(path)
    cols = result.columns()
    locks = []
    for i in range(8):
        values = {"friction.coefficient": cols["friction.coefficient"][i],
                  "dyad.2.C.slider_length": cols["dyad.2.C.slider_length"][i]}
        summary = single_run(shipped("self-locking.toml"), values)["summary"]
        locks.append(any(figure["value"] for name, figure in summary.items()
                         if name.startswith("locks_")))
    assert 0 < sum(locks) < 8  # the sample straddles the locking coefficient
    assert result.tolerance["probability"]["self_locks"] == pytest.approx(np.mean(locks))
    assert list(cols["status"] == "locks") == locks
    # the smallest coefficient at which the nominal slide locks, by bisection of single runs
    def locks(mu):
        result = dyade.analyse(dyade.read_mechanism(shipped("self-locking.toml"),
                                                    {"friction.coefficient": mu}))
        return any(value for name, value in result.summary().items()
                   if name.startswith("locks_"))

    low, high = 0.05, 0.3
    assert not locks(low) and locks(high)
    while high - low > 2e-3:
        middle = 0.5 * (low + high)
        low, high = (low, middle) if locks(middle) else (middle, high)
    fixed = study_file(tmp_path, "self-locking.toml",
                       {"friction.coefficient": f"{{ uniform = [0.02, {low}] }}"},
                       "kind = \"monte-carlo\"\nsamples = 6\nseed = 3",
                       extra="[tolerance]\n")
    assert dyade.study(fixed).tolerance["probability"]["self_locks"] == 0.0
    above = study_file(tmp_path, "self-locking.toml",
                       {"friction.coefficient": f"{{ uniform = [{high}, 0.3] }}"},
                       "kind = \"monte-carlo\"\nsamples = 3\nseed = 3",
                       extra="[tolerance]\n")
    assert dyade.study(above).tolerance["probability"]["self_locks"] == 1.0


def test_resume_computes_no_finished_block(tmp_path):
    path = study_file(tmp_path, "fourbar.toml", {"dyad.2.lengths.1": "[195, 200, 205]",
                                                 "links.4.mass": "[0.8, 0.9]"})
    whole = dyade.study(path).columns()
    output = str(tmp_path / "out.csv")

    class Stop(Exception):
        pass

    def stop_after_two_blocks(done, total):
        if done >= 4:
            raise Stop

    with pytest.raises(Stop):
        dyade.study(path, output=output, block_size=2, progress=stop_after_two_blocks)
    with open(output, "a", encoding="utf-8") as handle:
        handle.write("4,205.0,0.8,ok,,1.0")  # a line an interruption cut short
    resumed = dyade.study(path, output=output, resume=True, block_size=2)
    assert resumed.evaluations == 2
    again = dyade.study(path, output=output, resume=True)
    assert again.evaluations == 0
    for name in whole:  # the rows read back are the CSV's: 15 significant digits
        assert same_in_csv(resumed.columns()[name], whole[name]), name
    read = tables.read_csv(output)
    for name in whole:
        assert same_in_csv(read[name], whole[name]), name
    assert np.array_equal(read["dyad.2.lengths.1"], whole["dyad.2.lengths.1"])


def test_resume_refuses_the_rows_of_another_plan(tmp_path):
    path = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "{ uniform = [0.8, 1] }"},
                      "kind = \"monte-carlo\"\nsamples = 2\nseed = 1")
    output = str(tmp_path / "out.csv")
    dyade.study(path, output=output)
    other = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "{ uniform = [0.8, 1] }"},
                       "kind = \"monte-carlo\"\nsamples = 2\nseed = 2")
    out = CliRunner().invoke(main, ["study", other, "-o", output, "--resume"])
    assert out.exit_code == 2 and "other parameter values" in out.output


def test_parquet_reads_back_equal_to_csv_with_units(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    path = study_file(tmp_path, "fourbar.toml", {"dyad.2.lengths.1": "[190, 80]"})
    runner = CliRunner()
    assert runner.invoke(main, ["study", path, "-o", str(tmp_path / "s.csv")]).exit_code == 0
    out = runner.invoke(main, ["study", path, "-o", str(tmp_path / "s.parquet")])
    assert out.exit_code == 0, out.output
    assert not (tmp_path / "s.parquet.part.csv").exists()
    csv = tables.read_csv(str(tmp_path / "s.csv"))
    table = pq.read_table(tmp_path / "s.parquet")
    frame = table.to_pandas()
    for name in csv:  # Parquet keeps every digit, the CSV 15
        got = frame[name].to_numpy()
        assert same_in_csv(got, csv[name]), name
    units = json.loads(table.schema.metadata[b"dyade.units"])
    assert units["M_drive_max"] == "N·m" and units["dyad.2.lengths.1"] == "mm"
    assert table.schema.field("F_1_2_peak").metadata[b"unit"] == b"N"
    # and an analyse sweep
    assert runner.invoke(main, ["analyse", str(shipped("fourbar.toml")), "-o",
                                str(tmp_path / "sweep.csv")]).exit_code == 0
    assert runner.invoke(main, ["analyse", str(shipped("fourbar.toml")), "-o",
                                str(tmp_path / "sweep.parquet")]).exit_code == 0
    sweep = pq.read_table(tmp_path / "sweep.parquet")
    from tests.helpers import read_csv

    text = read_csv((tmp_path / "sweep.csv").read_text())
    for name, values in text.items():  # the CSV: 15 significant digits
        rounded = [float("%.15g" % v) for v in sweep.column(name).to_numpy()]
        assert np.array_equal(rounded, values, equal_nan=True), name
    assert json.loads(sweep.schema.metadata[b"dyade.units"])["M_drive"] == "N·m"


def test_json_and_table_outputs(tmp_path):
    path = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "{ nominal = 0.9, sd = 0.05 }"},
                      "kind = \"monte-carlo\"\nsamples = 5\nseed = 1",
                      extra="[tolerance]\ntransmission_deg = 63\njoint_force = 90\n")
    runner = CliRunner()
    out = runner.invoke(main, ["study", path, "-o", str(tmp_path / "s.json")])
    assert out.exit_code == 0, out.output
    document = json.loads((tmp_path / "s.json").read_text())
    assert document["summary"]["probability_transmission_below"] == {"value": 1.0, "unit": "-"}
    assert len(document["columns"]["variant"]) == 5
    out = runner.invoke(main, ["study", path])
    assert out.exit_code == 0 and "Probability of failure" in out.output
    assert out.stderr == ""  # no progress bar in a pipe


@pytest.mark.parametrize("parameters, plan, message", [
    ({"dyad.2.lenghts.1": "[190, 200]"}, "", "Did you mean `lengths`"),
    ({"dyad.2.lengths.1": "[]"}, "", "empty list: no variant"),
    ({"dyad.2.lengths.1": "{ range = [200, 200], count = 3 }"}, "", "no variant"),
    ({"dyad.2.lengths.1": "{ nominal = 200, sd = 40 }"}, "kind = \"monte-carlo\"\nsamples = 2",
     "Refused: give truncate"),
    ({"dyad.2.lengths.1": "{ nominal = 20, tol = 30 }"}, "kind = \"monte-carlo\"\nsamples = 2",
     "must stay positive"),
    ({"dyad.2.lengths.1": "{ uniform = [190, 210] }"}, "", "a grid needs a list or a range"),
    ({"dyad.2.lengths.1": "{ range = [190, 210] }"}, "", "a grid needs its values"),
    ({"links.4.mass": "[1]"}, "kind = \"monte-karlo\"", "Did you mean `monte-carlo`"),
    ({"crank.speed_rpm": "{ range = [-100, 300], count = 3 }"}, "",
     "is a crank speed and must stay positive"),
    ({"links.4.mass": "[-0.5, 1]"}, "", "is a mass and must not be negative"),
])
def test_bad_study_files_exit_2(tmp_path, parameters, plan, message):
    path = study_file(tmp_path, "fourbar.toml", parameters, plan)
    out = CliRunner().invoke(main, ["study", path])
    assert out.exit_code == 2, out.output
    assert message in out.output and "Traceback" not in out.output
    assert "study.toml" in out.output


def test_truncated_normal_length_stays_within_its_bounds(tmp_path):
    path = study_file(tmp_path, "fourbar.toml",
                      {"dyad.2.lengths.1": "{ nominal = 200, sd = 40, truncate = [190, 215] }"},
                      "kind = \"monte-carlo\"\nsamples = 40\nseed = 2")
    spec = dyade.study.read(path)
    from dyade.study.plans import variants

    values = variants(spec)[:, 0]
    assert values.min() >= 190 and values.max() <= 215 and values.std() > 5


def test_unreachable_scheduler_exits_2_naming_it(tmp_path):
    pytest.importorskip("distributed")
    path = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "[1]"})
    started = time.perf_counter()
    out = CliRunner().invoke(main, ["study", path, "--scheduler", "tcp://127.0.0.1:9"])
    assert out.exit_code == 2 and "tcp://127.0.0.1:9" in out.output, out.output
    assert time.perf_counter() - started < 15


def test_init_study_template_runs(tmp_path):
    runner = CliRunner()
    assert runner.invoke(main, ["init", "fourbar", str(tmp_path / "fourbar.toml")]).exit_code == 0
    out = runner.invoke(main, ["init", "study", str(tmp_path / "study.toml")])
    assert out.exit_code == 0, out.output
    result = dyade.study(str(tmp_path / "study.toml"))
    assert len(result.columns()["variant"]) > 1 and set(result.columns()["status"]) == {"ok"}


@pytest.mark.slow
def test_dask_local_cluster_gives_the_same_table(tmp_path):
    distributed = pytest.importorskip("distributed")
    path = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "{ uniform = [0.8, 1] }",
                                                 "dyad.2.lengths.1": "{ nominal = 200, sd = 1 }"},
                      "kind = \"monte-carlo\"\nsamples = 10\nseed = 5")
    local = dyade.study(path, jobs=2).columns()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote = dyade.study(path, executor=client.get_executor(), block_size=3).columns()
        out = CliRunner().invoke(main, ["study", path, "--scheduler", cluster.scheduler_address,
                                        "--format", "csv"])
    assert out.exit_code == 0, out.output
    for name in local:
        assert np.array_equal(local[name], remote[name]), name


@pytest.mark.slow
def test_optimise_finds_the_complete_force_balance(tmp_path):
    pytest.importorskip("scipy")
    bounds = "{ range = [-200, 200] }"
    path = study_file(tmp_path, "fourbar.toml",
                      {"links.2.centre.1": bounds, "links.2.centre.2": bounds,
                       "links.4.centre.1": bounds, "links.4.centre.2": bounds},
                      "kind = \"optimise\"\nseed = 1",
                      fixed={"links.2.mass": 0.6, "links.2.centre": [0, 0]},
                      extra="[optimise]\nminimise = \"F_shake_rms\"\nmaxiter = 60\n")
    result = dyade.study(path, jobs=2)
    x = result.optimum["x"]
    assert x == pytest.approx([-50, 0, -100, 0], abs=0.1)
    unbalanced = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), {
        "links.2.mass": 0.6, "links.2.centre": [0, 0]}))
    force = np.hypot(unbalanced.columns()["Fx_shake"], unbalanced.columns()["Fy_shake"])
    assert result.optimum["value"] < 1e-6 * np.sqrt(np.mean(force ** 2))
    # dyade balance: the same first moments m·c of crank and rocker, by least squares
    balanced = dyade.balance(dyade.read_mechanism(shipped("fourbar.toml"), {
        "links.2.mass": 0.6, "links.2.centre": [0, 0]})).after.mechanism.links
    for link, mass, (cx, cy) in ((2, 0.6, x[:2]), (4, 0.9, x[2:])):
        moment = balanced[link].mass * np.array(balanced[link].centre)
        assert mass * np.array([cx, cy]) / 1000 == pytest.approx(moment, abs=1e-4 * mass)


def test_plot_study_figures(tmp_path):
    pytest.importorskip("matplotlib")
    grid = study_file(tmp_path, "fourbar.toml", {"dyad.2.lengths.1": "[80, 190, 200]",
                                                 "dyad.2.lengths.2": "[150, 155]"})
    runner = CliRunner()
    for args in (["--x", "dyad.2.lengths.1"], ["--x", "dyad.2.lengths.1", "--y",
                                                "dyad.2.lengths.2"]):
        target = tmp_path / f"figure{len(args)}.png"
        out = runner.invoke(main, ["plot", "study", grid, "-o", str(target), *args])
        assert out.exit_code == 0, out.output
        assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    out = runner.invoke(main, ["plot", "study", grid, "--show-output", "M_drvie_rms",
                               "-o", str(tmp_path / "x.png")])
    assert out.exit_code == 2 and "Did you mean `M_drive_rms`" in out.output


def test_progress_bar_on_a_terminal_only(monkeypatch):
    import io
    import sys

    from dyade.cli.study import bar

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    with bar() as tick:  # a pipe (pytest's capture): no bar
        assert tick is None
    screen = Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    with bar() as tick:
        for done in (0, 10, 20):
            tick(done, 40)
            time.sleep(0.05)
    shown = screen.getvalue()
    assert "20/40" in shown and "variants/s" in shown


@pytest.mark.slow
def test_a_killed_study_resumes(tmp_path):
    import os
    import signal
    import subprocess
    import sys

    from tests.helpers import ROOT

    path = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "{ uniform = [0.8, 1] }"},
                      "kind = \"monte-carlo\"\nsamples = 400\nseed = 9")
    output = tmp_path / "out.csv"
    process = subprocess.Popen([sys.executable, "-m", "dyade", "study", path, "-o", str(output),
                                "--block-size", "10"], cwd=ROOT, stderr=subprocess.DEVNULL)
    deadline = time.time() + 60
    while time.time() < deadline:
        if output.exists() and output.read_text().count("\n") > 60:
            break
        time.sleep(0.05)
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    done = output.read_text().count("\n") - 1
    assert 0 < done < 400
    out = subprocess.run([sys.executable, "-m", "dyade", "study", path, "-o", str(output),
                          "--resume"], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    computed = int(out.stderr.split("(")[1].split(" computed")[0])
    assert 400 - done <= computed < 400 - done + 10  # a line cut short is computed again
    whole = dyade.study(path).columns()
    read = tables.read_csv(str(output))
    for name in whole:
        assert same_in_csv(read[name], whole[name]), name


def test_pareto_front_keeps_the_non_dominated_within_bounds():
    from dyade.study.questions import pareto

    columns = {"status": np.array(["ok", "ok", "ok", "ok", "locks", "does not close"],
                                  dtype=object),
               "a": np.array([1.0, 2, 3, 2, 0.5, np.nan]),
               "b": np.array([3.0, 2, 1, 3, 0.5, np.nan]),
               "c": np.array([0.0, 0, 0, 0, 9, 0])}
    front = pareto(columns, [("a", 1.0), ("b", 1.0)])
    assert list(np.flatnonzero(front)) == [4]  # (0.5, 0.5) beats every other
    front = pareto(columns, [("a", 1.0), ("b", 1.0)], {"c": (-1.0, 1.0)})
    assert list(np.flatnonzero(front)) == [0, 1, 2]
    front = pareto(columns, [("a", 1.0), ("b", -1.0)], {"c": (-1.0, 1.0)})  # max b
    assert list(np.flatnonzero(front)) == [0]


def test_sensitivity_from_a_grid_is_the_difference_of_its_neighbours(tmp_path):
    """A grid with a [sensitivity] table: the central differences about its middle point
    (its neighbours along each parameter) — the same derivatives as a sensitivity plan
    with the grid's spacing as its step, and as single runs."""
    grid = study_file(tmp_path, "fourbar.toml",
                      {"dyad.2.lengths.1": "[199.6, 200, 200.4]",
                       "links.4.mass": "[0.89, 0.9, 0.91]"},
                      "kind = \"grid\"", extra="[sensitivity]\n")
    by_grid = {(r["parameter"], r["output"]): r for r in dyade.study(grid).sensitivity}
    plan = study_file(tmp_path, "fourbar.toml",
                      {"dyad.2.lengths.1": "{ nominal = 200, step = 0.4 }",
                       "links.4.mass": "{ nominal = 0.9, step = 0.01 }"},
                      "kind = \"sensitivity\"")
    by_plan = {(r["parameter"], r["output"]): r for r in dyade.study(plan).sensitivity}
    assert by_grid.keys() == by_plan.keys()
    for key, row in by_plan.items():
        assert by_grid[key]["step"] == pytest.approx(row["step"], rel=1e-12)
        assert by_grid[key]["nominal"] == pytest.approx(row["nominal"], rel=1e-15)
        assert by_grid[key]["derivative"] == pytest.approx(row["derivative"], rel=1e-9,
                                                           abs=1e-12), key
    runs = [dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), {
        "dyad.2.lengths.1": 200, "links.4.mass": mass})).summary()["M_drive_rms"]
        for mass in (0.89, 0.91)]
    assert by_grid[("links.4.mass", "M_drive_rms")]["derivative"] == pytest.approx(
        (runs[1] - runs[0]) / 0.02, rel=1e-9)


def test_sensitivity_from_a_grid_needs_a_middle_value(tmp_path):
    path = study_file(tmp_path, "fourbar.toml", {"dyad.2.lengths.1": "[199, 201]"},
                      "kind = \"grid\"", extra="[sensitivity]\n")
    out = CliRunner().invoke(main, ["study", path])
    assert out.exit_code == 2 and "parameters.dyad.2.lengths.1" in out.output
    assert "odd number" in out.output and "Traceback" not in out.output


def test_coupling_extra_is_the_drive_lines_resonance(tmp_path):
    """`extra = ["coupling"]`: ω̄ of the file's [drive_line] with the linkage's mean
    reduced inertia J̄ (ω̄² = k/J̄ with an ideal motor), the first-order resonance speed
    ω̄·30/π and Ω/ω̄; a file without [drive_line] is refused naming the fix."""
    path = study_file(tmp_path, "slider-crank.toml", {"drive_line.stiffness": "[500, 2000]"},
                      fixed={"links.2.inertia": 0.01}, extra='[outputs]\nextra = ["coupling"]\n')
    cols = dyade.study(path).columns()
    mean_inertia = dyade.cycle.mean(*(lambda c: (np.deg2rad(c["angle_deg"]), c["J_red"]))(
        dyade.analyse(dyade.read_mechanism(shipped("slider-crank.toml"), {
            "links.2.inertia": 0.01})).columns()))
    for k, omega, rpm, ratio in zip((500, 2000), cols["omega_bar"], cols["resonance_speed_rpm"],
                                    cols["speed_ratio"]):
        assert omega ** 2 * mean_inertia == pytest.approx(k, rel=2e-3)
        assert rpm == pytest.approx(omega * 30 / math.pi, rel=1e-12)
        assert ratio == pytest.approx(1500 * math.pi / 30 / omega, rel=1e-12)
    assert cols["omega_bar"][1] / cols["omega_bar"][0] == pytest.approx(2.0, rel=1e-9)
    bare = study_file(tmp_path, "slider-crank.toml", {"crank.speed_rpm": "[500, 600]"},
                      extra='[outputs]\nextra = ["coupling"]\n')
    out = CliRunner().invoke(main, ["study", bare])
    assert out.exit_code == 2 and "[drive_line]" in out.output and "outputs.extra" in out.output


def test_a_mass_may_be_zero_as_in_the_mechanism_file(tmp_path):
    """A massless link is a mechanism file's ordinary case: a study over a mass may
    start at 0 (the variant's single run agrees)."""
    path = study_file(tmp_path, "fourbar.toml", {"links.4.mass": "[0, 0.9]"})
    cols = dyade.study(path).columns()
    assert list(cols["status"]) == ["ok", "ok"]
    alone = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml"), {"links.4.mass": 0}))
    assert cols["M_drive_rms"][0] == pytest.approx(alone.summary()["M_drive_rms"], rel=1e-12)
