"""Beyond the memoir without CFD: potential flow and time-domain decay models.

* :mod:`~floatfoam.potential.radiation`: added mass and radiation damping in heave, roll,
  pitch, surge and sway (Capytaine in 3D, :mod:`~floatfoam.potential.sections` for 2D sections
  and :mod:`~floatfoam.potential.sections_depth` for them in finite depth), natural periods
  with added mass (uncoupled, and roll with sway free);
* :mod:`~floatfoam.potential.bem_mesh`: the wetted-surface panel mesh of a 3D body;
* :mod:`~floatfoam.potential.resonance`: mass matrix, natural frequency, damping ratio, the
  impedance of a rotation with its horizontal partner free (``condensed``);
* :mod:`~floatfoam.potential.timedomain`: linear and Cummins (1962) free-decay models;
* :mod:`~floatfoam.potential.rigid_body`: the nonlinear model (exact hydrostatics, Euler's
  equations, no fluid inertia);
* :mod:`~floatfoam.potential.models`: one entry point for the three decay models;
* :mod:`~floatfoam.potential.plot`: A(ω), B(ω) figures.
"""
