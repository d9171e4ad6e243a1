"""The model layer (issue 36, point 5): the data files describe, below the readers and the
engine. Its kinds are the reader's and the engine's kinds; loading it loads no engine; a
reader returns model data in SI, and the engine computes on it."""

from __future__ import annotations

import importlib
import subprocess
import sys

import numpy as np
import pytest

from dyade.files.mechanism.dyads import MIDDLE
from dyade.model import dyad_kinds
from tests.helpers import shipped

MODEL = ("dyade.model.mechanism", "dyade.model.dyad_kinds", "dyade.model.drive",
         "dyade.model.drive_line", "dyade.model.coupling", "dyade.model.gears",
         "dyade.model.torque_table")


def test_every_kind_has_its_data_its_reader_and_its_closure():
    kinds = dyad_kinds.KINDS
    assert [k.number for k in kinds] == [1, 2, 3, 4, 5]
    assert [k.name for k in kinds] == ["RRR", "RRP", "RPR", "PRP", "PPR"]
    assert all(dyad_kinds.kind(k.number) is k and dyad_kinds.named(k.name.lower()) is k
               for k in kinds)
    assert dyad_kinds.named(0) is None and dyad_kinds.named("rrx") is None
    # a variant rule for each of the two closures exactly where the kind has two
    assert all(all(k.variant_rules) == k.has_variant and k.variant_rule(0) == "" for k in kinds)
    assert list(MIDDLE) == [k.name for k in kinds]                    # the file syntax
    for k in kinds:                                                    # the engine's closure
        module = importlib.import_module(f"dyade.linkage.dyads.{k.name.lower()}")
        assert callable(module.close)


def test_a_read_mechanism_closes_by_its_kinds():
    import dyade
    from dyade.linkage import dyads

    mechanism = dyade.read_mechanism(shipped("watt-sixbar.toml"))
    assert all(dyad.kind is dyad_kinds.kind(dyad.kind.number) for dyad in mechanism.dyads)
    assert all(dyads.closure_of(dyad.kind).__module__ == f"dyade.linkage.dyads."
               f"{dyad.kind.name.lower()}" for dyad in mechanism.dyads)


def test_the_model_loads_no_engine_and_no_reader():
    """Importing every model module loads only the model and the base (units, errors,
    arrays): the data do not pull in what computes on them or reads them."""
    code = ("import sys\n" + "".join(f"import {name}\n" for name in MODEL)
            + "print(' '.join(sorted(m for m in sys.modules if m.startswith('dyade'))))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    loaded = set(done.stdout.split())
    assert set(MODEL) <= loaded
    assert loaded - set(MODEL) <= {"dyade", "dyade.model", "dyade.arrays", "dyade.errors",
                                   "dyade.units"}, loaded


def test_the_torque_reader_returns_si_and_the_engine_computes():
    from dyade.errors import InputError
    from dyade.files.torque_curve import read_table
    from dyade.machine.flywheel import excess_curve, table_curve
    from dyade.model.torque_table import TorqueTable

    table = read_table(shipped("torque/engine.csv"))
    assert isinstance(table, TorqueTable) and not table.machine
    assert table.angle[1] == pytest.approx(np.pi / 180.0, rel=1e-15)   # degrees -> radians
    assert table.source == "engine.csv" and table.load is None
    speed = 250 * np.pi / 30
    curve = table_curve(table, speed)
    same = excess_curve(table.angle, table.drive, speed=speed, source="engine.csv")
    assert np.array_equal(curve.excess, same.excess) and curve.speed == speed
    with pytest.raises(InputError, match="speed_rpm"):
        table_curve(table)


def test_a_dyade_csv_is_a_machine_table(tmp_path):
    import dyade
    from click.testing import CliRunner

    from dyade.cli import main
    from dyade.errors import InputError
    from dyade.files.torque_curve import read_table

    path = tmp_path / "sweep.csv"
    done = CliRunner().invoke(main, ["analyse", str(shipped("slider-crank.toml")), "--format",
                                     "csv", "-o", str(path)])
    assert done.exit_code == 0, done.output
    table = read_table(path)
    assert table.machine and table.inertia is not None and table.speed is not None
    curve = dyade.read_torque_curve(path)          # the crank speed from the file's omega_2
    assert curve.speed == float(np.mean(table.speed)) and curve.machine_inertia > 0.0
    assert dyade.read_torque_curve(path, speed_rpm=30).speed == pytest.approx(np.pi, rel=1e-15)
    with pytest.raises(InputError, match="speed_rpm"):
        dyade.read_torque_curve(path, speed=3.0)
