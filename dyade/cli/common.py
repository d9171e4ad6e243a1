"""What the commands share: a mechanism file read with --set and the sweep options,
--save-as, the output format from -o, the API's errors named as the options give them,
and the analysis notes as warnings on stderr."""

from __future__ import annotations

import math
import os
import sys
from typing import Any, NamedTuple

import click

from dyade.cli.output import atomic, flags

FLAGS = {"friction_tol": "--friction-tol", "friction_max_iter": "--friction-max-iter",
         "start": "--start", "stop": "--stop", "step": "--step",
         "sweep": "the sweep (--start, --stop, --step)", "max_memory": "--max-memory",
         "dead_centre_deg": "--dead-centre",
         "transmission_warning_deg": "--transmission-warning",
         "run_up": "--run-up", "block_size": "--block-size"}
"""API parameter -> the flag it comes from"""


class SweepOptions(NamedTuple):
    """--start/--stop/--step [°], None where not given. (Option bundles are NamedTuples:
    each is 0.4 ms cheaper to create at start-up than a frozen dataclass.)"""

    start: float | None = None
    stop: float | None = None
    step: float | None = None


class Loaded(NamedTuple):
    """A mechanism as read, with what --save-as needs to write it again."""

    mechanism: Any
    text: str
    """the file's text as read (or standard input's)"""
    overrides: dict[str, Any]
    """--set key -> value"""
    label: str


def read_input(path: str) -> tuple[str, str]:
    """The text of an input file, or of standard input for "-"; and its name."""
    from dyade.files import schema

    if path == "-":
        return sys.stdin.read(), "<stdin>"
    return schema.read_text(path), path


def load(path: str, assignments: tuple[str, ...] = (), sweep: SweepOptions = SweepOptions(),
         text: str | None = None) -> Loaded:
    """Read a mechanism ("-": standard input) with --set overrides and
    --start/--stop/--step [°]; ``text``: standard input's content, when already read."""
    from dyade.files import mechanism as reader
    from dyade.files import schema
    from dyade.linkage.options import with_sweep

    overrides = dict(schema.parse_assignment(a) for a in assignments)
    text, label = (text, "<stdin>") if text is not None else read_input(path)
    data = reader.load_data(label, overrides, "--set", text)
    mechanism = reader.build(data, label)
    if sweep.start is None and sweep.stop is None and sweep.step is None:
        return Loaded(mechanism, text, overrides, label)
    current = mechanism.sweep  # the sweep options are in degrees whatever the file's unit
    start = math.radians(sweep.start) if sweep.start is not None else current.start
    stop = (math.radians(sweep.stop) if sweep.stop is not None
            else (start + 2 * math.pi if sweep.start is not None else current.stop))
    step = math.radians(sweep.step) if sweep.step is not None else current.step
    if step <= 0:
        raise click.BadParameter(f"must be positive, got {sweep.step:g}.", param_hint="--step")
    if stop < start:
        raise click.BadParameter(f"must not be below the start angle, got {sweep.stop:g}.",
                                 param_hint="--stop")
    if sweep.step is not None and stop > start and step > stop - start:
        raise click.BadParameter(f"{sweep.step:g}° is larger than the sweep "
                                 f"({math.degrees(start):g}° to {math.degrees(stop):g}°), which "
                                 f"would give one position: give a step of at most "
                                 f"{math.degrees(stop - start):g}°.", param_hint="--step")
    with flags(FLAGS):
        return Loaded(with_sweep(mechanism, start, stop, step), text, overrides, label)


def save_as(loaded: Loaded, path: str) -> None:
    """Write the effective mechanism (after --set) as TOML, atomically: the input's text
    with the overridden values replaced, its comments and layout kept."""
    from dyade.files.mechanism import edited

    text = edited(loaded.text, loaded.overrides, os.path.basename(loaded.label), "--set")
    with atomic(path) as handle:
        handle.write("# written by dyade --save-as: the effective mechanism after --set\n")
        handle.write(text)


FORMATS = {".csv": "csv", ".json": "json", ".txt": "table", ".parquet": "parquet", "": "csv"}
"""suffix of -o -> format (no suffix, or a directory: csv)"""


def infer_format(output: str | None) -> str:
    """table on stdout; with -o, from the suffix (.csv, .json, .txt); an unknown suffix
    is an error that lists the formats."""
    if output is None or output == "-":
        return "table"
    if os.path.isdir(output):
        return "csv"
    suffix = os.path.splitext(output)[1].lower()
    if suffix not in FORMATS:
        raise click.BadParameter(f"{output}: dyade does not write {suffix} files. It writes "
                                 f".csv (the sweep), .json (columns, units, summary, warnings) "
                                 f", .txt (the summary table) and .parquet (the sweep, "
                                 f"with units); or give --format table|csv|json|parquet.", param_hint="-o")
    return FORMATS[suffix]



class options_named:
    """Errors of the API named as the options give them: flags for parameters, and a
    partial closure suggests --allow-partial."""

    def __enter__(self) -> None:
        pass

    def __exit__(self, exc_type, exc, tb) -> bool:
        from dyade.errors import AssemblyError, InputError

        if isinstance(exc, InputError):
            raise exc.naming(FLAGS) from None
        if isinstance(exc, AssemblyError) and exc.partial:
            raise AssemblyError("; ".join(exc.problems) + ". Change the dimensions or the "
                                "sweep, or use --allow-partial to analyse only where it "
                                "closes.", exc.problems, exc.partial) from None
        return False


def sweep(mechanism, allow_partial: bool, friction_tol: float | None = None,
          friction_max_iter: int | None = None, **options):
    """``dyade.analyse`` with the options' names in its errors (a partial closure
    suggests --allow-partial); ``options``: its other keywords."""
    from dyade.linkage.sweep import analyse

    with options_named():
        return analyse(mechanism, allow_partial=allow_partial, friction_tol=friction_tol,
                       friction_max_iter=friction_max_iter, **options)


def warn(notes, mechanism, prefix: str = "") -> None:
    """A sweep's notes (of ``mechanism``) worded, on stderr as warnings
    (``dyade.cli.writers.warn``)."""
    from dyade.cli.writers import warn as warn_words
    from dyade.report.notes import say

    warn_words([say(note, mechanism) for note in notes], prefix)
