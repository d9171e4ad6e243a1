"""Design studies (issue 26) against their yardsticks, side by side in one run:

    pytest tests/benchmarks/test_study_speed.py -m benchmark --benchmark-enable \
        --benchmark-columns=min,median,rounds

- four-bar variants: ``dyade.study`` of 10 000 variants × 361 positions (the file
  read once per block, the variants an axis of the sweep pipeline:
  ``dyade.linkage.pipeline.prepare_variants``) against the numpy yardstick that
  broadcasts the four-bar's closed form over variants × positions
  (``yardstick.fourbar_variants``: every output the study gives, checked in
  tests/study/test_yardstick.py). Target (issue 41): within 1.2x (1.63x before);
- dyade-16 with friction: a study's cost per variant against ``read_mechanism`` and
  ``dyade.analyse`` of each variant in the same process (target ≤ 1.1x);
- ``-j 2`` against ``-j 1`` on a study of about 10 s (dyade-16 with friction; target
  ≤ 0.6x; needs 2 free cores).

Under CI=true (timing disabled, each body run once) the problems are a tenth as large.
"""

from __future__ import annotations

import os

import numpy as np
import pytest

import dyade
from tests.benchmarks.yardstick import fourbar_variants
from tests.helpers import shipped

SMALL = os.environ.get("CI") == "true"  # CI: each body once, a tenth of the size
VARIANTS = 1_000 if SMALL else 10_000
JOBS_VARIANTS = 60 if SMALL else 600
BLOCK = 200  # variants per stacked sweep: 72 200 positions, the arrays in cache
FRICTION = ('"friction.coefficient" = 0.1, "friction.pin_radius" = 10, '
            '"friction.slider_length" = 40, "friction.slider_height" = 20')


def _fourbar_study(tmp_path, samples: int) -> str:
    path = tmp_path / "fourbar-study.toml"
    path.write_text(f'mechanism = "{shipped("fourbar.toml")}"\n'
                    f'[plan]\nkind = "monte-carlo"\nsamples = {samples}\nseed = 1\n'
                    f'[parameters]\n"dyad.2.lengths.1" = {{ uniform = [195, 205] }}\n'
                    f'"dyad.2.lengths.2" = {{ uniform = [145, 155] }}\n')
    return str(path)


def test_fourbar_variants_yardstick(benchmark):
    rng = np.random.default_rng(1)
    r3, r4 = rng.uniform(0.195, 0.205, VARIANTS), rng.uniform(0.145, 0.155, VARIANTS)
    out = benchmark.pedantic(fourbar_variants, args=(r3, r4, np.deg2rad(np.arange(361.0)),
                                                     10 * np.pi), rounds=5, warmup_rounds=1)
    assert out["M_drive_rms"].shape == (VARIANTS,)


def test_fourbar_variants_study(benchmark, tmp_path):
    path = _fourbar_study(tmp_path, VARIANTS)
    result = benchmark.pedantic(dyade.study, args=(path,), rounds=5, warmup_rounds=1)
    assert (result.columns()["status"] == "ok").all()


@pytest.fixture
def dyade16_study(tmp_path):
    path = tmp_path / "dyade16-study.toml"
    path.write_text(f'mechanism = "{shipped("dyade-16.toml")}"\nset = {{ {FRICTION} }}\n'
                    f'[parameters]\n"dyad.2.lengths.2" = {{ range = [145, 155], count = 40 }}\n')
    return str(path)


def test_dyade16_friction_study(benchmark, dyade16_study):
    result = benchmark.pedantic(dyade.study, args=(dyade16_study,), rounds=5, warmup_rounds=1)
    assert len(result.columns()["variant"]) == 40


def test_dyade16_friction_single_runs(benchmark):
    overrides = {"friction.coefficient": 0.1, "friction.pin_radius": 10,
                 "friction.slider_length": 40, "friction.slider_height": 20}

    def each():
        for length in np.linspace(145, 155, 40):
            mechanism = dyade.read_mechanism(shipped("dyade-16.toml"),
                                             dict(overrides, **{"dyad.2.lengths.2": length}))
            dyade.analyse(mechanism)

    benchmark.pedantic(each, rounds=5, warmup_rounds=1)


@pytest.mark.parametrize("jobs", [1, 2])
def test_study_jobs(benchmark, tmp_path, jobs):
    """A study of about 10 s on one core: dyade-16 with friction (variant by variant),
    600 variants."""
    path = tmp_path / "dyade16-jobs.toml"
    path.write_text(f'mechanism = "{shipped("dyade-16.toml")}"\nset = {{ {FRICTION} }}\n'
                    f'[parameters]\n"dyad.2.lengths.2" = {{ range = [140, 160], count = {JOBS_VARIANTS} }}\n')
    result = benchmark.pedantic(dyade.study, args=(str(path),), kwargs={"jobs": jobs},
                                rounds=1, iterations=1)
    assert len(result.columns()["variant"]) == JOBS_VARIANTS


@pytest.fixture(scope="module")
def fourbar_variants_built():
    rng = np.random.default_rng(1)
    r3, r4 = rng.uniform(195, 205, VARIANTS), rng.uniform(145, 155, VARIANTS)
    return [dyade.read_mechanism(shipped("fourbar.toml"),
                                 {"dyad.2.lengths.1": a, "dyad.2.lengths.2": b})
            for a, b in zip(r3, r4)]


def test_fourbar_variants_stacked_engine(benchmark, fourbar_variants_built):
    """The engine's part of a batched study: the 10 000 variants stacked in blocks of
    ``BLOCK`` into one mechanism each (``dyade.linkage.stack``), each block's kinematics
    and forces one sweep of BLOCK × 361 positions (without the mechanism files' reading,
    the columns and the summary, which a study still runs per variant)."""
    from dyade.linkage import kinematics, kinetostatics
    from dyade.linkage.stack import stack

    variants = fourbar_variants_built
    positions = variants[0].sweep.count
    angle = np.tile(variants[0].sweep.angles(), BLOCK)

    def engine():
        torque = []
        for first in range(0, len(variants), BLOCK):
            together = stack(variants[first:first + BLOCK], positions)
            kin = kinematics.sweep(together, angle)
            torque.append(kinetostatics.solve(together, kin).drive_torque)
        return np.concatenate(torque)

    torque = benchmark.pedantic(engine, rounds=3, iterations=1)
    assert torque.shape == (VARIANTS * positions,) and np.isfinite(torque).all()
