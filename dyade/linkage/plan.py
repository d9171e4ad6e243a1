"""What a mechanism calls for: the stages of its sweep, decided from the data before
anything runs (``plan``) and shown by ``describe``.

masses, loads or springs → kinetostatics; a friction coefficient → friction solution and
self-locking verdict; a slider with friction → its self-locking margin; clearance data →
the clearance check; a ``[drive]`` table → the equation of motion. Stages the scene does
not call for are not run.
"""

from __future__ import annotations

from dataclasses import dataclass

from dyade.model.mechanism import Mechanism


@dataclass(frozen=True, slots=True)
class Plan:
    """The stages a sweep will run, decided from the data before anything runs
    (``plan``): each is a tuple of the joints it concerns, or a flag.

    >>> import dyade
    >>> the_plan = dyade.plan(dyade.read_mechanism("mechanisms/self-locking.toml"))
    >>> the_plan.friction, the_plan.self_locking
    (((1, 2), (2, 3), (3, 4), (1, 4)), ((1, 4),))
    >>> dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml"),
    ...               plan=dyade.Plan()).forces is None          # kinematics only
    True
    """

    kinematics: bool = True
    kinetostatics: bool = False
    """masses, loads or springs present"""
    friction: tuple[tuple[int, int], ...] = ()
    """joints with μ > 0 (friction runs only with kinetostatics)"""
    self_locking: tuple[tuple[int, int], ...] = ()
    """sliders with μ > 0"""
    clearance: tuple[tuple[int, int], ...] = ()
    """revolute joints with clearance data in the file (peak-force check)"""
    equation_of_motion: str = ""
    """the motor of a [drive] table ('' without one): the crank's speed comes from the
    equation of motion"""
    drive_line: str = ""
    """the elastic drive line of a [drive_line] table ('' without one): its lowest natural
    frequency ω̄ and the VDI 2149 check Ω/ω̄ ≤ 0.1 (the vibration: ``dyade driveline``)"""


def plan(mechanism: Mechanism) -> Plan:
    """Decide the stages from the data: only what the mechanism calls for.

    Parameters
    ----------
    mechanism : Mechanism
        From ``read_mechanism`` or ``build_mechanism``.

    Returns
    -------
    Plan
        The stages a sweep runs (kinetostatics, friction, self-locking, clearance, the
        equation of motion), each with the reason; ``dyade describe`` prints it.

    Examples
    --------

    >>> import dyade
    >>> dyade.plan(dyade.read_mechanism("mechanisms/fourbar.toml")).kinetostatics
    True
    """
    dynamics = mechanism.has_dynamics
    rubbing = tuple(j.name for j in mechanism.joints if j.friction > 0.0) if dynamics else ()
    locking = tuple(j.name for j in mechanism.friction_sliders) if dynamics else ()
    gaps = tuple(j.name for j in mechanism.joints
                 if getattr(j, "clearance", None) is not None) if dynamics else ()
    motion = ""
    if mechanism.drive is not None:
        motion = mechanism.drive.motor.describe()
        if mechanism.drive.flywheel_inertia:
            motion += f", flywheel {mechanism.drive.flywheel_inertia:g} kg·m²"
    line = "" if mechanism.drive_line is None else mechanism.drive_line.describe()
    return Plan(kinematics=True, kinetostatics=dynamics, friction=rubbing, self_locking=locking,
                clearance=gaps, equation_of_motion=motion, drive_line=line)
