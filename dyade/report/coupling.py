"""Coupling results -> columns, notes and rich tables."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from dyade.vibration import coupling as engine

COLUMNS = ["eta", "V_phi", "V_psi", "V_q", "V_r", "alpha_deg", "beta_deg", "gamma_deg",
           "delta_deg"]
MOMENT_COLUMNS = ["phi_hat", "psi_hat", "MQ_hat", "phir_hat"]


def columns(resp, amplitudes: dict | None = None) -> tuple[dict[str, Any], list[str]]:
    """The response as named columns (phases in degrees) and their order; with the
    physical ``amplitudes`` of a given exciting moment."""
    cols: dict[str, Any] = {"eta": resp.eta}
    cols.update(resp.transfer)
    for name in ("alpha", "beta", "gamma", "delta"):
        cols[f"{name}_deg"] = np.degrees(resp.phase[name])
    names = list(COLUMNS)
    if amplitudes is not None:
        cols.update(amplitudes)
        names += MOMENT_COLUMNS
    return cols, names


def fmt(value: float, digits: int = 5) -> str:
    if value != value:
        return "—"
    if value == math.inf:
        return "∞"
    return f"{value:.{digits}g}"


def tables(model, resp, cols, names, operating):
    """The summary, the operating points and the transfer functions, phases and
    amplitudes (every k-th row to about 40) as rich tables."""
    from rich.table import Table

    summary = Table(title="Stiff coupling: torsional resonance (Strümpfel, eqs. (4)–(9))",
                    title_justify="left")
    summary.add_column("quantity")
    summary.add_column("value", justify="right")
    summary.add_column("unit")
    eta0 = model.resonance()
    summary.add_row("natural frequency ω_t = sqrt((c1+c2)/J)", fmt(model.natural_frequency), "rad/s")
    summary.add_row("  as frequency", fmt(model.natural_frequency / (2 * math.pi)), "Hz")
    summary.add_row("damping ratio D = (b1+b2)/(2·J·ω_t)", fmt(model.damping_ratio), "-")
    summary.add_row("κ = c1/(c1+c2)", fmt(model.kappa), "-")
    summary.add_row("resonance η0, eq. (5)", fmt(eta0) if eta0 is not None else "none (no peak)", "-")
    if eta0 is not None:
        summary.add_row("  resonance speed ω = η0·ω_t", fmt(eta0 * model.natural_frequency), "rad/s")
    eta = cols["eta"]
    for name, peak in engine.peaks(resp, model).items():
        if peak is None:
            summary.add_row(f"peak of {name}", "not defined", "")
        elif math.isinf(peak[0]):
            summary.add_row(f"peak of {name}", f"unbounded at η0 = {peak[1]:.4g}", "-")
        else:
            summary.add_row(f"peak of {name} (in the range)", f"{fmt(peak[0])} at η = {peak[1]:.4g}",
                            "-")
    parts = [summary]
    if operating is not None:
        speeds, op_eta, op = operating.speeds_rpm, operating.eta, operating.response
        table = Table(title=f"Operating points (excitation order {operating.order:g})",
                      title_justify="left")
        for head in ("speed [rpm]", "η [-]", "V_φ [-]", "V_ψ [-]", "V_q [-]", "V_r [-]"):
            table.add_column(head, justify="right")
        for k in range(speeds.size):
            table.add_row(fmt(speeds[k]), fmt(op_eta[k], 4),
                          *[fmt(op.transfer[n][k], 4) for n in ("V_phi", "V_psi", "V_q", "V_r")])
        parts.append(table)
    stride = max(1, int(np.ceil(eta.size / 40)))
    note = (f" ({eta.size} rows, every {ordinal(stride)} shown; --format csv for all)"
            if stride > 1 else "")
    heads = {"eta": "η [-]", "V_phi": "V_φ [-]", "V_psi": "V_ψ [-]", "V_q": "V_q [-]",
             "V_r": "V_r [-]",
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
            table.add_row(*[fmt(float(cols[name][k]) + 0.0, 5) for name in group])
        parts.append(table)
    return parts


def ordinal(n: int) -> str:
    """1st, 2nd, 3rd, 4th, …, 11th, 12th, 13th, 21st."""
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


UNITS = {"eta": "-", "V_phi": "-", "V_psi": "-", "V_q": "-", "V_r": "-", "alpha_deg": "°",
         "beta_deg": "°", "gamma_deg": "°", "delta_deg": "°", "phi_hat": "rad",
         "psi_hat": "rad", "MQ_hat": "N·m", "phir_hat": "rad"}


def summary(model, resp, operating) -> dict[str, Any]:
    """The figures of the model and of the response, for JSON."""
    out: dict[str, Any] = {"omega_t": model.natural_frequency,
                           "f_t_Hz": model.natural_frequency / (2 * math.pi),
                           "D": model.damping_ratio, "kappa": model.kappa,
                           "eta0": model.resonance(),
                           "eta_unbounded": engine.undamped_resonance(model), "peaks": {}}
    for name, peak in engine.peaks(resp, model).items():
        out["peaks"][name] = (None if peak is None else
                              {"value": None if math.isinf(peak[0]) else peak[0],
                               "eta": peak[1], "unbounded": math.isinf(peak[0])})
    if operating is not None:
        out["operating_points"] = {"order": operating.order,
                                   "speed_rpm": operating.speeds_rpm, "eta": operating.eta,
                                   **{name: values for name, values in
                                      operating.response.transfer.items()}}
    return out


def notes(model, resp, eta) -> list[str]:
    """Notes on undamped and degenerate cases."""
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
