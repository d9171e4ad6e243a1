"""``gear-modes``, ``gear-campbell``, ``gear-response``: the vibration of a gear drive by
rigid finite elements (Berczyński, Maćkowiak and Marchelek 1978).

The input is a gear-drive file (a path, or its text as ``dyade.analyses.inputs.Text``),
a ``GearDrive`` or the ``Modes`` of one (``gear_modes``: reused, not computed again);
``set`` overrides keys of a file as ``--set`` does. ``load`` is the one reading of a
gear drive with its overrides for the command line, the API and the report.

- ``gear-modes``: the natural frequencies, energy shares, dominant parts and modal mesh
  forces of every elastic mode (``modes``: with the first N mode shapes; ``check``: with
  the paper's eliminated form solved beside, eqs. (27)–(33)).
- ``gear-campbell``: the resonance speeds where the excitation lines (shaft speeds,
  tooth-mesh harmonics, the file's excitations) cross the natural frequencies.
- ``gear-response``: the forced response to the file's excitations over a frequency
  range: amplitudes and phases, dynamic mesh forces, bearing forces.

This module imports no numpy at import time.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome, withheld
from dyade.analyses.inputs import SET, Text

MODES_TIME = 6e-8  # [s per coordinate³] assembly and eigensolution (about 1.5 s at 288)
SOLVE_TIME = 2e-9  # [s per frequency and reduced coordinate³] the forced response's solves
LINE_TIME = 1e-8  # [s per line and speed] a Campbell diagram's lines and crossings
DEFAULT_SPEEDS = 200  # [-] steps of the default Campbell speeds (0 to 1.5 × the file's)

MOTIONS = ("torsion", "lateral", "axial")
MODEL = {"rfe": "rigid finite elements, six coordinates per body",
         "torsional": "torsional model, one rotation per body"}
SHAPE_UNIT = {"u": "m/√kg", "r": "rad/√kg"}
"""the unit of a mode-shape component (M-orthonormal modes) by its first letter"""

SHAPES = Option("modes", int, positive=True, metavar="N", study=False,
                help="Also give the shapes of the first N modes (M-orthonormal, in each "
                     "body's own axes): columns BODY_ux … BODY_rz of their rows")
CHECK = Option("check", bool, study=False,
               help="Solve the paper's eliminated form (eqs. (27)–(33)) beside the "
                    "null-space solution: its frequencies, their relative difference and its "
                    "extra zero eigenvalues (one per mesh)")
SPEED_RANGE = Option("speed-range", str, "rpm", metavar="START:STOP:STEP", old=("--campbell",),
                     help="Input speeds of the Campbell diagram (default: 0 to 1.5 × the "
                          "file's [speed] rpm, in 200 steps)")
HARMONICS = Option("harmonics", int, default=3, metavar="N",
                   help="Tooth-mesh harmonics in the Campbell diagram")
FREQUENCY_RANGE = Option("frequency-range", str, "Hz", metavar="START:STOP:STEP",
                         old=("--response",),
                         help="Frequencies of the forced response to the file's excitations "
                              "(harmonic torques, transmission errors)")
DOF = Option("dof", str, multiple=True, metavar="BODY.DOF",
             help="Coordinate of the forced response (repeatable), DOF one of ux uy uz rx ry "
                  "rz in the body's own axes (default: rx of every body)")


@dataclass
class Drive:
    """A gear drive as read: the drive, the name messages give its file, and its modes
    where the source was a ``Modes``."""

    drive: Any
    label: str
    source: str | None = None
    """the file's path (None: standard input or a drive given as an object)"""
    modes: Any = None


def load(source: Any, options: dict[str, Any]) -> Drive:
    """The gear drive of ``source`` (a path, a ``Text``, a ``GearDrive`` or a ``Modes``)
    with the ``set`` overrides of ``options`` applied (only to a file)."""
    from dyade.errors import InputError
    from dyade.files import gears as reader
    from dyade.files import schema

    assignments = options.get(SET.api) or ()
    if hasattr(source, "system") and hasattr(source, "frequencies"):  # Modes
        loaded = Drive(source.system.drive, source.system.drive.name, None, source)
    elif hasattr(source, "meshes") and hasattr(source, "bodies"):  # GearDrive
        loaded = Drive(source, source.name)
    else:
        if source is None:
            raise InputError("no gear-drive file given.")
        overrides = dict(schema.parse_assignment(a) for a in assignments)
        if isinstance(source, Text):
            text, label, path = source.text, source.label, None
        else:
            label = path = os.fspath(source)
            text = schema.read_text(label)
        data = schema.load_data(label, overrides, "--set", text)
        return Drive(reader.build_gears(data, path), os.path.basename(label), path)
    if assignments:
        raise InputError.parameter(SET.api, "needs a gear-drive file (it overrides the file's "
                                            "keys); change the GearDrive instead.")
    return loaded


def naming(label: str) -> dict[str, str]:
    """The engine's parameters -> the options (API names) or file keys they come from."""
    return {"coordinates": DOF.api, "speeds_rpm": SPEED_RANGE.api,
            "frequencies": FREQUENCY_RANGE.api, "harmonics": HARMONICS.api,
            "max_memory": "max_memory_mb", "speed": f"{label}: `[speed]`"}


def solve_modes(loaded: Drive, budget: Budget):
    """The drive's modes (those of the source when it was a ``Modes``), refused with an
    ``InputError`` where nothing can vibrate; the time estimate first."""
    from dyade.errors import InputError
    from dyade.vibration.gears.modes import coordinate_count, gear_modes

    modes = loaded.modes
    if modes is None:
        n = coordinate_count(loaded.drive)
        budget.time(MODES_TIME * n ** 3, f"the modes of {n:,} coordinates")
        try:
            modes = gear_modes(loaded.drive, max_memory=budget.max_memory)
        except InputError as err:
            raise err.naming(naming(loaded.label)) from None
    if not modes.frequencies.size:
        raise InputError(f"{loaded.label}: nothing to vibrate: every motion of the drive is a "
                         f"rigid-body mode ({modes.rigid.shape[1]}), since no shaft, mesh "
                         f"stiffness, bearing or element resists it. Add the elements that "
                         f"hold its bodies.")
    return modes


def meta(loaded: Drive, modes) -> dict[str, Any]:
    """What was analysed: the drive, its file, its model and size."""
    system = modes.system
    return {"name": loaded.drive.name, "source": loaded.source, "model": loaded.drive.model,
            "coordinates": system.size, "bodies": len(system.bodies),
            "meshes": len(loaded.drive.meshes), "ideal_meshes": len(system.ideal),
            "rigid_directions": len(system.supports)}


# -- modes -------------------------------------------------------------------------------
def modes_asked(asked: int, available: int, most: int | None = None) -> tuple[int, str]:
    """The one rule for ``--modes N`` (N ≥ 1): N, or all there are (at most ``most``),
    with a note saying so when N asks for more."""
    given = min(asked, available, most if most is not None else asked)
    if given == asked:
        return given, ""
    why = (f"the drive has {available} elastic mode{'s' * (available != 1)}"
           if given == available else f"a figure shows at most {most}")
    return given, f"--modes {asked}: {why}; giving the first {given}."


def cleaned(values, rtol: float = 1e-9):
    """(meshes, modes) modal mesh forces or stiffnesses with the round-off of the modes
    that do not load a mesh (below ``rtol`` of that mesh's largest) as 0; κ = F²/ω² takes
    ``rtol`` squared."""
    import numpy as np

    values = np.asarray(values, dtype=float)
    largest = np.nanmax(np.abs(values), axis=1, initial=0.0)[:, None] if values.size else 0.0
    return np.where(np.abs(values) < rtol * largest, 0.0, values)


def mode_columns(modes) -> tuple[dict[str, Any], dict[str, str], dict[str, str]]:
    """One row per elastic mode: frequency, kinetic and strain shares by motion, strain
    shares per shaft, bearing, element and elastic mesh (by motion), the modal mesh force
    and modal mesh stiffness of every mesh, the dominant part; with units and
    descriptions."""
    import numpy as np

    count = modes.frequencies.size
    cols: dict[str, Any] = {"mode": np.arange(1, count + 1), "f_Hz": modes.frequencies}
    units = {"mode": "-", "f_Hz": "Hz"}
    text = {"mode": "elastic mode", "f_Hz": "natural frequency"}
    kinetic, strain = modes.totals("kinetic"), modes.totals("strain")
    for motion in MOTIONS:
        cols[f"T_{motion}"] = kinetic[motion]
        text[f"T_{motion}"] = f"kinetic-energy share of {motion}"
    for motion in MOTIONS + ("mesh",):
        cols[f"U_{motion}"] = strain[motion]
        text[f"U_{motion}"] = (f"strain-energy share of {motion}" if motion != "mesh" else
                               "strain-energy share of the elastic meshes")
    for (owner, motion), share in modes.strain.items():
        cols[f"U_{owner}_{motion}"] = share
        text[f"U_{owner}_{motion}"] = f"strain-energy share of {owner}, {motion}"
    forces = cleaned(modes.mesh_forces)
    stiffness = cleaned(modes.mesh_stiffness, 1e-18)
    for k, mesh in enumerate(modes.system.drive.meshes):
        cols[f"F_{mesh.name}"] = forces[k]
        units[f"F_{mesh.name}"] = "N/(m·√kg)"
        text[f"F_{mesh.name}"] = (f"modal mesh force of {mesh.name} along the plane-of-action "
                                  f"normal, compression positive, per unit modal coordinate")
        cols[f"kappa_{mesh.name}_N_per_m"] = stiffness[k]
        units[f"kappa_{mesh.name}_N_per_m"] = "N/m"
        text[f"kappa_{mesh.name}_N_per_m"] = f"modal mesh stiffness F²/ω² of {mesh.name}"
    cols["dominant"] = np.array([f"{owner} {motion}" for owner, motion, _ in modes.dominant()],
                                dtype=object)
    units["dominant"] = ""
    text["dominant"] = "the part and motion with the largest strain-energy share"
    for name in cols:
        units.setdefault(name, "-")
    return cols, units, text


def shape_columns(modes, count: int) -> tuple[dict[str, Any], dict[str, str], dict[str, str]]:
    """The shapes of the first ``count`` elastic modes as columns BODY_DOF of the mode
    rows (empty for the other modes): M-orthonormal, in each body's own axes (the
    torsional model has rx only)."""
    import numpy as np

    from dyade.model.gears import DOFS

    system = modes.system
    per = system.per_body
    dofs = DOFS if per == 6 else ("rx",)
    rows = modes.frequencies.size
    cols, units, text = {}, {}, {}
    for i, body in enumerate(system.bodies):
        for j, dof in enumerate(dofs):
            values = np.full(rows, np.nan)
            values[:count] = modes.shapes[i * per + j, :count]
            name = f"{body.name}_{dof}"
            cols[name] = values
            units[name] = SHAPE_UNIT[dof[0]]
            text[name] = f"mode shape: {dof} of {body.name} (M-orthonormal, its own axes)"
    return cols, units, text


def run_modes(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``gear-modes``: one row per elastic mode (with the first ``modes`` shapes; with
    the elimination check beside it where asked)."""
    import numpy as np

    loaded = load(source, options)
    modes = solve_modes(loaded, budget)
    outcome = Outcome("gear-modes", figures=("modes",), meta=meta(loaded, modes))
    cols, units, text = mode_columns(modes)
    notes = mode_notes(modes)
    shapes = 0
    if options.get(SHAPES.api):
        shapes, note = modes_asked(options[SHAPES.api], modes.frequencies.size)
        notes += [f"note: {note}"] * bool(note)
        more = shape_columns(modes, shapes)
        for part, extra in zip((cols, units, text), more):
            part.update(extra)
    elimination = None
    if options.get(CHECK.api):
        from dyade.vibration.gears.elimination import check

        elimination = check(modes.system, modes)
        count = modes.frequencies.size
        eliminated = np.full(count, np.nan)
        eliminated[:elimination.frequencies.size] = elimination.frequencies[:count]
        reference = np.full(count, np.nan)
        reference[:elimination.reference.size] = elimination.reference[:count]
        cols["f_eliminated_Hz"] = eliminated
        cols["rel_diff"] = np.abs(eliminated - reference) / reference
        units.update(f_eliminated_Hz="Hz", rel_diff="-")
        text.update(f_eliminated_Hz="natural frequency of the eliminated form, eq. (33)",
                    rel_diff="relative difference of the two frequencies")
        notes += check_notes(elimination)
    outcome.columns, outcome.units, outcome.descriptions = cols, units, text
    add = outcome.add
    add("f_1", float(modes.frequencies[0]), "Hz", description="first elastic natural frequency")
    add("elastic_modes", int(modes.frequencies.size), "-", description="elastic modes")
    add("rigid_modes", int(modes.rigid.shape[1]), "-",
        description="rigid-body modes (not resonances)")
    if elimination is not None:
        add("largest_rel_diff", float(elimination.difference), "-",
            description="largest relative frequency difference")
        add("extra_zeros", int(elimination.extra_zeros), "-",
            description="extra zero eigenvalues (eigenvectors violate gᵀq = 0; one per "
                        "ideal mesh or rigid direction)")
        add("ideal_meshes", int(elimination.meshes), "-", description="ideal meshes")
        add("rigid_zeros", int(elimination.rigid_zeros), "-",
            description="rigid-body zero eigenvalues (satisfy the constraints)")
        add("zero_eigenvalues", [float(z) for z in elimination.zeros], "1/s²",
            description="the zero eigenvalues (round-off)")
        add("largest_imaginary_share", float(elimination.largest_imaginary), "-",
            description="largest |Im ω²|/|ω²| of the elastic eigenvalues")
    outcome.notes = notes
    outcome.result = Modal(modes, shapes, elimination)
    return outcome


@dataclass
class Modal:
    """What ``gear-modes`` found, for the tables and figures: the modes, how many shapes
    were asked for, and the elimination check (None: not asked)."""

    modes: Any
    shapes: int = 0
    elimination: Any = None


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
    """The rigid-body modes, the unresolved ones and what ideal meshes store, worded."""
    import numpy as np

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


def check_notes(result) -> list[str]:
    """A count of extra zero eigenvalues other than one per ideal mesh, worded."""
    if result.extra_zeros != result.constraints:
        rigid = result.constraints - result.meshes
        also = f" and {rigid} rigid directions" if rigid else ""
        return [f"warning: the eliminated form has {result.extra_zeros} extra zero eigenvalues "
                f"for {result.meshes} ideal meshes{also} (expected one per constraint)."]
    return []


# -- Campbell ----------------------------------------------------------------------------
CROSSINGS = {"speed_rpm": ("rpm", "input speed of the resonance"),
             "mode": ("-", "elastic mode"),
             "f_Hz": ("Hz", "natural frequency"),
             "order": ("", "the excitation line"),
             "kind": ("", "shaft, mesh or excitation"),
             "mesh_share": ("-", "the mode's strain-energy share in the elastic meshes"),
             "kappa_N_per_m": ("N/m", "modal mesh stiffness F²/ω² of the exciting mesh"),
             "dominant": ("", "the part, motion and share with the most strain energy")}
"""column -> (unit, description) of the resonances"""


def campbell_speeds(loaded: Drive, options: dict[str, Any]) -> list[float]:
    """The speeds [rpm] of ``speed_range_rpm``, or 0 to 1.5 × the file's ``[speed]`` rpm."""
    from dyade.analyses.ranges import values
    from dyade.errors import InputError
    from dyade.vibration.gears.campbell import default_speeds

    text = options.get(SPEED_RANGE.api)
    if text is not None:
        return values(text, SPEED_RANGE.api, "rpm", "speed_rpm")
    if not loaded.drive.speed.rpm:
        raise InputError.parameter(SPEED_RANGE.api, f"must be given: {loaded.label} gives no "
                                                    f"operating speed ([speed] rpm) to take the "
                                                    f"speeds from (START:STOP:STEP).")
    return default_speeds(loaded.drive.speed.rpm, DEFAULT_SPEEDS).tolist()


def crossing_columns(diagram) -> dict[str, Any]:
    """One row per resonance; κ of the modes that do not load the mesh (round-off) as 0."""
    import numpy as np

    largest = np.nanmax(diagram.modes.mesh_stiffness, axis=1, initial=0.0)
    lines = {o.name: o for o in diagram.orders}
    rows = []
    for c in diagram.crossings:
        mesh = lines[c.order].mesh
        kappa = c.mesh_stiffness
        if mesh is not None and abs(kappa) < 1e-18 * largest[mesh]:
            kappa = 0.0
        rows.append((c.speed_rpm, c.mode, c.frequency, c.order, c.kind, c.mesh_share, kappa,
                     c.dominant))
    columns = list(zip(*rows)) if rows else [()] * len(CROSSINGS)
    out = {}
    for name, values in zip(CROSSINGS, columns):
        kind = CROSSINGS[name][0]
        out[name] = (np.array(values, dtype=object) if not kind else
                     np.array(values, dtype=int if name == "mode" else float))
    return out


def run_campbell(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``gear-campbell``: one row per resonance of the speed range; the lines and the
    natural frequencies in the summary."""
    from dyade.errors import InputError
    from dyade.limits import check_memory
    from dyade.vibration.gears.campbell import campbell, campbell_size, orders

    loaded = load(source, options)
    names = naming(loaded.label)
    harmonics = options[HARMONICS.api]
    try:
        if harmonics >= 0:  # the size before the lines are listed (a million harmonics)
            check_memory(campbell_size(loaded.drive, 1, harmonics),
                         f"a Campbell diagram of {harmonics:,} tooth-mesh harmonics",
                         budget.max_memory, "Ask for fewer harmonics")
        lines = orders(loaded.drive, harmonics)  # a [speed] body, harmonics ≥ 0: first
        speeds = campbell_speeds(loaded, options)
        modes = solve_modes(loaded, budget)
        budget.time(LINE_TIME * len(lines) * (len(speeds) + modes.frequencies.size),
                    f"a Campbell diagram of {len(speeds):,} speeds and {len(lines):,} lines")
        diagram = campbell(loaded.drive, speeds, harmonics=harmonics, modes=modes,
                           max_memory=budget.max_memory)
    except InputError as err:
        raise err.naming(names) from None
    outcome = Outcome("gear-campbell", figures=("campbell",), meta=meta(loaded, modes),
                      result=diagram)
    outcome.meta["speeds_rpm"] = {"start": speeds[0], "stop": speeds[-1], "count": len(speeds)}
    outcome.columns = crossing_columns(diagram)
    outcome.units = {name: unit for name, (unit, _) in CROSSINGS.items()}
    outcome.descriptions = {name: text for name, (_, text) in CROSSINGS.items()}
    add = outcome.add
    add("resonances", len(diagram.crossings), "-",
        description="crossings of an excitation line with a natural frequency")
    if diagram.crossings:
        first = diagram.crossings[0]
        add("resonance_speed_min_rpm", first.speed_rpm, "rpm",
            where={"mode": first.mode, "line": first.order},
            description="lowest resonance speed")
    add("natural_frequencies", [float(f) for f in modes.frequencies], "Hz",
        description="elastic natural frequencies (the same at every speed)")
    add("lines", [o.name for o in diagram.orders], "-",
        description="the excitation lines: shaft speeds, tooth-mesh harmonics, excitations")
    add("line_slopes", [float(o.slope) for o in diagram.orders], "Hz/rpm",
        description="each line's frequency per input rpm")
    add("line_offsets", [float(o.frequency) for o in diagram.orders], "Hz",
        description="each line's fixed frequency (a line is offset + slope × speed)")
    outcome.notes = campbell_notes(diagram)
    return outcome


def campbell_notes(diagram) -> list[str]:
    """The modes' notes (rigid-body, unresolved), what κ means, no crossing, worded."""
    out = [n for n in mode_notes(diagram.modes) if "ideal meshes" not in n]
    if diagram.modes.system.ideal:
        out.append("note: kappa = F²/ω² of the exciting mesh [N/m]: the dynamic mesh force a "
                   "transmission error e drives at that resonance is kappa·e/(2ζ); ideal meshes "
                   "store no strain energy, so their share is empty.")
    if not diagram.crossings:
        out.append("note: no excitation line meets a natural frequency in this speed range.")
    return out


# -- forced response ---------------------------------------------------------------------
def response_columns(response) -> tuple[dict[str, Any], dict[str, str], dict[str, str]]:
    """One row per frequency: the amplitude and phase of each coordinate, the dynamic
    mesh forces and their phases, the bearings' radial and axial forces."""
    import numpy as np

    cols: dict[str, Any] = {"f_Hz": response.frequencies}
    units, text = {"f_Hz": "Hz"}, {"f_Hz": "excitation frequency"}
    for k, (body, dof) in enumerate(response.coordinates):
        unit = "m" if dof.startswith("u") else "rad"
        x = response.displacement[:, k]
        cols[f"{body}_{dof}_{unit}"] = np.abs(x)
        units[f"{body}_{dof}_{unit}"] = unit
        text[f"{body}_{dof}_{unit}"] = f"amplitude of {dof} of {body}"
        cols[f"{body}_{dof}_phase_deg"] = phase(x)
        units[f"{body}_{dof}_phase_deg"] = "°"
        text[f"{body}_{dof}_phase_deg"] = f"phase of {dof} of {body}: lead over cos Ωt"
    for j, name in enumerate(response.mesh_names):
        cols[f"F_{name}_N"] = np.abs(response.mesh_forces[:, j])
        units[f"F_{name}_N"] = "N"
        text[f"F_{name}_N"] = f"dynamic mesh force of {name}"
        cols[f"F_{name}_phase_deg"] = phase(response.mesh_forces[:, j])
        units[f"F_{name}_phase_deg"] = "°"
        text[f"F_{name}_phase_deg"] = f"phase of the mesh force of {name}"
    radial = response.radial()
    for s, name in enumerate(response.supports):
        cols[f"{name}_radial_N"] = radial[:, s]
        units[f"{name}_radial_N"] = "N"
        text[f"{name}_radial_N"] = f"largest radial force of {name} over a cycle"
        cols[f"{name}_axial_N"] = np.abs(response.support_forces[:, s, 0])
        units[f"{name}_axial_N"] = "N"
        text[f"{name}_axial_N"] = f"axial force of {name}"
    return cols, units, text


def phase(x):
    """arg x in (−180°, 180°] [°]; NaN where x is zero or undefined."""
    import numpy as np

    angle = np.degrees(np.angle(x))
    angle = np.where(angle <= -180.0, 180.0, angle)
    return np.where((np.abs(x) == 0.0) | ~np.isfinite(x), np.nan, angle)


def identifier(name: str) -> str:
    """A column's name less its unit suffix, as a figure's name (letters, digits, _)."""
    import re

    for suffix in ("_N", "_m", "_rad"):
        if name.endswith(suffix):
            name = name[: -len(suffix)]
            break
    return re.sub(r"\W", "_", name)


def run_response(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """``gear-response``: one row per frequency; each amplitude's peak in the summary."""
    import numpy as np

    from dyade.analyses.ranges import values
    from dyade.errors import InputError
    from dyade.vibration.gears.response import gear_response

    loaded = load(source, options)
    names = naming(loaded.label)
    text = options.get(FREQUENCY_RANGE.api)
    if text is None:
        raise InputError.parameter(FREQUENCY_RANGE.api, "must be given: the frequencies of the "
                                                        "response, START:STOP:STEP [Hz].")
    frequencies = values(text, FREQUENCY_RANGE.api, "Hz", "frequency")
    modes = solve_modes(loaded, budget)
    system = modes.system
    size = system.size - system.constraints.shape[1]
    budget.time(SOLVE_TIME * len(frequencies) * size ** 3,
                f"the response at {len(frequencies):,} frequencies")
    try:
        response = gear_response(system, frequencies, coordinates=list(options[DOF.api] or ())
                                 or None, max_memory=budget.max_memory)
    except InputError as err:
        raise err.naming(names) from None
    outcome = Outcome("gear-response", meta=meta(loaded, modes), result=response)
    outcome.columns, outcome.units, outcome.descriptions = response_columns(response)
    outcome.notes = response_notes(response)
    withheld(outcome, ~response.unbounded, "no frequency of the range has a finite response")
    freq = response.frequencies
    for name, values_ in outcome.columns.items():
        if name == "f_Hz" or name.endswith("_phase_deg"):
            continue
        finite = np.where(np.isfinite(values_), values_, -np.inf)
        k = int(np.argmax(finite))
        outcome.add(f"{identifier(name)}_peak", float(values_[k]), outcome.units[name],
                    where={"f_hz": float(freq[k])},
                    description=f"peak {outcome.descriptions[name]}")
    return outcome


def response_notes(response) -> list[str]:
    """The frequencies without a finite response, worded."""
    import numpy as np

    out = []
    if np.any(response.unbounded):
        where = ", ".join(f"{f:g}" for f in response.frequencies[response.unbounded][:5])
        out.append(f"note: no finite response at {where} Hz (a rigid-body mode at 0 Hz, or an "
                   f"undamped resonance): empty in CSV, — in the table.")
    return out


ENTRIES = {
    "gear-modes": Analysis("gear-modes", "Natural frequencies and modes of a gear drive",
                           run_modes, (SET, SHAPES, CHECK), source="gears", figures=("modes",),
                           command="dyade gears"),
    "gear-campbell": Analysis("gear-campbell", "Campbell diagram of a gear drive: the "
                              "resonance speeds", run_campbell, (SET, SPEED_RANGE, HARMONICS),
                              source="gears", figures=("campbell",),
                              command="dyade gears --speed-range"),
    "gear-response": Analysis("gear-response", "Forced response of a gear drive to its "
                              "excitations", run_response, (SET, FREQUENCY_RANGE, DOF),
                              source="gears", command="dyade gears --frequency-range"),
}
