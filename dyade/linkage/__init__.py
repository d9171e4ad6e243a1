"""The DYADE engine: planar linkages as a crank and dyads in assembly order, swept
over the crank angle."""
