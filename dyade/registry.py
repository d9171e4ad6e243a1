"""The one registry of dyade's analyses: every command is an entry (issue 36).

The analyses (``dyade.analyses.ENTRIES``) and the design study (``dyade.study.entry``),
which evaluates the others and so sits above them, form one registry: name ->
``Analysis``, each module imported when one of its entries is asked for, so that the
command line lists them without importing numpy.

>>> from dyade.registry import REGISTRY
>>> outcome = REGISTRY["coupling"](None, J=1.0, c1=1.0, c2=1.0)
>>> outcome.summary["omega_t"].unit
'rad/s'
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping

from dyade.analyses import ENTRIES as ANALYSES
from dyade.analyses.base import Analysis

ENTRIES = {**ANALYSES, "study": "dyade.study.entry"}
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
    """Run an analysis of the registry: what its command does, as a Python function.

    Parameters
    ----------
    name : str
        The entry (``list(dyade.registry.REGISTRY)``): ``"sweep"`` (``dyade analyse``),
        ``"coupling"``, ``"gear-modes"``, ``"driveline-steady"``, ``"study"``, …
    source : str, os.PathLike or model object, optional
        The input file (a mechanism, gear, coupling or study file) or its model (a
        ``Mechanism``, ``GearDrive``, ``Coupling``); None where the options hold the
        whole input.
    **options
        The entry's options by their API names: the command line's flags with the unit
        in the name (``--step`` is ``step_deg``, ``--speed`` [rpm] ``speed_rpm``,
        ``--max-memory`` [MB] ``max_memory_mb``); ``REGISTRY[name].options`` lists them
        with unit, default and help.

    Returns
    -------
    Outcome
        Columns with their units, the summary's figures (value, unit, where), the notes;
        ``.to_document()`` is the JSON the command's ``--format json`` writes.

    Raises
    ------
    InputError
        A bad file or option (an old option name: naming its new one).
    DyadeError
        The analysis cannot give what was asked (every position withheld, …).

    Examples
    --------
    >>> import dyade
    >>> outcome = dyade.run("coupling", "mechanisms/coupling/stiff-coupling.toml")
    >>> figure = outcome.summary["omega_t"]
    >>> round(figure.value, 1), figure.unit
    (2886.8, 'rad/s')
    """
    return REGISTRY[name](source, **options)
