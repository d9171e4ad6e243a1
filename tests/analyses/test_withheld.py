"""The rule every analysis shares (issue 36): a run whose every position is withheld
exits 1 saying so, never a table of zeros or blanks.

A four-bar at 1e9 rpm: its accelerations pass 1e12 (SI) at every crank angle, beyond what
any machine has (``dyade.linkage.columns.PLAUSIBLE``), so the validity rules withhold
every position (the speed itself is read: a sweep beyond 1e6 rpm is analysed, but not
given)."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

import dyade
from dyade.cli import main
from tests.helpers import shipped

FAST = ["--set", "crank.speed_rpm=1e9"]
FOURBAR = shipped("fourbar.toml")

COMMANDS = {
    "analyse": ["analyse", FOURBAR, *FAST],
    "accuracy": ["accuracy", FOURBAR, *FAST, "--repeats", "1"],
    "clearance": ["clearance", FOURBAR, *FAST, "--stiffness", "1e8", "--clearance", "1e-4"],
    "balance": ["balance", FOURBAR, *FAST],
    "flywheel": ["flywheel", FOURBAR, *FAST, "--fluctuation", "0.02"],
}


def test_every_position_of_the_four_bar_at_1e9_rpm_is_withheld():
    mechanism = dyade.read_mechanism(FOURBAR, {"crank.speed_rpm": 1e9})
    cols = dyade.analyse(mechanism, allow_partial=True).columns()
    assert cols["kinematics_valid"].size == mechanism.sweep.count  # every row is there
    assert not cols["kinematics_valid"].any() and not cols["forces_valid"].any()
    assert np.isnan(cols["M_drive"]).all() and np.isnan(cols["alpha_3"]).all()


@pytest.mark.parametrize("command", COMMANDS)
def test_a_run_whose_every_position_is_withheld_exits_1_saying_so(command):
    result = CliRunner().invoke(main, [str(a) for a in COMMANDS[command]])
    assert result.exit_code == 1, result.output
    assert "nothing to report" in result.output
    assert "Traceback" not in result.output
    assert result.stdout == ""  # no table of zeros or blanks before the message


@pytest.mark.parametrize("name, options", [
    ("accuracy", {"repeats": 1}),
    ("balance", {}),
    ("flywheel", {"fluctuation": 0.02}),
])
def test_the_api_raises_the_same(name, options):
    from dyade.registry import REGISTRY
    from dyade.errors import DyadeError, InputError

    words = r"every position is withheld: values beyond what any machine has, 1e12 in SI " \
            r"units\): nothing to report"
    with pytest.raises(DyadeError, match=words) as err:
        REGISTRY[name](FOURBAR, set=("crank.speed_rpm=1e9",), **options)
    assert not isinstance(err.value, InputError)  # exit 1: an analysis problem, not input


def test_positions_partly_given_are_a_note_not_an_error():
    # at 1e6 rpm the forces pass 1e12 at part of the turn only: a result, and a note
    from dyade.registry import REGISTRY

    outcome = REGISTRY["balance"](FOURBAR, set=("crank.speed_rpm=1e6",))
    forces = dyade.analyse(dyade.read_mechanism(FOURBAR, {"crank.speed_rpm": 1e6})
                           ).columns()["forces_valid"]
    assert 0 < forces.sum() < forces.size
    assert outcome.notes == [f"the drive torque, the shaking moment and the joint forces are "
                             f"over the {int(forces.sum())} of {forces.size} positions where "
                             f"the forces are given (values beyond what any machine has, 1e12 "
                             f"in SI units; forces not valid)."]
    assert outcome.value("F_inertia_max_before") > 0
