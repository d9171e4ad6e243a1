"""The command line of a registry entry (``dyade.analyses``): its options made from the
entry's declarations (``declare``), the entry run with errors naming the flags and a
progress bar on a terminal (``run``), the Outcome written as the format asks
(``emit``). A command is these three and its own table layout, nothing else."""

from __future__ import annotations

from typing import Any

import click

from dyade.analyses.base import COMMON, Analysis, Option
from dyade.cli.options import FINITE, POSITIVE, Renamed

TYPES = {float: FINITE, int: int, str: str}


def click_option(option: Option, hidden: bool = False):
    """The click option of a declaration: flag ``--name``, parameter named by its API
    name (``--step`` -> ``step_deg``), the unit and default in its help."""
    kwargs: dict[str, Any] = {"help": option.text, "metavar": option.metavar,
                              "multiple": option.multiple, "hidden": hidden}
    if option.old:  # former flags: accepted, not shown
        kwargs.update(cls=Renamed, old=option.old)
    if option.kind is bool:
        return click.option(option.flag, option.api, is_flag=True, help=option.text,
                            hidden=hidden, **({"cls": Renamed, "old": option.old}
                                              if option.old else {}))
    if isinstance(option.kind, tuple):
        kwargs["type"] = click.Choice(option.kind)
    elif option.kind is float:
        kwargs["type"] = POSITIVE if option.positive else FINITE
    elif option.kind is int:
        kwargs["type"] = click.IntRange(min=option.least) if option.positive else int
    else:
        kwargs["type"] = str
    return click.option(option.flag, option.api, default=None, **kwargs)


def declare(entry: Analysis, skip: tuple[str, ...] = ()):
    """Decorate a command with the entry's options (its own and the common ones), less
    those named in ``skip`` (API names the command declares itself)."""
    def decorate(command):
        for option in reversed(entry.every_option):
            if option.api not in skip:
                command = click_option(option)(command)
        return command

    return decorate


def flags(entry: Analysis) -> dict[str, str]:
    """API name -> flag, for the errors of a run."""
    return {option.api: option.flag for option in entry.every_option}


def options_of(entry: Analysis, params: dict[str, Any]) -> dict[str, Any]:
    """The API options among a command's click parameters (a flag not given: absent)."""
    return options_of_declared(entry.every_option, params)


def options_of_declared(options, params: dict[str, Any]) -> dict[str, Any]:
    """The API options of the declarations ``options`` among a command's click
    parameters (a flag not given, or a flag not set: absent)."""
    names = {option.api for option in options}
    return {name: (tuple(value) if isinstance(value, list) else value)
            for name, value in params.items()
            if name in names and value is not None and value != () and value is not False}


def run(entry: Analysis, source: Any, params: dict[str, Any], what: str = "", **extra):
    """Run ``entry`` on ``source`` with the command's ``params`` (click's, by API name):
    errors name the flags; a progress bar on a terminal; the time estimate of a long run
    on stderr."""
    from dyade.cli.output import console, flags as naming, progress

    options = options_of(entry, params)
    err = console(stderr=True)
    with naming(flags(entry)), progress(what or entry.title) as tick:
        return entry(source, progress=tick, note=tick.note,
                     told=lambda text: err.print(text, markup=False),
                     **options, **extra)


def emit(outcome, fmt: str, output: str | None, tables=None, width: int | None = None) -> None:
    """Write ``outcome`` as ``fmt`` asks: ``json`` its document, ``csv`` its columns,
    ``table`` the renderables ``tables`` (default: its summary and columns, generic)."""
    from dyade.cli.output import atomic, show, to_file, write_json

    if fmt == "json":
        write_json(outcome.to_document(), output)
    elif fmt == "csv":
        import sys

        from dyade.report.outcome import write_csv

        if to_file(output):
            with atomic(output) as handle:
                write_csv(outcome, handle)
        else:
            write_csv(outcome, sys.stdout)
    else:
        if tables is None:
            from dyade.report.outcome import columns_table, summary_table

            tables = [summary_table(outcome, outcome.analysis),
                      columns_table(outcome, outcome.analysis)]
        show(tables, output, width=width)


def notes(outcome, prefix: str = "") -> None:
    """The Outcome's notes on stderr."""
    from dyade.cli.output import console

    err = console(stderr=True)
    for note in outcome.notes:
        err.print(f"{prefix}{note}", markup=False)


def declared(entries, skip: tuple[str, ...] = ()) -> list:
    """The options of ``entries``, each once, in the entries' order, the common ones
    (``--max-memory``, ``--max-time``) last; less those in ``skip`` (API names)."""
    out, seen = [], set(skip) | {option.api for option in COMMON}
    for entry in entries:
        for option in entry.options:
            if option.api not in seen:
                seen.add(option.api)
                out.append(option)
    return out + [option for option in COMMON if option.api not in skip]
