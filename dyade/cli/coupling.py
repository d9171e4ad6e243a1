"""``dyade coupling``: torsional resonance of a stiff coupling (Strümpfel); the
registry's ``coupling`` entry (``dyade.analyses.coupling``)."""

from __future__ import annotations

from pathlib import Path

import click

from dyade.analyses.coupling import ENTRIES
from dyade.cli import contract, main

ENTRY = ENTRIES["coupling"]


def coupling_options(command):
    """Decorate a command with the coupling file and the entry's options (shared with
    ``dyade plot coupling``)."""
    command = contract.declare(ENTRY)(command)
    return click.argument("coupling_file", required=False,
                          type=click.Path(exists=True, dir_okay=False, path_type=Path))(command)


def solve(coupling_file: Path | None, options: dict):
    """The entry run on the file and the command's options: an Outcome."""
    return contract.run(ENTRY, coupling_file, options)


@main.command()
@coupling_options
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: every η value.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
def coupling(coupling_file: Path | None, fmt, output, **options) -> None:
    """Torsional resonance of a stiff coupling (Strümpfel, eqs. (4)–(10)).

    The exciting moment M_E = M̂_E·sin Ωt drives the coupling inertia J_K through c1t ∥ b1;
    the secondary side holds it through c2t ∥ b2. For every tuning ratio η = Ω/ω_t dyade
    gives the transfer functions V_φ (coupling angle), V_ψ (exciting-side angle), V_q
    (counter-moment), V_r (relative angle) and their phases α, β, γ, δ (lead over M_E, true
    quadrant), plus ω_t, D, the resonance η0 (eq. 5) and the peak of each V:

    \b
        dyade coupling --J 1 --c1 1 --c2 1 --b1 0.05 --b2 0.05 --eta-range 0:3:0.01

    The same data may come from a TOML file with keys J, c1, c2, b1, b2, and optionally
    moment, eta_range = "0:3:0.01", speed_rpm, order (options override the file).
    """
    outcome = solve(coupling_file, options)
    tables = None
    if fmt == "table":
        from dyade.report import coupling as report

        tables = report.tables(outcome)
    contract.emit(outcome, fmt, output, tables, width=140 if output else None)
    contract.notes(outcome)
