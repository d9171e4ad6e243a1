"""Option parsers shared by the commands."""

from __future__ import annotations

import click

MAX_VALUES = 10_000_000


def value_range(text: str, hint: str, unit: str, positive_start: bool = False) -> list[float]:
    """Parse START:STOP:STEP into the list of values (STOP included)."""
    import numpy as np

    try:
        start, stop, step = (float(part) for part in text.split(":"))
    except ValueError:
        raise click.BadParameter(f"must be START:STOP:STEP{unit}, got {text!r}.",
                                 param_hint=hint) from None
    low = "0 < START" if positive_start else "0 <= START"
    if not (step > 0 and stop >= start and (start > 0 if positive_start else start >= 0)):
        raise click.BadParameter(f"needs {low} <= STOP and STEP > 0, got {text!r}.",
                                 param_hint=hint)
    count = int(np.floor((stop - start) / step + 1e-9)) + 1
    if count > MAX_VALUES:
        raise click.BadParameter(f"asks for {count} values; at most {MAX_VALUES}.", param_hint=hint)
    return (start + step * np.arange(count)).tolist()
