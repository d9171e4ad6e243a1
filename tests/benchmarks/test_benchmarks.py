"""Benchmarks (issue 7). Disabled in the normal test run (each body runs once as a smoke
test); measure with

    pytest tests/benchmarks --benchmark-enable --benchmark-columns=min,median,rounds
"""

from __future__ import annotations

import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from dyade.linkage import sweep as analysis, friction, kinematics, kinetostatics
from dyade import clearance
from dyade.model.mechanism import Prismatic
from dyade.vibration import coupling
from dyade.files import mechanism as toml_input
from tests import fixed_point
from tests.benchmarks.yardstick import fourbar, slider_crank
from tests.helpers import shipped

ROOT = Path(__file__).resolve().parents[2]
DYADE = str(Path(sys.executable).with_name("dyade"))


def _angles(count: int) -> np.ndarray:
    return np.linspace(0.0, 2 * np.pi, count, endpoint=False)


def _with_friction(mechanism, mu=0.1, edges=True):
    def rub(joint):
        if isinstance(joint, Prismatic):
            return replace(joint, friction=mu, slider_length=0.04, slider_height=0.02,
                           edge_friction=edges)
        return replace(joint, friction=mu, pin_radius=0.005)

    crank = replace(mechanism.crank, joint=rub(mechanism.crank.joint))
    dyads = tuple(replace(d, joints=tuple(rub(j) for j in d.joints)) for d in mechanism.dyads)
    return replace(mechanism, crank=crank, dyads=dyads, friction_tol=1e-9)


@pytest.mark.parametrize("count", [360, 3600])
@pytest.mark.parametrize("name", ["fourbar.toml", "slider-crank.toml"])
def test_full_analysis(benchmark, name, count):
    mechanism = toml_input.read_mechanism(shipped(name))
    angles = _angles(count)
    result = benchmark(lambda: analysis.analyse_si(mechanism, crank_angle=angles).columns())
    assert "M_drive" in result


@pytest.mark.parametrize("name, count", [("fourbar.toml", 360), ("fourbar.toml", 3600),
                                         ("slider-crank.toml", 3600)])
def test_engine_kinematics_and_forces(benchmark, name, count):
    """The general engine, kinematics + forces only: compare with the yardsticks."""
    mechanism = toml_input.read_mechanism(shipped(name))
    angles = _angles(count)

    def engine():
        kin = kinematics.sweep(mechanism, angles)
        return kinetostatics.solve(mechanism, kin)

    benchmark(engine)


@pytest.mark.parametrize("count", [360, 3600])
def test_fourbar_yardstick(benchmark, count):
    angles = _angles(count)
    benchmark(fourbar, angles, 300 * 2 * np.pi / 60)


@pytest.mark.parametrize("count", [3600])
def test_slider_crank_yardstick(benchmark, count):
    benchmark(slider_crank, _angles(count), 1500 * 2 * np.pi / 60)


@pytest.mark.parametrize("count", [3600, 360_000])
def test_fourbar_engine_cost_per_position(benchmark, count):
    """Kinematics and forces, whole sweep against blocks of 2048 positions (the streamed
    path): divide by the count for the cost per position."""
    from dyade.linkage.blocks import BLOCK_SIZE

    mechanism = toml_input.read_mechanism(shipped("fourbar.toml"))
    angles = _angles(count)

    def engine():
        for first in range(0, count, BLOCK_SIZE):
            kin = kinematics.sweep(mechanism, angles[first:first + BLOCK_SIZE])
            kinetostatics.solve(mechanism, kin)

    benchmark(engine)


@pytest.mark.parametrize("edges", [True, False], ids=["edge-friction", "no-edge-friction"])
@pytest.mark.parametrize("method", [friction.solve, fixed_point.iterate], ids=["solve", "iterate"])
def test_dyade16_with_friction_3600(benchmark, method, edges):
    """The direct solution (with the self-locking verdict) and the fixed-point iteration
    in one run, on the same friction model, at tolerance 1e-9."""
    mechanism = _with_friction(toml_input.read_mechanism(shipped("dyade-16.toml")), edges=edges)
    angles = _angles(3600)

    def engine():
        kin = kinematics.sweep(mechanism, angles)
        return method(mechanism, kin)

    result = benchmark(engine)
    assert result.converged.all()


def test_clearance_closed_form(benchmark):
    benchmark(clearance.peak_force, 3.6, 1e7, clearance=1e-4, slope=3.6e5)


@pytest.mark.parametrize("steps", [50, 400])
def test_clearance_simulation(benchmark, steps):
    benchmark(clearance.simulate, 3.6, 1e7, clearance=1e-4, slope=3.6e5, steps_per_period=steps)


def test_coupling_100000_eta(benchmark):
    model = coupling.Coupling(1, 1, 1, 0.05, 0.05)
    eta = np.linspace(0.0, 3.0, 100_000)
    benchmark(coupling.response, model, eta)


ASYNCHRONOUS = {"drive": {"motor": "asynchronous", "rated_torque": 1.0, "rated_speed_rpm": 298,
                          "synchronous_speed_rpm": 310, "flywheel_inertia": 0.34}}
FRICTION = {"friction.coefficient": 0.1, "friction.pin_radius": 5,
            "friction.slider_length": 40, "friction.slider_height": 20}


@pytest.mark.parametrize("rubbing", [False, True], ids=["frictionless", "friction"])
@pytest.mark.parametrize("speed", ["constant", "motor"])
def test_dyade16_drive(benchmark, speed, rubbing):
    """The equation of motion (720 steps, shooting; friction by passes) and the analysis
    at the real speed, against the constant-speed analysis of the same file (361
    positions) as the yardstick."""
    overrides = ASYNCHRONOUS | (FRICTION if rubbing else {})
    mechanism = toml_input.read_mechanism(shipped("dyade-16.toml"), overrides)
    result = benchmark(analysis.analyse, mechanism, constant_speed=speed == "constant")
    assert (result.drive is None) == (speed == "constant")


def test_dyade16_run_up(benchmark):
    mechanism = toml_input.read_mechanism(shipped("dyade-16.toml"), ASYNCHRONOUS)
    result = benchmark.pedantic(analysis.analyse, (mechanism,), {"run_up": True}, rounds=3)
    assert result.drive.figures["settled"]


def test_dyade16_flywheel(benchmark):
    import dyade

    mechanism = toml_input.read_mechanism(shipped("dyade-16.toml"))
    benchmark(lambda: dyade.size_flywheel(dyade.mechanism_torque_curve(mechanism), 0.02))


@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml"])
def test_balance(benchmark, name):
    import dyade

    mechanism = toml_input.read_mechanism(shipped(name))
    benchmark(dyade.balance, mechanism)


@pytest.mark.parametrize("command", [
    [sys.executable, "-c", "import numpy"],
    [DYADE, "analyse", "mechanisms/fourbar.toml", "--format", "csv"],
    [DYADE, "--help"],
], ids=["python -c import numpy", "dyade analyse fourbar csv", "dyade --help"])
def test_command(benchmark, command):
    """Whole commands in fresh processes (a regular install: an editable one adds an
    import finder); tests/benchmarks/command_time.py prints the ratios."""
    def run():
        subprocess.run(command, stdout=subprocess.DEVNULL, check=True, cwd=ROOT)

    benchmark.pedantic(run, rounds=15, iterations=1, warmup_rounds=1)


def _dyade16_columns():
    mechanism = toml_input.read_mechanism(shipped("dyade-16.toml"))
    return analysis.analyse(mechanism, step_deg=0.1).columns()


@pytest.mark.parametrize("writer", ["row by row (before issue 17)", "blocks"])
def test_csv_writer_dyade16_3600(benchmark, writer, tmp_path):
    """CSV throughput: the block writer against the one it replaced, same columns,
    same file; divide by the values written (3 601 rows × the columns)."""
    import os

    from dyade.report import csv_rows
    from tests.benchmarks import old_csv

    cols = _dyade16_columns()
    write = old_csv.write if writer.startswith("row") else csv_rows.write

    def run():
        with open(os.devnull, "w", encoding="utf-8", newline="") as handle:
            write(cols, handle)

    benchmark(run)
