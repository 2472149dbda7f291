"""Bodies: the shapes a case describes, in their own frame (docs/conventions.md).

* :mod:`~floatfoam.bodies.shapes`: the memoir's primitives (elliptic and conic cylinders, box
  with bilge radius, ellipsoid) and any closed triangle mesh;
* :mod:`~floatfoam.bodies.surfaces`: bodies a user brings, an implicit surface F = 0 or an STL;
* :mod:`~floatfoam.bodies.geometry`: rotations and triangle-mesh helpers shared by every stage.
"""
