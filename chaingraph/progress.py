"""A progress bar on a text stream (stderr), for the report and the atlas."""

from __future__ import annotations

import time

__all__ = ["ProgressBar"]


class ProgressBar:
    """``[#####.....] done/total  seconds  label``, redrawn in place; silent without a stream.

    Examples
    --------
    >>> import io
    >>> out = io.StringIO()
    >>> bar = ProgressBar(4, out, width=4)
    >>> bar.show(2, "half")
    >>> out.getvalue().split()[0:2]
    ['[##..]', '2/4']
    """

    def __init__(self, total, stream, *, width=30):
        self.total, self.stream, self.width = total, stream, width
        self.start = time.perf_counter()

    def show(self, done, label=""):
        if self.stream is None:
            return
        filled = int(self.width * done / max(self.total, 1))
        elapsed = time.perf_counter() - self.start
        self.stream.write(f"\r[{'#' * filled}{'.' * (self.width - filled)}] {done}/{self.total} "
                          f"{elapsed:6.1f} s  {label[:40]:40s}")
        self.stream.flush()

    def close(self):
        if self.stream is not None:
            self.stream.write("\n")
            self.stream.flush()
