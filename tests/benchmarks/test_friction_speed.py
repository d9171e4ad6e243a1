"""The friction solution against its yardstick (issue 15): the fixed-point iteration dyade
had before (``old_friction``: no edge friction, no verdict) on dyade-16 with μ = 0.1 in
all 22 joints, 3600 positions, tolerance 1e-9 — the same mechanism and angles as
``test_benchmarks.test_dyade16_with_friction_3600``, so that

    pytest tests/benchmarks -k dyade16_with_friction --benchmark-enable \
        --benchmark-columns=min,median,rounds

gives both in one run.
"""

from __future__ import annotations

import numpy as np

from dyade.files import mechanism as toml_input
from dyade.linkage import friction, kinematics
from tests.benchmarks import old_friction
from tests.benchmarks.test_benchmarks import _angles, _with_friction
from tests.helpers import shipped


def _dyade16(edges: bool):
    return _with_friction(toml_input.read_mechanism(shipped("dyade-16.toml")), edges=edges)


def test_dyade16_with_friction_3600_old_iteration(benchmark):
    mechanism = _dyade16(edges=False)  # the old model has no edge friction
    angles = _angles(3600)

    def engine():
        kin = kinematics.sweep(mechanism, angles)
        return old_friction.iterate(mechanism, kin)

    result = benchmark(engine)
    assert result.converged.all()


def test_old_iteration_is_the_same_model():
    """The yardstick computes what ``solve`` does without edge friction (to the
    tolerance), so the comparison is like for like."""
    mechanism = _dyade16(edges=False)
    kin = kinematics.sweep(mechanism, _angles(360))
    old, new = old_friction.iterate(mechanism, kin), friction.solve(mechanism, kin)
    assert new.converged.all() and old.converged.all()
    scale = np.abs(new.forces.drive_torque).max()
    assert np.abs(old.forces.drive_torque - new.forces.drive_torque).max() < 1e-7 * scale
