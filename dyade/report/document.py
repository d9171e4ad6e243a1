"""The one JSON shape of every command: columns, units, summary, warnings, meta.

``{"columns": {name: [...]}, "units": {name: unit}, "summary": {...}, "warnings": [...],
"meta": {...}}`` so that ``pandas.DataFrame(j["columns"])`` is the table; numbers are
written as in the CSV (15 significant digits), NaN and infinities as null
(``dyade.cli.output.jsonable``).
"""

from __future__ import annotations

from typing import Any


def document(command: str, columns: dict[str, Any], units: dict[str, str],
             summary: dict[str, Any], warnings: list[str], **meta: Any) -> dict[str, Any]:
    """The JSON document of a command's result."""
    from dyade import __version__

    return {"columns": columns, "units": {name: units.get(name, "") for name in columns},
            "summary": summary, "warnings": [str(w) for w in warnings],
            "meta": {"command": command, "dyade": __version__, **meta}}
