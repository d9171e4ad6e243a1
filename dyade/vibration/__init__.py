"""Vibration of drive elements.

- ``coupling``: the torsional resonance of a stiff coupling (Strümpfel), as phasors
- ``gears``: multistage gear drives as rigid finite elements (Berczyński, Maćkowiak and
  Marchelek): natural frequencies and modes, Campbell diagram, forced response, statics
"""
