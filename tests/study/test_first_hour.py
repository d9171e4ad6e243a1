"""Studies as a new user meets them (issue 42): a plan and a table that do not belong
together are refused, derivatives in one consistent unit, linked parameters, the
overrides of the command line, a study that `init` writes runs, JSON on stdout, the
words of a resume and of a failure, constant outputs, peak |M_drive|, withheld
variants, and the note on an extreme that crosses a grid point."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.errors import InputError
from dyade.study import expression, questions
from dyade.study.spec import parse
from tests.helpers import shipped

FOURBAR = str(shipped("fourbar.toml"))


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def write(tmp_path, text: str, mechanism: str = FOURBAR, name: str = "study.toml") -> str:
    path = tmp_path / name
    path.write_text(f"mechanism = {json.dumps(mechanism)}\n{text}", encoding="utf-8")
    return str(path)


MC = ('[plan]\nkind = "monte-carlo"\nsamples = 4\nseed = 1\n[parameters]\n'
      '"links.3.mass" = { nominal = 1.2, tol = 0.1 }\n')


# -- a plan and a table that do not belong together ------------------------------------

@pytest.mark.parametrize("data, named", [
    ({"plan": {"kind": "sensitivity"}, "tolerance": {"joint_force": 200}},
     ("[tolerance]", 'plan.kind = "sensitivity"')),
    ({"tolerance": {"joint_force": 200}}, ("[tolerance]", "plan.kind (not given")),
    ({"plan": {"kind": "monte-carlo", "samples": 5}, "sensitivity": {}},
     ("[sensitivity]", 'plan.kind = "monte-carlo"')),
    ({"plan": {"kind": "sensitivity", "samples": 500}}, ("plan.samples", "500", "sensitivity")),
    ({"plan": {"kind": "grid", "samples": 5}}, ("plan.samples", 'plan.kind = "grid"')),
    ({"plan": {"kind": "grid", "rel_step": 0.01}}, ("plan.rel_step", 'plan.kind = "grid"')),
    ({"plan": {"kind": "monte-carlo", "samples": 5}, "tolerance": {}, "optimise": {}},
     ("[tolerance]", "[optimise]")),
])
def test_a_plan_and_a_table_that_do_not_belong_are_refused_naming_both(data, named):
    with pytest.raises(InputError) as err:
        parse({"mechanism": FOURBAR, "parameters": {"dyad.2.lengths.1": [190, 200, 210]},
               **data})
    assert all(word in str(err.value) for word in named), str(err.value)


def test_the_sensitivity_plan_with_tolerance_exits_2(tmp_path):
    path = write(tmp_path, '[plan]\nkind = "sensitivity"\n[parameters]\n"links.3.mass" = 1.2\n'
                           '[tolerance]\njoint_force = 200\n')
    out = cli("study", path)
    assert out.exit_code == 2 and "[tolerance]" in out.output and "sensitivity" in out.output


# -- derivatives in one unit -----------------------------------------------------------

def test_the_stroke_per_crank_length_is_the_closed_form_in_metres_per_metre(tmp_path):
    # offset slider-crank: s = √((l+r)²−e²) − √((l−r)²−e²), ds/dr in m/m (not m/mm)
    path = write(tmp_path, '[plan]\nkind = "sensitivity"\n[parameters]\n"crank.length" = 40\n',
                 str(shipped("slider-crank.toml")))
    row, = [r for r in dyade.study(path).sensitivity if r["output"] == "stroke_1_4"]
    r, length, e = 0.04, 0.16, 0.01
    exact = ((length + r) / math.sqrt((length + r) ** 2 - e ** 2)
             + (length - r) / math.sqrt((length - r) ** 2 - e ** 2))
    assert row["unit"] == "-"
    assert row["derivative"] == pytest.approx(exact, rel=1e-4)
    outcome = dyade.run("study", path)
    figure = outcome.summary["d_stroke_1_4_d_crank_length"]
    assert figure.unit == "-" and figure.value == pytest.approx(exact, rel=1e-4)
    assert outcome.summary["d_M_drive_rms_d_crank_length"].unit == "N·m/m"


# -- linked parameters -----------------------------------------------------------------

def test_the_expression_parser_reads_arithmetic_and_nothing_else():
    tree = expression.parse("-(dyad.2.lengths.1 - 2e1) / 2 + links.3.mass ** 2 * 3")
    assert expression.names(tree) == ["dyad.2.lengths.1", "links.3.mass"]
    value = expression.evaluate(tree, {"dyad.2.lengths.1": np.array([200.0, 220.0]),
                                       "links.3.mass": 2.0})
    assert value.tolist() == [-(200 - 20) / 2 + 12, -(220 - 20) / 2 + 12]
    for bad in ("__import__('os')", "a +", "(a", "a b", "a; b", "", "a[1]", "f(a)"):
        with pytest.raises(expression.ExpressionError):
            expression.parse(bad)


@pytest.mark.parametrize("equals, words", [
    ("dyad.2.length.1 / 2", ("names dyad.2.length.1", "Did you mean `dyad.2.lengths.1`")),
    ("dyad.2.lengths.1 /", ("expected a number",)),
    ("links.4.centre.1 * 2", ("itself linked",)),
    ("dyad.2.lengths.1 / 0", ("nominal",)),
])
def test_a_wrong_expression_is_refused_naming_its_key(equals, words):
    with pytest.raises(InputError) as err:
        parse({"mechanism": FOURBAR,
               "parameters": {"dyad.2.lengths.1": [190, 210],
                              "links.3.centre.1": {"equals": equals},
                              "links.4.centre.1": {"equals": "links.3.centre.1"}}})
    text = str(err.value)
    assert "`parameters.links.3.centre.1.equals`" in text or "links.4" in text, text
    assert all(word in text for word in words), text


def test_a_linked_centre_follows_its_length_as_single_runs_give(tmp_path):
    path = write(tmp_path, '[parameters]\n"dyad.2.lengths.1" = [180, 220]\n'
                           '"links.3.centre.1" = { equals = "dyad.2.lengths.1 / 2" }\n')
    cols = dyade.study(path).columns()
    assert cols["links.3.centre.1"].tolist() == [90.0, 110.0]
    for i, length in enumerate((180, 220)):
        alone = dyade.analyse(dyade.read_mechanism(FOURBAR, {"dyad.2.lengths.1": length,
                                                             "links.3.centre.1": length / 2}))
        assert cols["M_drive_rms"][i] == pytest.approx(alone.summary()["M_drive_rms"],
                                                       rel=1e-12)


# -- overrides on the command line -----------------------------------------------------

def test_samples_seed_and_set_override_the_study_file(tmp_path):
    path = write(tmp_path, MC)
    same = write(tmp_path, MC.replace("samples = 4", "samples = 2").replace("seed = 1",
                                                                            "seed = 7"),
                 name="same.toml")
    quick = dyade.run("study", path, samples=2, seed=7, set=("crank.speed_rpm=600",))
    fixed = dyade.run("study", same, set=("crank.speed_rpm=600",))
    assert quick.columns["links.3.mass"].tolist() == fixed.columns["links.3.mass"].tolist()
    api = dyade.study(path, samples=2, seed=7, set=["crank.speed_rpm=600"]).columns()
    assert api["M_drive_rms"].tolist() == quick.columns["M_drive_rms"].tolist()
    mass = quick.columns["links.3.mass"][0]
    alone = dyade.analyse(dyade.read_mechanism(FOURBAR, {"links.3.mass": mass,
                                                         "crank.speed_rpm": 600}))
    assert quick.columns["M_drive_rms"][0] == pytest.approx(alone.summary()["M_drive_rms"],
                                                           rel=1e-12)
    assert cli("study", path, "--samples", "2", "--seed", "7", "--set",
               "crank.speed_rpm=600", "--format", "csv").exit_code == 0
    for args, flag in ((("--set", "links.3.mass=2"), "--set"),
                       (("--set", "crank.sped_rpm=2"), "--set"),
                       (("--seed", "-1"), "--seed")):
        out = cli("study", path, *args)
        assert out.exit_code == 2 and flag in out.output, out.output
    grid = write(tmp_path, '[parameters]\n"links.3.mass" = [1, 2]\n', name="grid.toml")
    out = cli("study", grid, "--samples", "3")
    assert out.exit_code == 2 and "--samples" in out.output and "grid" in out.output


# -- the first hour's commands ---------------------------------------------------------

def test_init_study_then_run_it(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = cli("init", "study", "s.toml")
    assert out.exit_code == 0 and (tmp_path / "fourbar.toml").exists()
    out = cli("study", "s.toml")
    assert out.exit_code == 0, out.output


def test_json_on_stdout_and_the_answers_beside_a_file(tmp_path):
    path = write(tmp_path, MC + "[tolerance]\njoint_force = 90\ntransmission_deg = 63\n")
    for args in (("--format", "json"), ("-o", "-", "--format", "json")):
        out = cli("study", path, *args)
        assert out.exit_code == 0
        document = json.loads(out.stdout)
        assert document["summary"]["variants"]["value"] == 4
    csv = tmp_path / "out.csv"
    out = cli("study", path, "-o", csv)
    assert out.exit_code == 0 and "Tolerance" in out.stdout
    assert "joint force above 90 N" in out.stdout          # the limit with its unit
    assert "transmission angle below 63°" in out.stdout
    again = cli("study", path, "-o", csv, "--resume")
    assert "already complete" in again.stderr and "interrupted" not in again.stderr


# -- constant outputs, peak |M_drive|, withheld variants --------------------------------

def test_constant_outputs_are_shown_as_constant(tmp_path):
    path = write(tmp_path, MC + "[tolerance]\n")  # a mass: the kinematics do not change
    result = dyade.study(path)
    stats = result.tolerance["outputs"]
    assert stats["mu_2_min_deg"]["constant"] and stats["mu_2_min_deg"]["sd"] == 0.0
    assert not stats["M_drive_rms"]["constant"]
    assert questions.constant([0.16, 0.16 + 2.8e-17]) and not questions.constant([1.0, 1.001])
    assert not questions.constant([3.0, math.nan])  # one variant proves nothing
    out = cli("study", path)
    constant_table = out.stdout.split("Constant over the variants")[1]
    assert "mu_2_min_deg" in constant_table and "mu_2_min_deg" not in out.stdout.split(
        "Constant over")[0].split("Tolerance")[1]
    from dyade.plot import study as figures

    fig = figures.question_figure(result)
    drawn = [ax.get_xlabel() for ax in fig.axes]
    assert "mu_2_min_deg [°]" not in drawn and "M_drive_rms [N·m]" in drawn
    assert "constant over the variants: mu_2_min_deg" in fig._suptitle.get_text()


def test_peak_drive_torque_is_the_largest_magnitude_of_the_sweep(tmp_path):
    path = write(tmp_path, '[parameters]\n"links.3.mass" = [1.2, 3]\n')
    result = dyade.study(path)
    assert result.units["M_drive_abs_max"] == "N·m"
    for i, mass in enumerate((1.2, 3)):
        sweep = dyade.analyse(dyade.read_mechanism(FOURBAR, {"links.3.mass": mass}))
        assert result.columns()["M_drive_abs_max"][i] == pytest.approx(
            np.nanmax(np.abs(sweep.columns()["M_drive"])), rel=1e-12)


def test_a_variant_whose_every_position_is_withheld_says_so(tmp_path):
    path = write(tmp_path, '[parameters]\n"crank.speed_rpm" = [300, 1e9]\n')
    outcome = dyade.run("study", path)
    assert outcome.columns["status"].tolist() == ["ok", "withheld"]
    assert "every position is withheld" in outcome.columns["reason"][1]
    assert np.isnan(outcome.columns["M_drive_rms"][1])
    assert outcome.summary["variants_withheld"].value == 1
    assert "swing_4_deg" in outcome.columns  # the outputs of the variant that gives them


# -- an extreme's sensitivity across a grid point --------------------------------------

def test_an_extreme_that_crosses_a_grid_point_is_said_with_the_crank_step(tmp_path):
    path = write(tmp_path, '[plan]\nkind = "sensitivity"\nrel_step = 0.01\n[parameters]\n'
                           '"dyad.2.lengths.1" = 200\n')
    outcome = dyade.run("study", path)
    note, = [n for n in outcome.notes if n.startswith("d M_drive_max/")]
    # the single runs at ±h put the peak at two crank angles of the 1° grid
    where = []
    for length in (198, 202):
        sweep = dyade.analyse(dyade.read_mechanism(FOURBAR, {"dyad.2.lengths.1": length}))
        where.append(float(np.nanargmax(sweep.columns()["M_drive"])))
    assert where[0] != where[1]
    assert f"from crank angle {where[0]:g}° to {where[1]:g}°" in note
    assert "sweep.step" in note and "1° step" in note
    # the default step: no crossing of this peak, no note
    plain = write(tmp_path, '[plan]\nkind = "sensitivity"\n[parameters]\n'
                            '"dyad.2.lengths.1" = 200\n', name="plain.toml")
    assert not any(n.startswith("d M_drive_max/") for n in dyade.run("study", plain).notes)
