"""A torque curve from a CSV file: the reader (``dyade.files.torque_curve``) gives its
columns in SI, the flywheel's engine (``dyade.machine.flywheel``) makes the curve. This is
``dyade.read_torque_curve``, the input of the flywheel from a CSV."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from dyade.machine.flywheel import TorqueCurve


def read_torque_curve(path: str | os.PathLike, *, speed_rpm: float | None = None,
                      text: str | None = None, **renamed) -> TorqueCurve:
    """The torque curve of a CSV file with columns ``angle_deg`` and ``M_drive`` [N·m] and
    optionally ``M_load`` [N·m] (positive where it drives; default a constant load equal
    to the mean drive torque).

    A CSV written by ``dyade analyse`` (it has ``dJ_red``) is a machine's drive torque at
    constant speed, with its loads already in it: it is read as by ``machine_curve``, with
    the machine's mean ``J_red`` and, unless ``speed_rpm`` is given, its crank speed.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file.
    speed_rpm : float, optional
        The mean crank speed [rpm]; required unless the file is dyade's.
    text : str, optional
        The file's content, when already read (standard input); ``path`` names it.
    **renamed
        The former ``speed`` [rad/s] is refused with an ``InputError`` naming
        ``speed_rpm``.

    Returns
    -------
    TorqueCurve

    Examples
    --------
    >>> import dyade
    >>> curve = dyade.read_torque_curve("mechanisms/torque/engine.csv", speed_rpm=250)
    >>> curve.angle.size, round(curve.mean_torque, 6)     # 0°…359°: 360° repeats 0°
    (360, 10000.0)
    """
    from dyade.errors import InputError
    from dyade.files.torque_curve import read_table
    from dyade.machine.flywheel import RENAMED, table_curve
    from dyade.units import rpm_to_rad_per_s

    InputError.refuse_renamed("read_torque_curve", renamed, RENAMED)
    speed = None if speed_rpm is None else rpm_to_rad_per_s(speed_rpm)
    table = read_table(path, text)
    try:
        return table_curve(table, speed)
    except InputError as err:  # the engine names its arguments: here they are columns
        column = {"angle": "angle_deg", "load": "M_load"}.get(err.key or "")
        if column is None or err.reason is None:
            raise
        raise InputError(f"{table.source}: column {column} {err.reason}", source=table.source,
                         key=column, value=err.value, unit=err.unit, reason=err.reason
                         ) from None
