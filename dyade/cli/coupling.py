"""``dyade coupling``: torsional resonance of a stiff coupling (Strümpfel)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, NamedTuple

import click

from dyade.cli import main
from dyade.cli.options import FINITE, value_range
from dyade.cli.output import console, flags, show, write_json, write_rows

OPTIONS = [
    click.argument("coupling_file", type=click.Path(exists=True, dir_okay=False, path_type=Path),
                   required=False),
    click.option("--J", "inertia", type=FINITE, help="Coupling inertia J_K [kg·m²]."),
    click.option("--c1", type=FINITE, help="Primary-side torsional stiffness c1t [N·m/rad]."),
    click.option("--c2", type=FINITE, help="Secondary-side torsional stiffness c2t [N·m/rad]."),
    click.option("--b1", type=FINITE, help="Primary-side damping b1 [N·m·s/rad] (default 0)."),
    click.option("--b2", type=FINITE, help="Secondary-side damping b2 [N·m·s/rad] (default 0)."),
    click.option("--eta-range", metavar="START:STOP:STEP",
                 help="Tuning ratios η = Ω/ω_t to evaluate  [default: 0:3:0.01]."),
    click.option("--moment", type=FINITE,
                 help="Exciting moment amplitude M̂_E [N·m]: adds φ̂, ψ̂ [rad], M̂_Q [N·m], φ̂_r "
                      "[rad]."),
    click.option("--speed-rpm", "speeds", type=FINITE, multiple=True, metavar="RPM",
                 help="Operating speed [rpm] to place on the η axis (repeatable), with --order."),
    click.option("--order", type=FINITE, default=None,
                 help="Excitation order: Ω = order · 2π·speed/60  [default: 1]."),
]
"""the data options of ``dyade coupling``, shared with ``dyade plot coupling``"""


def coupling_options(command):
    """Decorate a command with the coupling file and data options (``OPTIONS``)."""
    for option in reversed(OPTIONS):
        command = option(command)
    return command


class Inputs(NamedTuple):
    """The coupling as the options and the file give it, solved over η."""

    model: Any
    eta: Any
    response: Any
    amplitudes: Any
    operating: Any
    data: dict


def solve(coupling_file: Path | None, inertia, c1, c2, b1, b2, eta_range, moment, speeds,
          order) -> Inputs:
    """Merge the file and the options (options win), build the model and solve it;
    errors name each value by the file key or the flag it came from."""
    import numpy as np

    from dyade.files import coupling as reader
    from dyade.vibration import coupling as engine

    data: dict[str, Any] = reader.load_data(coupling_file) if coupling_file else {}
    given = {"J": inertia, "c1": c1, "c2": c2, "b1": b1, "b2": b2, "moment": moment,
             "eta_range": eta_range, "order": order, "speed_rpm": list(speeds) or None}
    # errors name a value by where it came from: the file's key, else its flag
    names = {param: (f"{coupling_file.name}: `{key}`" if key in data and given[key] is None
                     else "--speed-rpm" if key == "speed_rpm" else f"--{key}")
             for key, param in reader.PARAMETERS.items()}
    data.update({key: value for key, value in given.items() if value is not None})
    missing = [f"--{k}" for k in ("J", "c1", "c2") if k not in data]
    if missing:
        raise click.UsageError(f"missing {', '.join(missing)} (or give them in a coupling file).")
    with flags(names):
        model = engine.Coupling(float(data["J"]), float(data["c1"]), float(data["c2"]),
                                float(data.get("b1", 0.0)), float(data.get("b2", 0.0)))
    eta = np.array(value_range(data.get("eta_range", "0:3:0.01"), "--eta-range", ""))
    with flags(names):
        resp = engine.response(model, eta)
        amplitudes = (engine.amplitudes(model, resp, moment=float(data["moment"])) if "moment" in data
                      else None)
        operating = None
        if data.get("speed_rpm") is not None:
            speeds_rpm = data["speed_rpm"]
            operating = engine.operating_points(
                model, speeds_rpm if isinstance(speeds_rpm, list) else [speeds_rpm],
                order=float(data.get("order", 1.0)))
    return Inputs(model, eta, resp, amplitudes, operating, data)


@main.command()
@coupling_options
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: every η value.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
def coupling(coupling_file: Path | None, inertia, c1, c2, b1, b2, eta_range, moment, speeds,
             order, fmt, output) -> None:
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
    import numpy as np

    from dyade.report import coupling as report

    model, eta, resp, amplitudes, operating, data = solve(coupling_file, inertia, c1, c2, b1, b2,
                                                          eta_range, moment, speeds, order)
    cols, names = report.columns(resp, amplitudes)
    warnings = report.notes(model, resp, eta)
    if fmt in ("csv", "json"):
        table = np.column_stack([np.asarray(cols[name], dtype=float) for name in names]) + 0.0
        table[~np.isfinite(table)] = np.nan  # unbounded or undefined: an empty field / null
        if fmt == "csv":
            write_rows([dict(zip(names, row)) for row in table.tolist()], names, output)
        else:
            from dyade.report.document import document

            write_json(document("coupling", {name: table[:, k] for k, name in enumerate(names)},
                                report.UNITS, report.summary(model, resp, operating), warnings,
                                name=data.get("name")), output)
    else:
        show(report.tables(model, resp, cols, names, operating), output,
             width=140 if output else None)
    err = console(stderr=True)
    for line in warnings:
        err.print(line, markup=False)
