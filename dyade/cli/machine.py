"""``dyade flywheel`` and ``dyade balance``: the machine in motion."""

from __future__ import annotations

import math
import os

import click

from dyade.cli import main
from dyade.cli.common import infer_format, load, read_input
from dyade.cli.options import MECHANISM_FILE, Number, max_memory_option, set_option
from dyade.cli.output import atomic, flags, show, write_json, write_rows
from dyade.limits import PLAUSIBLE

FORMAT = click.Choice(["table", "csv", "json"])
FLYWHEEL_FLAGS = {"fluctuation": "--fluctuation", "inertia": "--inertia", "speed_rpm": "--speed-rpm",
                  "speed": "--speed-rpm", "step_deg": "--step", "max_memory": "--max-memory"}
BALANCE_FLAGS = {"links": "--link", "radius": "--radius"}
"""API parameter -> the flag it comes from"""


def _plausible(quantity: str, positive: bool = False) -> Number:
    low, high, unit = PLAUSIBLE[quantity]
    return Number(positive=positive, low=low, high=high, unit="" if unit == "-" else unit)


@main.command()
@click.argument("source", type=click.Path(exists=True, dir_okay=False, allow_dash=True))
@click.option("--fluctuation", type=_plausible("fluctuation"), metavar="DELTA",
              help="Size the flywheel for this speed fluctuation δ = (ω_max − ω_min)/ω_mean "
                   "[-], e.g. 0.02.")
@click.option("--inertia", type=Number(low=0.0, high=PLAUSIBLE["inertia"][1], unit="kg·m²"), metavar="KG_M2",
              help="Give the flywheel's moment of inertia J_F [kg·m²] and get the fluctuation.")
@click.option("--speed-rpm", type=_plausible("speed_rpm"), metavar="RPM",
              help="Mean crank speed [rpm] of a CSV source (a mechanism has its own).")
@click.option("--step", type=Number(positive=True, high=90.0, unit="°"), metavar="DEG",
              help="Crank angle step [°] for a mechanism's torque curve "
                   "[default: its sweep step, at most 0.1°].")
@set_option
@click.option("--format", "fmt", type=FORMAT, default=None,
              help="table, csv (one row: the keys below) or json. [default: table on stdout; "
                   "with -o: from its suffix]")
@click.option("-o", "--output", type=click.Path(dir_okay=False, allow_dash=True),
              help="Write to this file instead of standard output (-: standard output; a "
                   "missing folder is created).")
@max_memory_option
def flywheel(source: str, fluctuation: float | None, inertia: float | None,
             speed_rpm: float | None, step: float | None, assignments: tuple[str, ...],
             fmt: str | None, output: str | None, max_memory: float) -> None:
    """The flywheel from the torque curve over one revolution.

    SOURCE is a mechanism file, analysed at its constant crank speed (its drive torque
    M_drive against a motor of constant torque), or a CSV file with the columns
    angle_deg and M_drive [N·m] and optionally M_load [N·m] (positive where the load
    drives the machine; without it a constant load equal to the mean drive torque); a
    CSV written by `dyade analyse` is read as the machine's need at constant speed.

    With --fluctuation δ: the energy fluctuation delta_E [J] (the integral of the net
    torque over the cycle, max − min), the flywheel J_flywheel = ΔE/(δ·Ω²) − J_machine
    [kg·m²] and the crank angles of the highest and lowest speed. With --inertia J:
    the resulting fluctuation.

        dyade flywheel mechanisms/dyade-16.toml --fluctuation 0.02
    """
    import dyade

    if (fluctuation is None) == (inertia is None):
        raise click.UsageError("give either --fluctuation (to size the flywheel) or --inertia "
                               "(to get the fluctuation).")
    fmt = fmt or infer_format(output)
    text = None
    if source == "-":  # standard input: a CSV by its header, else a mechanism
        text, _ = read_input(source)
        first = text.lstrip("\ufeff").lstrip().split("\n", 1)[0]
        csv_source = "," in first and "=" not in first and "[" not in first
    else:
        csv_source = os.path.splitext(source)[1].lower() == ".csv"
    with flags(FLYWHEEL_FLAGS):
        if csv_source:
            if assignments or step is not None:
                raise click.UsageError("--set and --step apply to a mechanism file, not a CSV.")
            curve = dyade.read_torque_curve("<stdin>" if text is not None else source,
                                            speed_rpm=speed_rpm, text=text)
        else:
            if speed_rpm is not None:
                raise click.UsageError("--speed-rpm is for a CSV source; a mechanism has its "
                                       "own (change it with --set crank.speed_rpm=…).")
            mechanism = load(source, assignments, text=text).mechanism
            curve = dyade.mechanism_torque_curve(mechanism, step_deg=step,
                                                 max_memory=max_memory * 2 ** 20)
        if fluctuation is not None:
            result = dyade.size_flywheel(curve, fluctuation)
        else:
            result = dyade.speed_fluctuation(curve, inertia)
    from dyade.report import machine as report

    row = report.flywheel_row(result)
    if fmt == "csv":
        write_rows([row], report.FLYWHEEL_COLUMNS, output)
    elif fmt == "json":
        from dyade.report.document import document

        write_json(document("flywheel", {k: [v] for k, v in row.items()}, report.FLYWHEEL_UNITS,
                            row, list(result.notes), source=curve.source), output)
    else:
        asked = "fluctuation" if fluctuation is not None else "J_flywheel"
        show([report.flywheel_table(row, curve.source or os.path.basename(source), asked)],
             output)
    _notes(result.notes)


@main.command()
@click.argument("mechanism_file", type=MECHANISM_FILE)
@click.option("--link", "links", type=int, multiple=True, metavar="N",
              help="A link to carry a counterweight (repeatable); it must turn about a frame "
                   "pivot. [default: every such link]")
@click.option("--radius", type=Number(positive=True), metavar="M",
              help="Radius [m] of each counterweight's mass from its pivot. [default: the "
                   "link's reach: its farthest joint, named point or centre of mass]")
@set_option
@click.option("--save-as", "save_path", type=click.Path(dir_okay=False, allow_dash=True),
              help="Write the balanced mechanism (counterweights merged into the links' mass "
                   "data) to this TOML file, for `dyade analyse` (-: standard output).")
@click.option("--format", "fmt", type=FORMAT, default=None,
              help="table, csv (one row per counterweight) or json. [default: table on "
                   "stdout; with -o: from its suffix]")
@click.option("-o", "--output", type=click.Path(dir_okay=False, allow_dash=True),
              help="Write to this file instead of standard output (-: standard output; a "
                   "missing folder is created).")
def balance(mechanism_file: str, links: tuple[int, ...], radius: float | None,
            assignments: tuple[str, ...], save_path: str | None, fmt: str | None,
            output: str | None) -> None:
    """Counterweights against the shaking force of MECHANISM_FILE.

    Counterweights (first moment m·r [kg·m] and angle in the link's frame) on links
    turning about frame pivots, fitted by linear least squares to make the shaking
    force (the resultant of the inertia forces) smallest over the sweep; a four-bar
    comes out fully force-balanced (Berkof & Lowen). Reports the counterweights, the
    residual shaking force and how the shaking moment, the drive torque and the joint
    forces change (at the constant crank speed).

        dyade balance mechanisms/fourbar.toml --save-as fourbar-balanced.toml
    """
    import dyade

    fmt = fmt or infer_format(output)
    loaded = load(mechanism_file, assignments)
    mechanism = loaded.mechanism
    with flags(BALANCE_FLAGS):
        result = dyade.balance(mechanism, links=links or None, radius=radius)
    if save_path:
        from dyade.files.mechanism import edited, load_data

        data = load_data(loaded.label, loaded.overrides, "--set", loaded.text)
        overrides, removals = result.file_changes(data)
        text = edited(loaded.text, loaded.overrides | overrides, loaded.label, "--set",
                      removals)
        with atomic(save_path) as handle:
            handle.write("# written by dyade balance --save-as: the mechanism with its "
                         "counterweights\n")
            handle.write(text)
    from dyade.report import machine as report

    rows = report.counterweight_rows(result)
    changes = result.changes()
    if fmt == "csv":
        write_rows(rows, report.COUNTERWEIGHT_COLUMNS, output)
    elif fmt == "json":
        from dyade.report.document import document

        write_json(document("balance", {name: [r[name] for r in rows]
                                        for name in report.COUNTERWEIGHT_COLUMNS},
                            report.COUNTERWEIGHT_UNITS, {"counterweights": rows} | changes, [],
                            mechanism=mechanism.name), output)
    else:
        show(report.balance_tables(mechanism.name, rows, changes), output)


def _notes(notes) -> None:
    if notes:
        from dyade.cli.output import console

        err = console(stderr=True)
        for note in notes:
            err.print(f"note: {note}", markup=False)
