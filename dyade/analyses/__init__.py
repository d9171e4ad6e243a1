"""Every analysis of dyade as an entry of one registry (issue 36; ``base`` is the
contract).

>>> from dyade.analyses import REGISTRY
>>> outcome = REGISTRY["coupling"](None, J=1.0, c1=1.0, c2=1.0)
>>> outcome.summary["omega_t"].unit
'rad/s'

The entries are loaded on first use (``REGISTRY[name]``), so that the command line
lists them without importing numpy.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping

from dyade.analyses.base import Analysis

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
    "study": "dyade.analyses.study",
}
"""entry name -> the module that defines it (in its ``ENTRIES`` dict)"""


class Registry(Mapping):
    """name -> ``Analysis``, each module imported when one of its entries is asked for."""

    def __getitem__(self, name: str) -> Analysis:
        import importlib

        try:
            module = ENTRIES[name]
        except KeyError:
            raise KeyError(name) from None
        return importlib.import_module(module).ENTRIES[name]

    def __iter__(self) -> Iterator[str]:
        return iter(ENTRIES)

    def __len__(self) -> int:
        return len(ENTRIES)


REGISTRY = Registry()


def run(name: str, source=None, **options):
    """Run the analysis ``name`` of the registry on ``source`` with ``options`` (API
    names): ``dyade.run("sweep", "mechanisms/fourbar.toml", step_deg=1)`` -> ``Outcome``."""
    return REGISTRY[name](source, **options)
