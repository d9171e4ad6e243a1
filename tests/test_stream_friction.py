"""Sweeps with friction streamed (issue 17): block by block they give exactly the
columns, notes, summary, tables and JSON of the whole sweep, whatever the block size
(one position, a block boundary inside a self-locking range), in memory that does not
grow with the sweep but by a few bytes per position."""

from __future__ import annotations

import resource
import subprocess
import sys
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.files import mechanism as toml_input
from dyade.linkage import friction, kinematics
from dyade.linkage.stream import stream
from dyade.linkage.sweep import with_sweep
from tests.benchmarks.test_benchmarks import FRICTION, _with_friction
from tests.conftest import MECHANISMS
from tests.helpers import mechanism_from
from tests.test_machine import _driven
from tests.test_stream import _check

SET = [arg for key, value in FRICTION.items() for arg in ("--set", f"{key}={value}")]
"""μ = 0.1 in every joint (pins r_z = 5 mm, sliders 40 × 20 mm), on the command line"""
CASES = {"self-locking": ("self-locking.toml", []), "dyade-16": ("dyade-16.toml", SET),
         "slider-crank": ("slider-crank.toml", SET)}
"""the shipped mechanism with friction, and two with μ added in every joint"""


def _mechanism(label):
    name, extra = CASES[label]
    return toml_input.read_mechanism(MECHANISMS / name, FRICTION if extra else None)


@pytest.mark.parametrize("size", [1, 7, 100, 4096])
@pytest.mark.parametrize("label", list(CASES))
def test_streamed_friction_is_the_whole_sweep(label, size):
    """Columns (friction loads, passes, determinants, lock margins), notes and their
    ranges as the whole sweep's; at 1° the self-locking range 270°–332° is cut by every
    block size but 4096."""
    whole = _check(_mechanism(label), size, allow_partial=True)
    if label == "self-locking":
        assert any(note.kind == "self_locking" for note in whole.notes)
        assert any(note.kind == "near_self_locking" for note in whole.notes)


def test_a_joint_that_never_moves_is_decided_over_the_whole_sweep():
    """The slide at its dead points only (0°, 180°, 360°): at rest at every position, in
    every block of one; whether it never moves is the whole sweep's to say."""
    whole = _check(_mechanism("self-locking"), 1, step=np.pi)
    assert [note.kind for note in whole.notes].count("never_moves") == 1


def test_the_force_floor_is_the_whole_sweeps():
    """The press with its process force over 91°–359° only, and links of next to no
    mass (1e-20 of it): over 0°–90° the forces are about 1e-21 N, below the floor
    taken from the whole sweep (1e-12 of its median force, 4e-11 N), which then decides
    when the friction passes stop. A block there must not take its own."""
    data = tomllib.loads((MECHANISMS / "self-locking.toml").read_text())
    for link in data["links"].values():
        link["mass"] *= 1e-20
        if "inertia" in link:
            link["inertia"] *= 1e-20
    data["load"][0].pop("force")
    data["load"][0]["table"] = [[0, 0, 0, 0], [90, 0, 0, 0], [91, -40, 0, 0], [359, -40, 0, 0]]
    data["friction"]["coefficient"] = 0.1
    whole = _check(mechanism_from(data), 7)
    assert whole.friction.coupling.floors[(3, 4)] == pytest.approx(4e-11)


def test_a_slider_crank_with_every_joint_rubbing_streams():
    """The benchmarks' friction model (μ in the crank pin too, edge friction) at a
    finer step, block boundaries anywhere."""
    mechanism = _with_friction(dyade.read_mechanism(MECHANISMS / "slider-crank.toml"))
    _check(mechanism, 333, step=np.deg2rad(0.1))


def test_a_driven_mechanism_with_friction_streams():
    """The crank's speed varies (from the equation of motion with friction): the at-rest
    threshold takes the largest speed of the whole sweep, not of a block."""
    mechanism = _driven({"motor": "asynchronous", "rated_torque": 4.0,
                         "rated_speed_rpm": 290, "synchronous_speed_rpm": 302}, **FRICTION)
    whole = _check(mechanism, 50)
    assert whole.drive is not None and whole.friction is not None
    streamed = stream(mechanism, block_size=50)
    for _ in streamed.blocks():
        pass
    assert streamed.coupling == whole.friction.coupling
    assert streamed.coupling.speed > abs(mechanism.crank.speed)  # faster than the mean


def test_friction_options_reach_the_stream():
    _check(_mechanism("dyade-16"), 64, friction_tol=1e-6, friction_max_iter=3)


@pytest.mark.parametrize("label", ["dyade-16", "self-locking"])
def test_a_block_is_solved_as_within_the_whole_sweep(label):
    """``friction.solve`` on blocks with the whole sweep's ``Coupling`` gives the whole
    sweep's solution to the bit; the coupling from the sample positions alone is the
    whole sweep's."""
    mechanism = with_sweep(_mechanism(label), step=np.deg2rad(0.1))
    angle = mechanism.sweep.angles()
    whole = friction.solve(mechanism, kinematics.sweep(mechanism, angle))
    sample = kinematics.sweep(mechanism, angle[friction.sample(angle.size)])
    coupling = friction.coupling(mechanism, sample, whole.coupling.speed)
    assert coupling == whole.coupling
    for first in range(0, angle.size, 700):
        part = slice(first, first + 700)
        block = friction.solve(mechanism, kinematics.sweep(mechanism, angle[part]),
                               coupling=coupling)
        for name in whole.forces.revolute:
            assert np.array_equal(block.forces.revolute[name], whole.forces.revolute[name][part],
                                  equal_nan=True), name
        for field in ("power", "iterations", "residual", "locked", "near"):
            got, want = getattr(block, field), getattr(whole, field)
            if isinstance(want, dict):
                got, want = np.array(list(got.values())), np.array([w[part] for w in want.values()])
            else:
                want = want[part]
            assert np.array_equal(got, want, equal_nan=True), field


def test_compacting_the_newton_passes_changes_no_bit(monkeypatch):
    """Once few positions are left the passes go on at those alone (``COMPACT``): how
    many others converged must not change a position's arithmetic, or a block would
    differ from the whole sweep."""
    mechanism = with_sweep(_mechanism("dyade-16"), step=np.deg2rad(0.5))
    kin = kinematics.sweep(mechanism)
    compacted = friction.solve(mechanism, kin)
    monkeypatch.setattr(friction.solver, "COMPACT", 0.0)
    kept = friction.solve(mechanism, kinematics.sweep(mechanism))
    assert np.array_equal(compacted.iterations, kept.iterations)
    for name, force in compacted.forces.revolute.items():
        assert np.array_equal(force, kept.forces.revolute[name], equal_nan=True), name


def _run(args):
    result = CliRunner().invoke(main, ["analyse", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize("fmt, extra", [("csv", ()), ("json", ()), ("table", ()),
                                        ("table", ("--all",)),
                                        ("json", ("--columns", "lock_*,MR_*,friction_*"))])
@pytest.mark.parametrize("label", list(CASES))
def test_the_cli_streams_friction_to_the_byte(label, fmt, extra):
    """CSV, JSON (its summary: friction figures, worst residual, locking angles) and the
    tables, with the warnings, as the whole sweep's (--block-size 0)."""
    name, options = CASES[label]
    args = [str(MECHANISMS / name), *options, "--format", fmt, *extra]
    outputs = [_run([*args, "--block-size", blocks]) for blocks in ("7", "100", "0")]
    assert outputs[0][0] == 0, outputs[0][2]
    assert outputs[0] == outputs[2] and outputs[1] == outputs[2]
    if label == "self-locking" and fmt == "json" and not extra:
        assert '"locks": true' in outputs[0][1] and "locking_angles_deg" in outputs[0][1]


def test_fail_on_lock_when_streamed():
    args = [str(MECHANISMS / "self-locking.toml"), "--format", "csv", "--fail-on-lock"]
    streamed, whole = _run(args), _run([*args, "--block-size", "0"])
    assert streamed == whole and streamed[0] == 1
    assert "--fail-on-lock" in streamed[2]


def _peak_kb(*args: str) -> int:
    """Peak resident memory [kB] of ``dyade analyse ARGS`` in a fresh process."""
    code = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, "
            "stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL); "
            "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    out = subprocess.run([sys.executable, "-c", code, sys.executable, "-m", "dyade",
                          "analyse", *args], capture_output=True, text=True, check=True)
    return int(out.stdout)


@pytest.mark.skipif(not hasattr(resource, "getrusage"), reason="needs getrusage")
def test_memory_does_not_grow_with_a_friction_sweep():
    """The slider-crank with friction in every joint at 20 000 and 200 000 positions: the
    peak grows by less than 100 B a position (the whole sweep: about 2 kB a position,
    767 MB at 360 000)."""
    args = [str(MECHANISMS / "slider-crank.toml"), *SET, "--format", "csv", "-o", "/dev/null"]
    small = _peak_kb(*args, "--step", "0.018")
    large = _peak_kb(*args, "--step", "0.0018")
    growth = (large - small) * 1024 / (200_000 - 20_000)
    assert growth < 100, f"{growth:.0f} B per position"


def test_positions_left_unsolved_are_noted_as_in_the_whole_sweep():
    """Two friction passes (``--friction-max-iter 2``) leave the press's self-locking
    range unsolved (too few passes for a verdict): the note names them (not as positions
    without forces), streamed as whole."""
    args = [str(MECHANISMS / "self-locking.toml"), "--friction-max-iter", "2", "--format",
            "csv"]
    streamed, whole = _run([*args, "--block-size", "7"]), _run([*args, "--block-size", "0"])
    assert streamed == whole
    assert "no consistent friction solution was found" in streamed[2]
    assert "at 63 positions: crank angles 270.0°–332.0°" in streamed[2]
