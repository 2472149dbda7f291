"""A mesh checkMesh finds cells of negative volume in stops the run before the solver, in one
line naming the cause and what to try (floatfoam.foam.domain.make_polymesh)."""

from pathlib import Path

import pytest

from floatfoam.foam import domain, runner
from floatfoam.foam.meshcheck import parse_check_mesh

BAD = ("    Checking geometry...\n"  # checkMesh's lines, as v1912 prints them
       " ***Zero or negative cell volume detected.  Minimum negative volume: -1.2e-11, "
       "Number of negative volume cells: 5\n"
       " ***Error in face pyramids: 12 faces are incorrectly oriented.\n\n"
       "Failed 5 mesh checks.\n")


def test_the_counts_are_read_from_the_log():
    check = parse_check_mesh(BAD)
    assert check["negative_volume_cells"] == 5 and check["inverted_pyramid_faces"] == 12
    good = parse_check_mesh("    Face pyramids OK.\n\nMesh OK.\n")
    assert good["negative_volume_cells"] == 0 and good["mesh_ok"]


def test_a_mesh_with_inverted_cells_stops_before_the_solver(tmp_path, monkeypatch):
    def fake_app(run_dir, name, argv, **kwargs):
        log = Path(run_dir) / f"log.{name}"
        log.write_text(BAD if name == "checkMesh" else "")
        return log

    monkeypatch.setattr(runner, "run_app", fake_app)
    import floatfoam.foam.meshcheck as meshcheck
    import floatfoam.foam.splitfaces as splitfaces

    # no gmshToFoam ran: no mesh whose patches to type or whose split faces to join
    monkeypatch.setattr(meshcheck, "set_patch_types", lambda run_dir: None)
    monkeypatch.setattr(splitfaces, "join_split_faces", lambda run_dir: 0)
    mesh = domain.RunMesh(kind="3d", factor=1.0, cells=None, share=1.0, x_mid=None,
                          extents=(1.0, 1.0, 1.0), inner=0.1, outer=0.5)
    with pytest.raises(runner.RunError) as raised:
        domain.make_polymesh(mesh, tmp_path)
    message = str(raised.value)
    assert "\n" not in message and "5 cells of zero or negative volume" in message
    assert "mesh.gmsh.layers_3d = 0" in message and "log.checkMesh" in message
