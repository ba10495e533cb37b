"""A progress bar on a text stream (stderr), for the report and the atlas."""

from __future__ import annotations

import time

__all__ = ["ProgressBar"]


class ProgressBar:
    """``[#####.....] done/total  seconds  label``, redrawn in place on a terminal and
    cleared at the end; on a stream that is not a terminal (a log, a pipe), one plain
    line per item and no carriage returns; silent without a stream.

    Examples
    --------
    >>> import io
    >>> out = io.StringIO()
    >>> bar = ProgressBar(4, out, width=4)
    >>> bar.show(2, "half")
    >>> out.getvalue() == '[2/4] half\\n'
    True
    """

    def __init__(self, total, stream, *, width=30):
        self.total, self.stream, self.width = total, stream, width
        self.start = time.perf_counter()
        self._label, self._tenth = None, None

    @property
    def terminal(self):
        isatty = getattr(self.stream, "isatty", None)
        return bool(isatty and isatty())

    def show(self, done, label=""):
        if self.stream is None:
            return
        if not self.terminal:
            # a plain line when the stage changes, at every tenth, and at the end
            tenth = 10 * done // max(self.total, 1)
            if label and (label != self._label or tenth != self._tenth or done == self.total):
                self.stream.write(f"[{done}/{self.total}] {label}\n")
                self.stream.flush()
            self._label, self._tenth = label, tenth
            return
        filled = int(self.width * done / max(self.total, 1))
        elapsed = time.perf_counter() - self.start
        self.stream.write(f"\r[{'#' * filled}{'.' * (self.width - filled)}] {done}/{self.total} "
                          f"{elapsed:6.1f} s  {label[:40]:40s}")
        self.stream.flush()

    def close(self):
        if self.stream is not None and self.terminal:
            self.stream.write("\r" + " " * (self.width + 60) + "\r")   # leave nothing behind
            self.stream.flush()
