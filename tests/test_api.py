"""The Python API: what a notebook user reaches without the command line, and the
promises it keeps (no printing, no flags in its errors, nothing process-wide)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import dyade
from dyade.cli import main
from dyade.files import mechanism as reader
from tests.helpers import ROOT, read_csv, shipped


def _imports_after(code: str) -> set[str]:
    probe = f"import sys\n{code}\nprint(' '.join(sorted(sys.modules)))"
    run = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    return set(run.stdout.split())


def test_import_dyade_loads_no_numpy():
    assert "numpy" not in _imports_after("import dyade")


def test_the_library_leaves_the_allocator_alone():
    """The glibc tuning is process-wide: the command's decision, not the library's."""
    modules = _imports_after("import dyade\n"
                             "dyade.analyse(dyade.read_mechanism('mechanisms/dyade-16.toml'))")
    assert "dyade.linkage.kinetostatics" in modules  # it did run
    assert not any(name.startswith("dyade.cli") for name in modules)


def test_columns_equal_the_csv(tmp_path):
    from click.testing import CliRunner

    path = shipped("slider-crank.toml")
    csv = read_csv(CliRunner().invoke(main, ["analyse", str(path), "--format", "csv"],
                                      catch_exceptions=False).stdout)
    cols = dyade.analyse(dyade.read_mechanism(path)).columns()
    assert list(cols) == list(csv)
    for name, values in cols.items():
        assert np.allclose(values, csv[name], rtol=1e-14, atol=0, equal_nan=True), name


def test_a_mechanism_built_in_python_equals_the_file():
    data = reader.load_data(shipped("watt-sixbar.toml"))
    built = dyade.build_mechanism(data)
    a = dyade.analyse(built).columns()
    b = dyade.analyse(dyade.read_mechanism(shipped("watt-sixbar.toml"))).columns()
    assert all(np.array_equal(a[k], b[k], equal_nan=True) for k in b)


def test_sweep_overrides_in_degrees_and_their_errors():
    mechanism = dyade.read_mechanism(shipped("fourbar.toml"))
    result = dyade.analyse(mechanism, start_deg=30.0, step_deg=15.0)
    angle = result.columns()["angle_deg"]
    assert np.allclose(angle, 30.0 + 15.0 * np.arange(25), rtol=0, atol=1e-12)
    assert np.allclose(result.crank_angle, np.deg2rad(angle))
    with pytest.raises(dyade.InputError) as err:
        dyade.analyse(mechanism, step_deg=-1.0)
    assert err.value.key == "step_deg" and err.value.parameters == ("step_deg",)
    assert "--" not in str(err.value)  # the API names no flag


@pytest.mark.parametrize("old, new", [("step", "step_deg"), ("start", "start_deg"),
                                      ("stop", "stop_deg"), ("crank_angle", "crank_angle_deg"),
                                      ("dead_centre", "dead_centre_deg"),
                                      ("transmission_warning", "transmission_warning_deg")])
def test_an_angle_in_radians_under_its_old_name_is_refused_naming_the_new(old, new):
    """``dyade.analyse(m, step=0.5)`` once swept every 28.6°: the old names are refused,
    with an InputError (not a warning) that names the parameter in degrees."""
    mechanism = dyade.read_mechanism(shipped("fourbar.toml"))
    for function in (dyade.analyse, dyade.analyse_in_blocks):
        with pytest.raises(dyade.InputError) as err:
            function(mechanism, **{old: 0.5})
        assert f"takes {new} (degrees), not {old}" in str(err.value)
        assert err.value.key == old
    with pytest.raises(TypeError, match="unexpected keyword argument 'stpe_deg'"):
        dyade.analyse(mechanism, stpe_deg=0.5)


def test_step_half_a_degree_means_half_a_degree():
    mechanism = dyade.read_mechanism(shipped("fourbar.toml"))
    result = dyade.analyse(mechanism, step_deg=0.5)
    assert result.summary()["positions"] == 721
    assert np.allclose(np.diff(result.crank_angle), np.pi / 360.0)
    run = dyade.analyse_in_blocks(mechanism, step_deg=0.5, block_size=500)
    assert [block.columns["angle_deg"].size for block in run] == [500, 221]


@pytest.mark.parametrize("options, words", [
    ({"step_deg": 400.0}, "more than one revolution"),
    ({"start_deg": 10.0, "stop_deg": 10.0}, "one position"),
    ({"start_deg": 0.0, "stop_deg": 5.0, "step_deg": 10.0}, "one position"),
    ({"start_deg": 10.0, "stop_deg": 5.0}, "must not be below start_deg"),
    ({"step_deg": float("nan")}, "finite"),
    ({"dead_centre_deg": "two"}, "must be an angle"),
    ({"crank_angle_deg": [0.0, float("inf")]}, "finite")])
def test_a_wrong_looking_sweep_is_an_input_error_naming_the_fix(options, words):
    mechanism = dyade.read_mechanism(shipped("fourbar.toml"))
    for function in (dyade.analyse, dyade.analyse_in_blocks):
        if "crank_angle_deg" in options and function is dyade.analyse_in_blocks:
            continue
        with pytest.raises(dyade.InputError, match=words) as err:
            function(mechanism, **options)
        assert err.value.parameters and err.value.parameters[0] in options


def test_single_positions_are_given_in_degrees():
    mechanism = dyade.read_mechanism(shipped("slider-crank.toml"))
    one = dyade.analyse(mechanism, crank_angle_deg=90.0).columns()
    assert one["angle_deg"].tolist() == [90.0]
    sweep = dyade.analyse(mechanism, step_deg=1.0).columns()
    assert one["M_drive"][0] == pytest.approx(sweep["M_drive"][90], rel=1e-12)


def test_the_other_angles_of_the_api_carry_their_unit():
    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"))
    with pytest.raises(dyade.InputError, match="max_wander_deg"):
        dyade.check_clearance(mechanism, max_wander=0.5)
    strict = dyade.check_clearance(mechanism, joints=[(13, 14)], stiffness=1e8, clearance=1e-4)
    relaxed = dyade.check_clearance(mechanism, joints=[(13, 14)], stiffness=1e8,
                                    clearance=1e-4, max_wander_deg=40.0)
    assert not strict[0].applies and relaxed[0].applies  # it wanders up to 33°
    fourbar = dyade.read_mechanism(shipped("fourbar.toml"))
    with pytest.raises(dyade.InputError, match="step_deg"):
        dyade.mechanism_torque_curve(fourbar, step=0.001)
    with pytest.raises(dyade.InputError, match="below 90°"):
        dyade.mechanism_torque_curve(fourbar, step_deg=90.0)
    curve = dyade.mechanism_torque_curve(fourbar, step_deg=1.0)
    assert curve.angle.size == 360 and np.allclose(np.diff(curve.angle), np.pi / 180.0)


def test_summary_gives_plain_numbers_and_angles_at_the_sweeps_resolution():
    """No np.float64(...) in a notebook and no 359.50000000000006."""
    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"))
    summary = dyade.analyse(mechanism, step_deg=0.5).summary()

    def walk(value, key=""):
        if isinstance(value, dict):
            for k, v in value.items():
                yield from walk(v, k)
        elif isinstance(value, (list, tuple)):
            for v in value:
                yield from walk(v, key)
        else:
            yield key, value

    leaves = list(walk(summary))
    assert all(type(v) in (str, int, float, bool, type(None)) for _, v in leaves), \
        {type(v) for _, v in leaves}
    outcome = dyade.run("sweep", mechanism, step_deg=0.5)  # the same figures, with where
    where = [figure.where["angle_deg"] for figure in outcome.summary.values() if figure.where]
    assert where and all(type(v) is float for v in where)
    assert all(v == round(v, 1) and round(2 * v) == 2 * v for v in where)
    assert {name: figure.value for name, figure in outcome.summary.items()} == summary
    # the extremes are where the columns say
    cols = dyade.analyse(mechanism, step_deg=0.5).columns()
    k = int(np.nanargmax(cols["M_drive"]))
    assert outcome.summary["M_drive_max"].where == {
        "angle_deg": round(float(cols["angle_deg"][k]), 1)}
    assert summary["M_drive_max"] == float(cols["M_drive"][k])


def test_assembly_error_names_the_parameter_and_the_cli_the_flag(tmp_path):
    from click.testing import CliRunner

    short = dyade.read_mechanism(shipped("fourbar.toml"),
                                 overrides={"dyad.2.lengths": [200, 60]})
    with pytest.raises(dyade.AssemblyError) as err:
        dyade.analyse(short)
    assert "allow_partial=True" in str(err.value) and "--" not in str(err.value)
    assert err.value.partial and "dyad 2 (kind 1 RRR, links 3-4) cannot close" in err.value.problems[0]
    partial = dyade.analyse(short, allow_partial=True)
    assert partial.notes[0].kind == "partial" and partial.rows.sum() < partial.rows.size
    result = CliRunner().invoke(main, ["analyse", str(shipped("fourbar.toml")), "--set",
                                       "dyad.2.lengths=[200,60]"], catch_exceptions=False)
    assert result.exit_code == 1 and "use --allow-partial" in result.output


def test_notes_are_structured():
    result = dyade.analyse(dyade.read_mechanism(shipped("self-locking.toml")))
    lock, = [note for note in result.notes if note.kind == "self_locking"]
    assert lock.subject == "slider (1,4)"
    (first, last), = lock.ranges
    assert np.rad2deg([first, last]) == pytest.approx([90.0, 179.0])
    assert lock.figures["joint"] == (1, 4) and lock.figures["slider"]
    from dyade.report.notes import say

    assert say(lock, result.mechanism).startswith("slider (1,4) locks (self-locking) at crank "
                                                  "angles 90.0°–179.0°")


def test_to_pandas_without_pandas_says_how_to_get_it(monkeypatch):
    result = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml")))
    monkeypatch.setitem(sys.modules, "pandas", None)  # as if not installed
    with pytest.raises(ImportError, match="pip install pandas"):
        result.to_pandas()


def test_to_pandas_is_the_columns_by_crank_angle():
    pandas = pytest.importorskip("pandas")
    result = dyade.analyse(dyade.read_mechanism(shipped("fourbar.toml")))
    frame = result.to_pandas()
    cols = result.columns()
    assert isinstance(frame, pandas.DataFrame) and frame.index.name == "angle_deg"
    assert np.array_equal(frame.index.to_numpy(), cols["angle_deg"])
    assert np.array_equal(frame["M_drive"].to_numpy(), cols["M_drive"])


def test_summary_matches_the_columns():
    result = dyade.analyse(dyade.read_mechanism(shipped("dyade-16.toml")))
    cols = result.columns()
    summary = result.summary()
    torque = cols["M_drive"]
    assert summary["M_drive_max"] == np.nanmax(torque)
    assert summary["M_drive_min"] == np.nanmin(torque)
    k = int(np.nanargmin(torque))
    figure = dyade.run("sweep", result.mechanism).summary["M_drive_min"]
    assert figure.value == summary["M_drive_min"] and figure.where == {
        "angle_deg": cols["angle_deg"][k]}
    assert summary["F_shake_max"] == np.nanmax(np.hypot(cols["Fx_shake"], cols["Fy_shake"]))


def test_coupling_errors_name_parameters_flags_or_file_keys(tmp_path):
    from click.testing import CliRunner

    with pytest.raises(dyade.InputError, match=r"^inertia must be a non-negative number"):
        dyade.Coupling(-1.0, 1.0, 1.0, 0.0, 0.0)
    flag = CliRunner().invoke(main, ["coupling", "--J", "-1", "--c1", "1", "--c2", "1"],
                              catch_exceptions=False)
    assert flag.exit_code == 2 and "--J must be a non-negative number, got -1." in flag.output
    path = tmp_path / "loose.toml"
    path.write_text("J = 1\nc1 = 0\nc2 = 1\nb1 = 0\n")
    with pytest.raises(dyade.InputError, match=r"loose.toml: `c1` and loose.toml: `b1` are both"):
        dyade.read_coupling(path)
    from_file = CliRunner().invoke(main, ["coupling", str(path)], catch_exceptions=False)
    assert from_file.exit_code == 2
    assert "loose.toml: `c1` and loose.toml: `b1` are both zero" in from_file.output
    mixed = CliRunner().invoke(main, ["coupling", str(path), "--b1", "0"], catch_exceptions=False)
    assert "loose.toml: `c1` and --b1 are both zero" in mixed.output
    bad = tmp_path / "bad.toml"
    bad.write_text("J = -2\nc1 = 1\nc2 = 1\n")
    read = CliRunner().invoke(main, ["coupling", str(bad)], catch_exceptions=False)
    assert read.exit_code == 2 and "bad.toml: `J` must be positive [kg·m²], got -2." in read.output


def test_operating_points_are_the_response_at_their_eta():
    coupling = dyade.Coupling(0.012, 4e4, 6e4, 2.0, 1.5)
    points = dyade.operating_points(coupling, [1450.0, 2900.0], order=2)
    omega = 2 * np.array([1450.0, 2900.0]) * 2 * np.pi / 60
    assert np.allclose(points.eta, omega / coupling.natural_frequency, rtol=1e-15)
    direct = dyade.coupling_response(coupling, points.eta)
    assert np.array_equal(points.response.transfer["V_q"], direct.transfer["V_q"])


def test_clearance_speed_study_scales_the_slope_with_the_cube_of_speed():
    """Eq. (30): the slope at a reversal grows with Ω³ — checked on a mechanism, where
    it comes from its forces, not from the formula."""
    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"))
    study = dyade.clearance_speed_study(mechanism, [150.0, 300.0], joints=[(2, 7)],
                                        stiffness=1e8, clearance=1e-4)
    slow, fast = (checks[0].reversals[0].peak.slope for _, checks in study)
    # inertia forces scale with Ω², and dF/dt = dF/dφ·Ω; gravity and loads do not scale,
    # so the ratio lies between 2 and 8 and tends to 8 for inertia-dominated joints
    assert 2.0 < fast / slow <= 8.0 + 1e-9


def test_the_registry_describes_every_kind():
    from dyade.model import dyad_kinds as dyads

    kinds = [dyads.kind(k) for k in range(1, len(dyads.REGISTRY) + 1)]
    assert [k.name for k in kinds] == ["RRR", "RRP", "RPR", "PRP", "PPR"]
    assert [k.has_variant for k in kinds] == [True, True, True, False, False]
    assert all(dyads.named(k.name.lower()) is k and dyads.named(k.number) is k for k in kinds)
    assert dyads.named("RRX") is None and dyads.named(True) is None


def test_the_mechanism_reader_reads_every_kind():
    # the kinds' file syntax (dyade.files) and their geometry (dyade.linkage) list the same kinds
    from dyade.files.mechanism.dyads import MIDDLE
    from dyade.model import dyad_kinds as dyads

    assert list(MIDDLE) == [dyads.kind(k).name for k in range(1, len(dyads.REGISTRY) + 1)]


def test_a_torque_curve_takes_degrees_and_rpm():
    angle = np.arange(0.0, 360.0, 1.0)
    engine = 10000 + 2000 * np.sin(np.deg2rad(2 * angle))
    curve = dyade.torque_curve(angle, engine, speed_rpm=250)
    assert np.allclose(curve.angle, np.deg2rad(angle)) and curve.speed == 250 * np.pi / 30
    for old in ("angle", "speed"):
        with pytest.raises(dyade.InputError, match=f"not {old}:"):
            dyade.torque_curve(angle_deg=angle, drive=engine, **{old: 1.0})
    with pytest.raises(dyade.InputError, match="speed_rpm"):
        dyade.torque_curve(angle, engine)
    with pytest.raises(dyade.InputError, match="speed_rpm"):
        dyade.read_torque_curve(shipped("torque/engine.csv"), speed=26.0)
    read = dyade.read_torque_curve(shipped("torque/engine.csv"), speed_rpm=250)
    assert read.speed == 250 * np.pi / 30


def test_dyade_plot_is_there_after_import_dyade():
    pytest.importorskip("matplotlib")
    code = ("import dyade\n"
            "result = dyade.analyse(dyade.read_mechanism('mechanisms/fourbar.toml'))\n"
            "fig = dyade.plot.curves.figure(result)\n"
            "from matplotlib.figure import Figure\n"
            "print(isinstance(fig, Figure), 'plot' in dir(dyade))")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                          text=True, check=True)
    assert done.stdout.split() == ["True", "True"]


@pytest.mark.parametrize("statement", ["from dyade.plot import curves",
                                       "import dyade; dyade.plot.polar",
                                       "import dyade.plot.mechanism"])
def test_without_matplotlib_the_plots_name_the_extra_to_install(statement):
    """Without matplotlib, the API says what the command line says: pip install
    "dyade[plot]", as an ImportError that is also an InputError."""
    code = ("import sys\n"
            "sys.modules['matplotlib'] = None  # as if it were not installed\n"
            "from dyade.errors import InputError\n"
            "try:\n"
            f"    {statement}\n"
            "except ImportError as err:\n"
            "    print(isinstance(err, InputError), err)\n")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                          text=True, check=True)
    assert done.stdout.strip() == ('True plots need matplotlib, which dyade installs only with '
                                   'its plot extra: pip install "dyade[plot]"')


def test_the_api_results_are_plain_numbers():
    """Every number of the API's result records is a Python float, int or bool (no
    np.float64(...) in a notebook); arrays stay arrays."""
    import dataclasses

    def numbers(obj, depth=0):
        if dataclasses.is_dataclass(obj) and depth < 4:
            for f in dataclasses.fields(obj):
                yield from numbers(getattr(obj, f.name), depth + 1)
        elif isinstance(obj, (list, tuple)) and depth < 4:
            for item in obj[:3]:
                yield from numbers(item, depth + 1)
        elif not isinstance(obj, np.ndarray):
            yield obj

    mechanism = dyade.read_mechanism(shipped("dyade-16.toml"))
    fourbar = dyade.read_mechanism(shipped("fourbar.toml"))
    curve = dyade.mechanism_torque_curve(fourbar)
    drive = dyade.read_gears(shipped("gears/two-stage.toml"))
    results = [dyade.check_clearance(mechanism, joints=[(2, 7)], stiffness=1e8, clearance=1e-4),
               dyade.peak_force(3.6, 1e7, clearance=1e-4, slope=3.6e5),
               dyade.simulate_clearance(3.6, 1e7, clearance=1e-4, slope=3.6e5),
               curve, dyade.size_flywheel(curve, 0.02), dyade.balance(fourbar),
               dyade.campbell(drive, range(0, 3001, 100)).crossings,
               dyade.check_elimination(drive)]
    found = {type(value).__name__ for result in results for value in numbers(result)}
    assert not {name for name in found if name.startswith(("float64", "int64", "bool_"))}, found
