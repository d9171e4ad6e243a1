"""The ``flywheel`` and ``balance`` entries (``dyade.analyses.machine``): the command
line writes the entry's Outcome, every figure has its unit, and the physics."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from dyade.registry import REGISTRY
from dyade.analyses.base import jsonable
from dyade.cli import main
from tests.helpers import shipped

REPRS = ("np.float64(", "True", "False", "None", "nan", "inf")
"""what a table must never show (a missing value is —, a flag yes/no)"""


def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def document(outcome) -> dict:
    """The Outcome's JSON document as a reader gets it back."""
    return json.loads(json.dumps(jsonable(outcome.to_document())))


CASES = {
    "flywheel-mechanism": ("flywheel", shipped("dyade-16.toml"), {"fluctuation": 0.02},
                           ["--fluctuation", "0.02"]),
    "flywheel-mechanism-step": ("flywheel", shipped("fourbar.toml"),
                                {"inertia": 0.05, "step_deg": 1.0, "start_deg": 30.0},
                                ["--inertia", "0.05", "--step", "1", "--start", "30"]),
    "flywheel-csv": ("flywheel", shipped("torque/engine.csv"),
                     {"fluctuation": 0.005, "speed_rpm": 250.0},
                     ["--fluctuation", "0.005", "--speed", "250"]),
    "balance": ("balance", shipped("fourbar.toml"), {}, []),
    "balance-link": ("balance", shipped("dyade-16.toml"), {"link": (2,), "radius": 0.05,
                                                           "set": ("links.2.mass=2",)},
                     ["--link", "2", "--radius", "0.05", "--set", "links.2.mass=2"]),
}


@pytest.mark.parametrize("case", CASES)
def test_the_json_is_the_entrys_document(case):
    name, path, options, flags = CASES[case]
    outcome = REGISTRY[name](path, **options)
    out = cli(name, path, *flags, "--format", "json")
    assert out.exit_code == 0, out.output
    assert json.loads(out.stdout) == document(outcome)
    assert all(figure.unit for figure in outcome.summary.values()), outcome.summary
    table = cli(name, path, *flags)
    assert table.exit_code == 0
    for text in REPRS:
        assert text not in table.stdout, text
    csv = cli(name, path, *flags, "--format", "csv").stdout.splitlines()
    assert csv[0].split(",") == list(outcome.columns)
    assert len(csv) == 1 + len(next(iter(outcome.columns.values())))


def test_flywheel_of_the_textbook_engine():
    # T = 10000 + 2000·sin 2θ − 1800·cos 2θ N·m against a constant load: ΔE =
    # 2·√(1000² + 900²) J in closed form, J_F = ΔE/(δ·Ω²) (Dresig & Holzweißig); the
    # integration is of fourth order, at a 1° step
    outcome = REGISTRY["flywheel"](shipped("torque/engine.csv"), fluctuation=0.005,
                                   speed_rpm=250.0)
    omega = 250 * math.pi / 30
    assert outcome.value("delta_E") == pytest.approx(2 * math.hypot(1000, 900), rel=1e-7)
    assert outcome.value("J_flywheel") == pytest.approx(
        outcome.value("delta_E") / (0.005 * omega ** 2), rel=1e-12)
    assert outcome.summary["J_flywheel"].unit == "kg·m²"
    assert outcome.summary["fluctuation"].unit == "-"
    assert outcome.meta["given"] == "fluctuation"
    # the inverse: the flywheel gives back the fluctuation it was sized for
    back = REGISTRY["flywheel"](shipped("torque/engine.csv"),
                                inertia=outcome.value("J_flywheel"), speed_rpm=250.0)
    assert back.value("fluctuation") == pytest.approx(0.005, rel=1e-12)


def test_flywheel_source_by_suffix_and_by_header(tmp_path):
    from dyade.analyses.inputs import Text

    engine = shipped("torque/engine.csv")
    by_path = REGISTRY["flywheel"](engine, fluctuation=0.005, speed_rpm=250.0)
    by_text = REGISTRY["flywheel"](Text(engine.read_text()), fluctuation=0.005, speed_rpm=250.0)
    assert by_text.value("delta_E") == by_path.value("delta_E")
    mechanism = REGISTRY["flywheel"](Text(shipped("fourbar.toml").read_text()), fluctuation=0.02)
    assert mechanism.value("J_flywheel") == REGISTRY["flywheel"](
        shipped("fourbar.toml"), fluctuation=0.02).value("J_flywheel")
    wrong = cli("flywheel", engine, "--speed", 250, "--fluctuation", 0.02, "--set",
                "crank.speed_rpm=3")
    assert wrong.exit_code == 2 and "--set apply to a mechanism file" in wrong.output
    wrong = cli("flywheel", shipped("fourbar.toml"), "--speed", 250, "--fluctuation", 0.02)
    assert wrong.exit_code == 2 and "--speed is for a torque CSV" in wrong.output


def test_four_bar_counterweights_cancel_the_shaking_force():
    # Berkof & Lowen: on crank and rocker, 0.6 kg·0.05 m and 0.6 kg·0.15 m + 0.9 kg·0.075 m
    # opposite the links (the coupler's 1.2 kg counts half at each pin)
    outcome = REGISTRY["balance"](shipped("fourbar.toml"))
    assert outcome.columns["link"].tolist() == [2, 4]
    assert outcome.columns["first_moment"] == pytest.approx([0.03, 0.1575], rel=1e-9)
    assert np.abs(outcome.columns["angle_deg"]) == pytest.approx([180.0, 180.0], abs=1e-9)
    assert outcome.value("F_inertia_max_after") < 1e-12 * outcome.value("F_inertia_max_before")
    assert outcome.value("F_inertia_ratio") < 1e-12
    for name, figure in outcome.summary.items():
        unit = "-" if name == "F_inertia_ratio" else "N·m" if name.startswith("M_") else "N"
        assert figure.unit == unit, name
    table = cli("balance", shipped("fourbar.toml")).stdout
    assert "shaking force, largest           N     98.2126        0             0" \
        in table


@pytest.mark.parametrize("name, path, options", [
    ("flywheel", shipped("fourbar.toml"), {"fluctuation": 0.02, "step_deg": 0.01}),
    ("balance", shipped("fourbar.toml"), {"set": ("sweep.step=0.01",)}),
])
def test_a_run_above_max_time_is_refused_before_it_starts(name, path, options):
    from dyade.errors import InputError

    told = []
    with pytest.raises(InputError, match="max_time_s is 0.01 s"):
        REGISTRY[name](path, max_time_s=0.01, told=told.append, **options)
    assert not told  # refused, not announced
    out = cli(name, path, "--max-time", "0.01", *(
        ["--fluctuation", "0.02", "--step", "0.01"] if name == "flywheel"
        else ["--set", "sweep.step=0.01"]))
    assert out.exit_code == 2 and "--max-time is 0.01 s" in out.output


def test_max_memory_bounds_the_torque_curve():
    out = cli("flywheel", shipped("fourbar.toml"), "--fluctuation", 0.02, "--max-memory", 1)
    assert out.exit_code == 2 and "--max-memory is 1.05 MB" in out.output
    out = cli("balance", shipped("fourbar.toml"), "--max-memory", 1)
    assert out.exit_code == 2 and "--max-memory is 1.05 MB" in out.output
