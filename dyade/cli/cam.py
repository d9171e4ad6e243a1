"""``dyade cam``: a disc cam's checks over one turn and its profile to manufacture."""

from __future__ import annotations

from pathlib import Path

import click

from dyade.analyses.cam import ENTRIES
from dyade.cli import contract, main

ENTRY = ENTRIES["cam"]


def cam_options(command):
    """Decorate a command with the cam file and the entry's options (shared with
    ``dyade plot cam``)."""
    command = contract.declare(ENTRY)(command)
    return click.argument("cam_file", type=click.Path(exists=True, dir_okay=False,
                                                      path_type=Path))(command)


def solve(cam_file: Path, options: dict):
    """The entry run on the file and the command's options: an Outcome."""
    return contract.run(ENTRY, cam_file, options)


@main.command()
@cam_options
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: every cam angle.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
@click.option("--points", "points_file", type=click.Path(dir_okay=False, writable=True,
                                                         path_type=Path),
              help="Write the working curve's points as CSV (the file's length unit, the "
                   "file's chord tolerance).")
@click.option("--cutter-points", "cutter_file", type=click.Path(dir_okay=False, writable=True,
                                                                path_type=Path),
              help="Write the cutter centre's path as CSV (needs manufacture.cutter_radius).")
@click.option("--dxf", "dxf_file", type=click.Path(dir_okay=False, writable=True,
                                                   path_type=Path),
              help="Write the working curve (and the cutter's path) as a DXF drawing "
                   '(needs ezdxf: pip install "dyade[cad]").')
def cam(cam_file: Path, fmt, output, points_file, cutter_file, dxf_file, **options) -> None:
    """A disc cam and its follower over one turn: the pressure angle against its limit,
    the radii of curvature and undercut, the smallest base circle, the contact force, the
    lift-off speed, the Hertz stress, the drive torque; and the profile to manufacture.

    CAM_FILE holds [cam] (follower kind, base radius, speed), [follower] (roller,
    offset or arm, mass, spring), [manufacture] (chord tolerance, cutter radius) and the
    follower's motion as a [profile] over the cam angle (`dyade help cams`):

    \b
        dyade cam mechanisms/cams/translating-roller.toml
        dyade cam mechanisms/cams/translating-roller.toml --points cam.csv --dxf cam.dxf
        dyade init cam my-cam.toml

    A mechanism file whose [cam] drives link 2 (its follower) is checked the same way,
    the contact force and drive torque from the whole chain (`dyade analyse` sweeps it).

    Exit 1 where the follower can never keep contact; an undercut is a warning.
    """
    from dyade.report import cam as report

    if dxf_file is not None:
        report.require_ezdxf()  # before anything is computed or written
    outcome = solve(cam_file, options)
    result = outcome.result
    unit = outcome.meta["length_unit"]
    from dyade.cli.output import atomic, console

    err = console(stderr=True)
    for target, name in ((points_file, "working"), (cutter_file, "cutter")):
        if target is None:
            continue
        made = report.curve(result, name)
        if made is None:
            raise click.UsageError(f"--cutter-points: {cam_file.name} gives no "
                                   f"`manufacture.cutter_radius`, so there is no cutter path.")
        with atomic(target) as handle:
            report.write_points(made, handle, unit)
        err.print(f"wrote {target}: {made.points.shape[0]} points of the "
                  f"{'working curve' if name == 'working' else 'cutter path'} within "
                  f"{made.tolerance / _factor(unit):g} {unit} of the curve.", markup=False)
    if dxf_file is not None:
        report.write_dxf(result, dxf_file, unit)
        err.print(f"wrote {dxf_file} (DXF, {unit}).", markup=False)
    tables = report.tables(outcome) if fmt == "table" else None
    contract.emit(outcome, fmt, output, tables, width=160 if output else None)
    contract.notes(outcome)


def _factor(unit: str) -> float:
    from dyade.units import LENGTH_FACTORS

    return LENGTH_FACTORS[unit]
