"""The words of a sweep's notes, for the writers: ``say(note, mechanism)``. They are
written once, in ``dyade.analyses.notes`` (an analysis words its notes in its
Outcome); this module gives the writers and the API's users the same function."""

from __future__ import annotations

from dyade.analyses.notes import WORDS, say

__all__ = ["WORDS", "say"]
