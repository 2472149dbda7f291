"""The patches of every floatfoam run, named once: their OpenFOAM types and boundary conditions.

Both meshers (the gmsh domains of :mod:`floatfoam.meshing` and the blockMesh O-grid of
:mod:`floatfoam.foam.ogrid`) name their boundaries from :data:`PATCH_TYPES`:

    body          the floating body (moving wall)
    bottom, sides the tank's bottom and its ends (walls; a wedge's outer cylinder is ``sides``)
    atmosphere    the top of the air (open)
    frontAndBack  the two faces of a 2D mesh one cell thick (empty)
    wedge0/1      the two faces of an axisymmetric wedge (wedge)
    symmetry      a symmetry plane of a half 3D domain
"""

from __future__ import annotations

from foamlib import FoamFile

PATCH_TYPES = {
    "body": "wall",
    "bottom": "wall",
    "sides": "wall",
    "atmosphere": "patch",
    "frontAndBack": "empty",
    "wedge0": "wedge",
    "wedge1": "wedge",
    "symmetry": "symmetryPlane",
}

_ZERO = [0.0, 0.0, 0.0]
_WALL = {"U": {"type": "noSlip"}, "p_rgh": {"type": "fixedFluxPressure", "value": 0.0},
         "alpha.water": {"type": "zeroGradient"},
         "pointDisplacement": {"type": "fixedValue", "value": _ZERO}}
_BY_PATCH = {
    "body": {"U": {"type": "bodyVelocity", "value": _ZERO},
             "p_rgh": {"type": "fixedFluxPressure", "value": 0.0},
             "alpha.water": {"type": "zeroGradient"},
             "pointDisplacement": {"type": "calculated", "value": _ZERO}},
    "bottom": _WALL,
    "sides": _WALL,
    "atmosphere": {"U": {"type": "pressureInletOutletVelocity", "value": _ZERO},
                   "p_rgh": {"type": "totalPressure", "p0": 0.0},
                   "alpha.water": {"type": "inletOutlet", "inletValue": 0.0, "value": 0.0},
                   "pointDisplacement": {"type": "fixedValue", "value": _ZERO}},
}
FIELDS = ("U", "p_rgh", "alpha.water", "pointDisplacement")
_FIELD_SPEC = {  # class, dimensions (mass, length, time), internal value
    "U": ("volVectorField", (0, 1, -1), _ZERO),
    "p_rgh": ("volScalarField", (1, -1, -2), 0.0),
    "alpha.water": ("volScalarField", (0, 0, 0), 0.0),
    "pointDisplacement": ("pointVectorField", (0, 1, 0), _ZERO),
}


#: the body's velocity on an interFoam without floatfoam's bodyVelocity (``run.solver``):
#: v1912's, the wall's velocity over the step
STOCK_BODY_VELOCITY = {"type": "movingWallVelocity", "value": _ZERO}


def boundary_conditions(field: str, patches, body_velocity: bool = True) -> dict:
    """The boundary conditions of ``field`` on ``patches`` (names of :data:`PATCH_TYPES`):
    walls, body and atmosphere by role; empty, wedge and symmetry planes by their type. The
    body's velocity is floatfoam's ``bodyVelocity`` (the rigid body's at the step's end,
    src/solver/), or with ``body_velocity`` False :data:`STOCK_BODY_VELOCITY`."""
    out = {}
    for name in patches:
        if name in _BY_PATCH:
            out[name] = _BY_PATCH[name][field]
        else:
            out[name] = {"type": PATCH_TYPES[name]}
    if field == "U" and "body" in out and not body_velocity:
        out["body"] = STOCK_BODY_VELOCITY
    return out


def write_initial_fields(folder, patches, body_velocity: bool = True) -> None:
    """Initial fields in ``folder`` (``0.orig``): water and air at rest, the body unmoved; the
    free surface is set afterwards by setAlphaField. ``body_velocity``: as
    :func:`boundary_conditions`."""
    from floatfoam.foam.dictionaries import write_field

    for name in FIELDS:
        cls, (mass, length, time), internal = _FIELD_SPEC[name]
        dims = FoamFile.DimensionSet(mass=mass, length=length, time=time)
        write_field(folder / name, cls, dims, internal,
                    boundary_conditions(name, patches, body_velocity))
