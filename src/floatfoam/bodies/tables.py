"""A body from its ``[body]`` table: the shapes a case may name with their keys
(:data:`SHAPES`, :data:`OPTIONAL_BODY`), and the body built from the table, each value checked
with a one-line InputError naming its key (:func:`make_body`)."""

from __future__ import annotations

import math
from pathlib import Path

from floatfoam.bodies import shapes
from floatfoam.errors import InputError, is_number, number, table_number, table_vector

SHAPES = {
    "circular_cylinder": ("radius", "length"),
    "elliptic_cylinder": ("half_beam", "half_height", "length"),
    "parabolic_cylinder": ("half_beam", "height", "length"),
    "conic_cylinder": ("n", "m", "height", "length"),
    "box": ("beam", "height", "length"),
    "sphere": ("radius",),
    "ellipsoid": ("semi_axes",),
    "vertical_cylinder": ("radius", "height"),
    "implicit": ("expression", "bounds"),
    "stl": ("path",),
}


OPTIONAL_BODY = {"box": ("bilge_radius",), "implicit": ("resolution",), "stl": ("scale",),
                 "conic_cylinder": ()}


IMPLICIT_BYTES_PER_POINT = 32  # marching cubes input: F and the x, y, z grids, float64


MAX_RESOLUTION = 400  # 400³ points take ~2 GiB


def make_body(cfg: dict, folder: Path) -> shapes.Body:
    """Build the body of the [body] table."""
    shape = cfg["body"].get("shape")
    if shape not in SHAPES:
        raise InputError(f"body.shape = {shape!r}: valid shapes are {', '.join(SHAPES)}")
    allowed = {"shape", *SHAPES[shape], *OPTIONAL_BODY.get(shape, ())}
    for key in cfg["body"]:
        if key not in allowed:
            raise InputError(f"body.{key} does not apply to shape {shape!r}; valid keys are "
                             f"{', '.join(sorted(allowed))}")

    def num(key, positive=True):
        return table_number(cfg, "body", key, positive=positive)

    if shape == "circular_cylinder":
        return shapes.EllipticCylinder(num("radius"), num("radius"), num("length"))
    if shape == "elliptic_cylinder":
        return shapes.EllipticCylinder(num("half_beam"), num("half_height"), num("length"))
    if shape == "parabolic_cylinder":
        half_beam, height = num("half_beam"), num("height")
        return shapes.ConicCylinder(half_beam**2 / height, 0.0, height, num("length"))
    if shape == "conic_cylinder":
        return _conic(num("n"), num("m", positive=False), num("height"), num("length"))
    if shape == "box":
        beam, height = num("beam"), num("height")
        radius = number(cfg["body"].get("bilge_radius", 0.0), "body.bilge_radius")
        if not 0.0 <= radius <= min(beam / 2, height):
            raise InputError(f"body.bilge_radius = {radius!r}: valid is 0 ≤ r ≤ "
                             f"min(beam/2, height) = {min(beam / 2, height):g}")
        return shapes.Box(beam, height, num("length"), radius)
    if shape == "sphere":
        r = num("radius")
        return shapes.Ellipsoid([r, r, r])
    if shape == "ellipsoid":
        return shapes.Ellipsoid(table_vector(cfg, "body", "semi_axes", positive=True))
    if shape == "vertical_cylinder":
        return shapes.VerticalCylinder(num("radius"), num("height"))
    from floatfoam.bodies import surfaces

    if shape == "implicit":
        resolution = _resolution(cfg["body"].get("resolution", 96))
        expression = cfg["body"].get("expression")
        if not isinstance(expression, str):
            raise InputError(f"body.expression = {expression!r}: valid is a string F(x, y, z), "
                             "negative inside the body")
        return surfaces.implicit_body(expression, _bounds(cfg["body"].get("bounds")),
                                      resolution)
    scale = number(cfg["body"].get("scale", 1.0), "body.scale", minimum=0.0)
    path = cfg["body"].get("path")
    if not isinstance(path, str):
        raise InputError(f"body.path = {path!r}: valid is the path of an STL file (a string)")
    return surfaces.stl_body(folder / path, scale)


def _resolution(value) -> int:
    """body.resolution: points per axis of the implicit surface's grid, within memory."""
    if is_number(value) and value > MAX_RESOLUTION:
        need = IMPLICIT_BYTES_PER_POINT * float(value) ** 3 / 2**30
        raise InputError(f"body.resolution = {value!r}: valid is a whole number from 8 to "
                         f"{MAX_RESOLUTION} ({MAX_RESOLUTION}³ points take ~2 GiB; {value!r} "
                         f"would need ~{need:.3g} GiB)")
    resolution = number(value, "body.resolution", minimum=7, integer=True)
    return resolution


def _bounds(value) -> list:
    """body.bounds: [[x0, y0, z0], [x1, y1, z1]], numbers."""
    ok = isinstance(value, list) and len(value) == 2 and all(
        isinstance(row, list) and len(row) == 3 and all(is_number(v) for v in row)
        for row in value)
    if not ok:
        raise InputError(f"body.bounds = {value!r}: valid is [[x0, y0, z0], [x1, y1, z1]], "
                         "numbers in m")
    return value


def _conic(n: float, m: float, height: float, length: float) -> shapes.Body:
    if m < 0:
        full = -n / m
        if height > full * (1 + 1e-12):
            raise InputError(f"body.height = {height:g}: valid for this ellipse (m < 0) is "
                             f"0 < height ≤ −n/m = {full:g}")
        if height >= full * (1 - 1e-12):  # the whole ellipse
            return shapes.EllipticCylinder(n / (2 * math.sqrt(-m)), full / 2, length)
    return shapes.ConicCylinder(n, m, height, length)
