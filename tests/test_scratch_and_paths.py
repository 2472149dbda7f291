"""Scratch folders that no SIGKILL leaves behind, case lookup and build names, batch's run
folders, and the one-line errors of paths, argparse and a full disk (issue 37)."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from floatfoam import scratch
from floatfoam.case import build_name, case_dir, load_case
from floatfoam.cli import main
from floatfoam.errors import InputError
from floatfoam.foam import runner
from floatfoam.layout import CASES_DIR, MARKERS

FLOATFOAM = str(Path(sys.executable).with_name("floatfoam"))
HOLDER = """
import sys, time
from floatfoam.scratch import scratch_dir
with scratch_dir("mesh") as folder:
    print(folder, flush=True)
    time.sleep(60)
"""


def one_error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


def test_sweep_removes_only_the_folders_of_dead_commands(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    holder = subprocess.Popen([sys.executable, "-c", HOLDER], stdout=subprocess.PIPE,
                              text=True, env={**os.environ, "TMPDIR": str(tmp_path)})
    folder = Path(holder.stdout.readline().strip())
    time.sleep(scratch.LOCKING + 0.2)
    assert scratch.sweep(tmp_path) == [] and folder.is_dir()  # its command lives
    holder.send_signal(signal.SIGKILL)
    holder.wait()
    assert folder.is_dir()  # SIGKILL: no finally ran
    unlocked = tmp_path / "floatfoam-mesh-abcd1234"
    unlocked.mkdir()  # no lock file: never ours to remove
    user = tmp_path / "floatfoam-runs"  # a build folder named like a scratch folder
    (user / "coarse").mkdir(parents=True)
    (user / "coarse" / ".owner.lock").write_text("")
    old = time.time() - 7200
    for path in (unlocked, user, user / "coarse" / ".owner.lock"):
        os.utime(path, (old, old))
    assert scratch.sweep(tmp_path) == [folder] and not folder.exists()
    assert unlocked.is_dir() and (user / "coarse").is_dir()


def test_scratch_dir_is_removed_after_its_block(tmp_path, monkeypatch):
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))
    with scratch.scratch_dir("mesh") as folder:
        assert folder.parent == tmp_path and (folder / scratch.LOCK).is_file()
    assert not folder.exists()


def test_a_path_wins_over_a_builtin_name_and_says_so(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sphere").mkdir()
    (tmp_path / "sphere" / "case.toml").write_text((CASES_DIR / "cylinder_heave" /
                                                     "case.toml").read_text())
    assert case_dir("sphere") == CASES_DIR / "sphere"  # a bare name: the built-in case
    assert "./sphere names the folder here" in capsys.readouterr().err
    assert case_dir("./sphere") == tmp_path / "sphere"  # a path: the folder
    assert "not the built-in case sphere" in capsys.readouterr().err
    here, builtin = load_case("./sphere"), load_case("sphere")
    assert builtin.name == "sphere" and here.name.startswith("sphere-") and here.name != "sphere"


def test_two_cases_of_one_name_never_share_a_build_folder(tmp_path):
    for parent in ("a", "b"):
        (tmp_path / parent / "cyl").mkdir(parents=True)
        shutil.copy(CASES_DIR / "cylinder_heave" / "case.toml", tmp_path / parent / "cyl")
    names = {load_case(str(tmp_path / p / "cyl")).name for p in ("a", "b")}
    assert len(names) == 2 and all(n.startswith("cyl-") for n in names)
    assert build_name(CASES_DIR / "cylinder_heave") == "cylinder_heave"


def test_a_linked_case_is_named_after_its_link(tmp_path):
    """A link to a user's case takes the link's name; a link to a built-in case is that case."""
    shutil.copytree(CASES_DIR / "cylinder_heave", tmp_path / "v3")
    (tmp_path / "mybody").symlink_to(tmp_path / "v3")
    assert load_case(str(tmp_path / "mybody")).name.startswith("mybody-")
    (tmp_path / "cyl").symlink_to(CASES_DIR / "cylinder_heave")
    assert load_case(str(tmp_path / "cyl")).name == "cylinder_heave"


@pytest.mark.parametrize("argv", [["cylinder_heave", "cylinder_heave"],
                                  ["cylinder_heave", "--levels", "coarse", "coarse"]])
def test_batch_refuses_tasks_sharing_a_run_folder(tmp_path, build, capsys, argv):
    out = tmp_path / "sweep.sh"
    assert main(["batch", *argv, "--out", str(out)]) == 2
    assert "the same run folder" in one_error_line(capsys) and not out.exists()


def test_batch_refuses_a_run_folder_of_other_settings(tmp_path, build, capsys):
    run_dir = build / "cylinder_heave" / "coarse"
    (run_dir / MARKERS).mkdir(parents=True)
    (run_dir / MARKERS / "settings").write_text("0123456789abcdef 1\n")  # another digest
    out = tmp_path / "sweep.sh"
    assert main(["batch", "cylinder_heave", "--out", str(out)]) == 2
    assert "with other settings" in one_error_line(capsys) and not out.exists()


@pytest.mark.parametrize("argv, words", [
    (["gz", "sphere", "--plot", "/proc/x.png"], "cannot use /proc/x.png"),
    (["batch", "cylinder_heave", "--out", "/nonexistent/x.sh"], "no folder /nonexistent"),
])
def test_paths_that_cannot_be_used_are_one_line_exit_2(build, capsys, argv, words):
    assert main(argv) == 2
    assert words in one_error_line(capsys)


@pytest.mark.parametrize("argv, words", [
    (["run", "cylinder_heave", "--np", "two"],
     "floatfoam run: error: argument --np: invalid int value: 'two'"),
    (["nosuch"], "floatfoam: error: argument COMMAND: invalid choice: 'nosuch'"),
])
def test_argparse_errors_are_one_line_exit_2(capsys, argv, words):
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    assert one_error_line(capsys).startswith(words)


def test_mesh_out_never_overwrites(tmp_path, capsys):
    existing = tmp_path / "domain.msh"
    existing.write_text("mine\n")
    assert main(["mesh", "domain", "cylinder_heave", "--out", str(existing)]) == 2
    assert "exists; valid is a new file" in one_error_line(capsys)
    assert existing.read_text() == "mine\n"


def test_mesh_out_names_a_msh_file(tmp_path, capsys):
    """gmsh writes the format the name ends in: a name without .msh is refused before any
    meshing."""
    assert main(["mesh", "domain", "cylinder_heave", "--out", str(tmp_path / "domain")]) == 2
    assert one_error_line(capsys) == (f"floatfoam mesh: error: --out {tmp_path / 'domain'}: "
                                      "valid is a file name ending in .msh")
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("build, words", [("x" * 300, "bytes per folder name"),
                                          ("/".join(["y" * 200] * 5), "characters long")])
def test_build_paths_openfoam_cannot_take(tmp_path, monkeypatch, capsys, build, words):
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path / build))
    assert main(["run", "cylinder_heave"]) == 2
    assert words in one_error_line(capsys)
    assert not any(tmp_path.iterdir())  # nothing written


def _in_mount_namespace() -> bool:
    return subprocess.run(["unshare", "-m", "true"], capture_output=True).returncode == 0


@pytest.mark.skipif(not _in_mount_namespace(), reason="needs unshare -m (root) for a private "
                    "read-only or full file system")
def test_read_only_and_full_build_folders(tmp_path):
    """A read-only build folder is bad input (exit 2, one line); a full disk is named, before
    the run writes anything."""
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    script = (f"mount -t tmpfs -o size=1m none {mnt} && mount -o remount,ro {mnt} && "
              f"FLOATFOAM_BUILD={mnt} {FLOATFOAM} gz sphere; echo rc=$?; "
              f"mount -o remount,rw {mnt} && head -c 900k /dev/zero > {mnt}/fill && "
              f"FLOATFOAM_BUILD={mnt}/build {FLOATFOAM} run cylinder_heave; echo rc=$?")
    out = subprocess.run(["unshare", "-m", "sh", "-c", script], capture_output=True,
                         text=True, timeout=120)
    lines = out.stderr.strip().splitlines()
    assert out.stdout.split() == ["rc=2", "rc=2"], out.stderr
    assert len(lines) == 2 and "Read-only file system" in lines[0], lines
    assert "MiB free" in lines[1], lines


def test_disk_note_names_a_full_disk(tmp_path, monkeypatch):
    monkeypatch.setattr(runner, "free_bytes", lambda folder: runner.LOW_DISK)
    assert runner.disk_note(tmp_path) == ""
    monkeypatch.setattr(runner, "free_bytes", lambda folder: runner.LOW_DISK - 1)
    assert "is full" in runner.disk_note(tmp_path)
    with pytest.raises(InputError, match="MiB free"):
        runner.check_disk(tmp_path / "not" / "made" / "yet")
