"""A ``cam`` Outcome (``dyade.analyses.cam``) -> tables, and the profile to manufacture
as CSV points and as DXF (through ezdxf, the optional extra ``dyade[cad]``)."""

from __future__ import annotations

import os
from typing import TextIO

import numpy as np

from dyade.report.format import cell
from dyade.units import LENGTH_FACTORS

DXF_UNITS = {"m": 6, "cm": 5, "mm": 4, "um": 13}
"""length unit -> DXF $INSUNITS code"""
LAYERS = {"working": "CAM-WORKING", "outer": "CAM-OUTER", "cutter": "CAM-CUTTER"}
"""curve -> the DXF layer it is drawn on"""


COLUMNS = ("angle_deg", "s", "v", "a", "pressure_angle_deg", "rho_pitch", "rho_working",
           "undercut", "contact_force", "outer_flank", "hertz_stress", "drive_torque",
           "guide_margin", "jammed")
"""the columns of the table over the turn that ``dyade cam`` prints"""
REPORT_COLUMNS = ("angle_deg", "s", "v", "pressure_angle_deg", "rho_pitch", "undercut",
                  "contact_force", "hertz_stress", "drive_torque", "guide_margin")
"""the narrower table of the design report (``dyade report``), a page's width"""


def tables(outcome, columns=COLUMNS):
    """The summary (lengths in the file's unit) and every k-th angle of ``columns``
    (those the Outcome has)."""
    from dyade.report.outcome import columns_table, summary_table

    unit = outcome.meta.get("length_unit", "m")
    title = (f"Cam: {outcome.meta.get('name')} ({outcome.meta.get('follower')} follower, "
             f"{outcome.meta.get('rotation')}, {outcome.meta.get('closure')} closure)")
    names = [n for n in columns if n in outcome.columns]
    parts = [summary_table(outcome, title, length_unit=unit),
             columns_table(outcome, "Over the turn", names, length_unit=unit, most=36)]
    return [part for part in parts if part is not None]


def curve(result, name: str):
    """The ``Manufacture`` named ``name`` ("working", "outer", "cutter") of a CamResult;
    None if it was not made."""
    for made in result.manufacture:
        if made.name == name:
            return made
    return None


def write_points(made, handle: TextIO, length_unit: str) -> None:
    """A curve's points as CSV in ``length_unit``: ``angle_deg,x_<unit>,y_<unit>``, in
    the cam's frame (origin the cam centre), in the order of the cam angle; the polygon
    closes from the last point back to the first."""
    factor = LENGTH_FACTORS[length_unit]
    handle.write(f"angle_deg,x_{length_unit},y_{length_unit}\n")
    for angle, (x, y) in zip(np.degrees(made.theta).tolist(),
                             (made.points / factor).tolist()):
        handle.write(f"{cell(angle)},{cell(x)},{cell(y)}\n")


def require_ezdxf():
    """ezdxf, or ``MissingExtra`` naming the extra that installs it (exit 2)."""
    try:
        import ezdxf
    except ImportError:
        from dyade.errors import MissingExtra

        raise MissingExtra('a DXF drawing needs ezdxf: pip install "dyade[cad]" (or write '
                           'the points as CSV with --points).', key="ezdxf") from None
    return ezdxf


def write_dxf(result, path: str | os.PathLike, length_unit: str) -> None:
    """The curves to manufacture as closed polylines (layer CAM-WORKING, a groove's
    CAM-OUTER, CAM-CUTTER) of
    a DXF drawing in ``length_unit`` ($INSUNITS set), the cam centre at the origin.

    Raises
    ------
    MissingExtra
        ezdxf is not installed: ``pip install "dyade[cad]"``.
    """
    ezdxf = require_ezdxf()
    factor = LENGTH_FACTORS[length_unit]
    document = ezdxf.new("R2010")
    document.header["$INSUNITS"] = DXF_UNITS[length_unit]
    space = document.modelspace()
    for made in result.manufacture:
        layer = LAYERS[made.name]
        document.layers.add(layer)
        space.add_lwpolyline((made.points / factor).tolist(), format="xy", close=True,
                             dxfattribs={"layer": layer})
    space.add_circle((0.0, 0.0), result.cam.base_radius / factor,
                     dxfattribs={"layer": "CAM-BASE-CIRCLE"})
    document.saveas(os.fspath(path))
