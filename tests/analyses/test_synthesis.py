"""The ``synthesis`` entry: its progress (the rate and the best error so far) and its
options over the file's."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.errors import DyadeError
from dyade.files.synthesis import parse


def test_progress_tells_the_rate_and_the_best_error():
    # a self-crossing star no four-bar comes near: the search runs, no fit follows
    tips = np.exp(1j * (np.pi / 2 + 4 * np.pi / 5 * np.arange(6)))
    star = np.concatenate([a + (b - a) * np.linspace(0, 1, 8, endpoint=False)
                           for a, b in zip(tips[:-1], tips[1:])])
    problem = parse({"target": {"kind": "path", "points": [[z.real, z.imag] for z in star]},
                     "bounds": {"a": [0.1, 0.12], "b": [2.5, 3], "c": [2.5, 3],
                                "p": [0, 0.1], "q": [0, 0.1]},
                     "search": {"candidates": 800, "block": 200, "rounds": 1}})
    heard, notes = [], []
    with pytest.raises(DyadeError, match="of 400 candidates"):
        dyade.run("synthesis", problem, seed=3, candidates=400,
                  progress=lambda done, total: heard.append((done, total)),
                  note=notes.append)
    assert heard == [(200, 400), (400, 400)]  # --candidates over the file's
    assert len(notes) == 2 and "candidates/s, best error" in notes[-1]
