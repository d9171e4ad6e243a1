"""Figures of dyade's results (the optional extra ``pip install "dyade[plot]"``).

One module per figure kind, each a ``figure(...)`` that builds a matplotlib ``Figure``
with the object API (never pyplot's global state) from result objects of the API:

- ``polar``: joint-force polar diagrams with the crank angle and the reversals of the
  dominant line of action (Dresig & Thümmel);
- ``curves``: result columns against the crank angle, invalid and warned ranges shaded;
  by default the drive torque with its mean and energy surplus, and the transmission
  angles;
- ``mechanism``: the linkage drawn from its kinematics at chosen crank angles, with the
  paths of its named points; ``animate``: the same in motion, one frame per step;
- ``coupling``: the transfer functions and phases of a stiff coupling (Strümpfel);
- ``clearance``: f(τ) with the operating points, the peak force against crank speed and
  the simulated force history next to the closed form (Dresig & Thümmel);
- ``campbell``: a gear drive's natural frequencies against the input speed with the
  excitation lines and the resonance crossings ranked by modal mesh stiffness;
  ``modes``: its mode shapes per shaft line (Berczyński, Maćkowiak & Marchelek).

``canvas`` holds what they share: the style (line styles and markers that read in
grey-scale), shading of the result's notes and deterministic output (the same data
gives the same bytes). This package is the only one that imports matplotlib; importing
it does not (``require`` checks that matplotlib is there, and every figure module calls
it before it imports matplotlib: without the extra, ``from dyade.plot import curves``
raises ``MissingExtra``, an ``ImportError`` that names ``pip install "dyade[plot]"``).
The figure modules are loaded on first use: ``import dyade`` then
``dyade.plot.curves.figure(result)`` works.
"""

from __future__ import annotations

INSTALL = 'pip install "dyade[plot]"'
MINIMUM = (3, 7)  # matplotlib version the figures are written for


MODULES = ("animate", "campbell", "canvas", "clearance", "coupling", "curves", "mechanism",
           "modes", "polar", "profile")
"""the figure modules, loaded on first attribute access (``dyade.plot.curves``)"""


def require() -> None:
    """Raise ``MissingExtra`` (an ``InputError`` and ``ImportError`` naming the extra to
    install) unless matplotlib ≥ 3.7 can be imported."""
    from dyade.errors import MissingExtra

    try:
        import matplotlib
    except ImportError:
        raise MissingExtra(f"plots need matplotlib, which dyade installs only with its plot "
                           f"extra: {INSTALL}", key="matplotlib") from None
    version = tuple(int(part) for part in matplotlib.__version__.split(".")[:2]
                    if part.isdigit())
    if version < MINIMUM:
        raise MissingExtra(f"plots need matplotlib ≥ {MINIMUM[0]}.{MINIMUM[1]}, found "
                         f"{matplotlib.__version__}: {INSTALL} --upgrade")


def __getattr__(name: str):
    """Load a figure module on first use (PEP 562): ``dyade.plot.curves``."""
    if name in MODULES:
        import importlib

        return importlib.import_module(f"dyade.plot.{name}")
    raise AttributeError(f"module 'dyade.plot' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(("INSTALL", "MINIMUM", "MODULES", "require") + MODULES)
