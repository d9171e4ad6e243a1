"""Path generation by search: the seeded blocks, the recovery of a four-bar from its own
coupler curve (up to its Roberts–Chebyshev cognates), a straight-line stretch against
Hoeken's linkage, and the targets a topology cannot reach."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.errors import DyadeError, InputError
from dyade.files.mechanism import build
from dyade.files.synthesis import parse
from dyade.linkage.positions import positions
from dyade.synthesis import closed, synthesise
from dyade.synthesis.search import Block, Settings, draw, merge, run_blocks
from dyade.synthesis.shape import SAMPLES, resample
from dyade.synthesis.topology import FourBar, Placement, fourbar_from_points

BOUNDS = {"a": (0.1, 1.0), "b": (0.3, 3.0), "c": (0.3, 3.0), "d": (1.0, 1.0),
          "p": (-2.0, 2.0), "q": (-2.0, 2.0)}


def lengths(data: dict) -> np.ndarray:
    """(a, b, c, d) of a four-bar's mechanism data [m]."""
    frame = data["frame"]["points"]
    d = np.hypot(frame["B0"][0] - frame["A0"][0], frame["B0"][1] - frame["A0"][1])
    return np.array([data["crank"]["length"], *data["dyad"][0]["lengths"], d])[[0, 1, 2, 3]]


def test_the_same_seed_gives_the_same_candidates_in_any_block_order():
    settings = Settings(bounds=BOUNDS, candidates=300, block=100, seed=7)
    names = FourBar().names
    assert np.array_equal(draw(settings, names, 2), draw(settings, names, 2))
    assert not np.array_equal(draw(settings, names, 1), draw(settings, names, 2))
    lhs = draw(settings, names, 0)[:, 0]  # one point per stratum of the hypercube
    strata = np.floor((lhs - 0.1) / 0.9 * 100).astype(int)
    assert sorted(strata) == list(range(100))
    target = np.exp(1j * np.linspace(0, 2 * np.pi, 40, endpoint=False))
    block = Block(FourBar(), settings, resample(target[None, :], SAMPLES)[0])
    parts = run_blocks(block, [0, 1, 2])
    assert np.array_equal(merge(parts, 10).number, merge(parts[::-1], 10).number)


@pytest.mark.slow
def test_recovers_a_fourbar_from_60_points_of_its_coupler_curve():
    linkage = closed.FourBar(a=0.35, b=1.2, c=0.9, d=1.0, p=0.6, q=0.4, variant=1)
    place = Placement(0.03 + 0.02j, 0.2, 0.5)  # 200 mm frame, turned by 0.5 rad
    crank = 0.7 + np.linspace(0.0, 2 * np.pi, 60, endpoint=False)  # start unknown
    points = place.apply(FourBar().path(np.array([0.35, 1.2, 0.9, 1.0, 0.6, 0.4]), 1,
                                        crank)[0])
    problem = parse({"target": {"kind": "path", "points": [[z.real, z.imag] for z in points]},
                     "search": {"candidates": 6000, "seed": 1}, "output": {"keep": 1}})
    result = synthesise(problem)
    cognates = []
    for cognate in closed.cognates(linkage):
        (f0, f1), (m0, m1), p = cognate.fixed, cognate.moving, cognate.point
        values, _, _, _ = fourbar_from_points(f0, m0, m1, f1, p)
        cognates.append(values[:4] * place.scale)
    best = lengths(result.designs[0].data)
    misses = [np.abs(best / c - 1).max() for c in cognates]
    assert min(misses) < 1e-6, misses
    # a region about the original's crank pivot leaves only the original
    problem = parse({"target": {"kind": "path", "points": [[z.real, z.imag] for z in points]},
                     "regions": {"A0": [[0.02, 0.04], [0.01, 0.03]]},
                     "search": {"candidates": 6000, "seed": 1}, "output": {"keep": 1}})
    placed = synthesise(problem).designs[0].data
    assert np.abs(lengths(placed) / cognates[0] - 1).max() < 1e-6
    assert placed["frame"]["points"]["A0"] == pytest.approx([0.03, 0.02], abs=1e-9)
    # ... and its mechanism file traces the target through dyade's engine
    design = result.designs[0]
    mechanism = build(design.data)
    found = positions(mechanism, design.fitted.crank + design.fitted.placement.angle,
                      [(3, mechanism.links[3].points["P"])])
    traced = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
    assert np.abs(traced - points).max() < 1e-9 * 0.2


def hoeken_deviation(window_deg: float = 120.0) -> float:
    """Hoeken's straight-line linkage (crank 1, frame 2, coupler 2.5, rocker 2.5, the
    tracing point on the coupler's extension 5 from the crank pin): its largest
    deviation from the best straight line over the length, over its best window."""
    turn = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)
    a = np.exp(1j * turn)
    ac = 2.0 - a
    along = np.abs(ac) / 2  # isosceles: coupler = rocker = 2.5
    b = a + ac / np.abs(ac) * along + 1j * ac / np.abs(ac) * np.sqrt(2.5 ** 2 - along ** 2)
    p = a + 2.0 * (b - a)
    return best_straightness(p, int(window_deg * 10) + 1)


def best_straightness(path: np.ndarray, window: int) -> float:
    """min over windows of (largest distance from the total-least-squares line) / the
    extent along it, each window's line by an SVD."""
    best = np.inf
    for start in range(0, path.size, 5):
        z = np.take(path, np.arange(start, start + window), mode="wrap")
        xy = np.column_stack([z.real, z.imag])
        xy = xy - xy.mean(axis=0)
        _, _, vt = np.linalg.svd(xy, full_matrices=False)
        along, across = xy @ vt[0], xy @ vt[1]
        best = min(best, np.abs(across).max() / np.ptp(along))
    return best


@pytest.mark.slow
def test_a_straight_line_stretch_no_worse_than_hoeken():
    hoeken = hoeken_deviation(120.0)
    assert 1e-4 < hoeken < 1e-2  # the textbook linkage is straight to about 0.2 %
    problem = parse({"target": {"kind": "line", "stretch": 120},
                     "search": {"candidates": 4000, "rounds": 1, "seed": 2},
                     "output": {"keep": 1}})
    design = synthesise(problem).designs[0]
    start, stop = design.stretch
    mechanism = build(design.data)
    crank = np.linspace(start, stop, 1201)
    found = positions(mechanism, crank, [(3, mechanism.links[3].points["P"])])
    assert found.closes.all()
    path = found.points[:, 0, 0] + 1j * found.points[:, 0, 1]
    ours = best_straightness(np.concatenate([path, path[::-1]]), 1201)
    assert ours <= hoeken, (ours, hoeken)
    assert design.error == pytest.approx(ours, rel=0.05)


def test_bounds_that_let_no_linkage_assemble_are_refused():
    problem = parse({"target": {"kind": "line", "stretch": 90},
                     "bounds": {"a": [2, 3], "b": [0.1, 0.2], "c": [0.1, 0.2]},
                     "search": {"candidates": 200, "block": 100, "rounds": 1}})
    with pytest.raises(InputError, match="none of the 200 candidates assembles") as err:
        synthesise(problem)
    assert err.value.key == "bounds"


def test_regions_no_placed_candidate_meets_are_said():
    points = np.exp(1j * np.linspace(0, 2 * np.pi, 30, endpoint=False)) * (1 + 0.3j)
    problem = parse({"target": {"kind": "path", "points": [[z.real, z.imag] for z in points]},
                     "regions": {"A0": [[50, 51], [50, 51]]},
                     "search": {"candidates": 200, "block": 100, "rounds": 1}})
    with pytest.raises(DyadeError, match=r"frame pivots within the \[regions\]"):
        synthesise(problem)


def test_a_path_the_topology_cannot_reach_says_the_best_error():
    # a five-pointed star drawn in one stroke (it crosses itself five times), and links
    # too short to come near it
    tips = np.exp(1j * (np.pi / 2 + 4 * np.pi / 5 * np.arange(6)))
    star = np.concatenate([a + (b - a) * np.linspace(0, 1, 8, endpoint=False)
                           for a, b in zip(tips[:-1], tips[1:])])
    problem = parse({"target": {"kind": "path", "points": [[z.real, z.imag] for z in star]},
                     "bounds": {"a": [0.1, 0.12], "b": [2.5, 3], "c": [2.5, 3],
                                "p": [0, 0.1], "q": [0, 0.1]},
                     "search": {"candidates": 400, "block": 200, "rounds": 1},
                     "output": {"keep": 1}})
    with pytest.raises(DyadeError, match=r"deviates by [\d.]+ % RMS of the path's size") as err:
        synthesise(problem)
    assert not isinstance(err.value, InputError)


@pytest.mark.slow
def test_a_dask_cluster_gives_the_same_best_candidates_as_one_process():
    distributed = pytest.importorskip("distributed")
    from dyade.synthesis.search import search

    points = np.exp(1j * np.linspace(0, 2 * np.pi, 30, endpoint=False))
    points = points + 0.3 * points ** 2
    settings = Settings(bounds=BOUNDS, candidates=1000, block=250, seed=4, rounds=2)
    here = search(FourBar(), points, settings)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        there = search(FourBar(), points, settings, executor=client.get_executor())
    assert np.array_equal(here.number, there.number)
    assert np.array_equal(here.error, there.error)


@pytest.mark.slow
def test_a_stretch_the_topology_cannot_keep_says_the_best_deviation():
    # a crank as long as the coupler and the rocker, the coupler point on the coupler's
    # line near the rocker: its curve swings round and never runs straight for 200°
    problem = parse({"target": {"kind": "line", "stretch": 200},
                     "bounds": {"a": [0.9, 1], "b": [1, 1.1], "c": [1, 1.1],
                                "p": [0.9, 1], "q": [0, 0.05]},
                     "search": {"candidates": 200, "block": 100, "rounds": 1},
                     "output": {"keep": 1}})
    with pytest.raises(DyadeError, match=r"keeps to a straight line over 200° of crank: the "
                                         r"best of 200 candidates .* deviates by ([\d.]+) % of"
                       ) as err:
        synthesise(problem)
    assert not isinstance(err.value, InputError)
