"""Read a coupling file (TOML): the stiff coupling's data (Strümpfel), flat keys.

A file holds what ``dyade coupling`` takes as options: J, c1, c2 (and optionally b1,
b2, moment, eta_range, speed_rpm, order, name). Every key is checked here, by the
shared schema, with the file and key named in the error.
"""

from __future__ import annotations

import os
from typing import Any

from dyade.files.schema import Field, TableReader, read_toml

FIELDS = {
    "name": Field("string"),
    "J": Field("number", "kg·m²", "positive"),
    "c1": Field("number", "N·m/rad", "non_negative"),
    "c2": Field("number", "N·m/rad", "non_negative"),
    "b1": Field("number", "N·m·s/rad", "non_negative"),
    "b2": Field("number", "N·m·s/rad", "non_negative"),
    "moment": Field("number", "N·m", "positive"),
    "eta_range": Field("string"),
    "speed_rpm": Field("numbers", "rpm", "positive"),
    "order": Field("number", "-", "positive"),
}
"""key -> type, unit and range of a coupling file"""
PARAMETERS = {"J": "inertia", "c1": "c1", "c2": "c2", "b1": "b1", "b2": "b2",
              "moment": "moment", "order": "order", "speed_rpm": "speeds_rpm"}
"""file key -> the API parameter it feeds (``Coupling``, ``amplitudes``,
``operating_points``)"""


def load_data(path: str | os.PathLike) -> dict[str, Any]:
    """The checked keys of a coupling file (numbers as floats)."""
    path = os.fspath(path)
    return TableReader(os.path.basename(path), path).fields(read_toml(path), FIELDS)


def read_coupling(path: str | os.PathLike):
    """The coupling model of a coupling file (``b1``, ``b2`` default to 0).

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file (the coupling file reference documents every key).

    Returns
    -------
    Coupling

    Raises
    ------
    InputError
        Naming the file and the key.

    Examples
    --------

    >>> import dyade
    >>> coupling = dyade.read_coupling("mechanisms/coupling/stiff-coupling.toml")
    >>> round(coupling.natural_frequency, 3), round(coupling.damping_ratio, 4)
    (2886.751, 0.0505)
    """
    from dyade.errors import InputError
    from dyade.model.coupling import Coupling

    path = os.fspath(path)
    data = load_data(path)
    missing = [key for key in ("J", "c1", "c2") if key not in data]
    if missing:
        raise InputError(f"{os.path.basename(path)}: missing {', '.join(missing)}.", source=path)
    try:
        return Coupling(data["J"], data["c1"], data["c2"], data.get("b1", 0.0), data.get("b2", 0.0))
    except InputError as err:
        name = os.path.basename(path)
        raise err.naming({p: f"{name}: `{k}`" for k, p in PARAMETERS.items()}) from None
