"""``dyade plot``: figures of the analyses (the optional extra ``dyade[plot]``).

Each subcommand parses its options, calls the API and hands the result to its module of
``dyade.plot``; matplotlib is imported only there, when a figure is made. The output
format comes from the suffix of -o; without -o (and without --show) the figure is
written to NAME-KIND.png in the current directory.
"""

from __future__ import annotations

import math
import os
from typing import Callable, NamedTuple

import click

from dyade.cli import main
from dyade.cli.analyse import MECHANISM_FILE, SweepOptions, batch, load, set_option, sweep, warn
from dyade.cli.clearance import FLAGS as CLEARANCE_FLAGS
from dyade.cli.clearance import (clearance_options, inputs, mechanism_check, mechanism_options,
                                 standalone_check)
from dyade.cli.coupling import coupling_options, solve
from dyade.cli.output import console, flags

FORMATS = ("png", "svg", "pdf")


@main.group()
def plot() -> None:
    """Figures: polar diagrams, curves, the mechanism still and in motion, the coupling's
    resonance, the clearance peak force, and a gear drive's Campbell diagram and mode
    shapes.

    Needs the plot extra: pip install "dyade[plot]" (matplotlib). The format follows the
    suffix of -o (.png, .svg, .pdf; .gif for `plot animate`); without -o the figure is
    written to NAME-KIND.png here. --show opens a window instead, where a display exists.

        dyade plot polar mechanisms/fourbar.toml -o fourbar-polar.svg

        dyade plot animate mechanisms/slotted-lever.toml --step 5 -o motion.gif
    """


def output_options(default_format: str | None = "png"):
    """-o, --format, --show and --dpi, shared by every figure command."""
    def decorate(command):
        options = [
            click.option("-o", "--output", type=click.Path(writable=True),
                         help="Write the figure to this file, its format from the suffix; "
                              "with several mechanism files a directory (NAME-KIND.FORMAT "
                              "each)."),
            click.option("--show", is_flag=True,
                         help="Open the figure in a window (needs a display); with -o as "
                              "well, write it too."),
            click.option("--dpi", type=click.IntRange(min=20, max=1200), default=None,
                         help="Resolution of a PNG or GIF [dots per inch]  [default: 100 for "
                              "PNG, 72 for GIF]."),
        ]
        if default_format:
            options.insert(1, click.option(
                "--format", "fmt", type=click.Choice(FORMATS), default=None,
                help=f"Format when -o names no file with a suffix (a directory, or no -o)  "
                     f"[default: {default_format}]."))
        for option in reversed(options):
            command = option(command)
        return command
    return decorate


def linkage_options(command):
    """The mechanism files and the sweep options of `dyade analyse`."""
    options = [
        click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1, required=True),
        click.option("--start", type=float,
                     help="First crank angle [°] (overrides [sweep] start)."),
        click.option("--stop", type=float, help="Last crank angle [°] (default: start + 360)."),
        click.option("--step", type=float, help="Crank angle step [°] (overrides [sweep] step)."),
        set_option,
        click.option("--allow-partial", is_flag=True,
                     help="Draw only the crank angles where every dyad closes (gaps elsewhere) "
                          "instead of failing."),
    ]
    for option in reversed(options):
        command = option(command)
    return command


class Target(NamedTuple):
    """Where a figure goes: a file (None: only a window) and whether to show it."""

    path: str | None
    show: bool
    dpi: int | None


def _prepare(show: bool) -> None:
    """matplotlib is there (else exit 2 naming the extra); a window can open for --show."""
    from dyade.plot import require

    require()
    if show and os.name == "posix" and not (os.environ.get("DISPLAY")
                                            or os.environ.get("WAYLAND_DISPLAY")
                                            or os.uname().sysname == "Darwin"):
        raise click.UsageError("--show needs a display (DISPLAY is not set); write the figure "
                               "with -o FILE instead.")


def _suffix_format(path: str, allowed: tuple[str, ...]) -> str:
    fmt = os.path.splitext(path)[1].lower().lstrip(".")
    if fmt not in allowed:
        raise click.BadParameter(f"{path}: the format comes from the suffix, one of "
                                 f"{', '.join('.' + a for a in allowed)}.", param_hint="-o")
    return fmt


def _emit(fig, target: Target, announce: bool) -> None:
    """Write the figure when it has a file (its format from the suffix)."""
    from dyade.plot import canvas

    if target.path:
        canvas.save(fig, target.path, target.dpi or 100)
        if announce:
            console(stderr=True).print(f"wrote {target.path}")


def _figure_for(target: Target, size: tuple[float, float] = (7.0, 5.0)):
    """A window's figure for --show, else None (the plot module makes its own)."""
    if not target.show:
        return None
    from dyade.plot import canvas

    return canvas.window(*size)


def _run_linkage(kind: str, files: tuple[str, ...], output: str | None, fmt: str | None,
                 show: bool, dpi: int | None, options: tuple, draw: Callable,
                 suffixes: tuple[str, ...] = FORMATS) -> None:
    """Analyse each file and draw it with ``draw(result, target, announce)``; several
    files write one figure each into the directory -o."""
    from dyade.errors import DyadeError

    _prepare(show)
    sweep_options, assignments, allow_partial = options
    fmt = fmt or suffixes[0]

    def one(path: str, target: str | None, _: object = None) -> None:
        mechanism = load(path, assignments, sweep_options).mechanism
        result = sweep(mechanism, allow_partial)
        warn(result.notes, mechanism, f"{os.path.basename(path)}: " if len(files) > 1 else "")
        draw(result, Target(target, show, dpi), announce)

    announce = output is None
    if len(files) == 1 and not (output and os.path.isdir(output)):
        if output:
            _suffix_format(output, suffixes)
        elif not show:
            output = f"{os.path.splitext(os.path.basename(files[0]))[0]}-{kind}.{fmt}"
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


def _static(build: Callable) -> Callable:
    """A drawer for a still figure: ``build(result, fig)`` -> Figure."""
    def draw(result, target: Target, announce: bool) -> None:
        _emit(build(result, _figure_for(target)), target, announce)
    return draw


def _joints(texts: tuple[str, ...]) -> list[tuple[int, int]] | None:
    from dyade.cli.clearance import parse_joint

    return [parse_joint(text) for text in texts] or None


@plot.command()
@linkage_options
@click.option("--joint", "joints", multiple=True, metavar="I,J",
              help="A revolute joint to draw, e.g. --joint 5,6 (repeatable); default: every "
                   "revolute joint.")
@click.option("--max-wander", type=click.FloatRange(min=0, max=90), default=20.0,
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
            return figure.figure(result, chosen, max_wander=math.radians(max_wander), fig=fig)

    _run_linkage("polar", mechanism_files, output, fmt, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), _static(build))


@plot.command()
@linkage_options
@click.option("--y", "quantities", multiple=True, metavar="NAME,...",
              help="Columns to draw against the crank angle, as named in the CSV: --y "
                   "M_drive,F_2_3 (repeatable); columns of one unit share a panel. Default: "
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

        with flags({"quantities": "--y"}):
            return figure.figure(result, names or None, fig=fig)

    _run_linkage("curves", mechanism_files, output, fmt, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), _static(build))


def _angles(texts: tuple[str, ...]) -> list[float] | None:
    try:
        values = [float(part) for text in texts for part in text.split(",") if part.strip()]
    except ValueError:
        raise click.BadParameter(f"must be crank angles in degrees like 0,90,180, got "
                                 f"{' '.join(texts)!r}.", param_hint="--at") from None
    if not all(math.isfinite(v) for v in values):
        raise click.BadParameter("crank angles must be finite numbers.", param_hint="--at")
    return [math.radians(v) for v in values] or None


@plot.command()
@linkage_options
@click.option("--at", "at", multiple=True, metavar="DEG,...",
              help="Crank angles [°] to draw the linkage at, one panel each: --at 0,90,180  "
                   "[default: 0°, 90°, 180°, 270° from the start of a full turn, else the "
                   "sweep's start, middle and end].")
@output_options()
def mechanism(mechanism_files, start, stop, step, assignments, allow_partial, at, output, fmt,
              show, dpi) -> None:
    """The linkage of MECHANISM_FILES drawn from its kinematics at chosen crank angles:
    links as bars or plates, sliders on their guides, frame pivots hatched, the paths of
    the named link points traced over the sweep. Lengths in m."""
    angles = _angles(at)

    def build(result, fig):
        from dyade.plot import mechanism as figure

        return figure.figure(result, angles, fig=fig)

    _run_linkage("mechanism", mechanism_files, output, fmt, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), _static(build))


@plot.command()
@linkage_options
@click.option("--fps", type=click.FloatRange(min=1, max=100), default=20.0, show_default=True,
              help="Frames per second of the GIF.")
@output_options(default_format=None)
def animate(mechanism_files, start, stop, step, assignments, allow_partial, fps, output, show,
            dpi) -> None:
    """The linkage of MECHANISM_FILES in motion, one frame per step of the sweep, as an
    animated GIF (-o motion.gif; default NAME-motion.gif). A coarser --step makes a smaller
    file: `dyade plot animate mechanisms/slotted-lever.toml --step 5 -o motion.gif`."""
    window: list = []

    def draw(result, target: Target, announce: bool) -> None:
        from dyade.plot import animate as figure

        motion = figure.animation(result, fig=_figure_for(target, (4.0, 5.0)))
        if target.path:
            figure.save(motion, target.path, fps, target.dpi or figure.DPI)
            if announce:
                console(stderr=True).print(f"wrote {target.path} ({motion.count} frames)")
        if target.show:
            window.append(figure.play(motion, fps))  # kept while the window runs

    _run_linkage("motion", mechanism_files, output, None, show, dpi,
                 (SweepOptions(start, stop, step), assignments, allow_partial), draw,
                 suffixes=("gif",))


def _single_target(output: str | None, fmt: str | None, show: bool, dpi: int | None,
                   name: str) -> tuple[Target, bool]:
    """The target of a figure from options or a file (one figure)."""
    _prepare(show)
    if output and os.path.isdir(output):
        output = os.path.join(output, f"{name}.{fmt or 'png'}")
    elif output:
        _suffix_format(output, FORMATS)
    elif not show:
        return Target(f"{name}.{fmt or 'png'}", show, dpi), True
    return Target(output, show, dpi), False


def _finish(fig, target: Target, announce: bool) -> None:
    _emit(fig, target, announce)
    if target.show:
        from dyade.plot import canvas

        canvas.show()


@plot.command("coupling")
@coupling_options
@click.option("--log", is_flag=True, help="A logarithmic axis for the transfer functions.")
@output_options()
def coupling_figure(coupling_file, inertia, c1, c2, b1, b2, eta_range, moment, speeds, order,
                    log, output, fmt, show, dpi) -> None:
    """The stiff coupling's transfer functions V_φ, V_ψ, V_q, V_r against η with their
    phases (Strümpfel), η0 and the operating points marked; an undamped resonance is a
    gap, never a spike. The options and file of `dyade coupling`:

        dyade plot coupling mechanisms/coupling/stiff-coupling.toml -o coupling.png
    """
    name = (f"{os.path.splitext(coupling_file.name)[0]}-coupling" if coupling_file
            else "coupling")
    target, announce = _single_target(output, fmt, show, dpi, name)
    model, _, response, _, operating, _ = solve(coupling_file, inertia, c1, c2, b1, b2,
                                                eta_range, moment, speeds, order)
    from dyade.plot import coupling as figure

    _finish(figure.figure(model, response, operating, log=log, fig=_figure_for(target)),
            target, announce)


@plot.command("clearance")
@click.argument("mechanism_file", type=MECHANISM_FILE, required=False)
@clearance_options
@output_options()
def clearance_figure(mechanism_file, joints, masses, stiffness, gap, slope, speed_rpm,
                     speed_range, simulate, sim_steps, max_wander, output, fmt, show,
                     dpi) -> None:
    """The clearance peak force (Dresig & Thümmel): f(τ) of eq. (36) with the operating
    points; with --speed-range the peak force against crank speed; with --simulate the
    simulated force history next to the closed form, eq. (26) (over a mechanism: of its
    largest peak). The options and file of `dyade clearance`:

        dyade plot clearance --mass 3.6 --stiffness 1e7 --clearance 1e-4 --slope 360000 \\
            --speed-rpm 300 --speed-range 100:600:50 --simulate
    """
    import dyade
    from dyade import clearance as engine
    from dyade.plot import clearance as figure
    from dyade.report import clearance as clearance_report

    given = inputs(joints, masses, stiffness, gap, slope, speed_rpm, speed_range, simulate,
                   sim_steps, max_wander)
    name = (f"{os.path.splitext(os.path.basename(mechanism_file))[0]}-clearance"
            if mechanism_file else "clearance")
    if mechanism_file:
        mechanism_check(given)
    else:
        standalone_check(given)
    target, announce = _single_target(output, fmt, show, dpi, name)
    speeds = None
    with flags(CLEARANCE_FLAGS):
        if mechanism_file:
            mechanism = dyade.read_mechanism(mechanism_file)
            checks = dyade.check_clearance(mechanism, **mechanism_options(given))
            _, skipped = clearance_report.mechanism_rows([(None, checks)], False, 0)
            for line in clearance_report.mechanism_warnings(skipped, []):
                console(stderr=True).print(line)
            cases, title = figure.cases(checks), mechanism.name
            if given.speeds:
                speeds = figure.speed_lines(dyade.clearance_speed_study(
                    mechanism, given.speeds, **mechanism_options(given)))
        else:
            peak = engine.peak_force(given.mass, given.stiffness, clearance=given.gap,
                                     slope=given.slope)
            cases, title = [figure.Case("standalone", peak)], "Clearance peak force"
            if given.speeds:
                speeds = figure.standalone_speeds(engine.peaks_over_speed(
                    given.mass, given.stiffness, clearance=given.gap, slope=given.slope,
                    speed_rpm=given.speed_rpm, speeds_rpm=given.speeds))
        history = None
        if given.simulate and cases:
            worst = max(cases, key=lambda case: case.peak.force)
            p = worst.peak
            history = figure.History(worst, engine.simulate(
                p.mass, p.stiffness, clearance=p.clearance, slope=p.slope,
                steps_per_period=given.sim_steps, history=True))
    _finish(figure.figure(cases, speeds=speeds, history=history, title=title,
                          fig=_figure_for(target, (10.8, 3.7))), target, announce)


GEAR_FILE = click.Path(exists=True, dir_okay=False)
GEAR_FLAGS = {"speeds_rpm": "--speed-range", "harmonics": "--harmonics", "count": "--modes"}
"""API parameter -> the flag of `dyade plot campbell`/`modes` it comes from"""


def _gear_drive(gear_file: str, assignments: tuple[str, ...]):
    """The drive of GEAR_FILE with the --set overrides, and the flag names for errors."""
    from dyade.files import gears as reader
    from dyade.files import schema

    overrides = dict(schema.parse_assignment(a) for a in assignments)
    drive = reader.read_gears(gear_file, overrides)
    return drive, GEAR_FLAGS | {"speed": f"{os.path.basename(gear_file)}: `[speed]`"}


def _stem(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0]


gear_set_option = click.option(
    "--set", "assignments", multiple=True, metavar="KEY=VALUE",
    help="Override a key of the gear file by its dotted path (repeatable), as in `dyade gears`.")


@plot.command("campbell")
@click.argument("gear_file", type=GEAR_FILE)
@click.option("--speed-range", "speed_range", metavar="START:STOP:STEP",
              help="Input speeds [rpm], as `dyade gears --campbell`  [default: 0 to 1.5 × the "
                   "file's [speed] rpm, in 200 steps].")
@click.option("--harmonics", type=click.IntRange(min=0), default=3, show_default=True,
              help="Tooth-mesh harmonics drawn.")
@gear_set_option
@output_options()
def campbell_figure(gear_file, speed_range, harmonics, assignments, output, fmt, show,
                    dpi) -> None:
    """Campbell diagram of the gear drive in GEAR_FILE: the natural frequencies against the
    input speed (horizontal: no gyroscopic terms in this model), the excitation lines (shaft
    speeds, tooth-mesh frequency z·n/60 and its harmonics, the file's excitation orders) and
    the resonance crossings of `dyade gears --campbell`, each sized by the modal mesh
    stiffness of the exciting mesh.

        dyade plot campbell mechanisms/gears/two-stage.toml -o campbell.png
    """
    from dyade.cli.options import value_range

    target, announce = _single_target(output, fmt, show, dpi, f"{_stem(gear_file)}-campbell")
    drive, names = _gear_drive(gear_file, assignments)
    from dyade.plot import campbell as figure
    from dyade.vibration.gears.campbell import campbell, orders

    with flags(names):
        orders(drive, harmonics)  # a [speed] body and harmonics ≥ 0, before the speeds
        if speed_range:
            speeds = value_range(speed_range, "--speed-range", " [rpm]")
        elif drive.speed.rpm:
            speeds = figure.default_speeds(drive.speed.rpm)
        else:
            raise click.UsageError(f"{os.path.basename(gear_file)} gives no operating speed "
                                   f"([speed] rpm): give the speeds with --speed-range "
                                   f"START:STOP:STEP.")
        diagram = campbell(drive, speeds, harmonics=harmonics)
    _finish(figure.figure(diagram, fig=_figure_for(target, (8.5, 7.0))), target, announce)


@plot.command("modes")
@click.argument("gear_file", type=GEAR_FILE)
@click.option("--modes", "count", type=click.IntRange(min=1, max=24), default=4,
              show_default=True, help="The first N elastic modes, one row of panels each.")
@gear_set_option
@output_options()
def modes_figure(gear_file, count, assignments, output, fmt, show, dpi) -> None:
    """Mode shapes of the gear drive in GEAR_FILE per shaft line: for each of the first N
    elastic modes (rigid-body modes left out), the bodies along each shaft against their
    modal displacements — torsion ρ·rx, lateral uy and uz, axial ux — each mode divided by
    its largest entry, with its frequency and dominant part.

        dyade plot modes mechanisms/gears/two-stage.toml --modes 6 -o modes.svg
    """
    target, announce = _single_target(output, fmt, show, dpi, f"{_stem(gear_file)}-modes")
    drive, names = _gear_drive(gear_file, assignments)
    from dyade.plot import modes as figure
    from dyade.vibration.gears.modes import gear_modes

    with flags(names):
        modes = gear_modes(drive)
        _finish(figure.figure(modes, count, fig=_figure_for(target)), target, announce)
