"""Option parsers shared by the commands."""

from __future__ import annotations

import click

MAX_VALUES = 10_000_000


class Number(click.ParamType):
    """A finite number (nan and inf are refused where they are typed), optionally
    positive or within a range."""

    name = "number"

    def __init__(self, positive: bool = False, low: float | None = None,
                 high: float | None = None) -> None:
        self.positive, self.low, self.high = positive, low, high

    def convert(self, value, param, ctx) -> float:
        import math

        try:
            number = float(value)
        except (TypeError, ValueError):
            self.fail(f"must be a number, got {value!r}.", param, ctx)
        if not math.isfinite(number):
            self.fail(f"must be a finite number, got {value!r}.", param, ctx)
        if self.positive and number <= 0.0:
            self.fail(f"must be positive, got {value!r}.", param, ctx)
        if self.low is not None and number < self.low or self.high is not None and number > self.high:
            self.fail(f"must lie in {self.low:g}…{self.high:g}, got {value!r}.", param, ctx)
        return number


FINITE = Number()
POSITIVE = Number(positive=True)


def value_range(text: str, hint: str, unit: str, positive_start: bool = False) -> list[float]:
    """Parse START:STOP:STEP into the list of values (STOP included)."""
    import math

    import numpy as np

    try:
        start, stop, step = (float(part) for part in text.split(":"))
    except ValueError:
        raise click.BadParameter(f"must be START:STOP:STEP{unit}, got {text!r}.",
                                 param_hint=hint) from None
    low = "0 < START" if positive_start else "0 <= START"
    if not all(math.isfinite(v) for v in (start, stop, step)):
        raise click.BadParameter(f"needs finite numbers, got {text!r}.", param_hint=hint)
    if not (step > 0 and stop >= start and (start > 0 if positive_start else start >= 0)):
        raise click.BadParameter(f"needs {low} <= STOP and STEP > 0, got {text!r}.",
                                 param_hint=hint)
    count = int(np.floor((stop - start) / step + 1e-9)) + 1
    if count > MAX_VALUES:
        raise click.BadParameter(f"asks for {count} values; at most {MAX_VALUES}.", param_hint=hint)
    return (start + step * np.arange(count)).tolist()
