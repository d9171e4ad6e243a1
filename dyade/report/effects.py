"""The effects a sweep simulates, in words: what ``describe`` lists (the stages of
``dyade.linkage.plan.Plan``; an Outcome names them in ``meta["stages"]``)."""

from __future__ import annotations

from dyade.linkage.plan import Plan


def effects(the_plan: Plan) -> list[str]:
    """One line per effect a sweep of ``the_plan`` simulates."""
    out = ["kinematics: positions, velocities, accelerations of every link, joint and point"]
    if the_plan.kinetostatics:
        out.append("kinetostatics: joint forces, driving torque, shaking force (d'Alembert, "
                   "backward dyad by dyad)")
    if the_plan.friction:
        out.append("Coulomb friction (solved per dyad) in joints "
                   + ", ".join(f"({a},{b})" for a, b in the_plan.friction)
                   + "; self-locking (friction dead centres) of their dyads")
    if the_plan.self_locking:
        out.append("self-locking margin of sliders "
                   + ", ".join(f"({a},{b})" for a, b in the_plan.self_locking))
    if the_plan.clearance:
        out.append("clearance peak check (Dresig–Thümmel) in joints "
                   + ", ".join(f"({a},{b})" for a, b in the_plan.clearance))
    if the_plan.equation_of_motion:
        out.append(f"equation of motion J(φ)·φ̈ + ½·J′(φ)·φ̇² = M_M(φ̇) + M_L(φ) − M_F with "
                   f"the motor: {the_plan.equation_of_motion}; its periodic steady state "
                   f"(shooting over one revolution), or the run-up from rest when asked; "
                   f"then kinematics and forces at the real crank speed and acceleration")
    if the_plan.drive_line:
        out.append(f"elastic drive line ({the_plan.drive_line}): its lowest natural frequency "
                   f"ω̄ with the mean reduced inertia and the VDI 2149 check Ω/ω̄ ≤ 0.1 (a note "
                   f"when exceeded); its vibration, resonances and stability with "
                   f"`dyade driveline`")
    return out
