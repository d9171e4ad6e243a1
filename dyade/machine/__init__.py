"""The machine in motion (one degree of freedom): motor characteristics, the equation
of motion over the crank angle, and the flywheel from a torque curve.

Nothing here knows about linkages: the reduced inertia J(φ), its slope J′(φ) and the
reduced load torque M_L(φ) come in as tables (``dyade.linkage.drive`` makes them from a
mechanism, ``dyade.linkage.reduced`` computes them), a torque curve as arrays.
"""
