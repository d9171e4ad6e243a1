"""dyade: dynamics of planar linkages and machine drives.

A linkage is assembled from two-link groups (dyads) in assembly order and swept over
the crank angle, as in DYADE (Thümmel & Kretzschmar, 1987; its dynamics published by
Thümmel & Bartke, Technische Mechanik 8, 1987). Around it: the peak force in a revolute
joint with clearance (Dresig & Thümmel), the torsional resonance of a stiff coupling
(Strümpfel) and the vibration of multistage gear drives as rigid finite elements
(Berczyński, Maćkowiak & Marchelek).

Every command is an entry of one registry, run the same way from Python:
``run(name, source, **options)`` -> ``Outcome`` (``dyade.registry.REGISTRY`` lists the
entries, each with its options declared once: ``REGISTRY["sweep"].options``); the
Outcome holds the columns with their units, the summary's figures (value, unit, where),
the notes, and ``to_document()``, the JSON that ``--format json`` writes.

The engine's API, one package per analysis (``dyade.linkage``, ``dyade.clearance``,
``dyade.vibration``, ``dyade.machine``) over the data they compute on (``dyade.model``:
the mechanism, a drive, a gear drive, a coupling, as the files describe them), with the
everyday functions re-exported here:

- ``read_mechanism(path, overrides=None)``, ``build_mechanism(data)`` -> ``Mechanism``
- ``plan(mechanism)`` -> ``Plan``; ``analyse(mechanism, *, step_deg=..., ...)`` ->
  ``Result`` with
  ``.columns()``, ``.summary()``, ``.notes`` (``Note``: its ``NoteKind``, subject,
  crank-angle ranges and figures; ``dyade.report.notes.say`` words it), ``.to_pandas()``;
  ``analyse_in_blocks(mechanism, block_size=...)`` -> a run whose blocks give the same
  columns block by block, in bounded memory
- ``check_clearance(mechanism, ...)``, ``clearance_speed_study(mechanism, speeds_rpm, ...)``,
  ``peak_force(mass, stiffness, *, clearance, slope)``, ``simulate_clearance(...)``
- ``Coupling``, ``read_coupling(path)``, ``coupling_response(coupling, eta)``,
  ``operating_points(coupling, speeds_rpm, *, order=1)``
- ``accuracy_studies(mechanism)``
- ``mechanism_torque_curve(mechanism, *, step_deg=None)``,
  ``torque_curve(angle_deg, drive, load, *, speed_rpm)``,
  ``read_torque_curve(path, *, speed_rpm=None)``, ``size_flywheel(curve, fluctuation)``,
  ``speed_fluctuation(curve, inertia)``: the flywheel (``dyade.machine``)
- ``balance(mechanism, *, links, radius)``: counterweights against the shaking force
- ``drive_line_frequency(mechanism)``, ``drive_line_steady_state(mechanism, *,
  speed_rpm=None)``, ``drive_line_resonance(mechanism, speeds_rpm)``,
  ``drive_line_stability_map(mechanism, speeds_rpm, *, stiffness=None, damping=None)``,
  ``drive_line_run_up(mechanism)``: a linkage driven through an elastic shaft or
  coupling (``[drive_line]``, ``dyade.linkage.drive_line``)
- ``read_gears(path, overrides=None)``, ``build_gears(data)`` -> ``GearDrive``;
  ``gear_modes(drive)`` -> ``Modes``, ``campbell(drive, speeds_rpm, ...)``,
  ``gear_response(drive, frequencies, ...)``, ``gear_statics(drive, torques, ...)``,
  ``check_elimination(drive, modes=None)``: gear drives as rigid finite elements
  (``dyade.vibration.gears``)
- ``study(file, *, jobs, executor, output, resume)`` -> ``Study``: a design study, one
  row per variant (``dyade.study``; ``Study.columns()``, ``.to_pandas()``)
- ``DyadeError``, ``InputError``, ``AssemblyError``, ``MissingExtra`` (an optional
  extra not installed: an ``InputError`` and ``ImportError`` naming the pip command)
- ``dyade.plot``: the figures (the plot extra, ``pip install "dyade[plot]"``), loaded on
  first use: ``dyade.plot.curves.figure(result)``

Units: angles a person passes or reads carry their unit in the name, as the CSV columns
do: ``step_deg``, ``start_deg``, ``stop_deg``, ``crank_angle_deg``, ``max_wander_deg``;
speeds ``speed_rpm``. An old name (``step=`` in radians) is refused with an
``InputError`` naming the new one, and a step above one revolution or a sweep of one
position is refused as a likely mistake. Everything else is SI (m, s, kg, N, rad/s),
and so are the engine's arrays (``Result.kinematics``: rad). Mechanism files may use mm
and degrees. Nothing here prints or exits: problems are exceptions with structured
fields; results a person reads (``Result.summary()``) are plain Python numbers.

>>> import dyade
>>> result = dyade.analyse(dyade.read_mechanism("mechanisms/slider-crank.toml"))
>>> [note.kind for note in result.notes]
[]

This module imports nothing heavy (``import dyade`` loads no numpy), so that
``dyade --help`` stays fast; the functions load their modules on first use.
"""

from __future__ import annotations

__version__ = "0.1.0"
"""the one place the version is written: pyproject.toml reads it from here (setuptools
``dynamic``), the installed metadata and ``dyade --version`` say the same"""

_EXPORTS = {
    "run": "dyade.registry",
    "Outcome": "dyade.analyses.base",
    "read_mechanism": "dyade.files.mechanism",
    "build_mechanism": ("dyade.files.mechanism", "build"),
    "plan": "dyade.linkage.plan",
    "analyse": "dyade.linkage.sweep",
    "analyse_in_blocks": "dyade.linkage.sweep",
    "Plan": "dyade.linkage.plan",
    "Result": "dyade.linkage.sweep",
    "Note": "dyade.linkage.notes",
    "NoteKind": "dyade.linkage.notes",
    "Mechanism": "dyade.model.mechanism",
    "check_clearance": ("dyade.linkage.clearance_study", "check"),
    "clearance_speed_study": ("dyade.linkage.clearance_study", "speed_study"),
    "peak_force": "dyade.clearance",
    "simulate_clearance": ("dyade.clearance", "simulate"),
    "Coupling": "dyade.model.coupling",
    "read_coupling": "dyade.files.coupling",
    "coupling_response": ("dyade.vibration.coupling", "response"),
    "operating_points": "dyade.vibration.coupling",
    "accuracy_studies": ("dyade.linkage.accuracy", "studies"),
    "torque_curve": "dyade.machine.flywheel",
    "read_torque_curve": "dyade.analyses.torque_curve",
    "mechanism_torque_curve": ("dyade.linkage.machine_curve", "torque_curve"),
    "size_flywheel": "dyade.machine.flywheel",
    "speed_fluctuation": "dyade.machine.flywheel",
    "balance": ("dyade.linkage.balance", "balance"),
    "drive_line_frequency": ("dyade.linkage.drive", "natural_frequency"),
    "drive_line_steady_state": ("dyade.linkage.drive_line", "steady_state"),
    "drive_line_resonance": ("dyade.linkage.drive_line", "resonance_curve"),
    "drive_line_stability_map": ("dyade.linkage.drive_line", "stability_map"),
    "drive_line_run_up": ("dyade.linkage.drive_line", "run_up"),
    "read_gears": "dyade.files.gears",
    "build_gears": "dyade.files.gears",
    "GearDrive": "dyade.model.gears",
    "gear_modes": "dyade.vibration.gears.modes",
    "campbell": "dyade.vibration.gears.campbell",
    "gear_response": "dyade.vibration.gears.response",
    "gear_statics": "dyade.vibration.gears.response",
    "check_elimination": ("dyade.vibration.gears.elimination", "check"),
    "DyadeError": "dyade.errors",
    "InputError": "dyade.errors",
    "AssemblyError": "dyade.errors",
    "MissingExtra": "dyade.errors",
}

_SUBMODULES = {"analyses", "clearance", "errors", "files", "linkage", "machine", "model",
               "plot", "study", "units", "vibration"}
"""packages of the API, loaded on first attribute access (``dyade.clearance``)"""

__all__ = sorted(_EXPORTS) + ["__version__"]


def __getattr__(name: str):
    """Load an exported name on first use (PEP 562)."""
    import importlib

    if name in _SUBMODULES:
        return importlib.import_module(f"dyade.{name}")
    try:
        where = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'dyade' has no attribute {name!r}") from None
    module, attribute = where if isinstance(where, tuple) else (where, name)
    value = getattr(importlib.import_module(module), attribute)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(__all__ + list(_SUBMODULES))
