"""How much the mesh alone moves the body: the immersed volume of the discrete body at the
theory's equilibrium against the exact one.

The discrete body of a level (:mod:`floatfoam.meshing.body_surface`) is inscribed in the exact
surface, so it displaces a little less at the same attitude. Floating freely it therefore sits
lower, by the equilibrium shift Δz_c solving V_h(z_c + Δz_c) = V (≈ (V_h − V)/A_wp to first
order), which this module also solves for. Compare it with the release offset of a decay test.

Which discrete body:

* 2D section: the polygon of the section (the body patch of the 2D domain is this polygon);
* body of revolution about z: also the meridian polyline revolved (the wedge's body patch);
* any other body: the triangles of its surface (the STL; for ``stl``/``implicit`` bodies, the
  case's own triangles, which the theory uses too: the error is zero by construction).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from floatfoam.bodies.geometry import mesh_volume
from floatfoam.hydrostatics.immersion import mesh_immersed, section_immersed
from floatfoam.meshing import body_surface
from floatfoam.meshing.levels import mesh_spec


def discrete_volume_report(case, level: str, equilibrium=None) -> dict:
    """Immersed volume of the discrete body of ``level`` at the theory's equilibrium, against
    the exact (theory) value, with the equilibrium shift it implies.

    Returns
    -------
    dict with ``case``, ``level``, ``discrete`` (what was measured: "section polygon",
    "surface triangles" or "case triangles"), ``cell_size`` (m), ``elements`` (polygon edges or
    triangles), ``volume_exact``/``volume_discrete`` (whole body, m³), ``volume_error``
    (relative), ``immersed_exact``/``immersed_discrete`` (m³), ``immersed_error`` (relative),
    ``equilibrium_shift`` (m, the discrete body's z_c minus the exact one), ``release_heave``
    (m, for scale) and, for a body of revolution, ``meridian`` (the same for the wedge).
    """
    from floatfoam.hydrostatics.theory import equilibrium as solve

    eq = equilibrium or solve(case)
    spec = mesh_spec(case, level)
    body = case.body
    if body.is_section:
        polygon = body_surface.section_polygon(body, spec)
        kind, elements = "section polygon", len(polygon)

        def immersed(z_c):
            return section_immersed(polygon, body.length, z_c, eq.heel).volume

        total = _shoelace(polygon) * body.length
    else:
        vertices, faces = body_surface.body_triangles(body, spec)
        kind = "case triangles" if body.given_by_triangles else "surface triangles"
        elements = len(faces)

        def immersed(z_c):
            return mesh_immersed(vertices, faces, z_c, eq.heel, eq.trim).volume

        total = mesh_volume(vertices, faces)
    report = {
        "case": case.name, "level": level, "discrete": kind, "cell_size": spec.body_size,
        "elements": elements,
        **_compare(body.volume(), total, eq.immersed.volume, immersed, eq.z_c, spec.span),
        "release_heave": case.release["heave"],
    }
    if eq.heel == 0.0 and eq.trim == 0.0 and case.settings.mesh.gmsh.wedge \
            and body.is_axisymmetric:
        report["meridian"] = _meridian(body, spec, eq)
    return report


def _meridian(body, spec, eq) -> dict:
    """The body of revolution of the meridian polyline: V = 2π ∫ r dA (Pappus–Guldinus) over
    the meridian region closed by the axis, clipped at the free surface for the immersed part."""
    polyline = body_surface.meridian_polyline(body, spec)  # keel → top, then back down the axis

    def revolved(z_c):
        imm = section_immersed(polyline, 1.0, z_c, 0.0)
        return 2.0 * math.pi * imm.volume * imm.centroid[1]

    total = revolved(-10.0 * spec.span)  # fully submerged
    return {"elements": len(polyline) - 1,
            **_compare(body.volume(), total, eq.immersed.volume, revolved, eq.z_c, spec.span)}


def _compare(exact_total, total, exact_immersed, immersed, z_c, span) -> dict:
    at_equilibrium = immersed(z_c)
    shift = brentq(lambda z: immersed(z) - exact_immersed, z_c - span, z_c + span,
                   xtol=1e-12 * span)
    return {
        "volume_exact": exact_total, "volume_discrete": total,
        "volume_error": (total - exact_total) / exact_total,
        "immersed_exact": exact_immersed, "immersed_discrete": at_equilibrium,
        "immersed_error": (at_equilibrium - exact_immersed) / exact_immersed,
        "equilibrium_shift": shift - z_c,
    }


def _shoelace(polygon: np.ndarray) -> float:
    y, z = polygon[:, 0], polygon[:, 1]
    return 0.5 * float(np.sum(y * np.roll(z, -1) - np.roll(y, -1) * z))


def format_report(report: dict) -> str:
    """Readable lines of a :func:`discrete_volume_report`."""
    lines = [f"{report['case']} {report['level']}: {report['discrete']}, "
             f"{report['elements']} elements, cell size {report['cell_size'] * 1e3:.3g} mm"]
    rows = [("", report)] + ([("wedge meridian: ", report["meridian"])]
                              if "meridian" in report else [])
    for label, r in rows:
        lines.append(
            f"  {label}volume {r['volume_discrete']:.6g} m³ (exact {r['volume_exact']:.6g}, "
            f"{r['volume_error']:+.2e}); immersed at equilibrium {r['immersed_discrete']:.6g} "
            f"m³ (exact {r['immersed_exact']:.6g}, {r['immersed_error']:+.2e}); equilibrium "
            f"shift {r['equilibrium_shift'] * 1e3:+.3g} mm")
    if report["release_heave"]:
        lines.append(f"  (release heave {report['release_heave'] * 1e3:g} mm)")
    return "\n".join(lines)
