"""The DYADE engine: planar linkages as a crank and dyads in assembly order, swept
over the crank angle.

A sweep runs through one pipeline (``pipeline``): its plan (``plan``: the stages the
data calls for), blocks of positions (``blocks``) through the stages (``kinematics``,
``kinetostatics``, ``friction``, ``self_locking``; ``drive`` first where a motor sets
the crank's speed), each block's columns (``columns``), and what the sweep keeps of
them (``validity``, ``verdicts``, ``notes``, ``summary``). ``sweep`` is its door:
``analyse`` and ``analyse_in_blocks``."""
