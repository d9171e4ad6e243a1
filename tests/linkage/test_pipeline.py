"""The one sweep pipeline (issue 25): whatever the block size (one position, a block
boundary inside a dead-centre or self-locking range, one block for the whole sweep),
a sweep gives the same columns to the bit, the same notes and clearance check, and the
same summary; the command line gives the same bytes. What couples the blocks (the
friction solution's ``Coupling``) is the whole sweep's."""

from __future__ import annotations

import json
import math
import re
import resource
import subprocess
import sys
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.errors import AssemblyError
from dyade.files import mechanism as toml_input
from dyade.linkage import blocks, friction, kinematics, pipeline
from dyade.linkage.options import with_sweep
from tests.benchmarks.test_benchmarks import FRICTION, _with_friction
from tests.conftest import MECHANISMS, SHIPPED
from tests.helpers import mechanism_from, shipped
from tests.machine.test_machine import _driven

SET = [arg for key, value in FRICTION.items() for arg in ("--set", f"{key}={value}")]
"""μ = 0.1 in every joint (pins r_z = 5 mm, sliders 40 × 20 mm), on the command line"""
CASES = {"self-locking": ("self-locking.toml", []), "dyade-16": ("dyade-16.toml", SET),
         "slider-crank": ("slider-crank.toml", SET)}
"""the shipped mechanism with friction, and two with μ added in every joint"""


def _friction_case(label):
    name, extra = CASES[label]
    return toml_input.read_mechanism(MECHANISMS / name, FRICTION if extra else None)


def _close(a, b, path="summary") -> None:
    """Summaries equal, numbers to 1e-12 relative (sums taken block by block may differ
    in the last bits)."""
    if isinstance(a, dict):
        assert list(a) == list(b), path
        for key in a:
            _close(a[key], b[key], f"{path}.{key}")
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b)):
            _close(x, y, f"{path}[{k}]")
    elif isinstance(a, np.ndarray):
        np.testing.assert_allclose(a, b, rtol=1e-12, err_msg=path)
    elif isinstance(a, float) and isinstance(b, float):
        assert (math.isnan(a) and math.isnan(b)) or a == pytest.approx(b, rel=1e-12), path
    else:
        assert a == b, path


def _same(whole, other) -> None:
    cols, got = whole.columns(), other.columns()
    assert list(got) == list(cols)
    for name, values in cols.items():
        assert np.array_equal(got[name], values, equal_nan=True), name
    assert other.notes == whole.notes
    assert repr(other.clearance) == repr(whole.clearance)
    _close(whole.summary(), other.summary())


def _check(mechanism, size, **options):
    """The sweep in blocks of ``size`` positions against the sweep as one block."""
    whole = dyade.analyse(mechanism, **options)
    assert whole.block is not None  # one block: kept
    _same(whole, dyade.analyse(mechanism, block_size=size, **options))
    return whole


@pytest.mark.parametrize("size", [1, 7, 4096])
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_every_shipped_mechanism_in_any_block_size(path, size):
    coarse = {"step_deg": 4.0} if size == 1 else {}  # 91 blocks of one
    _check(dyade.read_mechanism(path), size, allow_partial=True, **coarse)


@pytest.mark.parametrize("size", [1, 7, 100])
@pytest.mark.parametrize("label", list(CASES))
def test_friction_in_any_block_size(label, size):
    whole = _check(_friction_case(label), size, step_deg=5.0 if size == 1 else 1.0)
    if label == "self-locking":
        assert any(note.kind == "self_locking" for note in whole.notes)


LEVER = (MECHANISMS / "slotted-lever.toml").read_text().replace(
    "B = { guide = 4, offset = 0 }", "B = { guide = 4, offset = 90 }")


@pytest.mark.parametrize("size", [1, 2, 5, 13, 271])
def test_blocks_that_split_a_dead_centre_range(tmp_path, size):
    """The lever's exact dead centre at 270° with a 4° band at a 0.5° step: a range of
    17 positions, cut by the blocks at every place."""
    path = tmp_path / "lever.toml"
    path.write_text(LEVER)
    whole = _check(dyade.read_mechanism(path), size, step_deg=0.5,
                   dead_centre_deg=4.0)
    assert any(note.kind == "dead_centre" for note in whole.notes)


@pytest.mark.parametrize("size", [1, 50, 1000])
def test_a_partial_sweep(size):
    """A coupler too short to close over part of the revolution: the rows left out, the
    same note; without allow_partial the same error before any block."""
    data = tomllib.loads((MECHANISMS / "fourbar.toml").read_text())
    data["dyad"][0]["lengths"] = [200, 80]
    shrunk = mechanism_from(data)
    whole = _check(shrunk, size, allow_partial=True)
    assert whole.notes[0].kind == "partial"
    with pytest.raises(AssemblyError) as whole_error:
        dyade.analyse(shrunk)
    with pytest.raises(AssemblyError) as block_error:
        next(iter(dyade.analyse_in_blocks(shrunk, block_size=size)))
    assert str(block_error.value) == str(whole_error.value)


@pytest.mark.parametrize("run_up, size", [(False, 3), (False, 33), (True, 50), (True, 5000)],
                         ids=["steady-3", "steady-33", "run-up-50", "run-up-5000"])
def test_a_drive_in_any_block_size(size, run_up):
    mechanism = _driven({"motor": "asynchronous", "rated_torque": 1.5,
                         "rated_speed_rpm": 288, "synchronous_speed_rpm": 300,
                         "flywheel_inertia": 0.05})
    whole = _check(mechanism, size, run_up=run_up)
    assert "t" in whole.columns()


def test_a_driven_mechanism_with_friction_couples_its_blocks_by_the_whole_sweep():
    """The crank's speed varies (from the equation of motion with friction): the at-rest
    threshold takes the largest speed of the whole sweep, not of a block."""
    mechanism = _driven({"motor": "asynchronous", "rated_torque": 4.0,
                         "rated_speed_rpm": 290, "synchronous_speed_rpm": 302}, **FRICTION)
    whole = _check(mechanism, 50)
    assert whole.drive is not None and whole.friction is not None
    run = dyade.analyse_in_blocks(mechanism, block_size=50)
    for _ in run:
        pass
    assert run.coupling == whole.friction.coupling
    assert run.coupling.speed > abs(mechanism.crank.speed)  # faster than the mean


def test_a_joint_that_never_moves_is_decided_over_the_whole_sweep():
    """The slide at its dead points only (0°, 180°, 360°): at rest at every position, in
    every block of one; whether it never moves is the whole sweep's to say."""
    whole = _check(_friction_case("self-locking"), 1, step_deg=180.0)
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


def test_friction_options_reach_every_block():
    _check(_friction_case("dyade-16"), 64, friction_tol=1e-6, friction_max_iter=3)


@pytest.mark.parametrize("label", ["dyade-16", "self-locking"])
def test_a_block_is_solved_as_within_the_whole_sweep(label):
    """``friction.solve`` on blocks with the whole sweep's ``Coupling`` gives the whole
    sweep's solution to the bit; the coupling from the sample positions alone
    (``blocks.friction_coupling``) is the one the whole sweep takes as it goes."""
    mechanism = with_sweep(_friction_case(label), step=np.deg2rad(0.1))
    angle = mechanism.sweep.angles()
    whole = friction.solve(mechanism, kinematics.sweep(mechanism, angle))
    coupling = blocks.friction_coupling(mechanism, angle, None, None, 700)
    assert coupling == whole.coupling
    assert blocks.friction_coupling(mechanism, angle, None, None, angle.size) is None
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
    mechanism = with_sweep(_friction_case("dyade-16"), step=np.deg2rad(0.5))
    kin = kinematics.sweep(mechanism)
    compacted = friction.solve(mechanism, kin)
    monkeypatch.setattr(friction.solver, "COMPACT", 0.0)
    kept = friction.solve(mechanism, kinematics.sweep(mechanism))
    assert np.array_equal(compacted.iterations, kept.iterations)
    for name, force in compacted.forces.revolute.items():
        assert np.array_equal(force, kept.forces.revolute[name], equal_nan=True), name


def test_the_whole_arrays_of_a_sweep_in_blocks_are_those_of_one_block():
    """A result computed in blocks gives its kinematics, forces and friction on asking,
    as one block: the same numbers as the sweep of one block."""
    mechanism = _friction_case("self-locking")
    whole, blocked = dyade.analyse(mechanism), dyade.analyse(mechanism, block_size=50)
    assert blocked.block is None
    assert np.array_equal(blocked.forces.drive_torque, whole.forces.drive_torque,
                          equal_nan=True)
    assert np.array_equal(blocked.forces.valid, whole.forces.valid)
    links = mechanism.moving_links
    assert np.array_equal(blocked.kinematics.motion.angle[:, links],
                          whole.kinematics.motion.angle[:, links], equal_nan=True)
    assert np.array_equal(blocked.friction.residual, whole.friction.residual)


def test_a_sweep_of_one_block_computes_its_kinematics_and_friction_once(monkeypatch):
    """Up to ``block_size`` positions the first pass's kinematics is the second's, and
    the friction solution of the block is the whole sweep's (no sample solved first)."""
    calls = []
    sweep = kinematics.sweep
    monkeypatch.setattr(kinematics, "sweep", lambda *args, **kw: calls.append(1) or sweep(
        *args, **kw))

    def refuse(*args, **kw):
        raise AssertionError("the sample of the force floors was solved")

    monkeypatch.setattr(friction, "coupling", refuse)
    for _ in dyade.analyse_in_blocks(dyade.read_mechanism(shipped("self-locking.toml"))):
        pass
    assert len(calls) == 1


def test_skipped_stages_do_not_run(monkeypatch):
    """A kinematics-only plan runs no force stage; a frictionless one no friction."""
    from dyade.linkage import kinetostatics

    def refuse(*args, **kw):
        raise AssertionError("a stage the plan does not call for ran")

    mechanism = dyade.read_mechanism(shipped("fourbar.toml"))
    monkeypatch.setattr(kinetostatics, "solve", refuse)
    result = dyade.analyse(mechanism, plan=dyade.Plan())
    assert result.forces_valid is None and "M_drive" not in result.columns()
    monkeypatch.undo()
    monkeypatch.setattr(friction, "solve", refuse)
    assert dyade.analyse(mechanism).rubbing is None


def test_the_spool_gives_back_every_column():
    from dyade.analyses.spool import Spool

    mechanism = dyade.read_mechanism(SHIPPED[0])
    whole = dyade.analyse(mechanism).columns()
    run = dyade.analyse_in_blocks(mechanism, block_size=13)
    with Spool(block.columns for block in run) as spool:
        assert list(spool) == list(whole)
        for name, values in whole.items():
            assert np.array_equal(spool[name], values, equal_nan=True), name


def test_progress_grows_to_the_whole_and_gives_the_first_pass_its_share():
    """The progress of a run: shares of the run that never shrink, the first pass
    ending at ``FIRST_PASS`` of it, the last block at the whole; in between the second
    pass's own pace (measured) decides."""
    run = dyade.analyse_in_blocks(dyade.read_mechanism(shipped("fourbar.toml")),
                                  block_size=50, step_deg=1.0)
    seen = []
    run.progress = lambda done, total: seen.append(done / total)
    for _ in run:
        pass
    blocks = -(-run.setup.positions // 50)
    assert len(seen) == 2 * blocks
    assert seen[blocks - 1] == pytest.approx(pipeline.FIRST_PASS)
    assert all(later >= earlier for earlier, later in zip(seen, seen[1:]))
    assert seen[-1] == pytest.approx(1.0)


def _run(args):
    result = CliRunner().invoke(main, ["analyse", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def _without_block_size(output):
    """A command's (exit code, stdout, stderr) with the JSON's record of the option
    --block-size left out (the one thing a block size changes)."""
    code, out, err = output
    return code, re.sub(r'\n  "block_size": \d+,', "", out), err


@pytest.mark.parametrize("fmt, extra", [("csv", ()), ("json", ()), ("table", ("--all",)),
                                        ("json", ("--columns", "lock_*,MR_*,friction_*,s_*,mu_*")),
                                        ("table", ("--columns", "mu_*,phi_*"))])
@pytest.mark.parametrize("label", ["fourbar", "dyade-16", "self-locking", "slotted-lever"])
def test_the_command_line_gives_the_same_bytes_in_any_block_size(label, fmt, extra):
    """CSV, JSON (its summary: friction figures, worst residual, locking angles) and the
    tables, with the warnings, as one block (--block-size 0). At a 4° step: 13 blocks of
    7 (a boundary every 28°), and blocks of 25 cut where blocks of 100 cut the 1° sweep
    (100°, inside the self-locking range 90°–179°, 200°, 300°) at a quarter of the cost."""
    name, options = CASES.get(label, (f"{label}.toml", []))
    args = [str(MECHANISMS / name), *options, "--allow-partial", "--format", fmt, *extra,
            "--step", "4"]
    outputs = [_without_block_size(_run([*args, "--block-size", blocks]))
               for blocks in ("7", "25", "0")]
    assert outputs[0][0] == 0, outputs[0][2]
    assert outputs[0] == outputs[2] and outputs[1] == outputs[2]
    if label == "self-locking" and fmt == "json" and not extra:
        summary = json.loads(outputs[0][1])["summary"]
        assert summary["locks_1_4"]["value"] is True and summary["lock_start_1_4_deg"]["value"]


def test_a_driven_json_gives_its_motion_summary_in_any_block_size(tmp_path):
    import json

    from tests.machine.test_machine import _drive_file

    path = _drive_file(tmp_path, {"motor": "asynchronous", "rated_torque": 4.0,
                                  "rated_speed_rpm": 290, "synchronous_speed_rpm": 302})
    texts = [_without_block_size(_run([str(path), "--format", "json", "--block-size", blocks,
                                       "--columns", "M_drive"]))[1] for blocks in ("50", "0")]
    assert texts[0] == texts[1]
    document = json.loads(texts[0])
    assert list(document["columns"]) == ["angle_deg", "M_drive"]
    extremes = [name for name in document["summary"] if name.endswith(("_min", "_max"))
                and name.rpartition("_")[0] in ("angle_deg", "phi_2_deg", "omega_2", "M_drive",
                                                "F_1_2", "mu_2_deg")]
    assert extremes == ["M_drive_max", "M_drive_min"]  # the key figures; no other column's
    assert document["summary"]["fluctuation"]["value"] > 0


def test_fail_on_lock_in_blocks():
    args = [str(MECHANISMS / "self-locking.toml"), "--format", "csv", "--fail-on-lock",
            "--step", "4"]
    blocked, whole = _run([*args, "--block-size", "7"]), _run([*args, "--block-size", "0"])
    assert blocked == whole and blocked[0] == 1
    assert "--fail-on-lock" in blocked[2]


def test_positions_left_unsolved_are_noted_in_any_block_size():
    """Two friction passes (``--friction-max-iter 2``) leave the press's self-locking
    range unsolved (too few passes for a verdict): the note names them (not as positions
    without forces). At a 4° step: blocks of 7 cut the range three times."""
    args = [str(MECHANISMS / "self-locking.toml"), "--friction-max-iter", "2", "--format",
            "csv", "--step", "4"]
    blocked, whole = _run([*args, "--block-size", "7"]), _run([*args, "--block-size", "0"])
    assert blocked == whole
    assert "no consistent friction solution was found" in blocked[2]
    assert "at 22 positions: crank angles 92.0°–176.0°" in blocked[2]


def _peak_kb(*args: str) -> int:
    """Peak resident memory [kB] of ``dyade analyse ARGS`` in a fresh process."""
    code = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, "
            "stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL); "
            "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    out = subprocess.run([sys.executable, "-c", code, sys.executable, "-m", "dyade",
                          "analyse", *args], capture_output=True, text=True, check=True)
    return int(out.stdout)


@pytest.mark.slow  # 4 s: the default suite's budget
@pytest.mark.skipif(not hasattr(resource, "getrusage"), reason="needs getrusage")
def test_memory_does_not_grow_with_a_friction_sweep():
    """The slider-crank with friction in every joint at 20 000 and 200 000 positions: the
    peak grows by less than 100 B a position (the whole sweep at once: about 2 kB a
    position)."""
    args = [str(MECHANISMS / "slider-crank.toml"), *SET, "--format", "csv", "-o", "/dev/null"]
    small = _peak_kb(*args, "--step", "0.018")
    large = _peak_kb(*args, "--step", "0.0018")
    growth = (large - small) * 1024 / (200_000 - 20_000)
    assert growth < 100, f"{growth:.0f} B per position"


def test_the_benchmark_friction_model_in_blocks():
    """The benchmarks' friction model (μ in the crank pin too, edge friction) at a
    finer step, block boundaries anywhere."""
    mechanism = _with_friction(dyade.read_mechanism(MECHANISMS / "slider-crank.toml"))
    _check(mechanism, 333, step_deg=0.1)


def _arrays(thing, seen=None) -> list:
    """Every numpy array a block holds, however deep (dataclasses, dicts, tuples)."""
    import dataclasses

    seen = set() if seen is None else seen
    if id(thing) in seen:
        return []
    seen.add(id(thing))
    if isinstance(thing, np.ndarray):
        return [thing]
    if dataclasses.is_dataclass(thing) and not isinstance(thing, type):
        parts = [getattr(thing, f.name) for f in dataclasses.fields(thing)
                 if f.name != "columns"]
    elif isinstance(thing, dict):
        parts = list(thing.values())
    elif isinstance(thing, (list, tuple)):
        parts = list(thing)
    else:
        return []
    return [array for part in parts for array in _arrays(part, seen)]


def test_what_analyse_hands_out_is_the_callers_in_any_block_size():
    """What ``analyse`` hands out is the caller's, and the same for
    any block size."""
    sl = dyade.read_mechanism(MECHANISMS / "self-locking.toml")
    for size in (None, 1):
        result = dyade.analyse(sl, step_deg=180.0, block_size=size)
        assert result.friction.never_moves == [(1, 4)]
        assert not result.friction.at_rest[(1, 4)].any()
    fourbar = dyade.read_mechanism(MECHANISMS / "fourbar.toml")
    result = dyade.analyse(fourbar)
    torque = result.forces.drive_torque.copy()
    result.columns()["M_drive"][:] = 0.0
    assert np.array_equal(result.forces.drive_torque, torque)
    for result in (dyade.analyse(_friction_case("self-locking")),
                   dyade.analyse(_friction_case("dyade-16"))):
        engine = _arrays(result.block)
        for name, values in result.columns().items():
            assert not any(np.shares_memory(values, array) for array in engine), name
    slider = dyade.read_mechanism(MECHANISMS / "slider-crank.toml")
    angle, speed = np.linspace(0.0, 57.0, 20), np.full(20, 10.0)
    for size in (None, 7):
        result = dyade.analyse(slider, crank_angle_deg=angle.copy(), crank_speed=[10.0],
                               block_size=size)
        assert np.array_equal(dyade.analyse(slider, crank_angle_deg=angle,
                                            crank_speed=np.array(10.0)).columns()["M_drive"],
                              result.columns()["M_drive"])
        given = dyade.analyse(slider, crank_angle_deg=angle, crank_speed=speed, block_size=size)
        torque = given.columns()["M_drive"].copy()
        speed[:] = 99.0
        assert np.array_equal(given.forces.drive_torque, torque)
        speed[:] = 10.0
    empty = dyade.analyse(slider, crank_angle_deg=[], block_size=7).columns()
    assert "M_drive" in empty and empty["angle_deg"].size == 0


def _unwrapped(angle):
    """The reference: ``np.unwrap`` of the finite values, the first brought into
    (−π, π], NaN left in place."""
    finite = np.isfinite(angle)
    out = np.full(angle.shape, np.nan)
    if finite.any():
        values = np.unwrap(angle[finite])
        turns = np.ceil((values[0] - np.pi) / (2.0 * np.pi))
        out[finite] = values - 2.0 * np.pi * turns if turns else values
    return out


def test_link_angles_unwrap_as_np_unwrap_in_any_block_size():
    """``columns.Continuous`` carries the unwrapping from block to block: the same bits
    (signs of zero included) as ``np.unwrap`` of the whole, with jumps, NaN and none."""
    from dyade.linkage.columns import Continuous

    rng = np.random.default_rng(7)
    for _ in range(500):
        n = int(rng.integers(1, 60))
        angle = np.cumsum(rng.normal(0.0, rng.choice([0.1, 1.0, 3.0]), n)) + rng.normal(0, 5)
        if rng.random() < 0.5:
            angle = np.angle(np.exp(1j * angle))  # wrapped into (−π, π]
        if rng.random() < 0.3:
            angle[rng.random(n) < 0.3] = np.nan
        size, phase, parts = int(rng.integers(1, 20)), Continuous(), []
        for first in range(0, n, size):
            parts.append(phase(angle[first:first + size].copy()))
            phase.commit()
        got, want = np.concatenate(parts), _unwrapped(angle)
        assert np.array_equal(got, want, equal_nan=True)
        assert np.array_equal(np.signbit(got), np.signbit(want))
