"""A ``coupling`` Outcome (``dyade.analyses.coupling``) -> rich tables."""

from __future__ import annotations

import math
import numpy as np

from dyade.report.format import number, ordinal
from dyade.vibration import coupling as engine


def fmt(value: float, digits: int = 5) -> str:
    """A value to ``digits`` significant digits (``dyade.report.format``)."""
    return number(value, spec=f".{digits}g")


def tables(outcome):
    """The summary, the operating points and the transfer functions, phases and
    amplitudes (every k-th row to about 40) of a ``coupling`` Outcome as rich tables."""
    from rich.table import Table

    model, resp, operating = outcome.result
    cols, names = outcome.columns, list(outcome.columns)
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


