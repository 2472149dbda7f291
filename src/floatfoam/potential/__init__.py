"""Beyond the memoir without CFD: potential flow and time-domain decay models.

* :mod:`~floatfoam.potential.radiation`: added mass and radiation damping (Capytaine in 3D,
  :mod:`~floatfoam.potential.sections` for 2D sections), natural periods with added mass;
* :mod:`~floatfoam.potential.bem_mesh`: the wetted-surface panel mesh of a 3D body;
* :mod:`~floatfoam.potential.resonance`: mass matrix, natural frequency, damping ratio;
* :mod:`~floatfoam.potential.timedomain`: linear and Cummins (1962) free-decay models;
* :mod:`~floatfoam.potential.rigid_body`: the nonlinear model (exact hydrostatics, Euler's
  equations, no fluid inertia);
* :mod:`~floatfoam.potential.models`: one entry point for the three decay models;
* :mod:`~floatfoam.potential.plot`: A(ω), B(ω) figures.
"""
