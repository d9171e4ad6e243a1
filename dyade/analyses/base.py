"""The contract every analysis keeps (issue 36): its options declared once, and one
``Outcome`` for what it found.

An analysis is an ``Analysis`` entry of the registry (``dyade.registry.REGISTRY``): a
name, a one-line purpose, its ``Option`` declarations and a function from (an input,
options) to an ``Outcome``. The command line's options, the API's keyword arguments,
the study's keys and the report's section all come from the declarations; the table,
the CSV, the JSON, Parquet, the HTML report and a study's row all come from the
Outcome. A new analysis is one entry: nothing else moves.

Names. An option is declared by its command-line name (``step``); its API name carries
its unit (``step_deg``): ``api_name`` and ``flag_name`` map one to the other, one
documented way (``UNIT_SUFFIX``). Values at the API are in the units their names say;
everything inside is SI.

This module imports no numpy at import time (the command line lists the options of an
entry for ``--help`` without it).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from dyade.errors import DyadeError, InputError

SCHEMA_VERSION = 2
"""the version of the JSON document (``Outcome.to_document``); 1 was each command's own
shape before issue 36"""

MISSING = "—"
"""how a table shows a value that is not given (not ``nan``, not an empty cell)"""

UNIT_SUFFIX = {"°": "deg", "rpm": "rpm", "MB": "mb", "s": "s", "Hz": "hz", "%": "percent"}
"""unit -> the suffix the API name of an option in that unit carries: ``--step`` [°] is
``step_deg``, ``--max-memory`` [MB] ``max_memory_mb``, ``--max-time`` [s]
``max_time_s``, ``--speed`` [rpm] ``speed_rpm``. Options in other units (SI, or none)
keep their name. A flag never carries its unit (its help says it); the API name always
does."""


def api_name(flag: str, unit: str) -> str:
    """An option's API keyword from its command-line name and unit:
    ``api_name("step", "°") == "step_deg"``; ``api_name("friction-tol", "") ==
    "friction_tol"``."""
    base = flag.lstrip("-").replace("-", "_")
    suffix = UNIT_SUFFIX.get(unit)
    return f"{base}_{suffix}" if suffix else base


def flag_name(name: str, unit: str) -> str:
    """The command-line flag of an API keyword (the inverse of ``api_name``):
    ``flag_name("step_deg", "°") == "--step"``."""
    suffix = UNIT_SUFFIX.get(unit)
    if suffix and name.endswith("_" + suffix):
        name = name[: -len(suffix) - 1]
    return "--" + name.replace("_", "-")


@dataclass(frozen=True)
class Option:
    """One option of an analysis, declared once.

    ``name`` is the command-line name without dashes (``step``, ``friction-tol``); the
    API keyword is ``api`` (``step_deg``), the flag ``flag`` (``--step``).
    """

    name: str
    kind: type | tuple[str, ...]
    """float, int, bool, str, or a tuple of the choices (strings)"""
    unit: str = ""
    """the unit the value is given in (°, rpm, MB, s, N·m, …); "" for none"""
    default: Any = None
    """None: not given (the file's value, or the analysis decides)"""
    help: str = ""
    """one sentence or two for ``--help`` and the docs, without the unit and default
    (they are added from ``unit`` and ``default``)"""
    multiple: bool = False
    """given several times (``--joint 5,6 --joint 7,8``): a tuple at the API"""
    metavar: str | None = None
    positive: bool = False
    """a number that must be above 0"""
    least: int = 1
    """a positive whole number's smallest allowed value (``--help`` shows the range)"""
    study: bool = True
    """a study file may vary it"""
    old: tuple[str, ...] = ()
    """former flags, still accepted for one release but not shown (``--speed-rpm``)"""

    @property
    def api(self) -> str:
        return api_name(self.name, self.unit)

    @property
    def flag(self) -> str:
        return "--" + self.name

    @property
    def text(self) -> str:
        """The help text with the unit and the default, as ``--help`` shows it."""
        unit = f" [{self.unit}]" if self.unit else ""
        default = "" if self.default in (None, False, ()) else f"  [default: {self.default}]"
        return f"{self.help}{unit}{default}"

    def check(self, value: Any) -> Any:
        """The value as the analysis takes it (an int stays int), refused with an
        ``InputError`` on the API name where it has the wrong kind."""
        if value is None or self.kind is bool and isinstance(value, bool):
            return value
        if self.multiple:
            values = value if isinstance(value, (list, tuple)) else (value,)
            return tuple(Option(self.name, self.kind, self.unit, positive=self.positive,
                                least=self.least).check(v) for v in values)
        if isinstance(self.kind, tuple):
            if value not in self.kind:
                raise InputError.parameter(self.api, f"must be one of {', '.join(self.kind)}, "
                                                     f"got {value!r}.", value=value)
            return value
        if self.kind in (float, int):
            try:
                number = self.kind(value) if not isinstance(value, bool) else None
            except (TypeError, ValueError, OverflowError):
                number = None
            if number is None or (self.kind is int and number != value) \
                    or not math.isfinite(number):
                what = "a whole number" if self.kind is int else "a finite number"
                raise InputError.parameter(self.api, f"must be {what}"
                                                     f"{f' [{self.unit}]' if self.unit else ''}, "
                                                     f"got {value!r}.", value=value,
                                           unit=self.unit or None)
            if self.positive and not number > 0:
                raise InputError.parameter(self.api, f"must be positive"
                                                     f"{f' [{self.unit}]' if self.unit else ''}, "
                                                     f"got {value!r}.", value=value,
                                           unit=self.unit or None)
            if self.positive and self.kind is int and number < self.least:
                raise InputError.parameter(self.api, f"must be at least {self.least}, got "
                                                     f"{value!r}.", value=value)
            return number
        if self.kind is bool and not isinstance(value, bool):
            raise InputError.parameter(self.api, f"must be True or False, got {value!r}.",
                                       value=value)
        return value


MAX_MEMORY = Option("max-memory", float, "MB", 4096.0, positive=True, metavar="MB",
                    help="Refuse, before computing, a run estimated to need more memory",
                    study=False)
MAX_TIME = Option("max-time", float, "s", None, positive=True, metavar="S",
                  help="Refuse, before computing, a run estimated to take longer (the "
                       "estimate is said before any run above a few seconds)", study=False)
COMMON = (MAX_MEMORY, MAX_TIME)
"""the options every analysis has: the bounds of a run"""


@dataclass(frozen=True)
class Column:
    """One column of an Outcome: a value per row (a crank position, a frequency, a
    speed, a variant)."""

    name: str
    values: Any
    """ndarray, shape (rows,), SI (angles in degrees where the name says ``_deg``)"""
    unit: str = ""
    description: str = ""


@dataclass(frozen=True)
class Figure:
    """One figure of an Outcome's summary: a value, its unit, where it occurs."""

    name: str
    value: Any
    """a number (SI, or the unit in the name), a flag (bool), a text, or None when not
    given (a table shows ``MISSING``)"""
    unit: str = ""
    where: Mapping[str, Any] | None = None
    """where the figure occurs, e.g. ``{"angle_deg": 37.0}``; None: everywhere or
    nowhere in particular"""
    description: str = ""
    limit: float | None = None
    """a bound the figure is checked against (same unit), shown beside it"""


@dataclass
class Outcome:
    """What an analysis found, in one shape for every writer.

    ``columns`` maps a name to its values (ndarray, shape (rows,)); ``units`` and
    ``descriptions`` give each column's unit and meaning. ``summary`` maps a name to its
    ``Figure``. ``notes`` are worded (dead centres, self-locking, resonances, what was
    not computed and why). ``figures`` names the plot kinds (``dyade plot KIND``) that
    can draw it. ``meta`` says what was analysed (the file, the mechanism's name).
    ``result`` keeps the engine's own result for the figures and the report (not
    written by any writer).

    Examples
    --------
    >>> import dyade
    >>> outcome = dyade.run("coupling", None, J=1.0, c1=1.0, c2=1.0, b1=0.05, b2=0.05)
    >>> outcome.units["V_phi"], outcome.summary["V_phi_max"].where
    ('-', {'eta': 0.71})
    >>> sorted(outcome.to_document())[:4]
    ['analysis', 'columns', 'meta', 'notes']
    """

    analysis: str
    columns: Mapping[str, Any] = field(default_factory=dict)
    units: Mapping[str, str] = field(default_factory=dict)
    descriptions: Mapping[str, str] = field(default_factory=dict)
    summary: dict[str, Figure] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    figures: tuple[str, ...] = ()
    meta: dict[str, Any] = field(default_factory=dict)
    options: dict[str, Any] = field(default_factory=dict)
    """the options the analysis ran with (API names)"""
    result: Any = None

    def column(self, name: str) -> Column:
        return Column(name, self.columns[name], self.units.get(name, ""),
                      self.descriptions.get(name, ""))

    def add(self, name: str, value: Any, unit: str = "", where: Mapping[str, Any] | None = None,
            description: str = "", limit: float | None = None) -> None:
        """Put a figure in the summary."""
        self.summary[name] = Figure(name, value, unit, where, description, limit)

    def value(self, name: str) -> Any:
        """A summary figure's value (None where it is not given)."""
        figure = self.summary.get(name)
        return None if figure is None else figure.value

    def to_document(self) -> dict[str, Any]:
        """The JSON document, one shape for every analysis (docs/reference/json.md):

        ``{"columns": {name: [values]}, "units": {name: unit}, "summary": {name:
        {"value", "unit", "where"}}, "notes": [...], "analysis", "options", "meta",
        "schema"}``; numbers to 15 significant digits, NaN and infinities null.
        Columns stay arrays here (the command line writes them a block at a time).
        """
        return {"columns": self.columns,
                "units": {name: self.units.get(name, "") for name in self.columns},
                "summary": {name: figure_document(figure) for name, figure in self.summary.items()},
                "notes": [str(note) for note in self.notes],
                "analysis": self.analysis,
                "options": jsonable(self.options),
                "meta": jsonable(self.meta),
                "schema": SCHEMA_VERSION}


def figure_document(figure: Figure) -> dict[str, Any]:
    """A summary figure as the JSON document writes it."""
    out = {"value": jsonable(figure.value), "unit": figure.unit}
    if figure.where is not None:
        out["where"] = jsonable(dict(figure.where))
    if figure.limit is not None:
        out["limit"] = jsonable(figure.limit)
    return out


def jsonable(value: Any) -> Any:
    """numpy values and floats as JSON values: numbers to 15 significant digits (as the
    CSV: no 3.0000000000000004 where the CSV says 3); NaN and ±inf null (as is a value
    within 1e-15 of the largest double, whose 15 digits read back as inf)."""
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if hasattr(value, "tolist") and not isinstance(value, (int, float, bool, str)):
        return jsonable(value.tolist())
    if isinstance(value, bool) or value is None or isinstance(value, (int, str)):
        return value
    if isinstance(value, float):
        rounded = float(f"{value + 0.0:.15g}")
        return rounded if math.isfinite(rounded) else None
    return value


def cell(value: Any) -> str:
    """One CSV field, the one rule of every CSV dyade writes (``report.format`` re-exports
    it; a study's journal writes by it too): 15 significant digits, empty for a value not
    given (None, NaN, ±inf), 1/0 for flags, text as it is (quoted where it holds a comma,
    a quote or a line break).

    >>> [cell(v) for v in (300.0, 0.1 + 0.2, float("nan"), True, -0.0, "a, b")]
    ['300', '0.3', '', '1', '0', '"a, b"']
    """
    if value is None:
        return ""
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return "1" if value else "0"
    if isinstance(value, str):
        return '"' + value.replace('"', '""') + '"' if any(c in value for c in ',"\n') else value
    value = float(value)
    return f"{value + 0.0:.15g}" if math.isfinite(value) else ""


@dataclass
class Budget:
    """The bounds of one run and its progress, as every analysis gets them.

    ``max_memory`` [B] and ``max_time`` [s] (None: no time bound); ``progress(done,
    total)`` is called as the work goes on (the command line draws a bar on a
    terminal), ``note(text)`` with words on how it goes where the analysis has them (a
    study's or a synthesis's rate, a synthesis's best error so far: the command line
    writes them beside the bar) right after the ``progress`` they belong to (``step``
    calls both); ``told(text)`` hears the estimate of a run above ``SAY_ABOVE`` seconds
    before it starts (the command line prints it on stderr). Every callback an API
    caller gives has these signatures, whichever entry runs.
    """

    max_memory: float | None = None
    max_time: float | None = None
    progress: Callable[[float, float | None], None] = lambda done, total=None: None
    told: Callable[[str], None] = lambda text: None
    note: Callable[[str], None] = lambda text: None

    def step(self, done: float, total: float | None, note: str | None = None) -> None:
        """``progress(done, total)``, then ``note(note)`` where there are words."""
        self.progress(done, total)
        if note:
            self.note(note)

    SAY_ABOVE = 5.0  # [s] a run estimated above this is announced with its estimate

    def time(self, seconds: float, what: str) -> None:
        """Check a run estimated at ``seconds`` against ``max_time`` (an InputError on
        ``max_time_s`` above it: nothing has run) and announce it above ``SAY_ABOVE``."""
        if self.max_time is not None and not seconds <= self.max_time:
            raise InputError.parameter(
                MAX_TIME.api, f"is {self.max_time:g} s, and {what} would take about "
                              f"{seconds:.3g} s. Ask for less, or raise the bound.",
                value=self.max_time, unit="s")
        if seconds > self.SAY_ABOVE:
            self.told(f"{what}: about {seconds:.3g} s.")


def budget(options: Mapping[str, Any], **callbacks: Any) -> Budget:
    """The Budget of the common options (API names) of a run."""
    memory = options.get(MAX_MEMORY.api)
    return Budget(None if memory is None else memory * 2 ** 20, options.get(MAX_TIME.api),
                  **callbacks)


@dataclass(frozen=True)
class Analysis:
    """An entry of the registry: an analysis with its options declared once.

    ``run(source, options, budget) -> Outcome``: ``source`` is a file path, a model
    object (a ``Mechanism``, a ``Coupling``, a ``GearDrive``) or None where the options
    hold the whole input; ``options`` the checked options by API name (defaults filled
    in), ``budget`` the run's bounds. ``source`` says what the entry reads:
    ``"mechanism"``, ``"gears"``, ``"coupling"``, ``"study"``, or ``""`` (none).
    """

    name: str
    title: str
    run: Callable[..., Outcome]
    options: tuple[Option, ...] = ()
    source: str = "mechanism"
    figures: tuple[str, ...] = ()
    command: str = ""
    """the command line that runs it (``dyade analyse``, ``dyade driveline --analysis
    steady``)"""

    @property
    def every_option(self) -> tuple[Option, ...]:
        return self.options + COMMON

    def option(self, api: str) -> Option:
        for option in self.every_option:
            if option.api == api:
                return option
        raise KeyError(api)

    def checked(self, given: Mapping[str, Any]) -> dict[str, Any]:
        """The options by API name with the defaults filled in; an unknown keyword is
        refused naming the close ones (an old name: its new one)."""
        known = {option.api: option for option in self.every_option}
        unknown = [name for name in given if name not in known]
        if unknown:
            import difflib

            name = unknown[0]
            close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
            renamed = {flag_name(o.api, o.unit).lstrip("-").replace("-", "_"): o.api
                       for o in self.every_option}
            hint = (f" It is {renamed[name]} (the unit in the name)." if name in renamed
                    else f" Did you mean {close[0]}?" if close else "")
            raise InputError.parameter(name, f"is not an option of {self.name}.{hint} Its "
                                             f"options: {', '.join(known)}.", value=given[name])
        return {api: option.check(given.get(api, option.default)) for api, option in known.items()}

    def __call__(self, source: Any = None, *, progress: Callable | None = None,
                 told: Callable[[str], None] | None = None,
                 note: Callable[[str], None] | None = None, **options: Any) -> Outcome:
        """Run the analysis from Python: ``REGISTRY["sweep"](path, step_deg=1)``;
        ``progress(done, total)`` hears how far it is, ``note(text)`` how it goes (a
        rate, a best error so far), ``told(text)`` the time estimate of a long run. The
        command line runs it the same way (``dyade.cli.contract``)."""
        checked = self.checked(options)
        callbacks = {name: f for name, f in (("progress", progress), ("told", told),
                                             ("note", note)) if f is not None}
        outcome = self.run(source, checked, budget(checked, **callbacks))
        outcome.options = {k: v for k, v in checked.items() if v is not None}
        return outcome


def withheld(outcome: Outcome, given: Iterable[bool] | Any, what: str) -> None:
    """The rule every analysis shares: a run whose every position (speed, frequency) is
    withheld exits 1 saying so, never a table of zeros or blanks. ``given`` is the
    mask of the rows that have their values; ``what`` names them ("no crank position of
    the sweep has its forces given")."""
    import numpy as np

    mask = np.asarray(given, dtype=bool)
    if mask.size and not mask.any():
        reasons = "; ".join(outcome.notes[:3])
        raise DyadeError(f"{what}{f' ({reasons})' if reasons else ''}: nothing to report.")
