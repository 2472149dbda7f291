"""Case files the tests write for bodies the project has no case folder for."""

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
