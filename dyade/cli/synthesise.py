"""``dyade synthesise``: which mechanism moves like this; the registry's ``synthesis``
entry (``dyade.analyses.synthesis``)."""

from __future__ import annotations

import os
from pathlib import Path

import click

from dyade.analyses.synthesis import ENTRIES
from dyade.cli import contract, main

ENTRY = ENTRIES["synthesis"]


def synthesis_options(command):
    """The synthesis file and the entry's options, -j (shared with ``dyade plot
    synthesis``)."""
    command = contract.declare(ENTRY, skip=("jobs",))(command)
    command = click.option("-j", "--jobs", "jobs", type=click.IntRange(min=0), default=1,
                           show_default=True, metavar="N",
                           help=ENTRY.option("jobs").help + ".")(command)
    return click.argument("synthesis_file",
                          type=click.Path(exists=True, dir_okay=False, path_type=Path))(command)


def solve(synthesis_file: Path, options: dict):
    """The entry run on the file and the command's options: an Outcome."""
    return contract.run(ENTRY, synthesis_file, options, what="synthesis: candidates")


@main.command("synthesise")
@synthesis_options
@click.option("--write", "folder", type=click.Path(file_okay=False, path_type=Path),
              help="Write the designs as mechanism files DIR/design-N.toml (a missing folder "
                   "is created), ready for `dyade analyse`.")
@click.option("--plot", "figure", type=click.Path(dir_okay=False, path_type=Path),
              help="Draw the target against the designs and the designs themselves into this "
                   "figure (.png, .svg, .pdf; needs the plot extra).")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: one row per design (function generation: "
                                      "per table row, with the structural error).")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
def synthesise(synthesis_file: Path, folder: Path | None, figure: Path | None, fmt, output,
               **options) -> None:
    """Find the mechanisms that do what SYNTHESIS_FILE asks: function generation (a
    four-bar's output angle or a slider-crank's slider position over the crank angle:
    three precision points in closed form, Chebyshev spacing or a least-squares fit of a
    table or of a motion profile), motion generation (three poses in closed form, four by
    the Burmester curves) or path generation (a closed coupler curve, a part of one
    without crank angles, or a straight-line or circular-arc stretch over a crank range)
    with a four-bar or a slider-crank; all of these also with the Watt I/II and
    Stephenson I/III six-bars (topology = "stephenson-sixbar", ...): a function is link
    6's angle (a table of at least nine rows), poses are link 5's (three to seven, [x,
    y, angle]), both found by a search and least squares.

    A path search traces many candidates in blocks through dyade's positions-only stage
    (seeded: the same result on any -j or cluster), matches them by a start-point-free
    Fourier shape distance and refines the best by least squares (needs scipy: pip
    install "dyade[study]"). With masses ([scores] mass_per_length or mass_each, kg/m or
    kg) every design gets the sweep's figures at the operating speed and the Pareto
    front of error against one of them. `dyade init synthesis FILE` writes a commented
    file (a closed coupler curve; synthesis-function, -slider, -poses, -open-path,
    -line, -sixbar-function and -sixbar-poses the other targets); `dyade help synthesis`
    documents every key. Every target estimates its time before the work (a timed
    trial): --max-time S refuses a longer run with exit 2 and the estimate, and a run
    above a few seconds says it. search.min_transmission [angle unit] drops the
    candidates (and holds the fits) whose least transmission angle falls below it: over
    the turn for paths, stretches and a six-bar's poses, over the range for a motion-law
    function and a six-bar's function; a six-bar's two dyads both count (a four-bar's
    closed forms through three points have no other solution to choose).

    \b
        dyade synthesise coupler-curve.toml -j 0 --write designs --plot designs.png
        dyade analyse designs/design-1.toml

    Exit status 1 when the topology cannot reach the target (the message gives the best
    error found), 2 for a bad file, too few points, bounds that let no linkage assemble
    or an estimate over --max-time.
    """
    outcome = solve(synthesis_file, options)
    if folder is not None:
        from dyade.cli.output import atomic, console
        from dyade.report.synthesis import mechanism_text

        os.makedirs(folder, exist_ok=True)
        for k, design in enumerate(outcome.result.designs, start=1):
            path = folder / f"design-{k}.toml"
            with atomic(path) as handle:
                handle.write(mechanism_text(design, synthesis_file.name))
        console(stderr=True).print(f"wrote {len(outcome.result.designs)} mechanism files to "
                                   f"{folder}/ (design-1.toml best); next: dyade analyse "
                                   f"{folder}/design-1.toml", markup=False)
    if figure is not None:
        from dyade.cli.plot.output import Target, emit, prepare, suffix_format, FORMATS

        prepare(False)
        suffix_format(str(figure), FORMATS)
        from dyade.plot import synthesis as plot

        emit(plot.figure(outcome.result), Target(str(figure), False, None), True)
    tables = None
    if fmt == "table":
        from dyade.report import synthesis as report

        tables = report.tables(outcome)
    contract.emit(outcome, fmt, output, tables, width=140 if output else None)
    contract.notes(outcome, prefix="note: ")
