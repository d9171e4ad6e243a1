"""The data that files describe, SI and checked: what the readers (``dyade.files``) build
and the engine (``dyade.linkage``, ``dyade.machine``, ``dyade.vibration``) computes on.

- ``mechanism``: the linkage (``Mechanism``: crank, dyads, links, joints, loads, springs,
  the crank-angle sweep)
- ``dyad_kinds``: the five dyad kinds as data (number, joint pattern, variants, frames)
- ``drive``: motor characteristics and the ``[drive]`` table
- ``drive_line``: the ``[drive_line]`` table (the elastic element between motor and crank)
- ``coupling``: the stiff coupling of Strümpfel
- ``gears``: a gear drive of rigid bodies, shafts, bearings, gears and meshes

Nothing here reads a file or solves anything: a module of this package imports only
``dyade.units``, ``dyade.errors``, ``dyade.arrays`` and its own package
(``tests/test_layers.py``).
"""
