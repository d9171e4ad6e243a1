"""The gear entries' Outcomes (``dyade.analyses.gears``) -> rich tables: the modes with
their energy shares and modal mesh forces, the mode shapes, the Campbell diagram's
lines and resonances, the forced response's peaks and amplitudes, and the elimination
check. Every number through ``dyade.report.format.number``."""

from __future__ import annotations

from typing import Any

import numpy as np

from dyade.analyses.base import MISSING
from dyade.analyses.gears import MODEL, MOTIONS, identifier
from dyade.model.gears import DOFS
from dyade.report.format import number, ordinal
from dyade.roundoff import EIGEN_ROUNDOFF, clean


def fmt(value: Any, digits: int = 5) -> str:
    """A value to ``digits`` significant digits (``dyade.report.format.number``)."""
    return number(value, spec=f".{digits}g")


def percent(value: float) -> str:
    """A share [-] as a percentage with one decimal."""
    return number(None if value != value else 100.0 * value, spec=".1f")


# -- modes -------------------------------------------------------------------------------
def mode_tables(outcome):
    """The title line, the modes table (energy shares [%], dominant part, modal mesh
    forces) and, where asked, the mode shapes (``gear-modes``)."""
    from rich.table import Table

    modal = outcome.result
    modes = modal.modes
    cols = outcome.columns
    meshes = modes.system.drive.meshes
    elastic = any(m.stiffness is not None for m in meshes)
    table = Table(title="Natural frequencies (no gyroscopic terms: the same at every speed); "
                        "energy shares [%]", title_justify="left")
    heads = ["mode", "f [Hz]", "T tors", "T lat", "T ax", "U tors", "U lat", "U ax"]
    heads += ["U mesh"] if elastic else []
    heads += ["dominant (strain)"] + [f"F {m.name}" for m in meshes]
    for head in heads:
        table.add_column(head, justify="left" if head.startswith("dominant") else "right")
    dominant = modes.dominant()
    for k in range(modes.frequencies.size):
        owner, motion, share = dominant[k]
        row = [number(int(cols["mode"][k])), fmt(cols["f_Hz"][k], 6)]
        row += [percent(cols[f"T_{m}"][k]) for m in MOTIONS]
        row += [percent(cols[f"U_{m}"][k]) for m in MOTIONS]
        row += [percent(cols["U_mesh"][k])] if elastic else []
        row += [f"{owner} {motion} {percent(share)}" if owner else MISSING]
        row += [fmt(cols[f"F_{m.name}"][k], 4) for m in meshes]
        table.add_row(*row)
    parts: list[Any] = [title(outcome), table]
    if meshes:
        parts.append("F: modal mesh force along the plane-of-action normal, compression "
                     "positive, per unit modal coordinate of the M-orthonormal mode [N/(m·√kg)]")
    if modal.shapes:
        parts.append(shape_table(outcome))
    return parts


def shape_table(outcome):
    """The mode shapes (columns BODY_DOF of the first modes) as one row per mode and
    body; a component below the round-off of its mode's largest one as 0."""
    from rich.table import Table

    modal = outcome.result
    modes, count = modal.modes, modal.shapes
    system = modes.system
    table = Table(title=f"Mode shapes of modes 1–{count} (M-orthonormal, each body's own axes; "
                        f"u [m/√kg], r [rad/√kg])", title_justify="left")
    for head in ("mode", "body", *DOFS):
        table.add_column(head, justify="left" if head == "body" else "right")
    cols = outcome.columns
    scales = np.max(np.abs(modes.shapes), axis=0, initial=0.0)
    for k in range(count):
        for body in system.bodies:
            values = [cols.get(f"{body.name}_{dof}") for dof in DOFS]
            table.add_row(number(k + 1), body.name,
                          *[MISSING if v is None else
                            fmt(clean(float(v[k]), scales[k], EIGEN_ROUNDOFF), 4)
                            for v in values])
    return table


def check_tables(outcome):
    """The elimination check of a ``gear-modes`` Outcome asked with ``check``: each
    mode's frequency by both methods, and the zero eigenvalues."""
    from rich.table import Table

    cols, value = outcome.columns, outcome.value
    table = Table(title="The paper's elimination (eqs. (27)–(33)) against the null-space "
                        "solution", title_justify="left")
    for head in ("mode", "null space [Hz]", "eliminated [Hz]", "rel. diff [-]"):
        table.add_column(head, justify="right")
    for k in range(len(cols["mode"])):
        table.add_row(number(int(cols["mode"][k])), fmt(cols["f_Hz"][k], 10),
                      fmt(cols["f_eliminated_Hz"][k], 10),
                      number(cols["rel_diff"][k], spec=".1e"))
    summary = Table(title="Zero eigenvalues of M⁻¹(K + K_f)", title_justify="left")
    summary.add_column("quantity")
    summary.add_column("value", justify="right")
    summary.add_column("unit")
    summary.add_row("extra zeros (eigenvectors violate gᵀq = 0; one per mesh)",
                    f"{number(value('extra_zeros'))} (meshes: {number(value('ideal_meshes'))})",
                    "-")
    summary.add_row("rigid-body zeros (satisfy the constraints)", number(value("rigid_zeros")),
                    "-")
    summary.add_row("their values (round-off)",
                    ", ".join(number(z, spec=".2g") for z in value("zero_eigenvalues"))
                    or MISSING, "1/s²")
    summary.add_row("largest relative frequency difference",
                    number(value("largest_rel_diff"), spec=".2e"), "-")
    return [title(outcome), table, summary]


# -- Campbell ----------------------------------------------------------------------------
def campbell_tables(outcome):
    """The excitation lines and the resonances of a ``gear-campbell`` Outcome."""
    from rich.table import Table

    diagram = outcome.result
    speeds = diagram.speeds_rpm
    lines = Table(title=f"Campbell diagram, input speed {fmt(speeds[0])}–{fmt(speeds[-1])} rpm "
                        f"({speeds.size} speeds): excitation lines", title_justify="left")
    for head in ("line", "kind", "Hz per rpm", f"at {fmt(speeds[-1])} rpm [Hz]"):
        lines.add_column(head, justify="left" if head in ("line", "kind") else "right")
    for k, order in enumerate(diagram.orders):
        lines.add_row(order.name, order.kind, fmt(order.slope, 5), fmt(diagram.lines[k, -1], 5))
    table = Table(title="Resonance speeds (natural frequencies do not depend on speed: no "
                        "gyroscopic terms)", title_justify="left")
    heads = ("speed [rpm]", "mode", "f [Hz]", "excitation", "mesh U share [%]", "kappa [N/m]",
             "dominant (strain)")
    for head in heads:
        table.add_column(head, justify="left" if head in ("excitation", "dominant (strain)")
                         else "right")
    cols = outcome.columns
    for k in range(len(cols["mode"])):
        table.add_row(fmt(cols["speed_rpm"][k], 6), number(int(cols["mode"][k])),
                      fmt(cols["f_Hz"][k], 6), cols["order"][k], percent(cols["mesh_share"][k]),
                      fmt(cols["kappa_N_per_m"][k], 3), cols["dominant"][k])
    return [title(outcome), lines, table]


# -- forced response ---------------------------------------------------------------------
def response_tables(outcome):
    """The peaks and the amplitudes (every k-th frequency to about 40 rows) of a
    ``gear-response`` Outcome."""
    from rich.table import Table

    cols = outcome.columns
    freq = cols["f_Hz"]
    stride = max(1, int(np.ceil(freq.size / 40)))
    note = (f" (every {ordinal(stride)} of {freq.size} rows; --format csv for all)"
            if stride > 1 else "")
    summary = Table(title=f"Forced response to the file's excitations, "
                          f"{fmt(freq[0])}–{fmt(freq[-1])} Hz: peaks", title_justify="left")
    for head in ("quantity", "peak", "unit", "at [Hz]"):
        summary.add_column(head, justify="right" if head in ("peak", "at [Hz]") else "left")
    amplitudes = [n for n in cols if n != "f_Hz" and not n.endswith("_phase_deg")]
    for name in amplitudes:
        figure = outcome.summary[f"{identifier(name)}_peak"]
        at = figure.where["f_hz"] if figure.value is not None else None
        summary.add_row(name, fmt(figure.value, 4), figure.unit, fmt(at, 6))
    table = Table(title="Amplitudes" + note, title_justify="left")
    columns = ["f_Hz"] + [n for n in amplitudes if np.any(np.nan_to_num(cols[n]) != 0.0)]
    for name in columns:
        head = "f" if name == "f_Hz" else identifier(name)
        table.add_column(f"{head} [{outcome.units[name]}]".replace("_", "\n", 1),
                         justify="right")
    for k in range(0, freq.size, stride):
        table.add_row(*[fmt(cols[name][k], 4) for name in columns])
    return [title(outcome), summary, table]


def title(outcome) -> str:
    """One line naming the drive of a gear entry's Outcome, its model and its size."""
    meta = outcome.meta
    meshes, ideal = meta["meshes"], meta["ideal_meshes"]
    mesh_text = f"{meshes} mesh{'es' if meshes != 1 else ''}" + (
        f" ({ideal} ideal)" if 0 < ideal < meshes else " (ideal)" if ideal else "")
    rigid = meta.get("rigid_directions", 0)
    rigid_text = f", {rigid} rigid support direction{'s' if rigid != 1 else ''}" if rigid else ""
    return (f"{meta['name']}: {MODEL[meta['model']]}; {meta['coordinates']} coordinates, "
            f"{mesh_text}{rigid_text}, {meta['bodies']} bodies")
