"""Read a mechanism file (TOML), validate it, and convert it to SI model objects.

Every error names the file, the key path, what was expected (with its unit) and what
was found; unknown keys get a "Did you mean" (``docs/reference/mechanism-file.md`` documents every
key). The primitives are the shared schema (``dyade.files.schema``); one module per
part of the file:

``reader``    the whole file: top-level keys, [units], [sweep], the order of the parts
``links``     links and their points, the crank, the outer joints A and C of dyads
``dyads``     the [[dyad]] tables: each kind's keys and its middle joint B
``loads``     [gravity], [[load]] and [[spring]]
``friction``  [friction] defaults, each joint's friction and clearance data
``drive``     the [drive] table: motor, flywheel, equation-of-motion settings
``editing``   the TOML: ``--set`` overrides, ``--save-as`` text, data written as TOML
"""

from __future__ import annotations

import os
from typing import Any

from dyade.errors import InputError
from dyade.files.mechanism.editing import NUMBERING, dumps, edited, load_data
from dyade.files.mechanism.reader import Reader
from dyade.files.schema import set_dotted
from dyade.model.mechanism import Mechanism

__all__ = ["NUMBERING", "InputError", "Reader", "build", "dumps", "edited", "load_data",
           "read_mechanism", "set_dotted"]


def read_mechanism(path: str | os.PathLike, overrides: dict[str, Any] | None = None
                   ) -> Mechanism:
    """Read and validate a mechanism file.

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file (``docs/reference/mechanism-file.md`` documents every key).
    overrides : dict, optional
        Dotted key path -> value, replacing keys of the file as ``--set`` does
        (``{"crank.speed_rpm": 600}``). Array entries go by their number: links and
        loads from 1, dyads as in DYADE from 2 (the crank is dyad 1, the first
        ``[[dyad]]`` table dyad 2): ``{"dyad.2.length": 0.2}``.

    Returns
    -------
    Mechanism
        In SI units, validated.

    Raises
    ------
    InputError
        Naming the file and the key path, what was expected and what was found.

    Examples
    --------
    >>> import dyade
    >>> fourbar = dyade.read_mechanism("mechanisms/fourbar.toml")
    >>> fourbar.name, [dyad.number for dyad in fourbar.dyads]
    ('Four-bar crank-rocker', [2])
    >>> faster = dyade.read_mechanism("mechanisms/fourbar.toml", {"crank.speed_rpm": 600})
    >>> round(faster.crank.speed, 3)     # [rad/s]
    62.832
    >>> longer = dyade.read_mechanism("mechanisms/slider-crank.toml", {"dyad.2.length": 200})
    >>> stroke = dyade.analyse(longer).columns()["s_1_4"]     # [m]
    >>> round(float(stroke.max() - stroke.min()), 4)
    0.0801
    """
    return build(load_data(path, overrides), path)


def build(data: dict[str, Any], path: str | os.PathLike | None = None) -> Mechanism:
    """Validate mechanism data and build the mechanism.

    Parameters
    ----------
    data : dict
        The parsed TOML of a mechanism file, or the same structure written in Python:
        the keys of the file reference, lengths in ``units`` (default mm), angles in
        degrees.
    path : str or os.PathLike, optional
        The file the data came from, named in errors.

    Returns
    -------
    Mechanism
        In SI units, validated.

    Examples
    --------
    >>> import dyade
    >>> slider_crank = dyade.build_mechanism({
    ...     "crank": {"length": 0.05, "speed_rpm": 600}, "units": {"length": "m"},
    ...     "dyad": [{"kind": "RRP", "links": [3, 4], "length": 0.2,
    ...               "A": {"link": 2, "point": "tip"}, "C": {"link": 1, "angle": 0}}]})
    >>> stroke = dyade.analyse(slider_crank).columns()["s_1_4"]     # [m]
    >>> round(float(stroke.max() - stroke.min()), 6)
    0.1
    """
    path = os.fspath(path) if path else None
    return Reader(os.path.basename(path) if path else "mechanism", path).mechanism(data)
