"""floatfoam on a real Slurm: a one-node slurmctld + slurmd started for these tests
(scripts/slurm_local.sh, Debian's slurm-wlm 22.05 and munge), an array of two runs with the
summary job after it, a task requeued mid-run that resumes and finishes with the motion of a
local run, a resubmitted script whose finished runs exit at once, and a validation study
submitted as an array with its study job after it. Then the commands' bad input, without
Slurm."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from procutil import SMALL_OGRID

from floatfoam.cli import main
from floatfoam.cluster import jobs, slurm
from floatfoam.foam.motionlog import RESUMED
from floatfoam.layout import ROOT, is_finished
from floatfoam.motion import read_motion

FLOATFOAM = str(Path(sys.executable).with_name("floatfoam"))
CASE = "cylinder_heave"
SHORT = ["--set", "run.end_time=0.1", "--set", "run.write_interval=0.02"]


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A one-node Slurm for this module's tests: its SLURM_CONF (stopped after them)."""
    folder = tmp_path_factory.mktemp("slurm")
    script = str(ROOT / "scripts" / "slurm_local.sh")
    started = subprocess.run(["bash", script, "start", str(folder)], capture_output=True,
                             text=True, timeout=120)
    assert started.returncode == 0, started.stderr
    conf = started.stdout.strip().split("=", 1)[1]
    yield {"SLURM_CONF": conf}
    subprocess.run(["bash", script, "stop", str(folder)], capture_output=True, timeout=120)


def environment(build: Path, cluster: dict) -> dict:
    """The submitter's environment, which Slurm hands to its jobs: the build folder (and the
    scratch in it) and the test's Slurm."""
    return {**os.environ, "FLOATFOAM_BUILD": str(build), "TMPDIR": str(build), **cluster}


def queued(ids: list[str], env: dict) -> dict[str, tuple[str, str]]:
    proc = subprocess.run(["squeue", "--noheader", "--array", "--jobs", ",".join(ids),
                           "--format=%i|%T|%r"], env=env, capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 0, proc.stderr
    return {p[0]: (p[1], p[2]) for p in (line.split("|") for line in proc.stdout.split())}


def wait_until(predicate, seconds: float, what: str) -> None:
    deadline = time.monotonic() + seconds
    while not predicate():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        time.sleep(0.5)


def floatfoam(*argv: str, env: dict, timeout: float = 600) -> subprocess.CompletedProcess:
    return subprocess.run([FLOATFOAM, *argv], env=env, capture_output=True, text=True,
                          timeout=timeout)


@pytest.mark.openfoam
def test_slurm_array_requeued_task_resumes_and_matches_a_local_run(tmp_path, cluster):
    build = tmp_path / "cluster"
    build.mkdir()
    env = environment(build, cluster)
    script = tmp_path / "sweep.sh"
    made = floatfoam("batch", CASE, "--levels", "coarse", "medium", "--np", "1", *SHORT,
                     "--out", str(script), "--submit", env=env)
    assert made.returncode == 0, made.stderr
    (record,) = jobs.read_records(None, build)
    job, gather, folder = record["job"], record["after"], Path(record["folder"])
    assert f"submitted as job {job}" in made.stdout and gather

    coarse = build / CASE / "coarse"
    # requeued once its run has written 0.04 s: mid-run (it goes to 0.1 s)
    wait_until(lambda: (coarse / "0.04" / "uniform" / "time").is_file(), 300, "t = 0.04 s")
    requeue = subprocess.run(["scontrol", "requeue", f"{job}_0"], env=env,
                             capture_output=True, text=True, timeout=60)
    assert requeue.returncode == 0, requeue.stderr
    wait_until(lambda: queued([job], env).get(f"{job}_0", ("",))[0] == "PENDING", 60,
               "the requeued task pending")
    status = floatfoam("status", job, env=env, timeout=60)
    assert status.returncode == 0, status.stderr
    assert f"{job}_0" in status.stdout and "pending" in status.stdout, status.stdout
    # Slurm holds a requeued job for two minutes (its BeginTime): released now
    release = subprocess.run(["scontrol", "update", f"jobid={job}_0", "StartTime=now"],
                             env=env, capture_output=True, text=True, timeout=60)
    assert release.returncode == 0, release.stderr
    wait_until(lambda: not queued([job, gather], env), 600, "the array and its summary job")

    output = (folder / f"{job}_0.out").read_text()
    assert "DUE TO JOB REQUEUE" in output  # the task was stopped by the requeue ...
    log = (coarse / "log.interFoam").read_text()
    assert RESUMED in log  # ... and its second start resumed the run, set nothing aside
    assert not (coarse / ".floatfoam" / "incomplete").exists()
    status = floatfoam("status", job, env=env, timeout=60)
    lines = status.stdout.splitlines()
    assert sum("finished  0.1 / 0.1" in line for line in lines) == 2, status.stdout
    assert f"then job {gather} (summary): ended" in status.stdout
    summary = json.loads((folder / "summary.json").read_text())
    assert [(e["run"], e["finished"], e["cells"] > 0) for e in summary] == \
        [("coarse", True, True), ("medium", True, True)]

    # the same runs made locally, without Slurm
    local = tmp_path / "local"
    local.mkdir()
    for level in ("coarse", "medium"):
        done = floatfoam("run", CASE, "--level", level, "--np", "1", *SHORT,
                         env={**os.environ, "FLOATFOAM_BUILD": str(local),
                              "TMPDIR": str(local)})
        assert done.returncode == 0, done.stderr
    for level, atol in (("coarse", 2e-5), ("medium", 1e-12)):
        there = read_motion(build / CASE / level / "motion.csv")
        here = read_motion(local / CASE / level / "motion.csv")
        assert is_finished(build / CASE / level)
        assert there["time"][-1] == pytest.approx(here["time"][-1], abs=1e-9) == 0.1
        # The task that ran through took the local run's steps: the same motion to round-off.
        # The requeued one restarted from 0.04 s, where a restarted solver takes other steps
        # than one that runs on: measured 3.3e-6 m apart at 0.1 s (0.01 % of the 25.4 mm
        # release); the bound is tests/foam/test_run_reliability.py's resume check's.
        assert there["z"][-1] == pytest.approx(here["z"][-1], abs=atol), level

    # resubmitted, the script finds both runs finished: each task exits at once
    again = subprocess.run(["sbatch", "--wait", "--parsable", str(script)], env=env,
                           capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    second = again.stdout.strip()
    for task in (0, 1):
        text = (folder / f"{second}_{task}.out").read_text()
        assert "holds a finished run" in text and "s to simulate" not in text, text


@pytest.mark.openfoam
def test_slurm_validation_study_as_an_array_and_a_dependent_study_job(tmp_path, cluster):
    env = environment(tmp_path, cluster)
    # two ranks a task: mpirun inside each takes the task's allocation (--ntasks 2, the 2 cores)
    made = floatfoam("validate", CASE, "--np", "2", "--set", "run.end_time=0.03", "--set",
                     "run.write_interval=0.03", *SMALL_OGRID, "--slurm", env=env)
    assert made.returncode == 0, made.stderr
    (record,) = jobs.read_records(None, tmp_path)
    runs = ["coarse", "medium", "fine", "medium-dt2", "coarse-morph1.5"]
    assert [t["run"] for t in record["tasks"]] == runs and record["kind"] == "validate"
    wait_until(lambda: not queued([record["job"], record["after"]], env), 600,
               "the study's runs and the study")
    study = json.loads((tmp_path / CASE / "validation" / "validation.json").read_text())
    assert study["runs"] == runs  # every run finished with the command's settings (stamps)
    for run in runs:
        assert is_finished(tmp_path / CASE / run)
        assert len(list((tmp_path / CASE / run).glob("processor[0-9]*"))) == 2
    gathered = (Path(record["folder"]) / f"{record['after']}.out").read_text()
    assert "written: " in gathered and "validation.json" in gathered


def test_submission_needs_sbatch_and_writes_nothing_without_it(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("FLOATFOAM_BUILD", str(tmp_path))
    monkeypatch.setattr(slurm.shutil, "which", lambda name: None)
    out = tmp_path / "sweep.sh"
    assert main(["batch", CASE, "--out", str(out), "--submit"]) == 2
    assert "no `sbatch` on PATH" in capsys.readouterr().err and not out.exists()
    assert main(["validate", CASE, "--slurm", "--no-run"]) == 2
    assert main(["validate", CASE, "--time", "1:00:00"]) == 2  # a time limit needs --slurm
    assert main(["validate", CASE, "--slurm", "--time", "soon"]) == 2
    assert "--time 'soon'" in capsys.readouterr().err
    assert main(["validate", CASE, "--slurm"]) == 2
    assert "no `sbatch` on PATH" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []  # nothing written
    assert main(["status"]) == 0
    assert "no job submitted from" in capsys.readouterr().out
    assert main(["status", "12345"]) == 2
    assert "JOB 12345: no job" in capsys.readouterr().err


def test_progress_reads_the_solver_log_since_its_last_start(tmp_path):
    log = tmp_path / "log.interFoam"
    steps = "".join(f"Time = {t:g}\n\nsolving\nExecutionTime = {c} s  ClockTime = {c} s\n\n"
                    for t, c in ((0.1, 10), (0.2, 20)))
    resumed = "".join(f"Time = {t:g}\n\nExecutionTime = {c} s  ClockTime = {c} s\n\n"
                      for t, c in ((0.3, 3), (0.4, 7), (0.5, 11)))
    log.write_text(steps + f"\n{RESUMED} at now\n" + resumed + "Time = 0.6\n")
    reached, rate = jobs.progress(tmp_path)
    assert reached == 0.5 and rate == pytest.approx(0.2 / 8)  # the rate since the restart
    assert jobs.progress(tmp_path / "none") == (None, None)
