"""Figures of a linkage's sweep: ``dyade plot polar``, ``curves``, ``mechanism`` and
``animate``, one figure per mechanism file (several files: one each into -o DIR)."""

from __future__ import annotations

import math
import os
from typing import Callable

import click

from dyade.cli.batch import batch
from dyade.cli.common import SweepOptions, load, sweep, warn
from dyade.cli.options import (FINITE, MECHANISM_FILE, POSITIVE, Renamed, max_memory_option,
                               set_option)
from dyade.limits import check_memory
from dyade.cli.output import console, flags
from dyade.cli.plot.output import (FORMATS, Target, emit, figure_for, output_options, prepare, stem,
                                    suffix_format)


def linkage_options(command):
    """The mechanism files and the sweep options of `dyade analyse`."""
    options = [
        click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1, required=True),
        click.option("--start", type=FINITE, metavar="DEG",
                     help="First crank angle [°] (overrides [sweep] start)."),
        click.option("--stop", type=FINITE, metavar="DEG",
                     help="Last crank angle [°] (default: start + 360)."),
        click.option("--step", type=POSITIVE, metavar="DEG",
                     help="Crank angle step [°] (overrides [sweep] step)."),
        set_option,
        click.option("--allow-partial", is_flag=True,
                     help="Draw only the crank angles where every dyad closes (gaps elsewhere) "
                          "instead of failing."),
    ]
    for option in reversed(options):
        command = option(command)
    return command


def run_linkage(kind: str, files: tuple[str, ...], output: str | None, fmt: str | None,
                 show: bool, dpi: int | None, options: tuple, draw: Callable,
                 suffixes: tuple[str, ...] = FORMATS, forces: bool = False) -> None:
    """Analyse each file and draw it with ``draw(result, target, announce)``; several
    files write one figure each into the directory -o. A sweep whose every position is
    withheld (its kinematics, or with ``forces`` its joint forces) draws nothing: exit 1
    saying so, as every analysis does (no empty panel that reads "no force")."""
    from dyade.errors import DyadeError

    prepare(show)
    sweep_options, assignments, allow_partial = options
    fmt = fmt or suffixes[0]

    def one(path: str, target: str | None, _: object = None) -> None:
        mechanism = load(path, assignments, sweep_options).mechanism
        result = sweep(mechanism, allow_partial)
        warn(result.notes, mechanism, f"{os.path.basename(path)}: " if len(files) > 1 else "")
        drawable(result, mechanism, forces)
        draw(result, Target(target, show, dpi, fmt), announce)

    announce = output is None
    if len(files) == 1 and not (output and os.path.isdir(output)):
        if output and output != "-":
            suffix_format(output, suffixes)
        elif not output and not show:
            output = f"{stem(files[0])}-{kind}.{fmt}"
        one(files[0], output)
    else:
        directory = output or "."
        os.makedirs(directory, exist_ok=True)
        announce = True
        failures = batch(files, directory, one, f"-{kind}.{fmt}")
        if failures:
            lines = "\n".join(f"  {path}: {reason}" for path, reason in failures)
            raise DyadeError(f"{len(failures)} of {len(files)} files failed:\n{lines}")
    if show:
        from dyade.plot import canvas

        canvas.show()


def drawable(result, mechanism, forces: bool = False) -> None:
    """Refuse (``DyadeError``, exit 1) a sweep with no position given: none with its
    kinematics, or with ``forces`` none with its joint forces; the reasons are its
    notes."""
    import numpy as np

    from dyade.errors import DyadeError
    from dyade.report.notes import say

    given = np.asarray(result.valid, dtype=bool)
    what = "kinematics"
    if forces and given.any() and result.forces_valid is not None:  # None: no masses,
        given = np.asarray(result.forces_valid, dtype=bool)     # which the figure refuses
        what = "joint forces"
    if given.size and not given.any():
        reasons = "; ".join(say(note, mechanism) for note in result.notes[:3])
        raise DyadeError(f"{mechanism.name}: no position of the sweep has its {what} given"
                         f"{f' ({reasons})' if reasons else ''}: nothing to draw.")


def static(build: Callable) -> Callable:
    """A drawer for a still figure: ``build(result, fig)`` -> Figure."""
    def draw(result, target: Target, announce: bool) -> None:
        emit(build(result, figure_for(target)), target, announce)
    return draw


def _joints(texts: tuple[str, ...]) -> list[tuple[int, int]] | None:
    from dyade.cli.clearance import parse_joint

    return [parse_joint(text) for text in texts] or None


@click.command()
@linkage_options
@click.option("--joint", "joints", multiple=True, metavar="I,J",
              help="A revolute joint to draw, e.g. --joint 5,6 (repeatable); default: every "
                   "revolute joint.")
@click.option("--max-wander", type=click.FloatRange(min=0, max=90), default=20.0, metavar="DEG",
              show_default=True,
              help="Largest angle [°] a force may leave its line of action for its reversals "
                   "to be numbered (as in `dyade clearance`).")
@output_options()
def polar(mechanism_files, start, stop, step, assignments, allow_partial, joints, max_wander,
          output, fmt, show, dpi) -> None:
    """Joint-force polar diagrams of MECHANISM_FILES: Fy against Fx over the crank cycle,
    one panel per revolute joint, the crank angle marked every 30°, the dominant line of
    action and its reversals numbered as `dyade clearance` numbers them, gaps where the
    forces are not given. The force is the one on the higher-numbered link [N]."""
    chosen = _joints(joints)

    def build(result, fig):
        from dyade.plot import polar as figure

        with flags({"joints": "--joint"}):
            return figure.figure(result, chosen, max_wander_deg=max_wander, fig=fig)

    run_linkage("polar", mechanism_files, output, fmt, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), static(build),
                 forces=True)


@click.command()
@linkage_options
@click.option("--columns", "quantities", cls=Renamed, old=("--y",), multiple=True,
              metavar="NAME,...",
              help="Columns to draw against the crank angle, as named in the CSV (as "
                   "`dyade analyse --columns`): --columns M_drive,F_2_3 (repeatable); columns "
                   "of one unit share a panel. Default: "
                   "the drive torque with its mean and energy surplus, and the transmission "
                   "angles.")
@output_options()
def curves(mechanism_files, start, stop, step, assignments, allow_partial, quantities, output,
           fmt, show, dpi) -> None:
    """Result quantities of MECHANISM_FILES against the crank angle, units on the axes,
    the ranges the analysis warns about (dead centres, forces not given, self-locking …)
    shaded and named, gaps where values are not given."""
    names = [name.strip() for text in quantities for name in text.split(",") if name.strip()]

    def build(result, fig):
        from dyade.plot import curves as figure

        with flags({"quantities": "--columns"}):
            return figure.figure(result, names or None, fig=fig)

    run_linkage("curves", mechanism_files, output, fmt, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), static(build))


def _angles(texts: tuple[str, ...]) -> list[float] | None:
    try:
        values = [float(part) for text in texts for part in text.split(",") if part.strip()]
    except ValueError:
        raise click.BadParameter(f"must be crank angles in degrees like 0,90,180, got "
                                 f"{' '.join(texts)!r}.", param_hint="--at") from None
    if not all(math.isfinite(v) for v in values):
        raise click.BadParameter("crank angles must be finite numbers.", param_hint="--at")
    return values or None


@click.command()
@linkage_options
@click.option("--at", "at", multiple=True, metavar="DEG,...",
              help="Crank angles [°] to draw the linkage at, one panel each: --at 0,90,180  "
                   "[default: 0°, 90°, 180°, 270° from the start of a full turn, else the "
                   "sweep's start, middle and end; with --allow-partial, positions where it "
                   "closes, spread over the sweep].")
@output_options()
def mechanism(mechanism_files, start, stop, step, assignments, allow_partial, at, output, fmt,
              show, dpi) -> None:
    """The linkage of MECHANISM_FILES drawn from its kinematics at chosen crank angles:
    links as bars or plates, sliders on their guides, frame pivots hatched, the paths of
    the named link points traced over the sweep. Lengths in m."""
    angles = _angles(at)

    def build(result, fig):
        from dyade.plot import mechanism as figure

        return figure.figure(result, at_deg=angles, fig=fig)

    run_linkage("mechanism", mechanism_files, output, fmt, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), static(build))


@click.command()
@linkage_options
@click.option("--fps", type=click.FloatRange(min=1, max=100), default=20.0, show_default=True,
              metavar="N",
              help="Frames per second of the GIF.")
@output_options(default_format=None)
@max_memory_option
def animate(mechanism_files, start, stop, step, assignments, allow_partial, fps, output, show,
            dpi, max_memory) -> None:
    """The linkage of MECHANISM_FILES in motion, one frame per step of the sweep, as an
    animated GIF (-o motion.gif; default NAME-motion.gif). A coarser --step makes a smaller
    file: `dyade plot animate mechanisms/slotted-lever.toml --step 5 -o motion.gif`."""
    window: list = []

    def draw(result, target: Target, announce: bool) -> None:
        from dyade.plot import animate as figure

        frames = int(result.crank_angle.size)
        pixels = (4.0 * (target.dpi or figure.DPI)) * (5.0 * (target.dpi or figure.DPI))
        with flags({"max_memory": "--max-memory"}):
            check_memory(4.0 * pixels * frames + (100 << 20), f"an animation of {frames:,} "
                         f"frames", max_memory * 2 ** 20, "Use a coarser --step or a lower --dpi")
        motion = figure.animation(result, fig=figure_for(target, (4.0, 5.0)))
        if target.path:
            figure.save(motion, target.path, fps, target.dpi or figure.DPI)
            if announce:
                console(stderr=True).print(f"wrote {target.path} ({motion.count} frames)")
        if target.show:
            window.append(figure.play(motion, fps))  # kept while the window runs

    run_linkage("motion", mechanism_files, output, None, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), draw,
                 suffixes=("gif",))
