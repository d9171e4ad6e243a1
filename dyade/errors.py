"""Exceptions that dyade explains to its users.

``DyadeError`` is an analysis problem (exit 1), ``InputError`` a bad file or option
(exit 2). Anything else that escapes is a bug and keeps its traceback.
"""

from __future__ import annotations


class DyadeError(Exception):
    """A problem dyade can explain: the mechanism cannot be analysed as asked."""


class InputError(DyadeError, ValueError):
    """Bad input: a file, key or option that must be fixed by the user."""


class AssemblyError(DyadeError):
    """A dyad cannot close (or is blocked) over part of the crank sweep."""
