"""``dyade cam``: a disc cam's checks over one turn and its profile to manufacture."""

from __future__ import annotations

from pathlib import Path

import click

from dyade.analyses.cam import CURVES, ENTRIES
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
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default=None,
              help="csv/json: every cam angle. [default: table on stdout; with -o: from its "
                   "suffix (.csv, .json, .txt)]")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
@click.option("--points", "points_file", type=click.Path(dir_okay=False, writable=True,
                                                         path_type=Path),
              help="Write the working curve's points as CSV (the file's length unit, the "
                   "file's chord tolerance).")
@click.option("--cutter-points", "cutter_file", type=click.Path(dir_okay=False, writable=True,
                                                                path_type=Path),
              help="Write the cutter centre's path as CSV (needs manufacture.cutter_radius).")
@click.option("--outer-points", "outer_file", type=click.Path(dir_okay=False, writable=True,
                                                              path_type=Path),
              help='Write a grooved cam\'s outer flank as CSV (needs cam.closure = "groove").')
@click.option("--dxf", "dxf_file", type=click.Path(dir_okay=False, writable=True,
                                                   path_type=Path),
              help="Write the working curve (and the cutter's path) as a DXF drawing "
                   '(needs ezdxf: pip install "dyade[cad]").')
def cam(cam_file: Path, fmt, output, points_file, cutter_file, outer_file, dxf_file,
        **options) -> None:
    """A disc cam and its follower over one turn: the pressure angle against its limit,
    the radii of curvature and undercut, the smallest base circle, the contact force, the
    lift-off speed, the Hertz stress, the drive torque; and the profile to manufacture.

    CAM_FILE holds [cam] (follower kind, base radius, speed), [follower] (roller,
    offset or arm, mass, spring), [manufacture] (chord tolerance, cutter radius) and the
    follower's motion as a [profile] over the cam angle (`dyade help cams`):

    \b
        dyade cam mechanisms/cams/translating-roller.toml
        dyade cam mechanisms/cams/translating-roller.toml --points cam.csv --dxf cam.dxf
        dyade cam mechanisms/cams/translating-roller.toml -o checks.json
        dyade init cam my-cam.toml

    A grooved cam (cam.closure = "groove") says which flank carries the load;
    --outer-points writes its outer flank. A mechanism file whose [cam] drives link 2 (its
    follower) is checked the same way, the contact force and drive torque from the whole
    chain (`dyade analyse` sweeps it).

    Exit 1 where the follower can never keep contact; an undercut, or a roller larger
    than the base circle, is a warning.
    """
    from dyade.cli.common import infer_format
    from dyade.report import cam as report

    fmt = fmt or infer_format(None if output is None else str(output))
    if fmt not in ("table", "csv", "json"):  # .parquet: not written by this command
        raise click.BadParameter(f"{output}: dyade cam writes .csv, .json or .txt (the "
                                 f"table); or give --format table|csv|json.", param_hint="-o")
    for flag, target, suffixes in (("--points", points_file, (".csv", ".txt")),
                                   ("--cutter-points", cutter_file, (".csv", ".txt")),
                                   ("--outer-points", outer_file, (".csv", ".txt")),
                                   ("--dxf", dxf_file, (".dxf",))):
        if target is not None and (str(target) == "-" or target.suffix.lower() not in suffixes):
            raise click.BadParameter(
                f"{target}: {flag} writes "
                f"{'a DXF drawing: name the file .dxf (CSV points: --points)' if flag == '--dxf' else 'CSV points: name the file .csv (a DXF drawing: --dxf)'}.",
                param_hint=flag)
    if dxf_file is not None:
        report.require_ezdxf()  # before anything is computed or written
    outcome = solve(cam_file, options)
    result = outcome.result
    unit = outcome.meta["length_unit"]
    from dyade.cli.output import atomic, console

    err = console(stderr=True)
    wanted = ((points_file, "working"), (cutter_file, "cutter"), (outer_file, "outer"))
    for target, name in wanted:  # every curve asked for is there before any is written
        if target is not None and report.curve(result, name) is None:
            raise click.UsageError(
                f"--cutter-points: {cam_file.name} gives no `manufacture.cutter_radius`, so "
                f"there is no cutter path." if name == "cutter" else
                f"--outer-points: {cam_file.name} is not a grooved cam (`cam.closure` = "
                f"\"groove\", a roller follower), so there is no outer flank.")
    for target, name in wanted:
        if target is None:
            continue
        made = report.curve(result, name)
        with atomic(target) as handle:
            report.write_points(made, handle, unit)
        err.print(f"wrote {target}: {made.points.shape[0]} points of the {CURVES[name]} "
                  f"within {made.tolerance / _factor(unit):g} {unit} of the curve.",
                  markup=False)
    if dxf_file is not None:
        from dyade.errors import InputError

        try:  # (ezdxf writes the file itself: the folder made as -o makes it)
            if dxf_file.parent != Path(""):
                dxf_file.parent.mkdir(parents=True, exist_ok=True)
            report.write_dxf(result, dxf_file, unit)
        except OSError as err:
            raise InputError(f"{dxf_file}: cannot write the file ({err.strerror or err}).",
                             source=str(dxf_file)) from None
        err.print(f"wrote {dxf_file} (DXF, {unit}).", markup=False)
    tables = report.tables(outcome) if fmt == "table" else None
    contract.emit(outcome, fmt, output, tables, width=160 if output else None)
    contract.notes(outcome)


def _factor(unit: str) -> float:
    from dyade.units import LENGTH_FACTORS

    return LENGTH_FACTORS[unit]
