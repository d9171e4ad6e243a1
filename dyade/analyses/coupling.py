"""``coupling``: the torsional resonance of a stiff coupling (Strümpfel, eqs. (4)–(10)).

The input is a coupling file (J, c1, c2, b1, b2, moment, eta_range, speed_rpm, order)
or None; the options override the file's keys. Errors name each value by where it came
from: the file's key, else the option.
"""

from __future__ import annotations

import math
import os
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome

OPTIONS = (
    Option("J", float, "kg·m²", help="Coupling inertia J_K"),
    Option("c1", float, "N·m/rad", help="Primary-side torsional stiffness c1t"),
    Option("c2", float, "N·m/rad", help="Secondary-side torsional stiffness c2t"),
    Option("b1", float, "N·m·s/rad", help="Primary-side damping b1 (default 0)"),
    Option("b2", float, "N·m·s/rad", help="Secondary-side damping b2 (default 0)"),
    Option("eta-range", str, metavar="START:STOP:STEP",
           help="Tuning ratios η = Ω/ω_t to evaluate  [default: 0:3:0.01]"),
    Option("moment", float, "N·m",
           help="Exciting moment amplitude M̂_E: adds φ̂, ψ̂ [rad], M̂_Q [N·m], φ̂_r [rad]"),
    Option("speed", float, "rpm", multiple=True, metavar="RPM", old=("--speed-rpm",),
           help="Operating speed to place on the η axis (repeatable), with --order"),
    Option("order", float, help="Excitation order: Ω = order · 2π·speed/60  [default: 1]"),
)

FILE_KEYS = {"J": "J", "c1": "c1", "c2": "c2", "b1": "b1", "b2": "b2", "eta_range": "eta_range",
             "moment": "moment", "speed_rpm": "speed_rpm", "order": "order"}
"""API option -> the coupling file's key"""

COLUMNS = {"eta": ("-", "tuning ratio η = Ω/ω_t"),
           "V_phi": ("-", "transfer function of the coupling angle φ"),
           "V_psi": ("-", "transfer function of the exciting-side angle ψ"),
           "V_q": ("-", "transfer function of the counter-moment M_Q"),
           "V_r": ("-", "transfer function of the relative angle φ_r"),
           "alpha_deg": ("°", "phase α of φ: lead over M_E"),
           "beta_deg": ("°", "phase β of ψ: lead over M_E"),
           "gamma_deg": ("°", "phase γ of M_Q: lead over M_E"),
           "delta_deg": ("°", "phase δ of φ_r: lead over M_E"),
           "phi_hat": ("rad", "amplitude φ̂ for the given M̂_E"),
           "psi_hat": ("rad", "amplitude ψ̂ for the given M̂_E"),
           "MQ_hat": ("N·m", "amplitude M̂_Q for the given M̂_E"),
           "phir_hat": ("rad", "amplitude φ̂_r for the given M̂_E")}
"""column -> (unit, description)"""


def merged(source: Any, options: dict[str, Any]) -> tuple[dict[str, Any], dict[str, str]]:
    """The file's keys with the options over them (API names), and for each parameter
    of the engine where its value came from (the file's key, else the option)."""
    from dyade.files import coupling as reader

    data: dict[str, Any] = {}
    name = ""
    if source is not None:
        name = os.path.basename(os.fspath(source))
        data = _file_values(reader.load_data(source))
    given = {api: value for api, value in options.items()
             if api in FILE_KEYS and value is not None and value != ()}
    origin = {api: f"{name}: `{key}`" if api in data and api not in given else api
              for api, key in FILE_KEYS.items()}
    # the engine's parameters (Coupling's inertia, operating_points' speeds_rpm) too
    origin.update({reader.PARAMETERS[key]: origin[api] for api, key in FILE_KEYS.items()
                   if key in reader.PARAMETERS})
    data.update(given)
    return data, origin


def _file_values(data: dict[str, Any]) -> dict[str, Any]:
    out = {api: data[key] for api, key in FILE_KEYS.items() if key in data}
    if "name" in data:
        out["name"] = data["name"]
    if "speed_rpm" in out and not isinstance(out["speed_rpm"], (list, tuple)):
        out["speed_rpm"] = (out["speed_rpm"],)
    return out


def run(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    import numpy as np

    from dyade.errors import InputError
    from dyade.files.schema import value_range
    from dyade.vibration import coupling as engine

    data, origin = merged(source, options)
    missing = [key for key in ("J", "c1", "c2") if key not in data]
    if missing:
        raise InputError.parameter(tuple(missing), "must be given (as options or in a coupling "
                                                   "file).")
    try:
        model = engine.Coupling(float(data["J"]), float(data["c1"]), float(data["c2"]),
                                float(data.get("b1", 0.0)), float(data.get("b2", 0.0)))
        try:
            eta = np.array(value_range(data.get("eta_range", "0:3:0.01"), "", False, 10_000_000))
        except ValueError as err:
            raise InputError.parameter("eta_range", str(err)) from None
        budget.time(eta.size * 2e-7, f"the response at {eta.size:,} tuning ratios")
        response = engine.response(model, eta)
        amplitudes = (engine.amplitudes(model, response, moment=float(data["moment"]))
                      if "moment" in data else None)
        operating = (engine.operating_points(model, list(data["speed_rpm"]),
                                             order=float(data.get("order", 1.0)))
                     if data.get("speed_rpm") else None)
    except InputError as err:
        raise err.naming(origin) from None
    outcome = Outcome("coupling", figures=("coupling",),
                      meta={"name": data.get("name"), "source": None if source is None
                            else os.fspath(source)},
                      result=(model, response, operating))
    columns: dict[str, Any] = {"eta": response.eta, **response.transfer}
    for phase in ("alpha", "beta", "gamma", "delta"):
        columns[f"{phase}_deg"] = np.degrees(response.phase[phase])
    if amplitudes is not None:
        columns.update(amplitudes)
    for name, values in columns.items():
        columns[name] = np.asarray(values, dtype=np.float64) + 0.0  # ∞: unbounded
    outcome.columns = columns
    outcome.units = {name: COLUMNS[name][0] for name in columns}
    outcome.descriptions = {name: COLUMNS[name][1] for name in columns}
    add = outcome.add
    add("omega_t", model.natural_frequency, "rad/s",
        description="natural frequency ω_t = sqrt((c1+c2)/J)")
    add("f_t", model.natural_frequency / (2 * math.pi), "Hz", description="  as frequency")
    add("D", model.damping_ratio, "-", description="damping ratio D = (b1+b2)/(2·J·ω_t)")
    add("kappa", model.kappa, "-", description="κ = c1/(c1+c2)")
    eta0 = model.resonance()
    add("eta0", eta0, "-", description="resonance η0, eq. (5)")
    add("eta_unbounded", engine.undamped_resonance(model), "-",
        description="undamped resonance η (b2 = 0), eq. (6)")
    for name, peak in engine.peaks(response, model).items():
        if peak is None:
            add(f"{name}_max", None, "-", description=f"peak of {name} (not defined)")
        else:
            unbounded = math.isinf(peak[0])
            add(f"{name}_max", None if unbounded else peak[0], "-", where={"eta": peak[1]},
                description=f"peak of {name} ({'unbounded' if unbounded else 'in the range'})")
            add(f"{name}_unbounded", unbounded, "-",
                description=f"  {name} unbounded (undamped resonance)")
    if operating is not None:
        add("order", operating.order, "-", description="excitation order")
        for k, speed in enumerate(operating.speeds_rpm.tolist()):
            place = {"speed_rpm": speed, "eta": float(operating.eta[k])}
            for name in ("V_phi", "V_psi", "V_q", "V_r"):
                add(f"{name}_op{k + 1}", float(operating.response.transfer[name][k]), "-",
                    where=place, description=f"{name} at {speed:g} rpm")
    outcome.notes = notes(model, response, eta)
    return outcome


def notes(model, resp, eta) -> list[str]:
    """The undamped and degenerate cases, worded."""
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
        out.append("note: c1 = 0: V_ψ and V_r are normalised by c1t and are not defined "
                   "(empty); with --moment, ψ̂ and φ̂_r are given.")
    zero_psi = np.isfinite(resp.transfer["V_psi"]) & (resp.transfer["V_psi"] == 0.0)
    if zero_psi.any():
        out.append(f"note: ψ̂ = 0 at η = {eta[zero_psi][0]:.6g} (undamped anti-resonance): its "
                   f"phase β is undefined there (empty).")
    return out


ENTRIES = {"coupling": Analysis("coupling", "Torsional resonance of a stiff coupling "
                                "(Strümpfel)", run, OPTIONS, source="coupling",
                                figures=("coupling",), command="dyade coupling")}
