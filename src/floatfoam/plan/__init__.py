"""A run's plan, resolved from the case before anything is meshed or written, and what the
analysis needs to know of a run without running it (below :mod:`floatfoam.meshing`,
:mod:`floatfoam.foam` and :mod:`floatfoam.analysis`):

* :mod:`~floatfoam.plan.runplan`: the :class:`~floatfoam.plan.runplan.RunPlan` resolved once;
* :mod:`~floatfoam.plan.level` the mesh level, :mod:`~floatfoam.plan.kind` the kind of
  domain, :mod:`~floatfoam.plan.release` the release, the mesh's pose and the end time;
* :mod:`~floatfoam.plan.zone` how the mesh follows the body, :mod:`~floatfoam.plan.morphing`
  that motion spread for a study;
* :mod:`~floatfoam.plan.stamps` what a run is of (its solver, settings digest and stamp),
  :mod:`~floatfoam.plan.record` what it recorded when rendered (its info.json).
"""
