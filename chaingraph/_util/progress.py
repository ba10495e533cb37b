"""A progress bar on a text stream (stderr), for the report and the atlas."""

from __future__ import annotations

from typing import TextIO

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

    def __init__(self, total: int, stream: TextIO | None, *, width: int = 30,
                 percent: bool = False, start: float | None = None) -> None:
        self.total, self.stream, self.width = total, stream, width
        self.percent = percent                    # show a percentage, not done/total
        self.start = time.perf_counter() if start is None else start
        self._label: str | None = None
        self._tenth: int | None = None

    @property
    def terminal(self) -> bool:
        isatty = getattr(self.stream, "isatty", None)
        return bool(isatty and isatty())

    def show(self, done: int, label: str = "") -> None:
        if self.stream is None:
            return
        if not self.terminal:
            # a plain line when the stage changes (for a percentage: at every tenth
            # alone), and at the end
            tenth = 10 * done // max(self.total, 1)
            changed = tenth != self._tenth or (label != self._label and not self.percent)
            if label and (changed or (done == self.total and label != self._label)):
                self.stream.write(f"[{self._count(done)}] {label}\n")
                self.stream.flush()
            self._label, self._tenth = label, tenth
            return
        filled = int(self.width * done / max(self.total, 1))
        elapsed = time.perf_counter() - self.start
        self.stream.write(f"\r[{'#' * filled}{'.' * (self.width - filled)}] "
                          f"{self._count(done)} {elapsed:6.1f} s  {label[:40]:40s}")
        self.stream.flush()

    def _count(self, done: int) -> str:
        if self.percent:
            return f"{100 * done / max(self.total, 1):3.0f}%"
        return f"{done}/{self.total}"

    def close(self) -> None:
        if self.stream is not None and self.terminal:
            self.stream.write("\r" + " " * (self.width + 60) + "\r")   # leave nothing behind
            self.stream.flush()
