"""The notes of a sweep are data (kind, subject, ranges, figures); the report words them
(``dyade.report.notes``), one sentence each."""

from __future__ import annotations

import numpy as np
import pytest

import dyade
from dyade.linkage.notes import NoteKind
from dyade.report.notes import WORDS, say
from tests.conftest import MECHANISMS, SHIPPED


def test_every_kind_of_note_has_words():
    assert set(WORDS) == set(NoteKind)


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_every_note_of_a_shipped_mechanism_is_worded(path):
    result = dyade.analyse(dyade.read_mechanism(path), allow_partial=True,
                           start_deg=0.0, stop_deg=360.0, step_deg=0.5)
    for note in result.notes:
        text = say(note, result.mechanism)
        assert isinstance(note.kind, NoteKind) and text.endswith(".")
        assert "{" not in text and "}" not in text


def test_a_note_names_its_ranges_in_the_sweeps_decimals():
    result = dyade.analyse(dyade.read_mechanism(MECHANISMS / "self-locking.toml"),
                           step_deg=0.05)
    lock, = [note for note in result.notes if note.kind == "self_locking"]
    assert lock.figures["digits"] == 2
    (first, last), = lock.ranges
    assert f"{np.rad2deg(first):.2f}°–{np.rad2deg(last):.2f}°" in say(lock, result.mechanism)
    assert repr(lock.kind) == "'self_locking'"  # prints as the string it equals
