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
from tests.helpers import read_csv, shipped


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


def test_sweep_overrides_in_radians_and_their_errors():
    mechanism = dyade.read_mechanism(shipped("fourbar.toml"))
    result = dyade.analyse(mechanism, start=0.5, step=0.25)
    angle = result.crank_angle
    assert angle[0] == 0.5 and np.allclose(np.diff(angle), 0.25)
    assert angle[-1] <= 0.5 + 2 * np.pi + 1e-12 and angle[-1] > 0.5 + 2 * np.pi - 0.25
    with pytest.raises(dyade.InputError) as err:
        dyade.analyse(mechanism, step=-1.0)
    assert err.value.key == "step" and err.value.parameters == ("step",)
    assert "--" not in str(err.value)  # the API names no flag


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
    assert summary["drive"]["M_max"] == np.nanmax(torque)
    k = int(np.nanargmin(torque))
    assert summary["columns"]["M_drive"]["min_at_deg"] == cols["angle_deg"][k]


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
    from dyade.linkage import dyads

    kinds = [dyads.kind(k) for k in range(1, len(dyads.REGISTRY) + 1)]
    assert [k.name for k in kinds] == ["RRR", "RRP", "RPR", "PRP", "PPR"]
    assert [k.has_variant for k in kinds] == [True, True, True, False, False]
    assert all(dyads.named(k.name.lower()) is k and dyads.named(k.number) is k for k in kinds)
    assert dyads.named("RRX") is None and dyads.named(True) is None


def test_the_mechanism_reader_reads_every_kind():
    # the kinds' file syntax (dyade.files) and their geometry (dyade.linkage) list the same kinds
    from dyade.files.mechanism.dyads import MIDDLE
    from dyade.linkage import dyads

    assert list(MIDDLE) == [dyads.kind(k).name for k in range(1, len(dyads.REGISTRY) + 1)]
