"""dyade: kinematics and kinetostatics of planar linkages built from dyads.

A linkage is assembled from two-link groups (dyads) in assembly order and swept over
the crank angle (Thümmel & Bartke 1987, the DYADE program). This module imports
nothing heavy, so that ``dyade --help`` stays fast.
"""

__version__ = "0.1.0"
