"""Categorical study parameters (issue 39, item 3): a segment's motion law as a choice
among names beside the gear ratio; the grid's best combination is the one direct
``dyade servo`` runs confirm; bad choices are refused naming the key."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.errors import InputError
from dyade.study import plans
from tests.helpers import shipped

LAWS = ["cycloid", "modified-sine", "polynomial-345"]
SAMPLES = 120
"""time steps per cycle: enough to rank the laws, cheap for the default suite"""


@pytest.fixture(scope="module")
def press(tmp_path_factory) -> str:
    """The shipped servo press at its own gear ratio (no ratio range, no catalogue: its
    figures are the gear's, which the study varies)."""
    text = shipped("servo/press.toml").read_text(encoding="utf-8")
    lines = [line for line in text.splitlines()
             if not line.startswith(("ratio_range", "catalogue"))]
    path = tmp_path_factory.mktemp("press") / "press.toml"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return str(path)


def spec(press: str, parameters: dict, **plan):
    data = {"mechanism": press, "parameters": parameters, "outputs": {"extra": ["servo"]},
            "set": {"servo.samples": SAMPLES}}
    if plan:
        data["plan"] = plan
    return dyade.study.parse(data)


RATIOS = [5.0, 10.0]


@pytest.fixture(scope="module")
def grid(press):
    return dyade.study(spec(press, {"profile.segment.2.law": LAWS, "servo.ratio": RATIOS}))


def test_the_grids_best_law_and_ratio_is_the_direct_runs_best(press, grid):
    ratios, result = RATIOS, grid
    table = result.columns()
    assert table["profile.segment.2.law"].tolist() == [law for law in LAWS for _ in ratios]
    rms = np.asarray(table["motor_torque_rms"], dtype=float)
    best = int(np.argmin(rms))
    direct = {}
    for law in LAWS:
        for ratio in ratios:
            outcome = dyade.run("servo", press, set=[f"profile.segment.2.law={law}",
                                                     f"servo.samples={SAMPLES}"], ratio=ratio)
            direct[law, ratio] = outcome.value("motor_torque_rms")
    found = (table["profile.segment.2.law"][best], float(table["servo.ratio"][best]))
    assert found == min(direct, key=direct.get)
    assert np.allclose(rms, [direct[law, ratio] for law in LAWS for ratio in ratios],
                       rtol=1e-12)
    assert len(set(np.round(rms, 6))) == len(rms)  # the laws and ratios do differ


def test_optimise_takes_every_choice_in_turn(press):
    study = dyade.study.parse({"mechanism": press, "set": {"servo.samples": SAMPLES},
                               "parameters": {"profile.segment.2.law": LAWS},
                               "outputs": {"extra": ["servo"]}, "plan": {"kind": "optimise"},
                               "optimise": {"minimise": "motor_torque_rms"}})
    result = dyade.study(study)
    each = result.optimum["choices"]
    assert [row["choice"]["profile.segment.2.law"] for row in each] == LAWS
    values = [row["value"] for row in each]
    assert result.optimum["x"] == [LAWS[int(np.argmin(values))]]
    assert result.optimum["value"] == min(values)
    assert result.columns()["profile.segment.2.law"].tolist() == result.optimum["x"]


def test_sampled_plans_draw_every_choice_by_the_seed(press):
    study = spec(press, {"profile.segment.2.law": LAWS, "servo.ratio": {"uniform": [5, 9]}},
                 kind="monte-carlo", samples=3000, seed=4)
    matrix = plans.variants(study)
    counts = np.bincount(matrix[:, 0].astype(int), minlength=3)
    assert counts.sum() == 3000 and np.all(np.abs(counts - 1000) < 100)  # ~5 sd of 1000
    assert np.array_equal(matrix, plans.variants(study))
    assert study.shown(matrix[0])[0] in LAWS


@pytest.mark.parametrize("parameters, plan, words", [
    ({"profile.segment.2.law": ["cycloid", "modifed-sine"]}, {},
     "`parameters.profile.segment.2.law` names 'modifed-sine', which is not a motion law. "
     "Did you mean `modified-sine`?"),
    ({"profile.segment.2.law": ["cycloid", 3]}, {}, "not both"),
    ({"profile.segment.2.law": ["cycloid", "cycloid"]}, {}, "twice"),
    ({"profile.segment.2.law": ["cycloid", "modified-sine"]}, {"kind": "sensitivity"},
     "central differences need numbers"),
    ({"profile.segment.2.law": ["cycloid", "modified-sine"],
      "servo.ratio": {"equals": "profile.segment.2.law * 2"}}, {}, "numbers only"),
])
def test_bad_choices_are_refused_naming_the_key(press, parameters, plan, words):
    with pytest.raises(InputError) as err:
        spec(press, parameters, **plan)
    assert words in str(err.value) and "profile.segment.2.law" in str(err.value)


def test_a_choice_the_reader_refuses_is_named_before_any_run(press):
    study = spec(press, {"profile.segment.1.law": ["cycloid", "modified-sine"]})
    with pytest.raises(InputError, match=r"`parameters.profile.segment.1.law`: the choice "
                                         r"'cycloid' is refused: .*given for a dwell"):
        dyade.study(study)


@pytest.mark.slow  # (matplotlib and its first figure: seconds)
def test_the_study_figure_names_the_choices(grid):
    pytest.importorskip("matplotlib")
    from dyade.plot.study import versus

    for x in ("servo.ratio", "profile.segment.2.law"):
        fig = versus(grid, "motor_torque_rms", x)
        labels = [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
        assert labels == ([f"profile.segment.2.law = {law}" for law in LAWS]
                          if x == "servo.ratio" else ["servo.ratio = 5", "servo.ratio = 10"])
