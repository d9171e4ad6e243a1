"""The streamed sweep (issue 17): block by block it gives exactly the columns, notes and
clearance check of the whole sweep, whatever the block size (one position, a block
boundary inside a dead-centre range, blocks larger than the sweep)."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from dyade.errors import AssemblyError
from dyade.files import mechanism as toml_input
from dyade.linkage.stream import stream
from tests.helpers import mechanism_from, shipped
from tests.conftest import SHIPPED
from tests.test_machine import _driven

SIZES = [1, 7, 100, 4096]


def _same(whole, streamed, parts) -> None:
    cols = whole.columns()
    got = {name: np.concatenate([part[name] for part in parts]) for name in parts[0]}
    assert list(got) == list(cols)
    for name, values in cols.items():
        assert np.array_equal(got[name], values, equal_nan=True), name
    assert [n.text for n in streamed.notes] == [n.text for n in whole.notes]
    assert [n.ranges for n in streamed.notes] == [n.ranges for n in whole.notes]
    assert repr(streamed.clearance) == repr(whole.clearance)
    assert streamed.positions == cols["angle_deg"].size


def _check(mechanism, size, **options):
    whole = dyade.analyse(mechanism, **options)
    streamed = stream(mechanism, block_size=size, **options)
    _same(whole, streamed, list(streamed.blocks()))
    return whole


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_every_shipped_mechanism(path, size):
    _check(dyade.read_mechanism(path), size, allow_partial=True)


LEVER = (SHIPPED[0].parent / "slotted-lever.toml").read_text().replace(
    "B = { guide = 4, offset = 0 }", "B = { guide = 4, offset = 90 }")


@pytest.mark.parametrize("size", [1, 2, 3, 5, 13, 90, 271])
def test_blocks_that_split_a_dead_centre_range(tmp_path, size):
    """The lever's exact dead centre at 270° with a 4° band at a 0.5° step: a range of
    17 positions, cut by the blocks at every place."""
    path = tmp_path / "lever.toml"
    path.write_text(LEVER)
    whole = _check(dyade.read_mechanism(path), size, step=np.deg2rad(0.5),
                   dead_centre=np.deg2rad(4.0))
    assert any(note.kind == "dead_centre" for note in whole.notes)


@pytest.mark.parametrize("size", [1, 50, 1000])
def test_a_partial_sweep(size):
    """A coupler too short to close over part of the revolution: the rows left out, the
    same note; without allow_partial the same error before any block."""
    data = tomllib.loads((SHIPPED[0].parent / "fourbar.toml").read_text())
    data["dyad"][0]["lengths"] = [200, 80]
    shrunk = mechanism_from(data)
    whole = _check(shrunk, size, allow_partial=True)
    assert whole.notes[0].kind == "partial"
    with pytest.raises(AssemblyError) as whole_error:
        dyade.analyse(shrunk)
    with pytest.raises(AssemblyError) as streamed_error:
        stream(shrunk, block_size=size).blocks().__next__()
    assert str(streamed_error.value) == str(whole_error.value)


@pytest.mark.parametrize("run_up, size", [(False, 1), (False, 33), (True, 50), (True, 5000)],
                         ids=["steady-1", "steady-33", "run-up-50", "run-up-5000"])
def test_a_drive_streams_its_kinematics_and_forces(size, run_up):
    mechanism = _driven({"motor": "asynchronous", "rated_torque": 1.5,
                         "rated_speed_rpm": 288, "synchronous_speed_rpm": 300,
                         "flywheel_inertia": 0.05})
    whole = _check(mechanism, size, run_up=run_up)
    assert "t" in whole.columns()


@pytest.mark.parametrize("size", ["1", "5", "64"])
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_the_cli_csv_is_byte_identical_to_the_whole_sweep(path, size, tmp_path):
    """``dyade analyse --format csv`` streams; --block-size 0 is the whole sweep at once."""
    runner = CliRunner()
    outputs = []
    for blocks in (size, "0"):
        target = tmp_path / f"out-{blocks}.csv"
        result = runner.invoke(main, ["analyse", str(path), "--allow-partial", "--block-size",
                                      blocks, "-o", str(target)], catch_exceptions=False)
        outputs.append((result.exit_code, result.output, target.read_bytes()))
    assert outputs[0] == outputs[1]


@pytest.mark.parametrize("fmt, extra", [("json", ()), ("table", ()), ("table", ("--all",)),
                                        ("json", ("--columns", "mu_*,s_*,F_*")),
                                        ("table", ("--columns", "mu_*,phi_*"))])
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_json_and_tables_stream_the_same_text(path, fmt, extra, tmp_path):
    """JSON and the tables go through a spool on disk, block by block; their text is the
    whole sweep's (--block-size 0) to the byte, --columns included (which once crashed
    the JSON summary: it needs columns the user did not choose)."""
    runner = CliRunner()
    outputs = []
    for blocks in ("7", "100", "0"):
        result = runner.invoke(main, ["analyse", str(path), "--allow-partial", "--block-size",
                                      blocks, "--format", fmt, *extra], catch_exceptions=False)
        outputs.append((result.exit_code, result.stdout, result.stderr))
    assert outputs[0][0] == 0, outputs[0][2]
    assert outputs[0] == outputs[2] and outputs[1] == outputs[2]


def test_a_driven_json_streams_its_motion_summary(tmp_path):
    import json

    from tests.test_machine import _drive_file

    path = _drive_file(tmp_path, {"motor": "asynchronous", "rated_torque": 4.0,
                                  "rated_speed_rpm": 290, "synchronous_speed_rpm": 302})
    runner = CliRunner()
    texts = [runner.invoke(main, ["analyse", str(path), "--format", "json", "--block-size",
                                  blocks, "--columns", "M_drive"]).stdout
             for blocks in ("50", "0")]
    assert texts[0] == texts[1]
    document = json.loads(texts[0])
    assert list(document["columns"]) == ["angle_deg", "M_drive"]
    assert list(document["summary"]["columns"]) == ["M_drive"]
    assert document["summary"]["motion"]["fluctuation"] > 0


def test_the_spool_gives_back_every_column():
    from dyade.linkage.stream import Spool

    mechanism = dyade.read_mechanism(SHIPPED[0])
    whole = dyade.analyse(mechanism).columns()
    with Spool(stream(mechanism, block_size=13).blocks()) as spool:
        assert list(spool) == list(whole)
        for name, values in whole.items():
            assert np.array_equal(spool[name], values, equal_nan=True), name


def test_progress_grows_to_the_whole_and_gives_the_first_pass_its_share():
    """The progress of a stream: shares of the run that never shrink, the first pass
    ending at ``FIRST_PASS`` of it, the last block at the whole; in between the second
    pass's own pace (measured) decides."""
    from dyade.linkage import stream as streaming

    sweep = stream(dyade.read_mechanism(shipped("fourbar.toml")), block_size=50,
                   step=np.radians(1.0))
    seen = []
    sweep.progress = lambda done, total: seen.append(done / total)
    for _ in sweep.blocks():
        pass
    n = sweep.crank_angle.shape[0]
    blocks = -(-n // 50)
    assert len(seen) == 2 * blocks
    assert seen[blocks - 1] == pytest.approx(streaming.FIRST_PASS)
    assert all(later >= earlier for earlier, later in zip(seen, seen[1:]))
    assert seen[-1] == pytest.approx(1.0)


def test_a_sweep_of_one_block_computes_its_kinematics_and_friction_once(monkeypatch):
    """Up to ``block_size`` positions the first pass's kinematics is the second's, and
    the friction solution of the block is the whole sweep's (no sample solved first)."""
    from dyade.linkage import friction, kinematics

    calls = []
    sweep = kinematics.sweep
    monkeypatch.setattr(kinematics, "sweep", lambda *args, **kw: calls.append(1) or sweep(
        *args, **kw))

    def refuse(*args, **kw):
        raise AssertionError("the sample of the force floors was solved")

    monkeypatch.setattr(friction, "coupling", refuse)
    mechanism = dyade.read_mechanism(shipped("self-locking.toml"))
    for _ in stream(mechanism).blocks():
        pass
    assert len(calls) == 1
