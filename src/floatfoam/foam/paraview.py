"""A run that ParaView opens: the ``<case>.foam`` file, the reconstructed fields, a VTK export.

ParaView's OpenFOAM reader, and pyvista's ``POpenFOAMReader``, open a case by an empty file
named ``*.foam`` in its folder (:func:`write_foam_file`, written before the solver starts, so
that an unfinished run opens too). Both read the reconstructed case by default: the time
folders in the run folder itself. A parallel run writes its fields into ``processor*/``, so
the driver gathers them with ``reconstructPar`` once the solver has finished
(:func:`reconstruct`): every written time, the moving mesh's ``polyMesh/points`` of each time
with them (v1912's reconstructPar reconstructs the points of every time whose processor meshes
moved). The processor folders stay: a run resumes from them.

``foamToVTK`` writes the reconstructed case's fields, on the mesh of each time, into
``<run>/VTK`` (:func:`export_vtk`, ``floatfoam export RUN --vtk``) for viewers without
OpenFOAM's reader.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from floatfoam import layout
from floatfoam.errors import InputError
from floatfoam.foam import runner
from floatfoam.plan.record import has_record

RECONSTRUCT = "reconstructPar"  # the driver's step (its marker), and the application
VTK_DIR = "VTK"  # where foamToVTK writes, in the run folder


def foam_file(run_dir: Path, case_name: str) -> Path:
    """The ``<case>.foam`` file of a run folder (ParaView's name for the case)."""
    return Path(run_dir) / f"{case_name}.foam"


def write_foam_file(run_dir: Path, case_name: str) -> Path:
    """Write the empty ``<case>.foam`` file ParaView opens the run by, unless it is there (the
    reader never reads it: its name and folder say which case to open)."""
    path = foam_file(run_dir, case_name)
    if not path.exists():
        path.write_bytes(b"")
    return path


def decomposed(run_dir: Path) -> bool:
    """Whether the run's fields are written into ``processor*`` folders (a parallel run)."""
    return any(Path(run_dir).glob("processor[0-9]*"))


def reconstruct(run_dir: Path) -> Path | None:
    """Gather a parallel run's written times into the run folder (``reconstructPar``, serial;
    its log ``log.reconstructPar``), once: a marker step of the run, skipped when done, redone
    in full when it was cut short. Returns the log, or None for a serial run (nothing to
    gather)."""
    if not decomposed(run_dir):
        return None
    return runner.run_app(Path(run_dir), RECONSTRUCT, [RECONSTRUCT])


def check_export(run_dir: Path, *, force: bool = False) -> Path:
    """Refuse (InputError, one line; nothing written) a folder that is no finished run of
    ``floatfoam run``, or whose ``VTK`` folder exists without ``force``. Returns the folder
    the export writes."""
    run = Path(run_dir)
    if not (run / "system" / "controlDict").is_file() or not has_record(run):
        raise InputError(f"RUN {run}: no run of floatfoam run (no system/controlDict and "
                         f"{layout.MARKERS}/info.json); valid is a run folder, "
                         "<build>/<case>/<level>")
    if not layout.is_finished(run):
        raise InputError(f"RUN {run}: the run is not finished; valid is a finished run "
                         "(the same `floatfoam run` command resumes it; ParaView opens an "
                         "unfinished one by its .foam file)")
    out = run / VTK_DIR
    if out.exists() and not force:
        raise InputError(f"RUN {run}: {out} exists and is never overwritten; valid is "
                         "--force to replace it, or moving it away first")
    return out


def export_vtk(run_dir: Path, *, force: bool = False) -> Path:
    """The run's fields at every written time as VTK files in ``<run>/VTK`` (``foamToVTK``,
    its log ``log.foamToVTK``); a parallel run finished before runs were reconstructed is
    reconstructed first, and gets its ``.foam`` file. With ``force`` an existing ``VTK``
    folder is deleted first; without it, refused (:func:`check_export`). Holds the run's
    lock (:mod:`floatfoam.foam.runlock`): no run writes the folder meanwhile."""
    from floatfoam.foam.runlock import RunLock, lock_path

    run = Path(run_dir).resolve()
    out = check_export(run, force=force)
    label = f"{run.parent.name}/{run.name}"
    with RunLock(lock_path(run.parent.name, run.name, run.parent.parent), label):
        write_foam_file(run, run.parent.name)
        reconstruct(run)
        if out.exists():
            shutil.rmtree(out)
        runner.run_app(run, "foamToVTK", ["foamToVTK"], marker=False)
    return out
