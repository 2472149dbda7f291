"""Hydrostatics and the linear theory of Le Barbier (1817), without the fluid's resistance.

* :mod:`~floatfoam.hydrostatics.immersion`: immersed volume, centre of buoyancy and waterplane
  of any body at any attitude (closed form where known, else numeric);
* :mod:`~floatfoam.hydrostatics.closed_forms`: the exact hydrostatics of the memoir's bodies;
* :mod:`~floatfoam.hydrostatics.theory`: equilibrium, stiffness, GM, verdicts, linear periods;
* :mod:`~floatfoam.hydrostatics.fluid_domain`: the body in its fluid: water under the keel at
  equilibrium, the release inside the case's tank (the checks every command goes through);
* :mod:`~floatfoam.hydrostatics.gz`: the righting-arm curve to large angles;
* :mod:`~floatfoam.hydrostatics.memoir`: the memoir's method, body by body (the corrected
  formulas); :mod:`~floatfoam.hydrostatics.printed` and
  :mod:`~floatfoam.hydrostatics.printed_ellipsoid`: its formulas as printed, errata included;
  :mod:`~floatfoam.hydrostatics.memoir_case` evaluates both for a case.
"""
