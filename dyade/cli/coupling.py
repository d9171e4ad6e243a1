"""``dyade coupling``: torsional resonance of a stiff coupling (SPEC §3)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click

from dyade.cli import main
from dyade.cli.options import value_range
from dyade.cli.output import console, show, write_json, write_rows

COLUMNS = ["eta", "V_phi", "V_psi", "V_q", "V_r", "alpha_deg", "beta_deg", "gamma_deg",
           "delta_deg"]
MOMENT_COLUMNS = ["phi_hat", "psi_hat", "MQ_hat", "phir_hat"]
FILE_KEYS = {"name", "J", "c1", "c2", "b1", "b2", "moment", "eta_range", "speed_rpm", "order"}


def _read_file(path: Path) -> dict[str, Any]:
    import difflib
    import tomllib

    from dyade.errors import InputError

    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"{path.name}: not valid TOML: {err}.") from None
    for key, value in data.items():
        if key not in FILE_KEYS:
            close = difflib.get_close_matches(key, sorted(FILE_KEYS), n=1)
            hint = f" Did you mean `{close[0]}`?" if close else f" Allowed: {', '.join(sorted(FILE_KEYS))}."
            raise InputError(f"{path.name}: unknown key `{key}`.{hint}")
        if key in ("name", "eta_range"):
            if not isinstance(value, str):
                raise InputError(f"{path.name}: `{key}` must be a string, got {value!r}.")
        elif key == "speed_rpm":
            values = value if isinstance(value, list) else [value]
            if any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in values):
                raise InputError(f"{path.name}: `speed_rpm` must be a number or a list of "
                                 f"numbers [rpm], got {value!r}.")
        elif isinstance(value, bool) or not isinstance(value, (int, float)):
            unit = {"J": "kg·m²", "c1": "N·m/rad", "c2": "N·m/rad", "b1": "N·m·s/rad",
                    "b2": "N·m·s/rad", "moment": "N·m", "order": "-"}[key]
            raise InputError(f"{path.name}: `{key}` must be a number [{unit}], got {value!r}.")
    return data


@main.command()
@click.argument("coupling_file", type=click.Path(exists=True, dir_okay=False, path_type=Path),
                required=False)
@click.option("--J", "inertia", type=float, help="Coupling inertia J_K [kg·m²].")
@click.option("--c1", type=float, help="Primary-side torsional stiffness c1t [N·m/rad].")
@click.option("--c2", type=float, help="Secondary-side torsional stiffness c2t [N·m/rad].")
@click.option("--b1", type=float, help="Primary-side damping b1 [N·m·s/rad] (default 0).")
@click.option("--b2", type=float, help="Secondary-side damping b2 [N·m·s/rad] (default 0).")
@click.option("--eta-range", metavar="START:STOP:STEP",
              help="Tuning ratios η = Ω/ω_t to evaluate  [default: 0:3:0.01].")
@click.option("--moment", type=float,
              help="Exciting moment amplitude M̂_E [N·m]: adds φ̂, ψ̂ [rad], M̂_Q [N·m], φ̂_r [rad].")
@click.option("--speed-rpm", "speeds", type=float, multiple=True,
              help="Operating speed [rpm] to place on the η axis (repeatable), with --order.")
@click.option("--order", type=float, default=None,
              help="Excitation order: Ω = order · 2π·speed/60  [default: 1].")
@click.option("--format", "fmt", type=click.Choice(["table", "csv", "json"]), default="table",
              show_default=True, help="csv/json: every η value.")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True, path_type=Path),
              help="Write the result to this file instead of standard output.")
def coupling(coupling_file: Path | None, inertia, c1, c2, b1, b2, eta_range, moment, speeds,
             order, fmt, output) -> None:
    """Torsional resonance of a stiff coupling (Strümpfel, SPEC §3).

    The exciting moment M_E = M̂_E·sin Ωt drives the coupling inertia J_K through c1t ∥ b1;
    the secondary side holds it through c2t ∥ b2. For every tuning ratio η = Ω/ω_t dyade
    gives the transfer functions V_φ (coupling angle), V_ψ (exciting-side angle), V_q
    (counter-moment), V_r (relative angle) and their phases α, β, γ, δ (lead over M_E, true
    quadrant), plus ω_t, D, the resonance η0 (eq. 5) and the peak of each V:

        dyade coupling --J 1 --c1 1 --c2 1 --b1 0.05 --b2 0.05 --eta-range 0:3:0.01

    The same data may come from a TOML file with keys J, c1, c2, b1, b2, and optionally
    moment, eta_range = "0:3:0.01", speed_rpm, order (options override the file).
    """
    import numpy as np

    from dyade.vibration import coupling as engine

    data: dict[str, Any] = _read_file(coupling_file) if coupling_file else {}
    for key, value in (("J", inertia), ("c1", c1), ("c2", c2), ("b1", b1), ("b2", b2),
                       ("moment", moment), ("eta_range", eta_range), ("order", order)):
        if value is not None:
            data[key] = value
    if speeds:
        data["speed_rpm"] = list(speeds)
    missing = [f"--{k}" for k in ("J", "c1", "c2") if k not in data]
    if missing:
        raise click.UsageError(f"missing {', '.join(missing)} (or give them in a coupling file).")
    model = engine.Coupling(float(data["J"]), float(data["c1"]), float(data["c2"]),
                            float(data.get("b1", 0.0)), float(data.get("b2", 0.0)))
    eta = np.array(value_range(data.get("eta_range", "0:3:0.01"), "--eta-range", ""))
    resp = engine.response(model, eta)
    cols: dict[str, Any] = {"eta": eta}
    cols.update(resp.transfer)
    for name in ("alpha", "beta", "gamma", "delta"):
        cols[f"{name}_deg"] = np.degrees(resp.phase[name])
    names = list(COLUMNS)
    if "moment" in data:
        cols.update(engine.amplitudes(model, resp, float(data["moment"])))
        names += MOMENT_COLUMNS
    operating = _operating_points(model, data, engine)
    warnings = _notes(model, resp, eta)
    if fmt in ("csv", "json"):
        table = np.column_stack([np.asarray(cols[name], dtype=float) for name in names]) + 0.0
        table[~np.isfinite(table)] = np.nan  # unbounded or undefined: an empty field / null
        if fmt == "csv":
            write_rows([dict(zip(names, row)) for row in table.tolist()], names, output)
        else:
            eta0 = model.resonance()
            summary = {"omega_t": model.natural_frequency, "D": model.damping_ratio,
                       "kappa": model.kappa, "eta0": eta0}
            write_json({name: table[:, k] for k, name in enumerate(names)}
                       | {"summary": summary, "warnings": warnings}, output)
    else:
        show(_tables(model, resp, cols, names, operating), output, width=140 if output else None)
    err = console(stderr=True)
    for line in warnings:
        err.print(line)



def _operating_points(model, data, engine):
    import numpy as np

    speeds = data.get("speed_rpm")
    if speeds is None:
        return None
    speeds = speeds if isinstance(speeds, list) else [speeds]
    order = float(data.get("order", 1.0))
    if order <= 0:
        raise click.BadParameter(f"must be positive, got {order:g}.", param_hint="--order")
    if any(s <= 0 for s in speeds):
        raise click.BadParameter("operating speeds must be positive [rpm].",
                                 param_hint="--speed-rpm")
    omega = order * np.array(speeds, dtype=float) * 2 * math.pi / 60
    eta = omega / model.natural_frequency
    return np.array(speeds, dtype=float), eta, engine.response(model, eta)


def _fmt(value: float, digits: int = 5) -> str:
    if value != value:
        return "—"
    if value == math.inf:
        return "∞"
    return f"{value:.{digits}g}"


def _tables(model, resp, cols, names, operating):
    import numpy as np
    from rich.table import Table

    summary = Table(title="Stiff coupling: torsional resonance (Strümpfel, SPEC §3)",
                    title_justify="left")
    summary.add_column("quantity")
    summary.add_column("value", justify="right")
    summary.add_column("unit")
    eta0 = model.resonance()
    summary.add_row("natural frequency ω_t = sqrt((c1+c2)/J)", _fmt(model.natural_frequency), "rad/s")
    summary.add_row("  as frequency", _fmt(model.natural_frequency / (2 * math.pi)), "Hz")
    summary.add_row("damping ratio D = (b1+b2)/(2·J·ω_t)", _fmt(model.damping_ratio), "-")
    summary.add_row("κ = c1/(c1+c2)", _fmt(model.kappa), "-")
    summary.add_row("resonance η0, eq. (5)", _fmt(eta0) if eta0 is not None else "none (no peak)", "-")
    if eta0 is not None:
        summary.add_row("  resonance speed ω = η0·ω_t", _fmt(eta0 * model.natural_frequency), "rad/s")
    eta = cols["eta"]
    for name in ("V_phi", "V_psi", "V_q", "V_r"):
        values = cols[name]
        if np.all(np.isnan(values)):
            summary.add_row(f"peak of {name}", "not defined", "")
            continue
        k = int(np.nanargmax(np.where(np.isnan(values), -np.inf, values)))
        summary.add_row(f"peak of {name} (in the range)", f"{_fmt(values[k])} at η = {eta[k]:.4g}", "-")
    parts = [summary]
    if operating is not None:
        speeds, op_eta, op = operating
        table = Table(title="Operating points", title_justify="left")
        for head in ("speed [rpm]", "η", "V_φ", "V_ψ", "V_q", "V_r"):
            table.add_column(head, justify="right")
        for k in range(speeds.size):
            table.add_row(_fmt(speeds[k]), _fmt(op_eta[k], 4),
                          *[_fmt(op.transfer[n][k], 4) for n in ("V_phi", "V_psi", "V_q", "V_r")])
        parts.append(table)
    stride = max(1, int(np.ceil(eta.size / 40)))
    note = f" (every {stride}. of {eta.size} rows; --format csv for all)" if stride > 1 else ""
    heads = {"eta": "η", "V_phi": "V_φ", "V_psi": "V_ψ", "V_q": "V_q", "V_r": "V_r",
             "alpha_deg": "α [°] (φ)", "beta_deg": "β [°] (ψ)", "gamma_deg": "γ [°] (M_Q)",
             "delta_deg": "δ [°] (φ_r)", "phi_hat": "φ̂ [rad]", "psi_hat": "ψ̂ [rad]",
             "MQ_hat": "M̂_Q [N·m]", "phir_hat": "φ̂_r [rad]"}
    groups = [("Transfer functions" + note, ["eta", "V_phi", "V_psi", "V_q", "V_r"]),
              ("Phases: lead over M_E·sin Ωt" + note, ["eta", "alpha_deg", "beta_deg",
                                                       "gamma_deg", "delta_deg"])]
    if "phi_hat" in names:
        groups.append(("Amplitudes for the given M̂_E" + note, ["eta"] + [n for n in names if n.endswith("_hat")]))
    for title, group in groups:
        table = Table(title=title, title_justify="left")
        for name in group:
            table.add_column(heads[name], justify="right")
        for k in range(0, eta.size, stride):
            table.add_row(*[_fmt(float(cols[name][k]) + 0.0, 5) for name in group])
        parts.append(table)
    return parts


def _notes(model, resp, eta) -> list[str]:
    import numpy as np

    out = []
    if resp.unbounded.any():
        where = ", ".join(f"{e:.6g}" for e in eta[resp.unbounded][:5])
        out.append(f"note: no damping on the secondary side acts at η = {where}: that is the "
                  f"undamped resonance, where φ̂, ψ̂ and M̂_Q are unbounded (∞ in the table, "
                  f"empty in CSV) and their phases undefined.")
    if model.b1 + model.b2 == 0.0:
        out.append("note: b1 + b2 = 0: an undamped coupling (D = 0).")
    if model.c2 == 0.0:
        out.append("note: c2 = 0: V_q is normalised by c2t and is not defined (empty); with "
                  "--moment, M̂_Q is given.")
    if model.c1 == 0.0:
        out.append("note: c1 = 0: V_ψ and V_r are normalised by c1t and are not defined (empty); "
                  "with --moment, ψ̂ and φ̂_r are given.")
    zero_psi = np.isfinite(resp.transfer["V_psi"]) & (resp.transfer["V_psi"] == 0.0)
    if zero_psi.any():
        out.append(f"note: ψ̂ = 0 at η = {eta[zero_psi][0]:.6g} (undamped anti-resonance): its "
                  f"phase β is undefined there (empty).")
    return out
