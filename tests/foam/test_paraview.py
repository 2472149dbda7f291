"""ParaView-ready runs (floatfoam.foam.paraview, ``floatfoam export``).

The ``.foam`` file, the reconstruction's marker and the export's refusals run on a one-cell case
written by hand (test_pictures.fake_run; no OpenFOAM utility runs in the fast tests); one test
(marker ``openfoam``) runs a short parallel roll and opens it as a user would.
"""

import json

import numpy as np
import pytest
from cfdcases import shared_run
from fakes import fake_run

from floatfoam import layout
from floatfoam.cli import main
from floatfoam.foam import paraview, runner


def test_the_foam_file_opens_the_run_in_pyvista(tmp_path):
    """Empty, named after the case, written once; pyvista's reader with its defaults opens the
    run by it and sees every written time."""
    import pyvista

    run = fake_run(tmp_path)
    path = paraview.write_foam_file(run, "sphere")
    assert path == run / "sphere.foam" and path.read_bytes() == b""
    path.write_text("kept")  # a second call (a resumed run) leaves the file as it is
    assert paraview.write_foam_file(run, "sphere").read_text() == "kept"
    reader = pyvista.POpenFOAMReader(str(path))
    assert reader.case_type == "reconstructed"
    assert reader.time_values == pytest.approx([0.0, 0.1, 0.2, 0.3])


def test_reconstruction_runs_once_and_only_for_a_parallel_run(tmp_path, monkeypatch):
    """A serial run has nothing to gather; a parallel run whose reconstruction is marked done
    (a run resumed after it) runs no application again."""
    def no_process(*args, **kwargs):
        raise AssertionError("an OpenFOAM application was started")

    monkeypatch.setattr(runner.processes, "run", no_process)
    run = fake_run(tmp_path)
    assert paraview.reconstruct(run) is None
    (run / "processor0").mkdir()
    layout.mark_done(run, paraview.RECONSTRUCT)
    assert paraview.reconstruct(run) == run / "log.reconstructPar"


def _export(capsys, *argv):
    code = main(["export", *map(str, argv)])
    out, err = capsys.readouterr()
    return code, out, err.strip().splitlines()


def test_export_refuses_an_existing_vtk_folder(tmp_path, capsys):
    """RUN/VTK is never overwritten: one line naming it and --force, exit 2, nothing
    touched (and nothing run). So are a run not finished, a folder that is no run, and no
    format."""
    run = fake_run(tmp_path)
    (run / "VTK").mkdir()
    (run / "VTK" / "earlier.vtm").write_text("mine")
    code, out, err = _export(capsys, run, "--vtk")
    assert code == 2 and out == "" and len(err) == 1
    assert "VTK exists" in err[0] and "--force" in err[0]
    assert (run / "VTK" / "earlier.vtm").read_text() == "mine"
    assert not (run / "sphere.foam").exists() and not (run / "log.foamToVTK").exists()
    unfinished = fake_run(tmp_path / "other", finished=False)
    code, _, err = _export(capsys, unfinished, "--vtk")
    assert code == 2 and len(err) == 1 and "not finished" in err[0]
    code, _, err = _export(capsys, tmp_path, "--vtk")
    assert code == 2 and len(err) == 1 and "no run of floatfoam run" in err[0]
    code, _, err = _export(capsys, run)
    assert code == 2 and len(err) == 1 and "valid is --vtk" in err[0]


@pytest.mark.openfoam
def test_a_parallel_roll_run_opens_in_paraview_and_analyses_as_roll(shared_runs, capsys):
    """elliptic_cylinder_roll on 2 ranks: the run folder holds elliptic_cylinder_roll.foam,
    and pyvista's POpenFOAMReader with its defaults (the reconstructed case) lists every time
    the ranks wrote, the body turned at the last one (the moving points reconstructed);
    `floatfoam analyse RUN --json` without --dof analyses the roll. The record is 2.0 s, as
    test_section_roll's: 0.2 s would be a quarter of a roll period, and a decay fit needs 1.5
    cycles (analysis.decay.MIN_CYCLES)."""
    import pyvista

    from floatfoam.layout import time_folders

    overrides = ["run.end_time=2.0"]  # test_section_roll's run: made once
    run = shared_run("elliptic_cylinder_roll", overrides, shared_runs, 2) / \
        "elliptic_cylinder_roll" / "coarse"
    foam = run / "elliptic_cylinder_roll.foam"
    assert foam.is_file() and foam.read_bytes() == b""
    written = [t for t, _ in time_folders(run / "processor0")]
    assert written[-1] == pytest.approx(2.0)
    reader = pyvista.POpenFOAMReader(str(foam))
    assert [t for t in reader.time_values if t > 0] == pytest.approx(written)
    body = []
    for t in (reader.time_values[0], reader.time_values[-1]):
        reader.set_active_time_value(t)
        body.append(np.asarray(reader.read()["boundary"]["body"].points))
    assert not np.allclose(body[0], body[1], atol=1e-4)  # the body moved (≥ 0.1 mm)
    capsys.readouterr()
    assert main(["analyse", str(run), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["dof"] == "roll" and data["dof_from"] == "released by the run"
