"""The elastic drive line (``dyade driveline``) as columns, summaries and tables."""

from __future__ import annotations

from typing import Any

import numpy as np
from rich.table import Table

from dyade.units import RAD_PER_S_TO_RPM as RPM  # [rpm per rad/s]

UNITS = {"angle_deg": "°", "shaft_torque": "N·m", "rigid_torque": "N·m", "speed_rpm": "rpm",
         "rigid_speed_rpm": "rpm", "acceleration": "rad/s²", "rigid_acceleration": "rad/s²",
         "twist_deg": "°", "eta": "-", "peak_torque": "N·m", "rigid_peak_torque": "N·m",
         "twist_amplitude_deg": "°", "fluctuation": "-", "floquet": "-", "unstable": "",
         "time": "s", "crank_speed_rpm": "rpm", "motor_speed_rpm": "rpm"}
"""column -> unit of every table of ``dyade driveline``"""


def frequency_summary(freq) -> dict[str, Any]:
    """ω̄, its range over the cycle, Ω/ω̄ and the VDI 2149 verdict."""
    return {"omega_bar": freq.omega_bar, "omega_bar_rpm": freq.omega_bar * RPM,
            "omega_min": freq.omega_min, "omega_max": freq.omega_max,
            "inertia_mean": freq.inertia_mean, "speed_rpm": freq.speed * RPM,
            "ratio": freq.ratio, "vdi_2149": bool(freq.vdi_2149)}


def steady_columns(state) -> dict[str, Any]:
    return {"angle_deg": np.degrees(state.crank_angle), "shaft_torque": state.shaft_torque,
            "rigid_torque": state.rigid_torque, "speed_rpm": state.crank_speed * RPM,
            "rigid_speed_rpm": state.rigid_speed * RPM, "acceleration": state.crank_acceleration,
            "rigid_acceleration": state.rigid_acceleration,
            "twist_deg": np.degrees(state.twist)}


def steady_summary(state) -> dict[str, Any]:
    out = dict(state.figures)
    out.update({"speed_mean_rpm": out.pop("speed_mean") * RPM,
                "peak_torque": float(np.max(np.abs(state.shaft_torque))),
                "rigid_peak_torque": float(np.max(np.abs(state.rigid_torque))),
                "twist_amplitude_deg": float(np.degrees(np.ptp(state.twist) / 2.0)),
                "floquet": [abs(complex(m)) for m in state.multipliers],
                "stable": state.stable})
    return out


def resonance_columns(curve) -> dict[str, Any]:
    return {"speed_rpm": curve.speed * RPM, "eta": curve.eta, "peak_torque": curve.peak_torque,
            "rigid_peak_torque": curve.rigid_peak_torque,
            "twist_amplitude_deg": np.degrees(curve.twist_amplitude),
            "fluctuation": curve.fluctuation, "floquet": curve.stability,
            "unstable": curve.unstable.astype(float)}


def resonance_labels(curve) -> list[dict[str, Any]]:
    return [{"harmonic": k, "speed_rpm": speed * RPM, "eta": speed / curve.omega_bar,
             "kind": kind} for k, speed, kind in curve.resonances]


def unstable_ranges(speed_rpm, unstable) -> list[tuple[float, float]]:
    """The speed ranges [rpm] of consecutive unstable points."""
    out, first = [], None
    for value, bad in zip(list(speed_rpm) + [None], list(unstable) + [False]):
        if bad and first is None:
            first = value
        if not bad and first is not None:
            out.append((first, last))
            first = None
        last = value
    return out


def table(title: str, columns: dict[str, Any], every: int = 1) -> Table:
    out = Table(title=title, title_justify="left")
    names = list(columns)
    for name in names:
        unit = UNITS.get(name, "")
        out.add_column(f"{name} [{unit}]" if unit and unit != "-" else name, justify="right")
    count = len(columns[names[0]])
    for i in range(0, count, every):
        out.add_row(*(f"{float(columns[n][i]):.6g}" for n in names))
    return out


def summary_table(title: str, summary: dict[str, Any]) -> Table:
    out = Table(title=title, title_justify="left")
    out.add_column("quantity")
    out.add_column("value", justify="right")
    for key, value in summary.items():
        if isinstance(value, float):
            text = f"{value:.6g}"
        elif isinstance(value, list):
            text = ", ".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in value)
        else:
            text = str(value)
        out.add_row(key, text)
    return out
