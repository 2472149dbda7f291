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

SCRIPT = f"""set -eu
. {SESSIONS}
trap stop_groups EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
session sleep 300 &
groups="$!"
echo started
in_background bash -c "$1"
"""


def start(folder: Path, foreground: str) -> subprocess.Popen:
    """The script in ``folder``: a session sleeping in the background, ``foreground`` (a bash
    command) as a session waited for; it prints "started" once both are on their way."""
    driver = subprocess.Popen(["bash", "-c", SCRIPT, "script", foreground], cwd=folder,
                              stdout=subprocess.PIPE, text=True, start_new_session=True)
    assert driver.stdout.readline().strip() == "started"
    return driver


def gone(folder: Path, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while processes_in(folder):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.1)
    return True


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 143), (signal.SIGKILL, -9)])
def test_a_stopped_or_killed_script_leaves_no_process(tmp_path, sig, code):
    driver = start(tmp_path, "sleep 301")
    time.sleep(0.5)
    assert len(processes_in(tmp_path)) >= 3  # the script and its two sleeps at least
    driver.send_signal(sig)
    assert driver.wait(timeout=10) == code
    # SIGTERM: the trap stops the sessions and waits for them; SIGKILL cannot be trapped, the
    # watchers poll each second whether the script is there
    assert gone(tmp_path, 3.0), [Path(f"/proc/{p}/cmdline").read_text() for p in
                                 processes_in(tmp_path)]


def test_a_session_gives_its_status_and_leaves_nothing_behind(tmp_path):
    # the foreground session fails with 7 after leaving a grandchild behind: the script's
    # `set -e` ends it with that status, and what the session left goes with it
    driver = start(tmp_path, "sleep 302 & sleep 0.5; exit 7")
    assert driver.wait(timeout=10) == 7
    assert gone(tmp_path, 3.0)
