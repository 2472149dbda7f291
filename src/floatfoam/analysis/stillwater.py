"""The currents of a run whose body is held still (``run.static_body``): what the numerics drive
by themselves.

With the body held and the water at rest, any motion is an error of the scheme. interFoam's
gravity term ``-ghf·snGrad(rho)`` balances the pressure exactly only where the free surface
lies in horizontal rows of cells (docs/openfoam-v1912.md, "the part no setting of v1912's
removes"); around a body-fitted mesh it does not, and the water at the waterline starts to
move. Held at the release position, the speeds here set the size of that error beside the
body's own speeds (cylinder_heave, coarse: 0.06 m/s in the interface cells after 1 s against a
peak heave speed of ~0.33 m/s; with ``run.interface_gravity``, 0.8 mm/s).

For each written time: the largest speed in the interface cells (0.01 < alpha < 0.99), in the
water (alpha ≥ 0.5), in the water below the free-surface band (z < −band, where the mesh's
fine band ends) and in the air (alpha ≤ 0.01).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from floatfoam.analysis.flowview import WATER, decomposed, offscreen_pyvista
from floatfoam.errors import InputError
from floatfoam.jsonfile import dump_json

FILE = "still_water.json"  # in the run directory


@dataclass(frozen=True)
class Currents:
    """Largest speeds (m/s) at one written time of a held-still run."""

    time: float
    interface: float
    water: float
    below_band: float
    air: float


def currents(run_dir: Path, band: float) -> list[Currents]:
    """The largest speeds at every written time after 0 of the run in ``run_dir`` (decomposed
    or not); ``band`` is the half-height (m) of the mesh's free-surface band."""
    run = Path(run_dir)
    controls = run / "system" / "controlDict"
    if not controls.is_file():
        raise InputError(f"run directory {run}: no OpenFOAM case; valid is a run directory "
                         "written by floatfoam run")
    reader = offscreen_pyvista().POpenFOAMReader(str(controls))
    if decomposed(run):
        reader.case_type = "decomposed"
    reader.disable_all_patch_arrays()
    reader.enable_patch_array("internalMesh")
    reader.cell_to_point_creation = False
    out = []
    for time in (t for t in reader.time_values if t > 0.0):
        reader.set_active_time_value(time)
        mesh = reader.read()["internalMesh"]
        alpha = np.asarray(mesh.cell_data[WATER])
        speed = np.linalg.norm(np.asarray(mesh.cell_data["U"]), axis=1)
        z = np.asarray(mesh.cell_centers().points)[:, 2]
        water = alpha >= 0.5

        def largest(where, speed=speed):
            return float(speed[where].max(initial=0.0))

        out.append(Currents(float(time), largest((alpha > 0.01) & (alpha < 0.99)),
                            largest(water), largest(water & (z < -band)),
                            largest(alpha <= 0.01)))
    return out


def write(rows: list[Currents], band: float, path: Path) -> None:
    """``rows`` and ``band`` as JSON (FILE in the run directory)."""
    path.write_text(dump_json({"band": band, "rows": [asdict(r) for r in rows]}) + "\n")


def summary(rows: list[Currents], band: float) -> str:
    """One sentence on the last written time's currents."""
    if not rows:
        return "no written time after 0: no currents to report"
    last = rows[-1]
    return (f"held still for {last.time:g} s: the water moves at up to {last.interface:.3g} m/s "
            f"in the interface cells, {last.water:.3g} m/s in the water, {last.below_band:.3g} "
            f"m/s below the free-surface band (z < −{band:.3g} m); the air at {last.air:.3g} "
            "m/s — the scheme's own currents (docs/openfoam-v1912.md)")
