"""The words of a sweep's notes (``dyade.linkage.notes.Note``): one sentence each, as the
command line prints them (a warning line each) and the Outcome of a sweep lists them
(``dyade.report.notes`` gives the writers the same ``say``)."""

from __future__ import annotations

import numpy as np

from dyade.model.mechanism import Mechanism
from dyade.linkage.notes import Note, NoteKind, format_ranges


def say(note: Note, mechanism: Mechanism) -> str:
    """The sentence of ``note``, a finding of a sweep of ``mechanism``."""
    return WORDS[note.kind](note, note.figures, mechanism)


def _at(note: Note, figures: dict) -> str:
    return format_ranges(note.ranges, digits=figures["digits"])


def _dyad(mechanism: Mechanism, number: int):
    return next(dyad for dyad in mechanism.dyads if dyad.number == number)


def _partial(note, figures, mechanism) -> str:
    problems = [f"{_dyad(mechanism, number).label} {_dyad(mechanism, number).kind.cannot_close} "
                f"for crank angles {format_ranges(spans, digits=figures['digits'])}"
                for number, spans in figures["failing"]]
    return ("; ".join(problems) + f". Those positions are left out ({figures['kept']} of "
            f"{figures['positions']} kept).")


def _dead_centre(note, figures, mechanism) -> str:
    dyad = _dyad(mechanism, figures["dyad"])
    return (f"{dyad.label} is within {np.rad2deg(figures['band']):g}° of a "
            f"{dyad.kind.singular} (transmission angle near 0° or 180°) at crank angles "
            f"{_at(note, figures)}: the rigid model is invalid there, and nothing is given "
            f"(empty in CSV, null in JSON).")


def _poor_transmission(note, figures, mechanism) -> str:
    digits = figures["digits"]
    return (f"{_dyad(mechanism, figures['dyad']).label} has a transmission angle below "
            f"{np.rad2deg(figures['warning']):g}° (the designers' rule) at crank angles "
            f"{_at(note, figures)}, {figures['least_deg']:.{digits}f}° at the least (crank "
            f"angle {np.rad2deg(figures['at']):.{digits}f}°): results are given, but the "
            f"drive is sensitive to friction, clearance and elasticity there.")


def _implausible(note, figures, mechanism) -> str:
    names = figures.get("columns", ())
    which = (f" ({', '.join(names[:4])}{' …' if len(names) > 4 else ''})" if names else "")
    return (f"{figures['part']}{which} beyond {figures['limit']:.0e} (SI units) at crank "
            f"angles {_at(note, figures)}: no machine moves or loads so; those rows are not "
            f"given.")


def _forces_invalid(note, figures, mechanism) -> str:
    return (f"forces are not given at crank angles {_at(note, figures)}, where the "
            f"kinematics is: the rigid model's forces are not valid there (forces_valid = 0, "
            f"force fields empty).")


def _lift_off(note, figures, mechanism) -> str:
    from dyade.units import RAD_PER_S_TO_RPM

    rpm = abs(mechanism.crank.speed) * RAD_PER_S_TO_RPM
    return (f"the cam's follower lifts off at cam angles {_at(note, figures)}: at {rpm:g} rpm "
            f"its contact force would have to fall below 0 (a pull), which the spring "
            f"closure cannot give; the chain's forces are not given there (forces_valid = 0, "
            f"force fields empty). A stiffer spring, more preload or a lower speed keeps it "
            f"on (`dyade cam` gives the lift-off speed).")


def _near_self_locking(note, figures, mechanism) -> str:
    band = np.sin(figures["band"])
    return (f"{_dyad(mechanism, figures['dyad']).label} is near self-locking at crank angles "
            f"{_at(note, figures)}: its friction-augmented determinant is below {band:.3g} or "
            f"friction multiplies its joint forces more than {1 / band:.0f}-fold (the sin of, "
            f"and one over, the {np.rad2deg(figures['band']):g}° dead-centre band); the rigid "
            f"model is invalid there (forces_valid = 0, force fields empty).")


def _friction_not_converged(note, figures, mechanism) -> str:
    if figures["where"] == "drive":
        return (f"the friction torque of the equation of motion did not settle in "
                f"{figures['passes']} passes (largest change {figures['change']:.3g} N·m).")
    restart = figures["restart_passes"]
    return (f"no consistent friction solution was found in {figures['passes']} passes "
            f"(tolerance {figures['tolerance']:g}) at {figures['positions']} positions: crank "
            f"angles {_at(note, figures)}; forces are not given there (forces_valid = 0)"
            + ("." if figures["verdict"] else
               f"; fewer than {restart} passes (friction.max_iter) give no self-locking "
               f"verdict."))


def _at_rest(note, figures, mechanism) -> str:
    a, b = figures["joint"]
    return (f"joint ({a},{b}) is at rest relative to its partner at crank angles "
            f"{_at(note, figures)}: the friction direction is undefined there and no friction "
            f"is applied.")


def _never_moves(note, figures, mechanism) -> str:
    a, b = figures["joint"]
    return (f"joint ({a},{b}) never moves relative to its partner over the sweep: it has no "
            f"friction loss.")


def _self_locking(note, figures, mechanism) -> str:
    a, b = figures["joint"]
    what = "slider" if figures["slider"] else "joint"
    return (f"{what} ({a},{b}) locks (self-locking) at crank angles {_at(note, figures)}: "
            f"{_dyad(mechanism, figures['dyad']).label} has no friction equilibrium there (its "
            f"friction-augmented determinant changes sign: a friction dead centre, caused by "
            f"the friction in ({a},{b})); forces are not given there (forces_valid = 0).")


def _run_up_not_settled(note, figures, mechanism) -> str:
    return (f"the run-up did not become periodic within {figures['revolutions']} revolutions "
            f"(raise [drive] max_revolutions).")


def _clearance_not_applicable(note, figures, mechanism) -> str:
    if figures.get("run_up"):
        return ("the clearance check is not made on a run-up: it needs the periodic cycle.")
    a, b = figures["joint"]
    return f"clearance check of joint ({a},{b}) does not apply: {figures['reason']}."


def _drive_line_soft(note, figures, mechanism) -> str:
    return (f"the drive line's lowest natural frequency ω̄ = {figures['omega_bar']:.5g} rad/s is "
            f"only {1.0 / figures['ratio']:.3g} times the crank speed (Ω/ω̄ = "
            f"{figures['ratio']:.3g} > 0.1, VDI 2149 Part 1): these rigid-drive results do not "
            f"hold; see `dyade driveline`.")


WORDS = {NoteKind.PARTIAL: _partial, NoteKind.DEAD_CENTRE: _dead_centre,
          NoteKind.POOR_TRANSMISSION: _poor_transmission, NoteKind.IMPLAUSIBLE: _implausible,
          NoteKind.FORCES_INVALID: _forces_invalid,
          NoteKind.NEAR_SELF_LOCKING: _near_self_locking,
          NoteKind.FRICTION_NOT_CONVERGED: _friction_not_converged,
          NoteKind.AT_REST: _at_rest, NoteKind.NEVER_MOVES: _never_moves,
          NoteKind.SELF_LOCKING: _self_locking,
          NoteKind.RUN_UP_NOT_SETTLED: _run_up_not_settled,
          NoteKind.CLEARANCE_NOT_APPLICABLE: _clearance_not_applicable,
          NoteKind.DRIVE_LINE_SOFT: _drive_line_soft, NoteKind.LIFT_OFF: _lift_off}
"""every kind of note -> its words (tests/linkage/test_notes.py: none missing)"""
