"""The mechanism file as TOML: its data with ``--set`` overrides, its text with them
applied (``--save-as``: comments and layout kept) and mechanism data written as TOML."""

from __future__ import annotations

import os
from typing import Any

from dyade.files.schema import load_data as schema_load_data
from dyade.files.schema import set_dotted

NUMBERING = {"dyad": (2, "dyads are numbered as in DYADE: the crank is dyad 1, the first "
                         "[[dyad]] table dyad 2")}
"""arrays of tables whose entries are not numbered from 1, for keys and overrides"""


def load_data(path: str | os.PathLike, overrides: dict[str, Any] | None = None,
              what: str = "override", text: str | None = None) -> dict[str, Any]:
    """The file's TOML data with ``overrides`` (dotted key -> value, dyads numbered as in
    DYADE) applied; ``what`` names them in messages; ``text``: the file's content when
    already read (stdin)."""
    return schema_load_data(path, overrides, what, text, NUMBERING)


def edited(text: str, overrides: dict[str, Any], label: str = "mechanism",
           what: str = "override", removals: tuple[str, ...] | list[str] = ()) -> str:
    """The file's text with ``overrides`` applied (and the dotted keys of ``removals``
    removed), everything else kept: comments, key order, inline tables, short arrays on
    one line (``--save-as``; tomlkit edits the parsed document in place)."""
    import tomlkit

    document = tomlkit.parse(text)
    for key in removals:
        *path, last = key.split(".")
        table = document
        for part in path:
            table = table[part]
        del table[last]
    for key, value in overrides.items():
        set_dotted(document, key, value, label, what, NUMBERING)
    return tomlkit.dumps(document)


def dumps(data: dict[str, Any]) -> str:
    """Mechanism data (a dict with the keys of a mechanism file) as TOML text."""
    import tomlkit

    return tomlkit.dumps(data)
