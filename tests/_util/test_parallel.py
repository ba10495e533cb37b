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


_SLOW_TO_START = """
import signal, sys, time
from chaingraph._util import parallel

def said(*_):
    sys.stderr.write("the main process's handler ran\\n")
    sys.exit(3)

signal.signal(signal.SIGTERM, said)
ready = parallel.prepare_worker

def slow(parent):            # a worker slow to set its own handlers
    time.sleep(1.0)
    ready(parent)

parallel.prepare_worker = slow
parallel.process_runner(2)(time.sleep, [30, 30], lambda *_: None)
"""


@pytest.mark.skipif(not hasattr(signal, "pthread_sigmask"), reason="POSIX signal masks")
def test_a_sigterm_before_a_worker_is_ready_runs_no_handler_of_the_main_process_in_it():
    """SIGTERM to the group (``timeout``, CI) while the workers were still starting ran
    the command line's handler in them: a traceback of a worker's under the one line.
    The signals are held while the workers are forked, and taken up when they are ready."""
    proc = subprocess.Popen([sys.executable, "-c", _SLOW_TO_START], stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    try:
        assert wait_for(lambda: len(children(proc.pid)) >= 2, 60), "no workers started"
        os.killpg(proc.pid, signal.SIGTERM)
        _, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    # the main process's handler ran once: in the main process, not in a worker
    assert err.count("the main process's handler ran") == 1, err
    assert proc.returncode == 3


_CUT_SHORT = """
import os, struct, time
from concurrent.futures import ProcessPoolExecutor
from chaingraph._util import parallel
pool = ProcessPoolExecutor(max_workers=1, initializer=parallel.prepare_worker,
                           initargs=(os.getpid(),))
pool.submit(time.sleep, 30)
time.sleep(0.5)
# what a worker stopped while it sent its result leaves in the pipe: a message's length
# and part of it
os.write(pool._result_queue._writer.fileno(), struct.pack("!i", 1000) + b"x" * 10)
time.sleep(0.3)
parallel._stop(pool)
print("stopped", flush=True)
"""


def test_a_worker_stopped_while_it_sent_a_result_leaves_no_wait_behind():
    """Ctrl-C while a worker was sending a result: the pool's reader waited for the rest
    of the message for ever, and the interrupted atlas never exited (seen once in the
    suite: test_ctrl_c_leaves_no_worker_and_a_resumable_folder timed out). The stop
    closes this process's end of the results' pipe once the workers are gone; here a
    message cut short is written as such a worker would leave it."""
    done = subprocess.run([sys.executable, "-c", _CUT_SHORT], capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0 and done.stdout == "stopped\n", done.stderr
