"""Meshes with gmsh: body surfaces and fluid domains at three levels of one refinement ratio.

* :mod:`~floatfoam.meshing.levels`: mesh levels (coarse, medium, fine) and their sizes; the tank
  (the case's ``[domain]`` table) and the body's poses (body frame, equilibrium, release) are
  :mod:`floatfoam.tank`'s, below every stage;
* :mod:`~floatfoam.meshing.sections`: a 2D section or a meridian as exact OpenCASCADE curves;
* :mod:`~floatfoam.meshing.body_surface`: the discrete body (STL triangles, section polygon);
* :mod:`~floatfoam.meshing.planar`: 2D (one cell thick) and axisymmetric wedge domains;
* :mod:`~floatfoam.meshing.domain3d`: 3D domains;
* :mod:`~floatfoam.meshing.domains`: one entry point for the domains (kind, file, body patch);
* :mod:`~floatfoam.meshing.volume_report`: the immersed volume the discrete body really has;
* :mod:`~floatfoam.foam.meshcheck`: gmshToFoam + checkMesh on a written mesh;
* :mod:`~floatfoam.meshing.table`: the mesh-levels table (Markdown);
* :mod:`floatfoam.gmshio` (below meshing and the potential flow, which share it): the gmsh
  session, mesh arrays, MSH 2.2 and STL output.

The command line is ``floatfoam mesh body|domain|table`` (:mod:`floatfoam.cli.mesh`), or
the scripts in meshes/.
"""
