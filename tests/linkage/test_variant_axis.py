"""Variants as an axis of the one sweep pipeline (issue 41): a run of variants stacked
into one mechanism (``pipeline.prepare_variants``) decides validity, dead-centre bands,
plausibility and notes per variant by the pipeline's own code, so that each variant's
notes, error, columns and validity are those of a sweep of it alone, to the bit."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.errors import AssemblyError
from dyade.linkage import columns, pipeline
from dyade.linkage.stack import NotStackable, stack
from tests.helpers import shipped

LENGTHS = [(200, 150), (100, 150), (170.03, 130), (172, 131), (195, 152), (250, 150),
           (201, 151)]
"""coupler, rocker [mm] of the shipped four-bar: closes; does not close; 1.6° from a
dead centre (inside the 2° band); a poor transmission angle (a note only); three that
close"""


def _variants(name, sets):
    return [dyade.read_mechanism(shipped(name), values) for values in sets]


def _run(variants, **options):
    setup = pipeline.prepare_variants(stack(variants, variants[0].sweep.count), len(variants))
    run = pipeline.Run(setup, setup.positions, **options)
    blocks = list(run)
    cols = {name: np.concatenate([b.columns[name] for b in blocks]) for name in blocks[0].columns}
    return run, cols


def _alone(mechanism):
    try:
        return dyade.analyse(mechanism)
    except AssemblyError as err:
        return err


def test_each_variant_is_its_own_sweep_notes_errors_and_columns():
    variants = _variants("fourbar.toml", [{"dyad.2.lengths.1": a, "dyad.2.lengths.2": b}
                                          for a, b in LENGTHS])
    run, cols = _run(variants)
    given = [v for v in range(len(variants)) if v not in run.failed]
    assert given == [0, 2, 3, 4, 5, 6]
    kinds = []
    for v, mechanism in enumerate(variants):
        alone = _alone(mechanism)
        if isinstance(alone, AssemblyError):
            assert str(run.failed[v]) == str(alone)
            assert not run.rows[v * 361:(v + 1) * 361].any()
            continue
        assert run.notes[v] == alone.notes  # kinds, ranges, figures: the same notes
        kinds.append(sorted(note.kind for note in run.notes[v]))
        k = given.index(v)
        mine = {name: values[k * 361:(k + 1) * 361] for name, values in cols.items()}
        theirs = alone.columns()
        for name, values in mine.items():  # the study's columns, to the bit
            np.testing.assert_array_equal(values, theirs[name], err_msg=name)
        assert np.array_equal(run.outcome.valid[v * 361:(v + 1) * 361], alone.valid)
    assert kinds[1] == ["dead_centre", "poor_transmission"] and kinds[2] == ["poor_transmission"]
    assert kinds[0] == kinds[3] == []


def test_the_columns_left_out_are_checked_for_plausibility_all_the_same():
    """At 3e7 rpm the joints' accelerations pass 1e12 while no column a study reads
    does at those positions (the forces are computed first): the bound does not clear,
    the point columns are computed for the check, and that variant's rows are taken
    out as alone, with its note; the other variant keeps every value."""
    variants = _variants("fourbar.toml", [{"crank.speed_rpm": 300}, {"crank.speed_rpm": 3e7}])
    run, cols = _run(variants, points=False, machine=False)
    assert not any(name.startswith(("x_", "ax_", "J_red")) for name in cols)
    for v, mechanism in enumerate(variants):
        alone = dyade.analyse(mechanism)
        assert run.notes[v] == alone.notes
        for name, values in cols.items():
            np.testing.assert_array_equal(values[v * 361:(v + 1) * 361], alone.columns()[name],
                                          err_msg=name)
    assert [note.kind for note in run.notes[1]] == ["implausible"]
    assert run.notes[0] == []


@pytest.mark.parametrize("name", ["fourbar.toml", "slider-crank.toml", "dyade-16.toml",
                                  "slotted-lever.toml"])
def test_the_bound_holds_every_column_it_stands_for(name):
    """``columns.bound`` is no smaller than any value of the point and machine columns
    (a bound that is too small would let an implausible value through unseen)."""
    variants = _variants(name, [{}, {"crank.speed_rpm": 600.0}])
    run, cols = _run(variants)  # every column computed
    block = run.setup
    top = max(float(np.nanmax(np.abs(values))) for key, values in cols.items()
              if key.split("_", 1)[0] in columns.POINT or key in ("J_red", "dJ_red"))
    kin = dyade.linkage.kinematics.sweep(block.mechanism, block.crank_angle, repeat=2)
    from dyade.linkage.block import Block

    whole = Block(0, block.positions, kin, None, None, None, run.rows, run.outcome.valid)
    machine = not (np.any(block.mechanism.gravity) or block.mechanism.loads
                   or block.mechanism.springs)
    bound = columns.bound(block.mechanism, whole, machine, 361)
    assert top <= bound < 1e3 * top + 1e3


def test_each_variant_unwraps_its_link_angles_as_alone():
    """A crank's angle wraps at ±π in every variant: each variant's unwrapping starts
    afresh (as a sweep of it alone), not on from the variant before."""
    rows = np.deg2rad(np.array([[170.0, -170.0, -150.0], [10.0, 179.0, -179.0]]))
    each = columns.EachVariant(3)(rows.reshape(-1)).reshape(2, 3)
    for k in range(2):
        np.testing.assert_array_equal(each[k], columns.Continuous()(rows[k]))


def test_stages_that_couple_positions_run_variant_by_variant():
    variants = _variants("fourbar.toml", [{"friction.coefficient": 0.1,
                                           "friction.pin_radius": 10}] * 2)
    with pytest.raises(NotStackable):
        pipeline.prepare_variants(stack(variants, 361), 2)
