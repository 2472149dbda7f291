"""Case files and triangle meshes the tests write for bodies the project has no case
folder for."""

import math

import numpy as np

from floatfoam.bodies.geometry import mesh_volume

#: the `sphere` case's body (radius 0.1 m, half immersed, G 20 mm below its centre, released
#: 10 mm) written as a user's implicit surface: triangles that are a body of revolution
IMPLICIT_SPHERE = """[body]
shape = "implicit"
expression = "x**2 + y**2 + z**2 - 0.01"
bounds = [[-0.11, -0.11, -0.11], [0.11, 0.11, 0.11]]
resolution = 60
[mass]
density = 500.0
cog = [0.0, 0.0, -0.02]
gyradius = [0.06325, 0.06325, 0.06325]
[release]
heave = 0.01
"""


def torus(big: float, small: float, n: int = 48, m: int = 24):
    """A ring of tube radius ``small`` about a circle of radius ``big`` in z = 0, ``n`` × ``m``
    quadrilaterals halved: vertices, faces, outward."""
    u = np.linspace(0, 2 * math.pi, n, endpoint=False)
    v = np.linspace(0, 2 * math.pi, m, endpoint=False)
    vertices = np.array([[(big + small * math.cos(b)) * math.cos(a),
                          (big + small * math.cos(b)) * math.sin(a), small * math.sin(b)]
                         for a in u for b in v])
    faces = []
    for i in range(n):
        for j in range(m):
            p, q = i * m + j, ((i + 1) % n) * m + j
            pj, qj = i * m + (j + 1) % m, ((i + 1) % n) * m + (j + 1) % m
            faces += [(p, q, qj), (p, qj, pj)]
    faces = np.array(faces)
    return (vertices, faces) if mesh_volume(vertices, faces) > 0 else (vertices, faces[:, ::-1])
