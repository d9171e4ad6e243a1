"""START:STOP:STEP options (speeds [rpm], frequencies [Hz]) read into their values, one
rule for every entry: refused naming the option (its API name; the command line names
its flag), and beyond what a machine has (``dyade.limits.PLAUSIBLE``) where a quantity
is named.

This module imports no numpy at import time.
"""

from __future__ import annotations

MOST = 10_000_000  # [-] values a range may have (the memory bound comes later)


def values(text: str, api: str, unit: str, quantity: str | None = None,
           positive_start: bool = False) -> list[float]:
    """The values of ``text`` (START:STOP:STEP, STOP included) of the option ``api`` in
    ``unit``; an ``InputError`` on ``api`` saying what is wrong, or, for a ``quantity``
    of ``dyade.limits.PLAUSIBLE``, where STOP lies beyond what a machine has.

    >>> values("100:300:100", "speed_range_rpm", "rpm")
    [100.0, 200.0, 300.0]
    """
    from dyade.errors import InputError
    from dyade.files.schema import value_range

    try:
        out = value_range(text, f" [{unit}]" if unit else "", positive_start, MOST)
    except ValueError as err:
        raise InputError.parameter(api, str(err), value=text, unit=unit or None) from None
    if quantity is not None:
        from dyade.limits import PLAUSIBLE

        low, high, _ = PLAUSIBLE[quantity]
        low = low if positive_start else 0.0  # a range that may start at rest says so
        if out[-1] > high or positive_start and out[0] < low:
            raise InputError.parameter(api, f"must stay within {low:g}…{high:g} {unit} "
                                            f"(what a machine has), got {text!r}.",
                                       value=text, unit=unit or None)
    return out
