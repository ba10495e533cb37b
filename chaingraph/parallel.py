"""Running independent tasks on local processes, as the atlas and the report do.

A runner is ``runner(fn, tasks, on_result)``: it calls ``on_result(i, fn(tasks[i]))``
for every task, in whatever order they finish. Workers leave Ctrl-C to the main
process, which stops them all (no worker left behind, no traceback of theirs).
"""

from __future__ import annotations

__all__ = ["serial", "process_runner", "ignore_interrupts"]


def serial(fn, tasks, on_result):
    """Run the tasks here, one after the other."""
    for i, task in enumerate(tasks):
        on_result(i, fn(task))


def ignore_interrupts():
    """In a worker process: leave Ctrl-C to the main process, which stops the workers."""
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def process_runner(workers):
    """A runner on ``workers`` local processes (results in any order).

    Examples
    --------
    >>> found = {}
    >>> process_runner(1)(abs, [-2, 3], found.__setitem__)
    >>> found
    {0: 2, 1: 3}
    """
    def run(fn, tasks, on_result):
        if workers <= 1 or len(tasks) <= 1:
            return serial(fn, tasks, on_result)
        from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
        pool = ProcessPoolExecutor(max_workers=min(workers, len(tasks)),
                                   initializer=ignore_interrupts)
        try:
            pending = {pool.submit(fn, task): i for i, task in enumerate(tasks)}
            while pending:
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in done:
                    on_result(pending.pop(future), future.result())
        except BaseException:
            # Ctrl-C or a failure: stop every worker now, leave nothing running
            for process in list(getattr(pool, "_processes", {}).values()):
                process.terminate()
            pool.shutdown(wait=True, cancel_futures=True)
            raise
        pool.shutdown()
    return run
