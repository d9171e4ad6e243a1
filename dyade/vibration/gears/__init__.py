"""Gear drives by rigid finite elements (Berczyński, Maćkowiak and Marchelek 1978).

A multistage gear drive as rigid bodies with six coordinates each (or one rotation each
in the torsional model), joined by spring-damper elements (shafts split by the RFE
method, bearings, explicit elements), with every gear mesh an ideal constraint on its
plane of action (or an elastic one). The drive as its file describes it (SI, validated;
no numpy) is ``dyade.model.gears``; the modules here compute on it:

- ``assembly``: M, K, L and the mesh constraint matrix g
- ``modes``: null-space reduction, natural frequencies, M-orthonormal modes, energy
  shares, modal mesh forces, rigid-body modes
- ``elimination``: the paper's own elimination of the multipliers (for ``--check``)
- ``campbell``: excitation orders and resonance speeds
- ``response``: forced response to harmonic torques and transmission errors; statics
"""
