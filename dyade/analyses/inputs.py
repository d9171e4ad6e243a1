"""What the entries of a mechanism file share: the file (or a ``Mechanism``) read with
its overrides (``set``), the sweep's range in degrees (``start_deg``, ``stop_deg``,
``step_deg``), and ``allow_partial``. One rule for every command and the API: a sweep
of one position is refused here (``dyade.linkage.options.sweep_in_degrees``), single
positions are asked for by their angles (``at_deg``)."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from dyade.analyses.base import Option

SET = Option("set", str, multiple=True, metavar="KEY=VALUE", study=False,
             help="Override a key of the file without editing it, with its dotted path as in "
                  "the file (repeatable): --set crank.speed_rpm=600 --set "
                  "dyad.2.lengths=[200,150]. Validated like the file")
START = Option("start", float, "°", metavar="DEG",
               help="First crank angle (overrides [sweep] start)")
STOP = Option("stop", float, "°", metavar="DEG", help="Last crank angle (default: start + 360)")
STEP = Option("step", float, "°", metavar="DEG", positive=True,
              help="Crank angle step (overrides [sweep] step)")
ALLOW_PARTIAL = Option("allow-partial", bool, study=False,
                       help="Analyse only the crank angles where every dyad closes; the others "
                            "are left out (and said) instead of failing")
SWEEP = (START, STOP, STEP)
"""the sweep's range, in degrees whatever the file's unit"""
MECHANISM = (SET,)
"""the options of every entry that reads a mechanism file"""


@dataclass(frozen=True)
class Text:
    """A mechanism file's text given directly (standard input): ``label`` names it in
    messages (``<stdin>``)."""

    text: str
    label: str = "<stdin>"


@dataclass
class Loaded:
    """A mechanism as read, with what ``--save-as`` needs to write it again."""

    mechanism: Any
    text: str | None = None
    """the file's text as read (None: given as a Mechanism)"""
    overrides: dict[str, Any] = field(default_factory=dict)
    """``set`` key -> value"""
    label: str = ""
    """the file as messages name it"""


def load(source: Any, options: dict[str, Any]) -> Loaded:
    """The mechanism of ``source`` (a path, a ``Text`` or a ``Mechanism``) with the
    ``set`` overrides and the sweep options (``start_deg``, ``stop_deg``, ``step_deg``)
    of ``options`` applied."""
    from dyade.errors import InputError
    from dyade.files import mechanism as reader
    from dyade.files import schema
    from dyade.linkage.options import sweep_in_degrees

    assignments = options.get(SET.api) or ()
    if hasattr(source, "dyads"):  # a Mechanism
        if assignments:
            raise InputError.parameter(SET.api, "needs a mechanism file (it overrides the "
                                                "file's keys); change the Mechanism instead.")
        loaded = Loaded(source, None, {}, getattr(source, "name", ""))
    else:
        if source is None:
            raise InputError("no mechanism file given.")
        overrides = dict(schema.parse_assignment(a) for a in assignments)
        if isinstance(source, Text):
            text, label = source.text, source.label
        else:
            label = os.fspath(source)
            text = schema.read_text(label)
        data = reader.load_data(label, overrides, "--set", text)
        loaded = Loaded(reader.build(data, label), text, overrides, label)
    loaded.mechanism = sweep_in_degrees(loaded.mechanism, options.get(START.api),
                                        options.get(STOP.api), options.get(STEP.api))
    return loaded
