"""``dyade clearance``: the joint-clearance peak check (Dresig & Thümmel)."""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import click

from dyade.cli import main
from dyade.cli.batch import SUFFIX, SWEEP, batch, workers_for
from dyade.cli.options import FINITE, MECHANISM_FILE, Number, jobs_option, value_range
from dyade.cli.output import console, flags, progress, show, write_json, write_rows

FLAGS = {"mass": "--mass", "stiffness": "--stiffness", "clearance": "--clearance",
         "slope": "--slope", "joints": "--joint", "speeds_rpm": "--speed-range"}
"""API parameter -> the flag it comes from"""


def parse_joint(text: str) -> tuple[int, int]:
    try:
        a, b = (int(part) for part in text.split(","))
    except ValueError:
        raise click.BadParameter(f"must be two link numbers like 5,6, got {text!r}.",
                                 param_hint="--joint") from None
    return (a, b) if a < b else (b, a)


def _emit(rows: list[dict], names: list[str], fmt: str, output: Path | None,
          summary: dict, warnings: list[str], parts) -> None:
    """CSV rows, JSON (columns, units, summary, warnings, meta) or rich tables."""
    if fmt == "csv":
        write_rows(rows, names, output)
    elif fmt == "json":
        from dyade.report.clearance import UNITS
        from dyade.report.document import document

        cols = {name: [row.get(name) for row in rows] for name in names}
        write_json(document("clearance", cols, UNITS, summary, warnings), output)
    else:
        show(parts(), output)
    err = console(stderr=True)
    for line in warnings:
        err.print(line, markup=False)


OPTIONS = [
    click.option("--joint", "joints", multiple=True, metavar="I,J",
                 help="Revolute joint to check, e.g. --joint 5,6 (repeatable); default: every "
                      "revolute joint (with a file)."),
    click.option("--mass", "masses", type=FINITE, multiple=True, metavar="KG",
                 help="Reduced mass m [kg]; give it twice (--mass m11 --mass m22) for the two "
                      "masses of eq. (17). With a file: default from the joint's "
                      "`clearance.mass` or the two links' masses."),
    click.option("--stiffness", type=FINITE, help="Contact stiffness c [N/m] (typical 1e7…1e9)."),
    click.option("--clearance", "gap", type=FINITE,
                 help="Clearance (radial play) 2s [m] (typical 2e-5…2e-4)."),
    click.option("--slope", type=FINITE,
                 help="Standalone: force slope F0/t0 at the reversal [N/s]."),
    click.option("--speed-rpm", type=FINITE, metavar="RPM",
                 help="Standalone: crank speed [rpm] at which --slope holds (for --speed-range)."),
    click.option("--speed-range", metavar="START:STOP:STEP",
                 help="Peak force against crank speed [rpm]; the slope grows with Ω³ (eq. 30)."),
    click.option("--simulate", is_flag=True,
                 help="Also integrate the two-mass model directly; report its peak, the cost of "
                      "each method and whether contact holds (rebound)."),
    click.option("--sim-steps", type=click.IntRange(min=10), default=400, show_default=True,
                 metavar="N",
                 help="RK4 steps per contact period for --simulate."),
    click.option("--max-wander", type=Number(low=0.0, high=90.0), default=20.0, metavar="DEG",
                 show_default=True,
                 help="Largest angle [°] the force may leave its line of action (forces ≥ 25 % "
                      "of the peak) for the model to apply."),
]
"""the data options of ``dyade clearance``, shared with ``dyade plot clearance``"""


def clearance_options(command):
    """Decorate a command with the clearance data options (``OPTIONS``)."""
    for option in reversed(OPTIONS):
        command = option(command)
    return command


class Inputs(NamedTuple):
    """The clearance options, checked: SI values, None where not given."""

    joints: list[tuple[int, int]]
    mass: float | None
    stiffness: float | None
    gap: float | None
    slope: float | None
    speed_rpm: float | None
    speeds: list[float] | None
    simulate: bool
    sim_steps: int
    wander: float
    """--max-wander [°]"""


def inputs(joints, masses, stiffness, gap, slope, speed_rpm, speed_range, simulate, sim_steps,
           max_wander) -> Inputs:
    """Check the clearance options that do not depend on a file."""
    from dyade import clearance as engine
    from dyade.errors import InputError

    if len(masses) > 2:
        raise click.BadParameter("give one reduced mass, or the two masses m11 and m22.",
                                 param_hint="--mass")
    for name, value in (("mass", masses[0] if masses else None), ("stiffness", stiffness),
                        ("clearance", gap), ("slope", slope)):
        if value is not None and not value > 0:
            raise InputError(f"--{name} must be a positive number, got {value:g}.")
    if len(masses) == 2 and not masses[1] > 0:
        raise InputError(f"--mass must be a positive number, got {masses[1]:g}.")
    mass = engine.reduced_mass(*masses) if len(masses) == 2 else (masses[0] if masses else None)
    speeds = (value_range(speed_range, "--speed-range", " in rpm", positive_start=True)
              if speed_range else None)
    return Inputs([parse_joint(j) for j in joints], mass, stiffness, gap, slope, speed_rpm, speeds,
                  simulate, sim_steps, max_wander)


def standalone_check(given: Inputs) -> None:
    """The standalone check needs the four numbers (and a speed for a speed range)."""
    missing = [flag for flag, value in (("--mass", given.mass), ("--stiffness", given.stiffness),
                                        ("--clearance", given.gap), ("--slope", given.slope))
               if value is None]
    if missing:
        raise click.UsageError(f"the standalone check needs {', '.join(missing)} (or give a "
                               f"mechanism file).")
    if given.speeds and given.speed_rpm is None:
        raise click.UsageError("--speed-range needs --speed-rpm: the speed at which --slope holds.")
    if given.speed_rpm is not None and given.speed_rpm <= 0:
        raise click.BadParameter(f"must be a positive speed [rpm], got {given.speed_rpm:g}.",
                                 param_hint="--speed-rpm")


def mechanism_check(given: Inputs) -> None:
    """Over a mechanism the slope comes from its forces; c and 2s go together."""
    if given.slope is not None or given.speed_rpm is not None:
        raise click.UsageError("--slope and --speed-rpm are for the standalone check; over a "
                               "mechanism the slope comes from its joint forces.")
    if (given.stiffness is None) != (given.gap is None):
        raise click.UsageError("give --stiffness and --clearance together (or neither, to use "
                               "the clearance data of the mechanism file).")


def mechanism_options(given: Inputs) -> dict:
    """The API's keyword arguments of ``check_clearance`` from the options."""
    return {"joints": given.joints or None, "stiffness": given.stiffness,
            "clearance": given.gap, "mass": given.mass, "max_wander_deg": given.wander}


@main.command()
@click.argument("mechanism_files", type=MECHANISM_FILE, nargs=-1)
@clearance_options
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: one row (record) per reversal.")
@click.option("-o", "--output", type=click.Path(writable=True, path_type=Path),
              help="Write the result to this file instead of standard output; with several "
                   "mechanism files a directory with one result per file.")
@jobs_option
def clearance(mechanism_files: tuple[Path, ...], joints: tuple[str, ...], masses: tuple[float, ...],
              stiffness: float | None, gap: float | None, slope: float | None,
              speed_rpm: float | None, speed_range: str | None, simulate: bool,
              sim_steps: int, max_wander: float, fmt: str, output: Path | None,
              jobs: int) -> None:
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
    given = inputs(joints, masses, stiffness, gap, slope, speed_rpm, speed_range, simulate,
                   sim_steps, max_wander)
    if not mechanism_files:
        _standalone(given, fmt, output)
    else:
        mechanism_check(given)

        if len(mechanism_files) == 1 and not (output and output.is_dir()):
            OverMechanism(given, fmt, jobs)(mechanism_files[0], output)
            return
        run_one = OverMechanism(given, fmt)  # the files run in parallel, not their speeds
        from dyade.errors import DyadeError

        if output is None:
            raise click.UsageError(f"{len(mechanism_files)} mechanism files need -o DIR.")
        output.mkdir(parents=True, exist_ok=True)
        failures = batch(mechanism_files, output, run_one, SUFFIX[fmt], jobs,
                         SWEEP + ("dyade.linkage.joint_clearance", "dyade.report.clearance"))
        if failures:
            lines = "\n".join(f"  {path}: {reason}" for path, reason in failures)
            raise DyadeError(f"{len(failures)} of {len(mechanism_files)} files failed:\n{lines}")


class OverMechanism(NamedTuple):
    """The check over one mechanism file, as the options describe it (picklable, for -j);
    ``jobs``: processes for its speeds."""

    given: Inputs
    fmt: str
    jobs: int = 1

    def __call__(self, path, target=None, _: object = None) -> None:
        _over_mechanism(path, self.given, self.fmt, target, self.jobs)


def _standalone(given: Inputs, fmt, output):
    from dyade import clearance as engine
    from dyade.report import clearance as report

    standalone_check(given)
    speeds = given.speeds
    cases = ([(None, given.slope)] if not speeds
             else [(rpm, engine.scaled_slope(given.slope, given.speed_rpm, rpm)) for rpm in speeds])
    with flags(FLAGS):
        rows = report.standalone_rows(given.mass, given.stiffness, given.gap, cases,
                                      given.simulate, given.sim_steps)
    warnings = [line for row in rows for line in report.notes(row)]
    _emit(rows, report.standalone_names(bool(speeds), given.simulate), fmt, output,
          {"cases": len(rows)}, warnings,
          lambda: [report.standalone_table(rows, bool(speeds), given.simulate)])


def _over_mechanism(path, given: Inputs, fmt, output, jobs: int = 1):
    import dyade
    from dyade.cli.common import load
    from dyade.report import clearance as report

    mechanism = load(path).mechanism
    with flags(FLAGS):
        if given.speeds:
            with progress(f"{mechanism.name}: clearance at {len(given.speeds)} speeds",
                          show=len(given.speeds) > 5) as tick:
                study = dyade.clearance_speed_study(mechanism, given.speeds, progress=tick,
                                                    workers=workers_for(jobs),
                                                    **mechanism_options(given))
        else:
            study = [(None, dyade.check_clearance(mechanism, **mechanism_options(given)))]
    checks = [check for _, result in study for check in result]
    if checks and all(check.missing == "data" for check in checks):  # nothing to compute
        from dyade.errors import InputError

        name = "<stdin>" if str(path) == "-" else Path(path).name
        raise InputError(f"{name}: nothing to compute: no joint has clearance "
                         f"data. Give --stiffness and --clearance, or `clearance = {{ gap = …, "
                         f"stiffness = … }}` in a joint table.", source=str(path))
    rows, skipped = report.mechanism_rows(study, given.simulate, given.sim_steps)
    joints = given.joints or [j.name for j in mechanism.joints if j.kind == "R"]
    summary = {"mechanism": mechanism.name, "reversals": len(rows),
               "joints_checked": [f"{a}-{b}" for a, b in joints]}
    _emit(rows, report.mechanism_names(bool(given.speeds), given.simulate), fmt, output, summary,
          report.mechanism_warnings(skipped, rows),
          lambda: [report.mechanism_table(mechanism.name, rows, given.speeds, given.simulate)])
