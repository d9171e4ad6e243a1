"""The analyses of dyade, each an entry of the one registry (``dyade.registry``; the
contract is ``dyade.analyses.base``): ``ENTRIES`` names the module of each. The design
study evaluates these entries and sits above them (``dyade.study.entry``)."""

from __future__ import annotations

ENTRIES = {
    "sweep": "dyade.analyses.sweep",
    "describe": "dyade.analyses.describe",
    "accuracy": "dyade.analyses.accuracy",
    "clearance-check": "dyade.analyses.clearance",
    "clearance-speeds": "dyade.analyses.clearance",
    "clearance-peak": "dyade.analyses.clearance",
    "coupling": "dyade.analyses.coupling",
    "gear-modes": "dyade.analyses.gears",
    "gear-campbell": "dyade.analyses.gears",
    "gear-response": "dyade.analyses.gears",
    "flywheel": "dyade.analyses.machine",
    "balance": "dyade.analyses.machine",
    "driveline-frequency": "dyade.analyses.drive_line",
    "driveline-steady": "dyade.analyses.drive_line",
    "driveline-resonance": "dyade.analyses.drive_line",
    "driveline-stability": "dyade.analyses.drive_line",
    "driveline-map": "dyade.analyses.drive_line",
    "driveline-run-up": "dyade.analyses.drive_line",
    "profile": "dyade.analyses.profile",
    "servo": "dyade.analyses.servo",
    "synthesis": "dyade.analyses.synthesis",
}
"""entry name -> the module that defines it (in its ``ENTRIES`` dict)"""
