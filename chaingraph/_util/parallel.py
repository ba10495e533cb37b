"""Running independent tasks on local processes, as the atlas and the report do.

A runner is ``runner(fn, tasks, on_result)``: it calls ``on_result(i, fn(tasks[i]))``
for every task, in whatever order they finish. Workers leave Ctrl-C to the main
process, which stops them all (no worker left behind, no traceback of theirs), end at
once on SIGTERM (whatever handler the main process set, which a forked worker would
otherwise inherit), and end by themselves when the main process is gone (killed with
SIGKILL, say).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import ctypes
import os
import signal
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

__all__ = ["serial", "process_runner", "ignore_interrupts", "prepare_worker", "Runner"]

#: ``runner(fn, tasks, on_result)``: runs ``fn`` on each task somewhere and calls
#: ``on_result(index, result)`` as each finishes
Runner = Callable[[Callable[[Any], Any], Sequence[Any], Callable[[int, Any], None]], None]


def serial(fn: Callable[[Any], Any], tasks: Sequence[Any],
           on_result: Callable[[int, Any], None]) -> None:
    """Run the tasks here, one after the other."""
    for i, task in enumerate(tasks):
        on_result(i, fn(task))


def ignore_interrupts() -> None:
    """In a worker process: leave Ctrl-C to the main process, which stops the workers,
    and end quietly on SIGTERM (the signal the main process stops them with; a worker
    forked from a command line would otherwise inherit its handler, and print)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def prepare_worker(parent: int) -> None:
    """In a worker process: leave Ctrl-C to the main process, and end when the main
    process ``parent`` (its pid) is gone however it went (killed, out of memory, a
    closed terminal), so that no worker outlives it: the kernel is asked to kill the
    worker with its parent (Linux), and a watch thread checks the parent every quarter
    second everywhere (also where the kernel's request does not apply)."""
    ignore_interrupts()
    _unblock(_STOPS)                             # blocked by the main process as it forked
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)            # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.25)
        os._exit(1)
    if os.getppid() != parent:                   # gone before the request was made
        os._exit(1)
    threading.Thread(target=watch, name="chaingraph-parent-watch", daemon=True).start()


#: the signals that stop a run
_STOPS = {signal.SIGINT, signal.SIGTERM}


def _block(signals: set[signal.Signals]) -> set[int | signal.Signals] | None:
    """Hold ``signals`` in this thread (where the platform can); the mask before."""
    if not hasattr(signal, "pthread_sigmask"):
        return None
    return set(signal.pthread_sigmask(signal.SIG_BLOCK, signals))


def _unblock(signals: set[signal.Signals]) -> None:
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, signals)


def _restore(mask: set[int | signal.Signals] | None) -> None:
    if mask is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)


def _stop(pool: ProcessPoolExecutor) -> None:
    """Ctrl-C or a failure: stop every worker now, leave nothing running.

    A worker stopped while it sent a result leaves part of a message in the results'
    pipe, and the pool's reader waits for the rest, which no process will write: the
    shutdown below would wait for that reader for ever. So the workers are waited for
    once stopped, and then this process's own end of that pipe is closed (the pool reads
    results only; it is the last writer left): the reader sees the pipe end, takes the
    pool for broken and ends."""
    processes = list(getattr(pool, "_processes", {}).values())
    for process in processes:
        process.terminate()
    for process in processes:
        process.join(timeout=10)
    writer = getattr(getattr(pool, "_result_queue", None), "_writer", None)
    if writer is not None:
        writer.close()
    try:
        pool.shutdown(wait=True, cancel_futures=True)
    except RuntimeError:
        # interrupted while the pool started its manager thread: nothing to join, and
        # the interruption is what the caller must see
        pass


def process_runner(workers: int) -> Runner:
    """A runner on ``workers`` local processes (results in any order).

    Examples
    --------
    >>> found = {}
    >>> process_runner(1)(abs, [-2, 3], found.__setitem__)
    >>> found
    {0: 2, 1: 3}
    """
    def run(fn: Callable[[Any], Any], tasks: Sequence[Any],
            on_result: Callable[[int, Any], None]) -> None:
        if workers <= 1 or len(tasks) <= 1:
            return serial(fn, tasks, on_result)
        # Ctrl-C and SIGTERM are held while the workers are forked: one that came
        # before a worker set its own handlers would run the main process's in it
        # (a traceback of the worker's); the worker takes them up once it is ready
        pool = None
        held = _block(_STOPS)
        try:
            pool = ProcessPoolExecutor(max_workers=min(workers, len(tasks)),
                                       initializer=prepare_worker, initargs=(os.getpid(),))
            pending = {pool.submit(fn, task): i for i, task in enumerate(tasks)}
            _restore(held)
            while pending:
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in done:
                    on_result(pending.pop(future), future.result())
        except BaseException:
            if pool is not None:
                _stop(pool)
            _restore(held)
            raise
        pool.shutdown()
    return run
