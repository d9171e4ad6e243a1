"""``dyade gears``: natural frequencies, Campbell diagram, forced response of a gear drive
(Berczyński, Maćkowiak and Marchelek 1978)."""

from __future__ import annotations

import click

from dyade.cli import main
from dyade.cli.options import Renamed, max_memory_option, modes_asked, value_range_checked
from dyade.cli.output import console, flags, show, write_json, write_rows
from dyade.report.document import document

FLAGS = {"coordinates": "--dof", "speeds_rpm": "--speed-range",
         "frequencies": "--frequency-range", "harmonics": "--harmonics",
         "max_memory": "--max-memory"}
"""API parameter -> the flag it comes from"""


@main.command()
@click.argument("gear_file", type=click.Path(exists=True, dir_okay=False, allow_dash=True))
@click.option("--modes", "shapes", type=click.IntRange(min=1), metavar="N",
              help="Also give the shapes of the first N modes (mode, body, ux … rz; "
                   "M-orthonormal, in each body's own axes); with --format csv, only them.")
@click.option("--speed-range", "speed_range", cls=Renamed, old=("--campbell",),
              metavar="START:STOP:STEP",
              help="Campbell diagram over the input speed [rpm]: excitation lines (shaft speeds, "
                   "tooth-mesh harmonics, the file's excitation orders) and the resonance "
                   "speeds in the range.")
@click.option("--harmonics", type=click.IntRange(min=0), default=3, show_default=True,
              metavar="N", help="Tooth-mesh harmonics in the Campbell diagram.")
@click.option("--frequency-range", "frequency_range", cls=Renamed, old=("--response",),
              metavar="START:STOP:STEP",
              help="Forced response [Hz] to the file's excitations (harmonic torques, "
                   "transmission errors): amplitude and phase of the --dof coordinates, dynamic "
                   "mesh forces, bearing forces.")
@click.option("--dof", "dofs", multiple=True, metavar="BODY.DOF",
              help="Coordinate for --frequency-range (repeatable), DOF one of ux uy uz rx ry rz in "
                   "the body's own axes  [default: rx of every body].")
@click.option("--check", is_flag=True,
              help="Solve the paper's eliminated form (eqs. (27)–(33)) and compare it with the "
                   "null-space solution; report its extra zero eigenvalues (one per mesh).")
@click.option("--set", "assignments", multiple=True, metavar="KEY=VALUE",
              help="Override a key of the file by its dotted path (repeatable): "
                   "--set shaft.1.segments=8.")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: every mode, resonance or frequency.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, allow_dash=True),
              help="Write the result to this file instead of standard output (-: standard "
                   "output; a missing folder is created).")
@max_memory_option
def gears(gear_file: str, shapes: int | None, speed_range: str | None, harmonics: int,
          frequency_range: str | None, dofs: tuple[str, ...], check: bool,
          assignments: tuple[str, ...], fmt: str, output: str | None, max_memory: float) -> None:
    """Natural frequencies and modes of the gear drive in GEAR_FILE (rigid finite elements,
    or the torsional model): each mode's energy shares (torsion, lateral, axial per shaft
    and bearing; elastic meshes), the dominant part and the modal mesh forces. Rigid-body
    modes are reported as such, never as 0 Hz resonances.

    \b
        dyade gears mechanisms/gears/two-stage.toml
        dyade gears mechanisms/gears/two-stage.toml --speed-range 0:3000:10
        dyade gears mechanisms/gears/two-stage.toml --frequency-range 10:1000:1 --format csv

    docs/reference/gear-file.md documents every key of a gear-drive file.
    """
    from dyade.cli.common import read_gear_file
    from dyade.report import gears as report
    from dyade.vibration.gears.modes import gear_modes

    chosen = [name for name, given in (("--speed-range", speed_range),
                                        ("--frequency-range", frequency_range),
                                        ("--check", check)) if given]
    if len(chosen) > 1:
        raise click.UsageError(f"{' and '.join(chosen)}: one analysis per run.")
    drive, label = read_gear_file(gear_file, assignments)
    names = FLAGS | {"speed": f"{label}: `[speed]`"}
    max_memory = max_memory * 2 ** 20
    with flags(names):
        modes = gear_modes(drive, max_memory=max_memory)
    if not modes.frequencies.size:
        raise click.UsageError(
            f"{label}: nothing to vibrate: every motion of the drive is a rigid-body "
            f"mode ({modes.rigid.shape[1]}), since no shaft, mesh stiffness, bearing or element "
            f"resists it. Add the elements that hold its bodies.")
    label = report.title(modes)
    if speed_range:
        from dyade.vibration.gears.campbell import campbell

        speeds = value_range_checked(speed_range, "--speed-range", " [rpm]", "speed_rpm")
        with flags(names):
            diagram = campbell(drive, speeds, harmonics=harmonics, modes=modes,
                               max_memory=max_memory)
        warnings = report.campbell_notes(diagram)
        rows = report.crossing_rows(diagram)
        if fmt == "csv":
            write_rows(rows, report.CROSSING_COLUMNS, output)
        elif fmt == "json":
            summary = report.campbell_json(diagram)
            resonances = summary.pop("resonances")
            write_json(document("gears", resonances, report.units_of(resonances), summary,
                                warnings, analysis="campbell", drive=drive.name), output)
        else:
            show(report.campbell_tables(diagram), output)
    elif frequency_range:
        from dyade.vibration.gears.response import gear_response

        frequencies = value_range_checked(frequency_range, "--frequency-range", " [Hz]",
                                          "frequency")
        with flags(names):
            response = gear_response(modes.system, frequencies, coordinates=list(dofs) or None,
                                     max_memory=max_memory)
        warnings = report.response_notes(response)
        cols, columns = report.response_columns(response)
        if fmt == "csv":
            write_rows([dict(zip(columns, row)) for row in zip(*(cols[c].tolist()
                                                                  for c in columns))],
                       columns, output)
        elif fmt == "json":
            write_json(document("gears", cols, report.units_of(cols), {}, warnings,
                                analysis="response", drive=drive.name), output)
        else:
            show(report.response_tables(response, cols, columns, label), output)
    elif check:
        from dyade.vibration.gears.elimination import check as eliminate

        result = eliminate(modes.system, modes)
        warnings = report.check_notes(result)
        if fmt == "csv":
            write_rows(report.check_rows(result), report.CHECK_COLUMNS, output)
        elif fmt == "json":
            rows = report.check_rows(result)
            cols = {name: [row[name] for row in rows] for name in report.CHECK_COLUMNS}
            write_json(document("gears", cols, report.units_of(cols),
                                report.check_summary(result), warnings, analysis="check",
                                drive=drive.name), output)
        else:
            show(report.check_tables(result, label), output)
    else:
        warnings = report.mode_notes(modes)
        if shapes:
            shapes, note = modes_asked(shapes, modes.frequencies.size)
            warnings = warnings + [f"note: {note}"] * bool(note)
        if fmt == "csv":
            if shapes:
                write_rows(report.shape_rows(modes, shapes), report.SHAPE_COLUMNS, output)
            else:
                rows, columns = report.mode_rows(modes)
                write_rows(rows, columns, output)
        elif fmt == "json":
            rows, columns = report.mode_rows(modes)
            cols = {name: [row[name] for row in rows] for name in columns}
            summary = {"rigid_modes": report.rigid_description(modes)}
            if shapes:
                summary["shapes"] = report.shape_rows(modes, shapes)
            write_json(document("gears", cols, report.units_of(cols), summary, warnings,
                                analysis="modes", drive=drive.name), output)
        else:
            show(report.mode_tables(modes, shapes or 0), output)
    err = console(stderr=True)
    for line in warnings:
        err.print(line, markup=False)
