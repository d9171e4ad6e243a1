"""``dyade clearance``: the joint-clearance peak check (Dresig & Thümmel); the registry's
``clearance-peak``, ``clearance-check`` and ``clearance-speeds`` entries
(``dyade.analyses.clearance``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, NamedTuple

import click

from dyade.analyses.clearance import ENTRIES, SPEED_RANGE
from dyade.cli import contract, main
from dyade.cli.batch import SUFFIX, SWEEP, batch
from dyade.cli.options import MECHANISM_FILE, jobs_option

PEAK, CHECK, SPEEDS = (ENTRIES[name] for name in ("clearance-peak", "clearance-check",
                                                  "clearance-speeds"))
STANDALONE_ONLY = ("slope", "speed_rpm")
"""options of the standalone check that a mechanism gives itself"""


def parse_joint(text: str) -> tuple[int, int]:
    """``--joint I,J`` as (a, b), a < b; refused naming the flag."""
    from dyade.analyses.clearance import JOINT, joints_of
    from dyade.errors import InputError

    try:
        return joints_of({JOINT.api: (text,)})[0]
    except InputError as err:
        raise click.BadParameter(err.reason, param_hint="--joint") from None


def clearance_options(command):
    """Decorate a command with the options of the three clearance entries, each once
    (``-j``, shared with batches of files, is the command's), shared with ``dyade plot
    clearance``."""
    for option in reversed(contract.declared((SPEEDS, PEAK), skip=("jobs",))):
        command = contract.click_option(option)(command)
    return command


def source_of(path: str):
    """A mechanism file's path, or standard input's text for "-"."""
    if str(path) != "-":
        return path
    import sys

    from dyade.analyses.inputs import Text

    return Text(sys.stdin.read())


def entry_for(files: bool, options: dict[str, Any]):
    """The entry the command's options ask for, refusing options that do not apply."""
    given = {name for name, value in contract.options_of_declared(
        SPEEDS.every_option + PEAK.every_option, options).items()}
    if not files:
        extra = sorted(given - {option.api for option in PEAK.every_option})
        if extra:
            flags = contract.flags(SPEEDS)
            raise click.UsageError(f"{', '.join(flags[name] for name in extra)}: for a check "
                                   f"over a mechanism; give a mechanism file.")
        return PEAK
    if given & set(STANDALONE_ONLY):
        raise click.UsageError("--slope and --speed are for the standalone check; over a "
                               "mechanism the slope comes from its joint forces.")
    return SPEEDS if options.get(SPEED_RANGE.api) else CHECK


def tables(outcome):
    """The command's table of an Outcome of one of its entries."""
    from dyade.report import clearance as report

    if outcome.analysis == "clearance-peak":
        return [report.standalone_table(outcome)]
    return [report.mechanism_table(outcome)]


@main.command()
@click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1)
@clearance_options
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: one row (record) per reversal.")
@click.option("-o", "--output", type=click.Path(writable=True, path_type=Path),
              help="Write the result to this file instead of standard output; with several "
                   "mechanism files a directory with one result per file.")
@jobs_option
def clearance(mechanism_files: tuple[str, ...], fmt: str, output: Path | None, jobs: int,
              **options) -> None:
    """Peak force in a revolute joint with clearance (Dresig & Thümmel, eq. (36)).

    Where a joint force reverses its sense, the pin crosses the clearance 2s and strikes
    the bearing. Standalone, from four numbers:

    \b
        dyade clearance --mass 3.6 --stiffness 1e7 --clearance 1e-4 --slope 360000

    gives the paper's 2182 N. Over a mechanism (the rigid forces from its kinetostatics):

    \b
        dyade clearance mechanisms/dyade-16.toml --stiffness 1e8 --clearance 1e-4

    checks every revolute joint: the dominant line of action of its force, whether the
    force keeps to it (else the model does not apply, and dyade says why), and for each
    reversal the slope F0/t0 = |dF/dφ21|·Ω, τ, f(τ), the peak and its amplification over
    the rigid force. Impacts per revolution = number of reversals.
    """
    entry = entry_for(bool(mechanism_files), options)
    if entry is PEAK:
        OverMechanism(PEAK.name, options, fmt)(None, output)
        return
    if len(mechanism_files) == 1 and not (output and output.is_dir()):
        OverMechanism(entry.name, {**options, "jobs": jobs}, fmt)(mechanism_files[0], output)
        return
    from dyade.errors import DyadeError

    if output is None:
        raise click.UsageError(f"{len(mechanism_files)} mechanism files need -o DIR.")
    output.mkdir(parents=True, exist_ok=True)
    run_one = OverMechanism(entry.name, options, fmt)  # the files in parallel, not their speeds
    failures = batch(mechanism_files, output, run_one, SUFFIX[fmt], jobs,
                     SWEEP + ("dyade.linkage.joint_clearance", "dyade.analyses.clearance",
                              "dyade.report.clearance"))
    if failures:
        lines = "\n".join(f"  {path}: {reason}" for path, reason in failures)
        raise DyadeError(f"{len(failures)} of {len(mechanism_files)} files failed:\n{lines}")


class OverMechanism(NamedTuple):
    """One run of a clearance entry (its name) with the command's options on one file
    (None: standalone), written as ``fmt`` asks (picklable, for -j)."""

    entry: str
    options: dict
    fmt: str

    def __call__(self, path, target=None, _: object = None) -> None:
        entry = ENTRIES[self.entry]
        source = None if path is None else source_of(path)
        outcome = contract.run(entry, source, self.options)
        contract.emit(outcome, self.fmt, target, tables(outcome) if self.fmt == "table" else None)
        contract.notes(outcome)
