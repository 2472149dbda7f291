"""scripts/sessions.sh, which scripts/setup.sh runs the interFoam build and the pip install in:
however the script that started them ends (its jobs done, an error, SIGTERM, SIGKILL), no
process it started outlives it by more than the watcher's second."""

from __future__ import annotations

import signal
import subprocess
import time
from pathlib import Path

import pytest
from procutil import processes_in

SESSIONS = Path(__file__).resolve().parents[1] / "scripts" / "sessions.sh"

PREAMBLE = f"""set -eu
. {SESSIONS}
trap stop_groups EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
"""


def start(folder: Path, body: str) -> subprocess.Popen:
    """The preamble and ``body`` as a bash script working in ``folder``; ``body`` prints
    "started" once its sessions are on their way."""
    driver = subprocess.Popen(["bash", "-c", PREAMBLE + body], cwd=folder,
                              stdout=subprocess.PIPE, text=True, start_new_session=True)
    assert driver.stdout.readline().strip() == "started"
    return driver


def running(folder: Path, command: str) -> list[int]:
    """The processes in ``folder`` whose command line is ``command``."""
    found = []
    for pid in processes_in(folder):
        try:
            if Path(f"/proc/{pid}/cmdline").read_text().replace("\0", " ").strip() == command:
                found.append(pid)
        except OSError:
            continue
    return found


def within(condition, seconds: float) -> bool:
    """Whether ``condition()`` holds within ``seconds``: a process sent SIGTERM is gone once
    the kernel has scheduled its exit, which takes a moment when other work holds the cores
    (make test runs its solver beside these tests)."""
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.02)
    return True


def gone(folder: Path, seconds: float) -> bool:
    return within(lambda: not processes_in(folder), seconds)


TWO_SESSIONS = """session sleep 300 &
groups="$!"
echo started
in_background sleep 301
"""


def test_a_stopped_script_stops_its_sessions_at_once(tmp_path):
    driver = start(tmp_path, TWO_SESSIONS)
    time.sleep(0.5)
    assert running(tmp_path, "sleep 300") and running(tmp_path, "sleep 301")
    driver.send_signal(signal.SIGTERM)
    assert driver.wait(timeout=10) == 143
    # the EXIT trap stopped both sessions and waited for them: nothing is left when the
    # script is gone, well before the watchers' one-second poll would have noticed
    assert gone(tmp_path, 0.3)


def test_a_killed_script_leaves_no_process(tmp_path):
    driver = start(tmp_path, TWO_SESSIONS)
    time.sleep(0.5)
    assert running(tmp_path, "sleep 300") and running(tmp_path, "sleep 301")
    driver.kill()  # cannot be trapped: the watchers see their sessions' parent gone
    assert gone(tmp_path, 3.0), [Path(f"/proc/{p}/cmdline").read_text() for p in
                                 processes_in(tmp_path)]
    driver.wait(timeout=10)


def test_a_finished_session_takes_what_it_left_and_gives_its_status(tmp_path):
    # the session's job leaves a grandchild behind and succeeds: the grandchild goes with the
    # session while the script goes on; then a failing session's status ends the script
    driver = start(tmp_path, """echo started
in_background bash -c 'sleep 302 & exit 0'
echo after
sleep 0.5
in_background bash -c 'exit 7'
echo never
""")
    assert driver.stdout.readline().strip() == "after"
    # stopped by the session's own end, well before the watcher's one-second poll
    assert within(lambda: not running(tmp_path, "sleep 302"), 0.3)
    assert driver.wait(timeout=10) == 7
    assert driver.stdout.read().strip() == ""
    assert gone(tmp_path, 1.0)


def test_session_refuses_the_foreground(tmp_path):
    # in the foreground it would exec, replacing the script and its EXIT trap
    proc = subprocess.run(["bash", "-c", f". {SESSIONS}; session true; echo rc=$?"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=10)
    assert proc.stdout.strip() == "rc=2" and "in the background" in proc.stderr


@pytest.mark.parametrize("job, code", [("sleep 0.2; exit 5", 5), ("kill -TERM $$", 143)])
def test_a_session_gives_its_jobs_status(tmp_path, job, code):
    proc = subprocess.run(["bash", "-c", PREAMBLE + f"in_background bash -c '{job}'"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=10)
    assert proc.returncode == code
