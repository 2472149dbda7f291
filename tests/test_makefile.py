"""The Makefile's logic of its own: `make clean` (its recipe, as `make -n` prints it, run in a
scratch project folder: never on this one), `make pictures`, and the case targets (one per
folder of cases/)."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def dry_run(target: str, **variables) -> str:
    """The commands ``make <target>`` would run (``make -n``), as one shell script."""
    env = {k: v for k, v in os.environ.items() if k != "FLOATFOAM_BUILD"}
    args = [f"{k}={v}" for k, v in variables.items()]
    return subprocess.run(["make", "--no-print-directory", "-n", target, *args], cwd=ROOT,
                          env=env, capture_output=True, text=True, check=True).stdout


def _tree(root: Path, *files: str) -> None:
    for name in files:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text("x")


def _clean(recipe: str, project: Path, build: Path | None = None):
    env = {k: v for k, v in os.environ.items() if k != "FLOATFOAM_BUILD"}
    env["HOME"] = str(project.parent / "home")
    if build is not None:
        env["FLOATFOAM_BUILD"] = str(build)
    return subprocess.run(["bash", "-c", recipe], cwd=project, env=env, capture_output=True,
                          text=True)


@pytest.fixture
def project(tmp_path):
    """A scratch project folder: build/ with the solver, a run and a hidden lock file."""
    folder = tmp_path / "project"
    _tree(folder / "build", "solver/bin/interFoam", "cylinder_heave/coarse/motion.csv",
          "cylinder_heave/.coarse.lock", "potential/cache.json")
    return folder


def test_make_clean_keeps_the_solver(project):
    """build/ is emptied but for build/solver, floatfoam's rebuilt interFoam."""
    done = _clean(dry_run("clean"), project)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in (project / "build").iterdir()) == ["solver"]
    assert (project / "build" / "solver" / "bin" / "interFoam").read_text() == "x"


def test_make_clean_honours_floatfoam_build(project, tmp_path):
    """With FLOATFOAM_BUILD, that folder is emptied (a folder there named solver too: it is
    not the project's) and the project's build/ is left alone; a FLOATFOAM_BUILD naming the
    project itself or $HOME is refused in one line, exit 2, nothing removed (/ is refused
    alike, and not tried here)."""
    other = tmp_path / "runs"
    _tree(other, "sphere/coarse/motion.csv", "solver/bin/interFoam", ".sphere.lock")
    recipe = dry_run("clean")
    done = _clean(recipe, project, other)
    assert done.returncode == 0, done.stderr
    assert other.is_dir() and not any(other.iterdir())
    assert (project / "build" / "cylinder_heave" / "coarse" / "motion.csv").is_file()
    for bad in (project, tmp_path / "home"):
        done = _clean(recipe, project, bad)
        assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1
        assert "FLOATFOAM_BUILD" in done.stderr
    assert (project / "build" / "potential" / "cache.json").is_file()


def test_make_pictures_runs_floatfoam_pictures():
    assert "floatfoam pictures elliptic_cylinder_roll --level medium" in dry_run(
        "pictures", CASE="elliptic_cylinder_roll", LEVEL="medium")


def test_every_case_folder_has_its_target():
    """`make <case>` for every folder of cases/ with a case.toml (the shared ones, `_…`, have
    none): the target list comes from the folders, so a new case needs no Makefile edit."""
    names = sorted(p.parent.name for p in (ROOT / "cases").glob("*/case.toml")
                   if not p.parent.name.startswith("_"))
    listed = [line.split()[-1] for line in subprocess.run(
        ["make", "--no-print-directory", "help"], cwd=ROOT, capture_output=True, text=True,
        check=True).stdout.splitlines() if line.startswith("    make ")]
    assert listed == names and len(names) >= 20
    assert "floatfoam run lab_sphere --level medium" in dry_run("lab_sphere", LEVEL="medium")
    with pytest.raises(subprocess.CalledProcessError):
        dry_run("_flume_section")
