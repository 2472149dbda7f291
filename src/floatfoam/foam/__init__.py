"""OpenFOAM: render a run directory from a case, run its applications, read their output.

* :mod:`~floatfoam.foam.render`: the run directory (shared dictionaries + case values, foamlib);
  :mod:`~floatfoam.foam.ogrid` the blockMesh O-grid of a circular section;
* :mod:`~floatfoam.foam.dictionaries`: the one writer of OpenFOAM dictionaries;
* :mod:`~floatfoam.foam.runner`: the one runner of OpenFOAM applications (logs, MPI, progress,
  divergence, motion.csv as the solver goes); :mod:`~floatfoam.foam.logwatch` reads its log;
* :mod:`~floatfoam.foam.driver`: ``floatfoam run``, render → mesh → initialise → solve,
  resumable, from a run's plan (:mod:`floatfoam.plan`); :mod:`~floatfoam.foam.ranks` its MPI
  ranks (the --np default);
* :mod:`~floatfoam.foam.paraview`: the run as ParaView opens it (``<case>.foam``,
  reconstructPar, foamToVTK);
* :mod:`~floatfoam.foam.meshcheck`: gmshToFoam + checkMesh on a gmsh mesh;
* :mod:`~floatfoam.foam.postproc`: function-object output of a run.
"""
