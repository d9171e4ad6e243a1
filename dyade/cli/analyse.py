"""``dyade analyse`` and ``dyade describe``."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import click

from dyade.cli import main

MECHANISM_FILE = click.Path(exists=True, dir_okay=False, path_type=Path)


def _console(stderr: bool = False):
    from rich.console import Console

    return Console(stderr=stderr, highlight=False)


def _read(mechanism_file: Path, start: float | None, stop: float | None, step: float | None):
    from dyade import toml_input

    overrides = {}
    for key, value in (("start", start), ("stop", stop), ("step", step)):
        if value is not None:
            overrides[f"sweep.{key}"] = value
    mechanism = toml_input.read_mechanism(mechanism_file)
    if overrides:  # the sweep options are in degrees whatever the file's angle unit
        from dataclasses import replace

        sweep = mechanism.sweep
        start_rad = math.radians(start) if start is not None else sweep.start
        stop_rad = (math.radians(stop) if stop is not None
                    else (start_rad + 2 * math.pi if start is not None else sweep.stop))
        step_rad = math.radians(step) if step is not None else sweep.step
        if step_rad <= 0:
            raise click.BadParameter(f"must be positive, got {step:g}.", param_hint="--step")
        if stop_rad < start_rad:
            raise click.BadParameter(f"must not be below the start angle, got {stop:g}.",
                                     param_hint="--stop")
        mechanism = replace(mechanism, sweep=type(sweep)(start_rad, stop_rad, step_rad))
    return mechanism


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
def describe(mechanism_file: Path) -> None:
    """Show MECHANISM_FILE in assembly order: crank, dyads, joints, link points, mobility,
    and which effects an analysis will simulate."""
    from dyade import analysis
    from dyade.report import tables

    mechanism = _read(mechanism_file, None, None, None)
    _console().print(tables.describe(mechanism, analysis.plan(mechanism)))


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@click.option("--format", "fmt", type=click.Choice(["table", "csv"]), default="table",
              show_default=True, help="table: a summary (min/max and where); csv: the whole sweep.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
@click.option("--start", type=float, help="First crank angle [°] (overrides [sweep] start).")
@click.option("--stop", type=float, help="Last crank angle [°] (default: start + 360).")
@click.option("--step", type=float, help="Crank angle step [°] (overrides [sweep] step).")
@click.option("--allow-partial", is_flag=True,
              help="Analyse only the crank angles where every dyad closes; the others are "
                   "left out of the output (and named on stderr) instead of failing.")
@click.option("--friction-tol", type=click.FloatRange(min=0.0, min_open=True),
              help="Stop the friction iteration at a position when the relative change of "
                   "its joint forces is below this [-]  [default: file's [friction] tol, 1e-9].")
@click.option("--friction-max-iter", type=click.IntRange(min=1),
              help="Most friction iterations per dyad and position  [default: file's "
                   "[friction] max_iter, 50]; positions not converged are named on stderr.")
@click.option("--fail-on-lock", is_flag=True,
              help="Exit with status 1 when a slider self-locks (otherwise a locking slider is "
                   "a finding: reported, exit status 0).")
def analyse(mechanism_file: Path, fmt: str, output: Path | None, start: float | None,
            stop: float | None, step: float | None, allow_partial: bool,
            friction_tol: float | None, friction_max_iter: int | None,
            fail_on_lock: bool) -> None:
    """Sweep the crank of MECHANISM_FILE: positions, velocities and accelerations of every
    link, joint and named point.

    With masses, loads or springs in the file: joint forces, driving torque and shaking
    force; with friction coefficients: Coulomb friction and the self-locking test of
    every slider with friction.

    Units: SI (m, m/s, m/s², rad/s, rad/s², N, N·m, W) except angles in degrees. Exit
    status 1 when a dyad cannot close over part of the sweep (the message names the dyad
    and the crank-angle ranges) or, with --fail-on-lock, when a slider locks; 2 for a bad
    file or option.
    """
    from dataclasses import replace

    from dyade import analysis
    from dyade.errors import DyadeError
    from dyade.report import columns

    mechanism = _read(mechanism_file, start, stop, step)
    if friction_tol is not None:
        mechanism = replace(mechanism, friction_tol=friction_tol)
    if friction_max_iter is not None:
        mechanism = replace(mechanism, friction_max_iter=friction_max_iter)
    result = analysis.run(mechanism, analysis.plan(mechanism), allow_partial=allow_partial)
    cols = columns.columns(result)
    if fmt == "csv":
        from dyade.report import csv_rows

        if output:
            with _atomic(output) as handle:
                csv_rows.write(cols, handle)
        else:
            csv_rows.write(cols, sys.stdout)
    else:
        from dyade.report import tables

        parts = [tables.sweep_summary(result, cols), tables.force_summary(result, cols),
                 tables.clearance_summary(result)]
        parts = [part for part in parts if part is not None]
        if output:
            from rich.console import Console

            with _atomic(output) as handle:
                Console(file=handle, width=120).print(*parts)
        else:
            _console().print(*parts)
    err = _console(stderr=True)
    for note in result.notes:
        err.print(f"warning: {note}")
    if fail_on_lock and any(lock.locks[result.rows].any() for lock in (result.locking or {}).values()):
        raise DyadeError("a slider self-locks (see the warning above); --fail-on-lock was given.")


class _atomic:
    """Write to a temporary file beside ``path``, rename on success, remove on failure."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.tmp = path.with_name(f".{path.name}.part")

    def __enter__(self):
        self.handle = open(self.tmp, "w", encoding="utf-8", newline="")
        return self.handle

    def __exit__(self, exc_type, exc, tb) -> None:
        self.handle.close()
        if exc_type is None:
            self.tmp.replace(self.path)
        else:
            self.tmp.unlink(missing_ok=True)
