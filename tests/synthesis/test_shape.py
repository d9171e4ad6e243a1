"""The shape distance: free of start point, direction, placement and scale; the
similarity it recovers is the one that made the copy."""

from __future__ import annotations

import numpy as np

from dyade.synthesis.shape import closed_match, resample, timed_match

T = np.linspace(0.0, 2.0 * np.pi, 720, endpoint=False)
CURVE = np.exp(1j * T) + 0.3 * np.exp(2j * T) + 0.1j * np.exp(-3j * T)


def test_a_moved_turned_scaled_restarted_copy_matches_with_its_similarity():
    target = resample(CURVE[None, :], 64)[0]
    factor = 2.0 * np.exp(0.7j)
    copy = np.roll(CURVE * factor + (3 - 1j), 170)
    other = np.exp(1j * T) + 0.5 * np.exp(-2j * T)  # another shape
    match = closed_match(target, resample(np.stack([copy, copy[::-1], other]), 64))
    assert match.error[0] < 2e-3 and match.error[1] < 1e-2  # discretisation only
    assert match.error[2] > 0.1
    assert abs(match.factor[0] * factor - 1) < 5e-3  # the similarity undone
    assert not match.reversed[0] and match.reversed[1]
    rigid = closed_match(target, resample(copy[None, :], 64), scale=False)
    assert rigid.error[0] > 0.5  # twice the size: not matched without scale


def test_the_timed_match_finds_the_crank_zero():
    crank = np.deg2rad(np.arange(0.0, 150.0, 10.0))
    curve = CURVE[::10]  # 72 samples of a turn, 5° apart
    target = (curve[(5 + 2 * np.arange(15)) % 72] * 0.5 * np.exp(-0.2j)) + 1.0
    match = timed_match(target, crank, curve[None, :])
    assert match.shift[0] == 5 and match.error[0] < 1e-6  # (the root of a round-off)
    assert abs(match.factor[0] - 0.5 * np.exp(-0.2j)) < 1e-12
