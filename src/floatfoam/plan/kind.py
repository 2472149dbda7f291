"""The kind of fluid domain a run's body is meshed in, from the body, its pose and the case:
``2d`` (a 2D section, one cell thick), ``wedge`` (a body of revolution about z, upright, in
heave: a shape of revolution, or triangles found to be one, unless ``mesh.gmsh.wedge`` is
false), ``3d-half`` (x ≥ 0 and a symmetry plane x = 0 for a heel or a heave, y ≥ 0 and y = 0
for a trim: a body symmetric about that plane and a motion that keeps it), ``3d`` otherwise
(:func:`default_kind`, :func:`half_plane`); and what each kind admits (prism layers, the DoFs
the body can move in)."""

from __future__ import annotations

from floatfoam.errors import InputError
from floatfoam.tank import Pose


def kind_of(case, where: Pose) -> str:
    """The domain a run meshes: "ogrid" (``mesh.mesher``), else :func:`default_kind`."""
    return "ogrid" if case.settings.mesh.mesher == "ogrid" else default_kind(case, where)


def default_kind(case, where: Pose) -> str:
    """The lightest domain that represents the case at this pose."""
    if case.body.is_section and where.trim == 0.0:
        return "2d"
    if where.heel == 0.0 and where.trim == 0.0 and _frees_only(case, ("heave",)) \
            and case.settings.mesh.gmsh.wedge and case.body.is_axisymmetric:
        return "wedge"
    return "3d-half" if half_plane(case, where) else "3d"


def _frees_only(case, names) -> bool:
    """``[motion] free`` (when given) names none but ``names``."""
    return all(name in names for name in case.settings.motion.free or ())


def half_plane(case, where: Pose) -> str | None:
    """The symmetry plane the body and its motion keep, "x" (x = 0: no trim, no DoF freed
    out of the (y, z) plane) or "y" (y = 0: no heel, none out of the (x, z) plane), for a
    body symmetric about it (an ellipsoid, a sphere or a vertical cylinder about both; a body
    given by triangles, STL or implicit, where :func:`floatfoam.bodies.mirror.mirror_planes`
    finds it) with G on it; None otherwise, or when ``mesh.gmsh.half_3d`` is false."""
    if not case.settings.mesh.gmsh.half_3d:
        return None
    planes = case.body.mirror_planes
    if "x" in planes and where.trim == 0.0 and case.cog[0] == 0.0 \
            and _frees_only(case, ("heave", "roll", "sway")):
        return "x"
    if "y" in planes and where.heel == 0.0 and case.cog[1] == 0.0 \
            and _frees_only(case, ("heave", "pitch", "surge")):
        return "y"
    return None


def check_layers(case, kind: str) -> None:
    """Prism layers (``mesh.gmsh.layers_3d``) are made in 3D domains only: asked for in a
    2D slab or a wedge they are refused, not silently left out (left out, a body given by
    triangles takes them in 3D alone)."""
    layers = case.settings.mesh.gmsh.layers_3d
    asked = "layers_3d" in case.raw.get("mesh", {}).get("gmsh", {})
    if layers and asked and kind not in ("3d", "3d-half"):
        other = ", or mesh.gmsh.wedge = false (a 3D tank)" if kind == "wedge" else ""
        raise InputError(f"mesh.gmsh.layers_3d = {layers}: prism layers are made in 3D domains "
                         f"only, and {case.name} meshes a {kind} domain at its release; valid "
                         f"is 0{other}")


#: the DoFs a body can move in in each domain: a 2D slab (x one cell thick) and a half domain
#: with its symmetry plane x = 0 keep the (y, z) plane, one with y = 0 the (x, z) plane, a
#: wedge its axis
MOVABLE = {"2d": ("heave", "roll", "sway"), "ogrid": ("heave", "roll", "sway"),
           "wedge": ("heave",), "3d-half x": ("heave", "roll", "sway"),
           "3d-half y": ("heave", "pitch", "surge"),
           "3d": ("heave", "roll", "pitch", "surge", "sway")}


def check_free_in(case, kind: str, plane: str | None = None) -> None:
    """An InputError naming ``motion.free`` when it frees a DoF the run's domain cannot move
    the body in (:data:`MOVABLE`), before anything is written."""
    free = case.settings.motion.free
    movable = MOVABLE[f"{kind} {plane}" if plane else kind]
    out = [name for name in free or () if name not in movable]
    if out:
        where = {"2d": "a 2D slab", "ogrid": "a 2D O-grid", "wedge": "a wedge (axisymmetric)",
                 "3d-half": f"a half domain (symmetry plane {plane} = 0)",
                 "3d": "a 3D domain"}[kind]
        raise InputError(f"motion.free = {list(free)!r}: {case.name} is meshed in {where}, "
                         f"where the body cannot move in {', '.join(out)}; valid names are "
                         f"{', '.join(movable)}")
