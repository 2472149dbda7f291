"""One way to name a run in every command on a run (analyse, pictures, export): RUN is a run
folder as given, or a CASE whose run at --level (default coarse) is meant
(floatfoam.cli.common.resolve_run). Runs written by hand (test_pictures.fake_run)."""

import json

import pytest
from conftest import ROOT
from fakes import fake_run

from floatfoam.cli import main
from floatfoam.cli.common import resolve_run
from floatfoam.errors import InputError


def test_a_case_names_its_run_at_the_level(build):
    run = fake_run(build)
    assert resolve_run("sphere", None) == run  # the default level: coarse
    with pytest.raises(InputError, match=r"^sphere --level medium: no run in .* yet; valid is "
                       r"a case run first \(floatfoam run sphere --level medium\)"):
        resolve_run("sphere", "medium")  # not run yet: the command to run, as typed
    assert resolve_run(str(run), None) == run  # a run folder: as given


def test_a_csv_is_a_record_only_where_one_is_taken(build):
    run = fake_run(build)
    csv = run / "motion.csv"
    assert resolve_run(str(csv), None, csv=True) == csv
    with pytest.raises(InputError, match="a run folder nor a case"):
        resolve_run(str(csv), None)


@pytest.mark.parametrize("argv, says", [
    (["RUN", "--level", "medium"], "--level medium: "),  # a run folder has its own level
    (["sphere", "--level", "huge"], "--level 'huge': valid levels are coarse, medium, fine"),
    (["no_such_case"], "no_such_case"),
])
def test_a_bad_name_is_one_line(build, capsys, argv, says):
    run = fake_run(build)
    argv = [str(run) if a == "RUN" else a for a in argv]
    for command in (["analyse"], ["export", "--vtk"], ["pictures"]):
        assert main([*command, *argv]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and says in err[0], (command, err)


def test_analyse_takes_a_case_or_its_run_folder_alike(build, capsys):
    run = fake_run(build, times=(0.0, 0.5, 1.0))  # 2.5 cycles of a 0.4 s heave
    outputs = []
    for name in ("sphere", str(run), str(run / "motion.csv")):
        assert main(["analyse", name, "--json"]) == 0
        outputs.append(json.loads(capsys.readouterr().out))
    assert outputs[0] == outputs[1]
    assert outputs[0]["period_mean"] == outputs[2]["period_mean"]


def test_a_users_case_run_is_drawn_beside_its_model(tmp_path, build):
    """A run of a case outside cases/ (its folder in the run's info.json) gets Cummins' model
    in its figure, as a case of cases/ does (analysis.overlay.run_overlay)."""
    import shutil

    from floatfoam.analysis.overlay import run_overlay

    own = tmp_path / "bodies" / "barge"
    own.mkdir(parents=True)
    shutil.copy(ROOT / "cases" / "elliptic_cylinder_roll" / "case.toml", own / "case.toml")
    (own / "case.toml").write_text((own / "case.toml").read_text().replace(
        'extends = "elliptic_cylinder"', f'extends = "{ROOT}/cases/'
        'elliptic_cylinder"'))
    run = fake_run(build, times=(0.0, 0.5, 1.0))
    info = run / ".floatfoam" / "info.json"
    info.write_text(json.dumps({**json.loads(info.read_text()), "case_path": str(own)}))
    overlay, why = run_overlay(run, "roll", 2.5)  # the model over 3 roll periods
    assert overlay is not None and why == ""  # the model computed
