"""A study's variants as an axis of the sweep pipeline (issue 41): every row of a run of
stacked variants (``pipeline.prepare_variants``) equals the row of the variant evaluated
alone (its own reading, ``analyse`` and summary) to the bit, the variants that do not
close, meet a dead centre or hold implausible values included (the same validity
policy, bands and plausibility check decide per variant); refused variants are read
alone; stages that couple positions (friction) run variant by variant."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from dyade.files.mechanism import load_data
from dyade.linkage.stack import pick, same
from dyade.study.evaluate import Evaluator
from tests.helpers import shipped
from tests.strategies import chained_files


def _pair(name, keys, data=None):
    data = data if data is not None else load_data(shipped(name))
    together = Evaluator(str(shipped(name)), data, keys)
    alone = Evaluator(str(shipped(name)), data, keys)
    alone.stacks = False
    return together, alone


def _assert_same_rows(rows, want):
    assert [r[:3] for r in rows] == [w[:3] for w in want]
    for (_, _, _, got), (_, _, _, expected) in zip(rows, want):
        assert set(got) == set(expected)
        for name, value in expected.items():
            if np.isnan(value):
                assert np.isnan(got[name]), name
            else:  # to the bit: the same pipeline, per variant
                assert got[name] == value, name


def _uniform(rng, bounds, count):
    return np.column_stack([rng.uniform(lo, hi, count) for lo, hi in bounds])


CASES = {
    "four-bar lengths": ("fourbar.toml", ("dyad.2.lengths.1", "dyad.2.lengths.2"),
                         [(190, 210), (140, 160)]),
    "slider-crank": ("slider-crank.toml", ("dyad.2.length", "crank.length", "links.4.mass"),
                     [(150, 170), (36, 44), (0.3, 0.8)]),
    "dyade-16 (every kind)": ("dyade-16.toml", ("dyad.2.lengths.2", "dyad.7.lengths.1",
                                                "frame.points.C0.2"),
                              [(146, 154), (158, 163), (-144, -136)]),
    "slotted lever": ("slotted-lever.toml", ("dyad.2.B.offset",), [(-4, 5)]),
    "dyade-16 masses (gravity, loads, springs)": (
        "dyade-16.toml", ("links.8.mass", "links.3.inertia", "links.5.mass"),
        [(0.5, 1.5), (0.001, 0.01), (0.2, 2.0)]),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_stacked_block_gives_the_rows_of_each_variant_alone(case):
    name, keys, bounds = CASES[case]
    values = _uniform(np.random.default_rng(7), bounds, 24)
    together, alone = _pair(name, keys)
    rows = together((5, values))
    assert together.together == 24 and together.calls == 24  # all in one sweep
    _assert_same_rows(rows, alone((5, values)))


def test_masses_centres_and_the_speed_stack_too():
    data = load_data(shipped("fourbar.toml"))
    data["links"]["2"] = {"mass": 0.6, "centre": [0.0, 0.0]}
    keys = ("links.2.centre.1", "links.2.centre.2", "links.4.centre.1", "links.3.mass",
            "crank.speed_rpm")
    values = _uniform(np.random.default_rng(3), [(-100, 50), (-20, 20), (-150, 0), (0.5, 2),
                                                 (100, 600)], 30)
    together, alone = _pair("fourbar.toml", keys, data)
    rows = together((0, values))
    assert together.together == 30
    _assert_same_rows(rows, alone((0, values)))


def test_variants_that_do_not_close_or_meet_a_dead_centre_in_the_stacked_run():
    """Refused (a negative length: the block is read variant by variant and stacked;
    the reader's refusal comes from reading it alone), not closing (the pipeline's
    assembly check names it, as a sweep of it alone does), and at a dead centre
    (coupler + rocker = frame + crank: the rigid model has no value there, the
    pipeline's band leaves those positions out of that variant only)."""
    values = np.array([[200, 150], [-5, 150], [100, 150], [170, 130], [195, 152],
                       [250, 150], [201, 151]], dtype=float)
    together, alone = _pair("fourbar.toml", ("dyad.2.lengths.1", "dyad.2.lengths.2"))
    rows = together((0, values))
    want = alone((0, values))
    _assert_same_rows(rows, want)
    assert [r[1] for r in rows] == ["ok", "refused", "does not close", "ok", "ok", "ok", "ok"]
    assert together.together == 6  # all but the refused one in the one run
    assert rows[2][2].startswith("dyad 2")  # the pipeline's reason, as alone
    assert np.isnan(rows[3][3]["mu_2_min_deg"]) or rows[3][3]["mu_2_min_deg"] < 2.0


@pytest.mark.parametrize("overrides, output", [
    ({"friction.coefficient": 0.1, "friction.pin_radius": 10}, "P_friction_mean"),
    ({"drive_line.stiffness": 1000.0}, "M_drive_rms")])
def test_friction_and_drive_lines_are_swept_variant_by_variant(monkeypatch, overrides, output):
    """A file with friction (each variant's own Newton solve) or an elastic drive line
    (whose check a single sweep makes per variant) is never stacked: the stacked sweep
    does not even run."""
    from dyade.linkage import pipeline

    def forbidden(*args, **kwargs):
        raise AssertionError("the study was stacked")

    monkeypatch.setattr(pipeline, "prepare_variants", forbidden)
    data = load_data(shipped("fourbar.toml"), overrides)
    together = Evaluator(str(shipped("fourbar.toml")), data, ("dyad.2.lengths.1",))
    rows = together((0, np.array([[198.0], [202.0]])))
    assert [r[1] for r in rows] == ["ok", "ok"] and together.together == 0
    assert output in rows[0][3]


def test_the_block_read_at_once_is_each_variant_read_alone():
    data = load_data(shipped("fourbar.toml"))
    data["links"]["2"] = {"mass": 0.6, "centre": [0.0, 0.0]}
    keys = ("dyad.2.lengths.1", "links.2.centre.1", "links.3.inertia", "crank.speed_rpm",
            "crank.length")
    values = _uniform(np.random.default_rng(5), [(190, 210), (-60, 0), (0.002, 0.006),
                                                 (200, 400), (45, 55)], 12)
    evaluator = Evaluator(str(shipped("fourbar.toml")), data, keys)
    together = evaluator.read_together(values)
    assert together is not None
    for index, row in enumerate(values):
        assert same(pick(together, index), evaluator.mechanism(row), rtol=0.0) == ""


def test_a_reading_that_differs_is_not_used(monkeypatch):
    """The block read at once is checked against its first and last variant read alone:
    a reader that took an array differently would be caught (here: a mechanism that is
    one bit off) and the block read variant by variant."""
    evaluator = Evaluator(str(shipped("fourbar.toml")), load_data(shipped("fourbar.toml")),
                          ("dyad.2.lengths.1",))
    values = np.array([[199.0], [201.0]])
    assert evaluator.read_together(values) is not None
    build = evaluator.mechanism

    def off(row):
        import dataclasses

        mechanism = build(row)
        crank = dataclasses.replace(mechanism.crank, length=mechanism.crank.length * (1 + 1e-12))
        return dataclasses.replace(mechanism, crank=crank)

    monkeypatch.setattr(evaluator, "mechanism", off)
    assert evaluator.read_together(values) is None


def test_a_study_sweeps_its_variants_in_blocks(tmp_path):
    """The API's study of 1000 four-bar variants: every variant in a stacked sweep, in
    blocks of whole sweeps."""
    import dyade
    from dyade.study import run

    path = tmp_path / "study.toml"
    path.write_text(f'mechanism = "{shipped("fourbar.toml")}"\n[plan]\nkind = "monte-carlo"\n'
                    f'samples = 1000\nseed = 2\n[parameters]\n'
                    f'"dyad.2.lengths.1" = {{ uniform = [195, 205] }}\n')
    calls = []
    original = run.Evaluator.swept_together

    def counting(self, values, *args):
        calls.append(len(values))
        return original(self, values, *args)

    import unittest.mock

    with unittest.mock.patch.object(run.Evaluator, "swept_together", counting):
        result = dyade.study(str(path))
    assert (result.columns()["status"] == "ok").all()
    assert sum(calls) >= 1000 and max(calls) <= 200 and min(calls) > 1


def test_a_variant_beyond_the_plausible_has_no_values_there():
    """At 3e7 rpm the accelerations pass 1e12 (``columns.PLAUSIBLE``): a single run
    gives those rows no values, and so does the pipeline's plausibility check for that
    variant in the stacked run (and for no other); every position is withheld there: the
    variant's status says so (issue 42)."""
    values = np.array([[300.0], [2e6], [3e7]])
    together, alone = _pair("fourbar.toml", ("crank.speed_rpm",))
    rows = together((0, values))
    _assert_same_rows(rows, alone((0, values)))
    assert rows[2][1] == "withheld" and "M_drive_max" not in rows[2][3]
    assert together.together == 3
    assert not np.isnan(rows[1][3]["M_drive_max"])


def test_kinematics_only_variants_at_a_dead_centre():
    """Without masses only the kinematics is swept: the dead-centre band itself (not the
    forces' validity) takes the positions of the 170.03/130 variant (smallest
    transmission angle 1.6°, inside the 2° band, not singular) out, in the stacked run
    as alone."""
    data = load_data(shipped("fourbar.toml"))
    del data["links"]
    values = np.array([[200.0, 150.0], [170.03, 130.0], [195.0, 152.0]])
    together, alone = _pair("fourbar.toml", ("dyad.2.lengths.1", "dyad.2.lengths.2"), data)
    rows = together((0, values))
    _assert_same_rows(rows, alone((0, values)))
    assert together.together == 3 and "M_drive_max" not in rows[0][3]


def _numbers(data, prefix=""):
    """The dotted key paths (as ``--set`` numbers them: dyads from 2, list entries from
    1) of every float of a mechanism's data."""
    if isinstance(data, dict):
        for key, value in data.items():
            yield from _numbers(value, f"{prefix}{key}.")
    elif isinstance(data, list):
        first = 2 if prefix == "dyad." else 1
        for index, value in enumerate(data, start=first):
            yield from _numbers(value, f"{prefix}{index}.")
    elif isinstance(data, float):
        yield prefix[:-1], data


@pytest.mark.slow
@given(data=chained_files(), picks=st.lists(st.integers(0, 10_000), min_size=1, max_size=3),
       scatter=st.lists(st.floats(-1.0, 1.0), min_size=12, max_size=12))
def test_random_chains_stacked_as_each_variant_alone(data, picks, scatter):
    """Random two-dyad chains (every kind, on any placed links, with masses and maybe
    gravity): a block of 6 variants, 1 to 3 of the file's numbers scattered by ±2 %,
    gives each variant's own row (its status, reason and every key result), whatever
    the stacked sweep vouches for."""
    numbers = dict(_numbers(data))
    keys = sorted({list(numbers)[k % len(numbers)] for k in picks})
    scale = data["crank"]["length"]
    values = np.array([[numbers[key] * (1 + 0.02 * u) + (0.0 if numbers[key] else 0.02 * u * scale)
                        for key, u in zip(keys, scatter[6 * i % 12:])] for i in range(6)])
    together = Evaluator("random.toml", data, tuple(keys))
    alone = Evaluator("random.toml", data, tuple(keys))
    alone.stacks = False
    _assert_same_rows(together((0, values)), alone((0, values)))


def test_a_variant_has_the_figures_it_has_alone():
    """A slotted lever whose crank (200 mm) passes its pivot distance turns its lever
    right round: no swing, no time ratio — its row has none of those keys, beside a
    variant that has them (from the review of the stacked path)."""
    together, alone = _pair("slotted-lever.toml", ("crank.length",))
    values = np.array([[60.0], [200.0]])
    rows = together((0, values))
    _assert_same_rows(rows, alone((0, values)))
    assert together.together == 2
    assert "swing_4_deg" in rows[0][3] and "swing_4_deg" not in rows[1][3]


def test_a_dead_centre_band_that_differs_between_variants():
    """`sweep.dead_centre` as a parameter: each variant is judged by its own band (a
    kinematics-only file of four dyads at two positions, where one band per position
    once lined up with the dyads instead)."""
    data = load_data(shipped("dyade-16.toml"))
    data["sweep"] = {"start": 161, "stop": 162, "step": 1}
    data["links"] = {}
    for key in ("load", "spring", "gravity"):
        data.pop(key)
    data["dyad"] = [data["dyad"][i] for i in (0, 1, 5, 3)]
    data["crank"]["points"] = {k: data["crank"]["points"][k] for k in ("P2", "P4", "P5")}
    together, alone = _pair("dyade-16.toml", ("sweep.dead_centre",), data)
    values = np.array([[31.0], [2.0]])
    _assert_same_rows(together((0, values)), alone((0, values)))
    assert together.together == 2  # the 31° band holds a dyad: in that variant only
