"""The process runner of the atlas and the report: results, and no worker outliving the
main process however it ends."""

import os
import signal
import subprocess
import sys

import pytest

from chaingraph._util.parallel import process_runner, serial

from ..conftest import alive, children, wait_for


def test_every_task_runs_once_on_processes_and_here():
    for runner in (process_runner(2), serial):
        found = {}
        runner(abs, [-3, 4, -5, 6], found.__setitem__)
        assert found == {0: 3, 1: 4, 2: 5, 3: 6}


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="reads processes from /proc")
@pytest.mark.parametrize("argv", [
    ["report", "-o", "{out}", "--workers", "2"],
    ["atlas", "--links", "14", "--dof", "1", "--workers", "2", "--out", "{out}", "-q"],
], ids=["report", "atlas"])
def test_workers_end_when_the_main_process_is_killed(tmp_path, argv):
    """SIGKILL of the main process (a CI timeout, the OOM killer): its workers notice
    and leave (they stayed forever, asleep, before)."""
    argv = [a.format(out=tmp_path / "out") for a in argv]
    proc = subprocess.Popen([sys.executable, "-m", "chaingraph", *argv],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        assert wait_for(lambda: len(children(proc.pid)) >= 2, 120), "no workers started"
        workers = children(proc.pid)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        assert wait_for(lambda: not any(alive(w) for w in workers), 5), \
            [w for w in workers if alive(w)]
    finally:
        proc.kill()
