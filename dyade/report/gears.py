"""Gear-drive results -> columns (CSV/JSON), notes and rich tables: modes with energy
shares and modal mesh forces, mode shapes, the Campbell diagram's resonances, the forced
response and the elimination check."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from dyade.model.gears import DOFS
from dyade.roundoff import EIGEN_ROUNDOFF, clean

MOTIONS = ("torsion", "lateral", "axial")
MODEL = {"rfe": "rigid finite elements, six coordinates per body",
         "torsional": "torsional model, one rotation per body"}


def fmt(value: Any, digits: int = 5) -> str:
    if value is None:
        return "—"
    if isinstance(value, str):
        return value
    value = float(value)
    if value != value:
        return "—"
    if math.isinf(value):
        return "∞"
    return f"{value:.{digits}g}"


def percent(value: float) -> str:
    return "—" if value != value else f"{100.0 * value:.1f}"


def title(modes) -> str:
    system = modes.system
    drive = system.drive
    ideal = len(system.ideal)
    meshes = len(drive.meshes)
    mesh_text = f"{meshes} mesh{'es' if meshes != 1 else ''}" + (
        f" ({ideal} ideal)" if 0 < ideal < meshes else " (ideal)" if ideal else "")
    return (f"{drive.name}: {MODEL[drive.model]}; {system.size} coordinates, {mesh_text}, "
            f"{len(system.bodies)} bodies")


# -- modes -------------------------------------------------------------------------------
def mode_columns(modes) -> tuple[dict[str, np.ndarray], list[str]]:
    """One row per elastic mode: frequency, kinetic and strain shares by motion, strain
    shares per shaft, bearing, element and elastic mesh (by motion), the modal mesh force
    and modal mesh stiffness of every mesh."""
    count = modes.frequencies.size
    cols: dict[str, Any] = {"mode": np.arange(1, count + 1), "f_Hz": modes.frequencies}
    kinetic, strain = modes.totals("kinetic"), modes.totals("strain")
    for motion in MOTIONS:
        cols[f"T_{motion}"] = kinetic[motion]
    for motion in MOTIONS + ("mesh",):
        cols[f"U_{motion}"] = strain[motion]
    for (owner, motion), share in modes.strain.items():
        cols[f"U_{owner}_{motion}"] = share
    forces = cleaned(modes.mesh_forces)
    stiffness = cleaned(modes.mesh_stiffness, 1e-18)
    for k, mesh in enumerate(modes.system.drive.meshes):
        cols[f"F_{mesh.name}"] = forces[k]
        cols[f"kappa_{mesh.name}_N_per_m"] = stiffness[k]
    cols["dominant"] = [f"{owner} {motion}" for owner, motion, _ in modes.dominant()]
    return cols, list(cols)


def mode_rows(modes) -> tuple[list[dict], list[str]]:
    cols, names = mode_columns(modes)
    rows = [{name: _item(cols[name][k]) for name in names} for k in range(modes.frequencies.size)]
    return rows, names


def cleaned(values: np.ndarray, rtol: float = 1e-9) -> np.ndarray:
    """(meshes, modes) modal mesh forces or stiffnesses with the round-off of the modes
    that do not load a mesh (below ``rtol`` of that mesh's largest) shown as 0; κ = F²/ω²
    takes ``rtol`` squared."""
    values = np.asarray(values, dtype=float)
    largest = np.nanmax(np.abs(values), axis=1, initial=0.0)[:, None] if values.size else 0.0
    return np.where(np.abs(values) < rtol * largest, 0.0, values)


def _item(value: Any) -> Any:
    return value.item() if isinstance(value, np.generic) else value


SHAPE_COLUMNS = ["mode", "body", "ux", "uy", "uz", "rx", "ry", "rz"]


def shape_rows(modes, count: int) -> list[dict]:
    """Mode shapes of the first ``count`` elastic modes, one row per (mode, body), in each
    body's own axes, M-orthonormal (the torsional model has rx only)."""
    system = modes.system
    per = system.per_body
    rows = []
    for k in range(min(count, modes.frequencies.size)):
        for i, body in enumerate(system.bodies):
            values = modes.shapes[i * per:(i + 1) * per, k]
            row: dict[str, Any] = {"mode": k + 1, "body": body.name}
            if per == 6:
                row.update({d: float(v) for d, v in zip(DOFS, values)})
            else:
                row.update({d: (float(values[0]) if d == "rx" else None) for d in DOFS})
            rows.append(row)
    return rows


def rigid_description(modes) -> list[str]:
    """One line per rigid-body mode: which motion it is."""
    system = modes.system
    per = system.per_body
    kinds = ("axial", "lateral", "lateral", "torsion", "lateral", "lateral") if per == 6 else (
        "torsion",)
    out = []
    for k in range(modes.rigid.shape[1]):
        energy = system.mass * modes.rigid[:, k] ** 2
        shares = {m: 0.0 for m in MOTIONS}
        for i, value in enumerate(energy):
            shares[kinds[i % per]] += float(value)
        total = sum(shares.values()) or 1.0
        parts = ", ".join(f"{m} {100 * s / total:.0f} %" for m, s in shares.items()
                          if s / total >= 0.005)
        out.append(f"rigid-body mode {k + 1}: {parts} of its kinetic energy")
    return out


def mode_notes(modes) -> list[str]:
    out = []
    rigid = modes.rigid.shape[1]
    if rigid:
        out.append(f"note: {rigid} rigid-body mode{'s' if rigid > 1 else ''}: the drive can "
                   f"move without deforming anything (no element or mesh resists it); "
                   f"{'they are' if rigid > 1 else 'it is'} not a resonance and not listed as "
                   f"one. " + "; ".join(rigid_description(modes)) + ".")
    if np.any(modes.unresolved):
        out.append(f"note: {int(np.sum(modes.unresolved))} mode(s) lie below "
                   f"{modes.resolution:.3g} Hz, the smallest frequency this computation resolves "
                   f"next to the stiffest parts of the drive: no value is given for them.")
    if modes.system.ideal:
        out.append("note: ideal meshes store no strain energy (U_mesh = 0); their modal mesh "
                   "stiffness kappa = F²/ω² [N/m] ranks a mode's response to a transmission "
                   "error (dynamic mesh force F²·e/(2ζ·ω²) at resonance).")
    return out


def mode_tables(modes, shapes: int = 0):
    """The modes table (and the first ``shapes`` mode shapes) as rich tables."""
    from rich.table import Table

    meshes = modes.system.drive.meshes
    elastic = any(m.stiffness is not None for m in meshes)
    table = Table(title="Natural frequencies (no gyroscopic terms: the same at every speed); "
                        "energy shares [%]", title_justify="left")
    heads = ["mode", "f [Hz]", "T tors", "T lat", "T ax", "U tors", "U lat", "U ax"]
    heads += ["U mesh"] if elastic else []
    heads += ["dominant (strain)"] + [f"F {m.name}" for m in meshes]
    for head in heads:
        table.add_column(head, justify="left" if head.startswith("dominant") else "right")
    kinetic, strain = modes.totals("kinetic"), modes.totals("strain")
    dominant = modes.dominant()
    forces = cleaned(modes.mesh_forces)
    for k in range(modes.frequencies.size):
        owner, motion, share = dominant[k]
        row = [str(k + 1), fmt(modes.frequencies[k], 6)]
        row += [percent(kinetic[m][k]) for m in MOTIONS] + [percent(strain[m][k]) for m in MOTIONS]
        row += [percent(strain["mesh"][k])] if elastic else []
        row += [f"{owner} {motion} {percent(share)}" if owner else "—"]
        row += [fmt(forces[j, k], 4) for j in range(len(meshes))]
        table.add_row(*row)
    parts: list[Any] = [title(modes), table]
    if meshes:
        parts.append("F: modal mesh force along the plane-of-action normal, compression "
                     "positive, per unit modal coordinate of the M-orthonormal mode [N/(m·√kg)]")
    if shapes:
        parts.append(shape_table(modes, shapes))
    return parts


def shape_table(modes, count: int):
    from rich.table import Table

    table = Table(title=f"Mode shapes of modes 1–{min(count, modes.frequencies.size)} "
                        f"(M-orthonormal, each body's own axes; u [m/√kg], r [rad/√kg])",
                  title_justify="left")
    for head in SHAPE_COLUMNS:
        table.add_column(head, justify="left" if head == "body" else "right")
    # a component below the round-off of its mode's largest one is 0 (``dyade.roundoff``)
    scales = np.max(np.abs(modes.shapes), axis=0, initial=0.0)
    for row in shape_rows(modes, count):
        scale = scales[row["mode"] - 1]
        table.add_row(*[str(row[name]) if name == "mode" else
                        fmt(clean(row[name], scale, EIGEN_ROUNDOFF) if isinstance(row[name], float)
                            else row[name], 4)
                        for name in SHAPE_COLUMNS])
    return table


# -- Campbell ------------------------------------------------------------------------------
CROSSING_COLUMNS = ["speed_rpm", "mode", "f_Hz", "order", "kind", "mesh_share",
                    "kappa_N_per_m", "dominant"]


def crossing_rows(diagram) -> list[dict]:
    """One row per resonance; κ of the modes that do not load the mesh (round-off) as 0."""
    largest = np.nanmax(diagram.modes.mesh_stiffness, axis=1, initial=0.0)
    lines = {o.name: o for o in diagram.orders}
    rows = []
    for c in diagram.crossings:
        mesh = lines[c.order].mesh
        kappa = c.mesh_stiffness
        if mesh is not None and abs(kappa) < 1e-18 * largest[mesh]:
            kappa = 0.0
        rows.append({"speed_rpm": c.speed_rpm, "mode": c.mode, "f_Hz": c.frequency,
                     "order": c.order, "kind": c.kind, "mesh_share": c.mesh_share,
                     "kappa_N_per_m": kappa, "dominant": c.dominant})
    return rows


def campbell_json(diagram) -> dict:
    return {"speeds_rpm": diagram.speeds_rpm, "modes_Hz": diagram.modes.frequencies,
            "lines_Hz": {o.name: diagram.lines[k] for k, o in enumerate(diagram.orders)},
            "resonances": {name: [row[name] for row in crossing_rows(diagram)]
                           for name in CROSSING_COLUMNS}}


def campbell_tables(diagram):
    from rich.table import Table

    speeds = diagram.speeds_rpm
    lines = Table(title=f"Campbell diagram, input speed {fmt(speeds[0])}–{fmt(speeds[-1])} rpm "
                        f"({speeds.size} speeds): excitation lines", title_justify="left")
    for head in ("line", "kind", "Hz per rpm", f"at {fmt(speeds[-1])} rpm [Hz]"):
        lines.add_column(head, justify="left" if head in ("line", "kind") else "right")
    for k, order in enumerate(diagram.orders):
        lines.add_row(order.name, order.kind, fmt(order.slope, 5), fmt(diagram.lines[k, -1], 5))
    table = Table(title="Resonance speeds (natural frequencies do not depend on speed: no "
                        "gyroscopic terms)", title_justify="left")
    heads = ("speed [rpm]", "mode", "f [Hz]", "excitation", "mesh U share", "kappa [N/m]",
             "dominant (strain)")
    for head in heads:
        table.add_column(head, justify="left" if head in ("excitation", "dominant (strain)")
                         else "right")
    for c in crossing_rows(diagram):
        table.add_row(fmt(c["speed_rpm"], 6), str(c["mode"]), fmt(c["f_Hz"], 6), c["order"],
                      percent(c["mesh_share"]), fmt(c["kappa_N_per_m"], 3), c["dominant"])
    return [title(diagram.modes), lines, table]


def campbell_notes(diagram) -> list[str]:
    out = [n for n in mode_notes(diagram.modes) if "ideal meshes" not in n]
    if diagram.modes.system.ideal:
        out.append("note: kappa = F²/ω² of the exciting mesh [N/m]: the dynamic mesh force a "
                   "transmission error e drives at that resonance is kappa·e/(2ζ); ideal meshes "
                   "store no strain energy, so their share is empty.")
    if not diagram.crossings:
        out.append("note: no excitation line meets a natural frequency in this speed range.")
    return out


# -- forced response -------------------------------------------------------------------------
def response_columns(response) -> tuple[dict[str, np.ndarray], list[str]]:
    cols: dict[str, np.ndarray] = {"f_Hz": response.frequencies}
    for k, (body, dof) in enumerate(response.coordinates):
        unit = "m" if dof.startswith("u") else "rad"
        x = response.displacement[:, k]
        cols[f"{body}_{dof}_{unit}"] = np.abs(x)
        cols[f"{body}_{dof}_phase_deg"] = _phase(x)
    for j, name in enumerate(response.mesh_names):
        cols[f"F_{name}_N"] = np.abs(response.mesh_forces[:, j])
        cols[f"F_{name}_phase_deg"] = _phase(response.mesh_forces[:, j])
    radial = response.radial()
    for s, name in enumerate(response.supports):
        cols[f"{name}_radial_N"] = radial[:, s]
        cols[f"{name}_axial_N"] = np.abs(response.support_forces[:, s, 0])
    return cols, list(cols)


def _phase(x: np.ndarray) -> np.ndarray:
    """arg x in (−180°, 180°]; NaN where x is zero or undefined."""
    angle = np.degrees(np.angle(x))
    angle = np.where(angle <= -180.0, 180.0, angle)
    return np.where((np.abs(x) == 0.0) | ~np.isfinite(x), np.nan, angle)


def response_tables(response, cols, names, label: str):
    from rich.table import Table

    freq = response.frequencies
    stride = max(1, int(np.ceil(freq.size / 40)))
    note = f" (every {stride}. of {freq.size} rows; --format csv for all)" if stride > 1 else ""
    summary = Table(title=f"Forced response to the file's excitations, "
                          f"{fmt(freq[0])}–{fmt(freq[-1])} Hz: peaks", title_justify="left")
    for head in ("quantity", "peak", "at [Hz]"):
        summary.add_column(head, justify="left" if head == "quantity" else "right")
    amplitudes = [n for n in names if n != "f_Hz" and not n.endswith("_phase_deg")]
    for name in amplitudes:
        values = np.where(np.isfinite(cols[name]), cols[name], -np.inf)
        if np.all(values == -np.inf):
            summary.add_row(name, "—", "—")
            continue
        k = int(np.argmax(values))
        summary.add_row(name, fmt(cols[name][k], 4), fmt(freq[k], 6))
    table = Table(title="Amplitudes" + note, title_justify="left")
    shown = ["f_Hz"] + [n for n in amplitudes if np.any(np.nan_to_num(cols[n]) != 0.0)]
    for name in shown:
        table.add_column(name.replace("_", "\n", 1), justify="right")
    for k in range(0, freq.size, stride):
        table.add_row(*[fmt(cols[name][k], 4) for name in shown])
    return [label, summary, table]


def response_notes(response) -> list[str]:
    out = []
    if np.any(response.unbounded):
        where = ", ".join(f"{f:g}" for f in response.frequencies[response.unbounded][:5])
        out.append(f"note: no finite response at {where} Hz (a rigid-body mode at 0 Hz, or an "
                   f"undamped resonance): empty in CSV, — in the table.")
    return out


# -- elimination check -----------------------------------------------------------------------
CHECK_COLUMNS = ["mode", "f_Hz", "f_eliminated_Hz", "rel_diff"]


def check_rows(result) -> list[dict]:
    return [{"mode": k + 1, "f_Hz": float(a), "f_eliminated_Hz": float(b),
             "rel_diff": float(abs(b - a) / a)}
            for k, (a, b) in enumerate(zip(result.reference, result.frequencies))]


def check_summary(result) -> dict:
    return {"largest_rel_diff": result.difference, "extra_zeros": result.extra_zeros,
            "meshes": result.meshes, "rigid_zeros": result.rigid_zeros,
            "zero_eigenvalues": result.zeros, "largest_imaginary_share": result.largest_imaginary}


def check_tables(result, label: str):
    from rich.table import Table

    table = Table(title="The paper's elimination (eqs. (27)–(33)) against the null-space "
                        "solution", title_justify="left")
    for head in ("mode", "null space [Hz]", "eliminated [Hz]", "rel. diff"):
        table.add_column(head, justify="right")
    for row in check_rows(result):
        table.add_row(str(row["mode"]), fmt(row["f_Hz"], 10), fmt(row["f_eliminated_Hz"], 10),
                      f"{row['rel_diff']:.1e}")
    summary = Table(title="Zero eigenvalues of M⁻¹(K + K_f)", title_justify="left")
    summary.add_column("quantity")
    summary.add_column("value", justify="right")
    summary.add_row("extra zeros (eigenvectors violate gᵀq = 0; one per mesh)",
                    f"{result.extra_zeros} (meshes: {result.meshes})")
    summary.add_row("rigid-body zeros (satisfy the constraints)", str(result.rigid_zeros))
    summary.add_row("their values [1/s²] (round-off)",
                    ", ".join(f"{z:.2g}" for z in result.zeros) or "—")
    summary.add_row("largest relative frequency difference", f"{result.difference:.2e}")
    return [label, table, summary]


def check_notes(result) -> list[str]:
    if result.extra_zeros != result.meshes:
        return [f"warning: the eliminated form has {result.extra_zeros} extra zero eigenvalues "
                f"for {result.meshes} ideal meshes (expected one per mesh)."]
    return []


def units_of(cols) -> dict[str, str]:
    """The unit of each column, from its name: ``_Hz``, ``_rpm``, ``_N``, ``_m``, ``_rad``
    suffixes; energy shares (T_…, U_…) and the mode number are dimensionless."""
    suffixes = {"_Hz": "Hz", "_rpm": "rpm", "_N": "N", "_m": "m", "_rad": "rad",
                "_deg": "°", "_N_per_m": "N/m"}
    out = {}
    for name in cols:
        unit = next((u for s, u in sorted(suffixes.items(), key=lambda kv: -len(kv[0]))
                     if name.endswith(s)), "")
        if not unit and name.startswith(("T_", "U_", "rel_", "mode")):
            unit = "-"
        out[name] = unit
    return out
