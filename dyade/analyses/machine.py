"""``flywheel`` and ``balance``: the machine in motion (Dresig & Holzweißig,
*Maschinendynamik*; Berkof & Lowen).

``flywheel`` sizes the flywheel for a speed fluctuation δ (or gives δ for a flywheel)
from the torque curve over one revolution: of a mechanism file at its constant crank
speed, or of a torque CSV (``angle_deg``, ``M_drive`` [N·m], optionally ``M_load``
[N·m]; a CSV of ``dyade analyse`` is read as the machine's need). ``balance`` fits
counterweights on the links that turn about frame pivots against the inertia shaking
force, and says what they change at the constant crank speed.
"""

from __future__ import annotations

import math
import os
from dataclasses import replace
from typing import Any

from dyade.analyses.base import Analysis, Budget, Option, Outcome
from dyade.analyses.inputs import MECHANISM, START, STEP, Text, load
from dyade.units import RAD_PER_S_TO_RPM

FLYWHEEL_OPTIONS = (
    Option("fluctuation", float, "-", metavar="DELTA", positive=True, study=False,
           help="Size the flywheel for this speed fluctuation δ = (ω_max − ω_min)/ω_mean, "
                "e.g. 0.02"),
    Option("inertia", float, "kg·m²", metavar="KG_M2", study=False,
           help="Give the flywheel's moment of inertia J_F and get the fluctuation"),
    Option("speed", float, "rpm", metavar="RPM", old=("--speed-rpm",),
           help="Mean crank speed of a torque CSV (a mechanism has its own)"),
    *MECHANISM, START,
    replace(STEP, help="Crank angle step of a mechanism's torque curve, at most 90° "
                       "(default: its sweep step, at most 0.1°)"),
)
BALANCE_OPTIONS = (
    Option("link", int, multiple=True, metavar="N", study=False,
           help="A link to carry a counterweight (repeatable); it must turn about a frame "
                "pivot [default: every such link]"),
    Option("radius", float, "m", metavar="M", positive=True,
           help="Radius of each counterweight's mass from its pivot [default: the link's "
                "reach: its farthest joint, named point or centre of mass]"),
    *MECHANISM,
)

FLYWHEEL = {  # key -> (unit, description): the summary's figures, the CSV's one row
    "speed_rpm": ("rpm", "mean speed Ω"),
    "P_mean": ("W", "mean power"),
    "M_mean": ("N·m", "mean drive torque"),
    "delta_E": ("J", "energy fluctuation ΔE"),
    "J_machine": ("kg·m²", "machine's mean reduced inertia"),
    "J_flywheel": ("kg·m²", "flywheel inertia J_F"),
    "fluctuation": ("-", "speed fluctuation δ"),
    "angle_max_speed_deg": ("°", "highest speed at φ21"),
    "angle_min_speed_deg": ("°", "lowest speed at φ21"),
}
"""the flywheel's figures (the CSV has one row of them, the JSON its summary)"""
MAX_STEP_DEG = 90.0  # [°] the largest step of a mechanism's torque curve

COUNTERWEIGHTS = {  # column -> (unit, description): one row per counterweight
    "link": ("", "the link that carries the counterweight"),
    "first_moment": ("kg·m", "first moment m·r of the counterweight about the pivot"),
    "angle_deg": ("°", "direction of the counterweight in the link's frame"),
    "radius": ("m", "radius of the counterweight's mass from the pivot"),
    "mass": ("kg", "mass of the counterweight"),
}

WITHHOLDING = {
    "implausible": "values beyond what any machine has, 1e12 in SI units",
    "dead_centre": "dead centres",
    "partial": "positions where the mechanism does not close",
    "forces_invalid": "forces not valid",
    "near_self_locking": "near self-locking",
    "self_locking": "self-locking",
    "friction_not_converged": "no friction solution",
}
"""the kinds of a sweep's notes that withhold positions -> their words in a message"""


def withholding(notes) -> str:
    """Why a sweep's positions are withheld, from its notes (``dyade.linkage.notes``):
    "values beyond what any machine has, 1e12 in SI units"."""
    kinds = dict.fromkeys(str(getattr(note, "kind", "")) for note in notes)
    return "; ".join(WITHHOLDING[kind] for kind in kinds if kind in WITHHOLDING)


def none_given(name: str, what: str, notes) -> None:
    """The rule every analysis shares, for a sweep: every position withheld -> exit 1
    saying so (a ``DyadeError``), never a table of zeros."""
    from dyade.errors import DyadeError

    why = withholding(notes)
    raise DyadeError(f"{name}: {what} (every position is withheld{f': {why}' if why else ''}): "
                     f"nothing to report.")


def sweep_seconds(mechanism, positions: int) -> float:
    """About how long a sweep of ``positions`` positions of ``mechanism`` takes [s]:
    ``SECONDS_PER_VALUE`` per column and position (five times that with friction)."""
    from dyade.linkage.options import column_count

    rubbing = mechanism.has_dynamics and any(j.friction > 0.0 for j in mechanism.joints)
    return positions * column_count(mechanism) * SECONDS_PER_VALUE * (5.0 if rubbing else 1.0)


SECONDS_PER_VALUE = 1e-7
"""[s] per column and position of a sweep (measured 20-90 ns on the shipped files, about
400 ns with friction)"""


# -- flywheel -----------------------------------------------------------------------------
def is_torque_csv(source: Any) -> bool:
    """A torque curve's CSV: a path ending in .csv, or a text whose first line is a CSV
    header (commas, no ``=`` and no ``[`` of TOML)."""
    if isinstance(source, Text):
        first = source.text.lstrip("\ufeff").lstrip().split("\n", 1)[0]
        return "," in first and "=" not in first and "[" not in first
    return (isinstance(source, (str, os.PathLike))
            and os.path.splitext(os.fspath(source))[1].lower() == ".csv")


def flywheel(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """The flywheel of ``source``: a torque CSV (path or ``Text``), a mechanism file
    (path or ``Text``), a ``Mechanism`` or a ``TorqueCurve``."""
    from dyade.errors import InputError
    from dyade.limits import PLAUSIBLE, check_plausible
    from dyade.machine import flywheel as engine
    from dyade.analyses.torque_curve import read_torque_curve

    fluctuation, inertia = options.get("fluctuation"), options.get("inertia")
    if (fluctuation is None) == (inertia is None):
        raise InputError.parameter(("fluctuation", "inertia"),
                                   f"are {'both given' if fluctuation is not None else 'missing'}"
                                   f": give either (the first sizes the flywheel, the second "
                                   f"gives the fluctuation).")
    if fluctuation is not None:
        check_plausible("fluctuation", fluctuation, "fluctuation")
    if inertia is not None and not 0.0 <= inertia <= PLAUSIBLE["inertia"][1]:
        most = PLAUSIBLE["inertia"][1]
        raise InputError.parameter("inertia", f"must lie in 0…{most:g} kg·m² (what a machine "
                                              f"has), got {inertia:g}.", value=inertia,
                                   unit="kg·m²")
    speed_rpm = options.get("speed_rpm")
    mechanism_only = [name for name in ("set", START.api, STEP.api) if options.get(name)
                      not in (None, ())]
    if isinstance(source, engine.TorqueCurve):
        curve = source
    elif is_torque_csv(source):
        if mechanism_only:
            raise InputError.parameter(tuple(mechanism_only), "apply to a mechanism file, not "
                                                              "a torque CSV.")
        if speed_rpm is not None:
            check_plausible("speed_rpm", speed_rpm, "speed_rpm")
        text = source.text if isinstance(source, Text) else None
        path = source.label if isinstance(source, Text) else source
        curve = read_torque_curve(path, speed_rpm=speed_rpm, text=text)
    else:
        curve = mechanism_curve(source, options, budget)
    result = (engine.size_flywheel(curve, fluctuation) if fluctuation is not None
              else engine.speed_fluctuation(curve, inertia))
    row = {"speed_rpm": result.speed * RAD_PER_S_TO_RPM, "P_mean": result.power,
           "M_mean": result.mean_torque, "delta_E": result.delta_energy,
           "J_machine": result.machine_inertia, "J_flywheel": result.flywheel,
           "fluctuation": result.fluctuation,
           "angle_max_speed_deg": math.degrees(result.angle_max_speed),
           "angle_min_speed_deg": math.degrees(result.angle_min_speed)}
    import numpy as np

    asked = "fluctuation" if fluctuation is not None else "J_flywheel"
    outcome = Outcome("flywheel", columns={k: np.array([v]) for k, v in row.items()},
                      units={k: unit for k, (unit, _) in FLYWHEEL.items()},
                      descriptions={k: text for k, (_, text) in FLYWHEEL.items()},
                      notes=list(result.notes), result=(result, curve),
                      meta={"name": curve.source, "given": asked,
                            "source": None if not isinstance(source, (str, os.PathLike))
                            else os.fspath(source)})
    for key, (unit, text) in FLYWHEEL.items():
        outcome.add(key, row[key], unit, description=text + (" (given)" if key == asked else ""))
    return outcome


def mechanism_curve(source: Any, options: dict[str, Any], budget: Budget):
    """The torque curve of a mechanism (file, text or ``Mechanism``) at its constant crank
    speed, its size and time checked before the sweep."""
    from dyade.errors import DyadeError, InputError
    from dyade.linkage.machine_curve import FINE_STEP, torque_curve
    from dyade.linkage.options import check_size

    if options.get("speed_rpm") is not None:
        raise InputError.parameter("speed_rpm", "is for a torque CSV: a mechanism has its own "
                                                "crank speed (its file's crank.speed_rpm).",
                                   unit="rpm")
    step_deg = options.get(STEP.api)
    if step_deg is not None and step_deg > MAX_STEP_DEG:
        raise InputError.parameter(STEP.api, f"must be at most {MAX_STEP_DEG:g} °, got "
                                             f"{step_deg:g}.", value=step_deg, unit="°")
    mechanism = load(source, {k: v for k, v in options.items() if k != STEP.api}).mechanism
    step = (min(mechanism.sweep.step, FINE_STEP) if step_deg is None
            else math.radians(step_deg))
    count = int(math.ceil(2.0 * math.pi / step - 1e-9))
    try:
        check_size(mechanism, count, budget.max_memory,  # one revolution: no range to shorten
                   advice="Use a coarser step (the torque curve covers one revolution)")
        budget.time(sweep_seconds(mechanism, count), f"the torque curve at {count:,} positions")
        return torque_curve(mechanism, step_deg=step_deg, max_memory=budget.max_memory)
    except InputError as err:
        raise err.naming({"max_memory": "max_memory_mb"}) from None
    except DyadeError as err:
        if not hasattr(err, "notes"):
            raise
        none_given(mechanism.name, "no crank position of the revolution has its drive torque "
                                   "given, so no flywheel can be sized from it", err.notes)


# -- balance ------------------------------------------------------------------------------
BEFORE_AFTER = (
    ("F_inertia_max", "N", "shaking force, largest"),
    ("F_inertia_rms", "N", "shaking force, RMS"),
    ("M_shake_max", "N·m", "shaking moment M_shake, largest"),
    ("M_shake_rms", "N·m", "shaking moment M_shake, RMS"),
    ("M_drive_peak", "N·m", "drive torque M_drive, largest"),
    ("M_drive_rms", "N·m", "drive torque M_drive, RMS"),
)
"""the figures of ``balance`` before and after (``NAME_before``, ``NAME_after``)"""


def balance(source: Any, options: dict[str, Any], budget: Budget) -> Outcome:
    """Counterweights against the shaking force of a mechanism (file, text or
    ``Mechanism``) and what they change."""
    import numpy as np

    from dyade.errors import InputError
    from dyade.linkage.balance import balance as fit
    from dyade.linkage.options import check_size

    loaded = load(source, options)
    mechanism = loaded.mechanism
    count = mechanism.sweep.count
    try:
        check_size(mechanism, 3 * count, budget.max_memory)  # the fit and two sweeps
        budget.time(3 * sweep_seconds(mechanism, count), f"the balance over {count:,} positions")
        result = fit(mechanism, links=options.get("link") or None, radius=options.get("radius"))
    except InputError as err:
        raise err.naming({"links": "link", "max_memory": "max_memory_mb"}) from None
    given = result.before.columns()["kinematics_valid"] == 1.0
    if not given.any():
        none_given(mechanism.name, "no crank position of the sweep has its shaking force given",
                   result.before.notes)
    if not (result.before.columns()["forces_valid"] == 1.0).any():  # beyond what a machine has
        none_given(mechanism.name, "no crank position of the sweep has its forces given, so "
                                   "no balance can be judged", result.before.notes)
    weights = result.counterweights
    columns = {"link": np.array([w.link for w in weights], dtype=np.int64),
               "first_moment": np.array([w.first_moment for w in weights]),
               "angle_deg": np.degrees([w.angle for w in weights]),
               "radius": np.array([w.radius for w in weights]),
               "mass": np.array([w.mass for w in weights])}
    outcome = Outcome("balance", columns=columns,
                      units={k: unit for k, (unit, _) in COUNTERWEIGHTS.items()},
                      descriptions={k: text for k, (_, text) in COUNTERWEIGHTS.items()},
                      result=(result, loaded), meta={"name": mechanism.name,
                                                     "source": loaded.label or None})
    changes = result.changes()
    shaking = changes["shaking_force"]
    values = {"F_inertia_max": (shaking["before_max"], shaking["after_max"]),
              "F_inertia_rms": (shaking["before_rms"], shaking["after_rms"])}
    for key, name in (("shaking_moment", "M_shake"), ("drive_torque", "M_drive")):
        entry = changes[key]
        values[f"{name}_max" if name == "M_shake" else f"{name}_peak"] = (entry["before_max"],
                                                                          entry["after_max"])
        values[f"{name}_rms"] = (entry["before_rms"], entry["after_rms"])
    for name, unit, text in BEFORE_AFTER:
        before, after = values[name]
        outcome.add(f"{name}_before", before, unit, description=f"{text}, before")
        outcome.add(f"{name}_after", after, unit, description=f"{text}, with the counterweights")
    outcome.add("F_inertia_ratio", shaking["residual"], "-",
                description="residual shaking force: RMS with the counterweights over RMS "
                            "before")
    for name, entry in changes["joint_forces"].items():
        outcome.add(f"{name}_peak_before", entry["before"], "N",
                    description=f"{name} largest, before")
        outcome.add(f"{name}_peak_after", entry["after"], "N",
                    description=f"{name} largest, with the counterweights")
    forces = result.before.columns()["forces_valid"] == 1.0
    for mask, what in ((given, "the figures are over the {} of {} positions where the "
                                "kinematics is given"),
                       (forces, "the drive torque, the shaking moment and the joint forces "
                                "are over the {} of {} positions where the forces are given")):
        if not mask.all():
            why = withholding(result.before.notes) or "the others withheld"
            outcome.notes.append(f"{what.format(int(mask.sum()), mask.size)} ({why}).")
            break
    return outcome


ENTRIES = {
    "flywheel": Analysis("flywheel", "The flywheel from the torque curve over one revolution",
                         flywheel, FLYWHEEL_OPTIONS, source="mechanism",
                         command="dyade flywheel"),
    "balance": Analysis("balance", "Counterweights against the shaking force", balance,
                        BALANCE_OPTIONS, command="dyade balance"),
}
