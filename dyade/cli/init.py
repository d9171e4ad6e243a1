"""``dyade init``: a commented starting mechanism file for a dyad kind."""

from __future__ import annotations

import os

import click

from dyade.cli import main
from dyade.cli.output import atomic, console


TEMPLATES = {"fourbar": "RRR", "slider-crank": "RRP", "slotted-lever": "RPR",
             "tangent-drive": "PRP", "scotch-yoke": "PPR", "study": "", "profile": "",
             "servo": "RRP", "synthesis": "", "cam": "",
             **{f"synthesis-{target}": "" for target in (
                 "function", "slider", "poses", "open-path", "line", "sixbar-function",
                 "sixbar-poses")}}
NEXT = {"study": ("a design study", "dyade study"),
        "profile": ("a motion profile", "dyade profile"),
        "servo": ("a servo press", "dyade servo"),
        "synthesis": ("a synthesis file: a closed coupler curve", "dyade synthesise"),
        "synthesis-function": ("a synthesis file: a four-bar's function through three "
                               "precision points", "dyade synthesise"),
        "synthesis-slider": ("a synthesis file: a slider's position table",
                             "dyade synthesise"),
        "synthesis-poses": ("a synthesis file: a four-bar through four poses",
                            "dyade synthesise"),
        "synthesis-open-path": ("a synthesis file: an open path with its crank angles",
                                "dyade synthesise"),
        "synthesis-line": ("a synthesis file: a straight-line stretch", "dyade synthesise"),
        "synthesis-sixbar-function": ("a synthesis file: a six-bar's function",
                                      "dyade synthesise"),
        "synthesis-sixbar-poses": ("a synthesis file: a six-bar through five poses",
                                   "dyade synthesise"),
        "cam": ("a disc cam", "dyade cam")}
"""a template that is not a plain mechanism -> (what it is, the command that runs it)"""
KIND_ALIASES = {"rrr": "fourbar", "four-bar": "fourbar", "rrp": "slider-crank",
                "rpr": "slotted-lever", "prp": "tangent-drive", "ppr": "scotch-yoke"}


@main.command()
@click.argument("kind", type=click.Choice(sorted(TEMPLATES) + sorted(KIND_ALIASES),
                                          case_sensitive=False))
@click.argument("file", type=click.Path(dir_okay=False, writable=True, allow_dash=True))
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
def init(kind: str, file: str, force: bool) -> None:
    """Write a commented starting mechanism FILE for KIND: fourbar (RRR), slider-crank
    (RRP), slotted-lever (RPR), tangent-drive (PRP) or scotch-yoke (PPR). The file is
    valid and analysable as written: edit the numbers, then `dyade analyse FILE`.
    KIND study writes a design study of fourbar.toml (`dyade study FILE`); KIND profile
    a motion profile of VDI 2143 laws over a machine cycle (`dyade profile FILE`); KIND
    servo a servo press, a slider-crank whose ram follows a motion profile (`dyade servo
    FILE`); KIND cam a disc cam with its follower and motion profile (`dyade cam FILE`).
    KIND synthesis writes a synthesis file (`dyade synthesise FILE`), a four-bar through
    a closed coupler curve; one per target: synthesis-function (a four-bar's output
    angle, three precision points), synthesis-slider (a slider-crank's slider position
    table), synthesis-poses (a four-bar through four poses), synthesis-open-path (an
    open path with its crank angles), synthesis-line (a straight-line stretch over 120°
    of crank), synthesis-sixbar-function and synthesis-sixbar-poses (a Stephenson III
    six-bar's output angle table, its link 5 through five poses). Each runs as written,
    in seconds.
    FILE "-" prints the template.

    \b
        dyade init synthesis-line line.toml
        dyade synthesise line.toml --write designs"""
    from importlib.resources import files

    name = KIND_ALIASES.get(kind.lower(), kind.lower())
    text = files("dyade").joinpath("templates", f"{name}.toml").read_text(encoding="utf-8")
    if file == "-":
        click.echo(text, nl=False)
        return
    if os.path.exists(file) and not force:
        raise click.UsageError(f"{file} exists; give --force to overwrite it.")
    with atomic(file) as handle:
        handle.write(text)
    also = ""
    if name == "study":  # and the mechanism it names, beside it, where it is not there yet
        mechanism = os.path.join(os.path.dirname(file), "fourbar.toml")
        if not os.path.exists(mechanism):
            with atomic(mechanism) as handle:
                handle.write(files("dyade").joinpath("templates", "fourbar.toml").read_text(
                    encoding="utf-8"))
            also = f" and {mechanism} (its mechanism)"
    if name in NEXT:
        what, command = NEXT[name]
        console(stderr=True).print(f"wrote {file} ({what}){also}; next: {command} {file}")
        return
    console(stderr=True).print(f"wrote {file} ({name}, dyad kind {TEMPLATES[name]}); next: "
                               f"dyade describe {file}")
