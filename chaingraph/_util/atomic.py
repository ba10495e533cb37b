"""Writing so that a reader never sees a half-made result: a file appears whole (written
under a temporary name, then renamed), and a folder of pages is built where nobody
looks and moved into place at the end, its index last, after the old index is
withdrawn. An interrupted run leaves the old result as it was, or no index at all:
never an index beside a mixture of old and new pages.
"""

from __future__ import annotations

from collections.abc import Iterator

import contextlib
import os
import shutil
import tempfile
from pathlib import Path

__all__ = ["write_atomic", "withdraw", "staged", "INDEX"]

#: the page that presents a folder as a complete result
INDEX = "index.html"


def write_atomic(path: str | os.PathLike[str], text: str | bytes, *,
                 encoding: str | None = "utf-8") -> Path:
    """Write ``text`` (str, or bytes when ``encoding`` is None) to ``path`` under a
    temporary name beside it, then rename it onto ``path``: the file is never seen half
    written, even when the run is interrupted."""
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    try:
        if isinstance(text, bytes):
            tmp.write_bytes(text)
        else:
            tmp.write_text(text, encoding=encoding)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path


def withdraw(folder: str | os.PathLike[str], name: str = INDEX) -> None:
    """Remove ``folder/name`` (by default the index) before the folder is rewritten,
    so that what follows, until a new index is written, is not presented as complete."""
    Path(folder, name).unlink(missing_ok=True)


@contextlib.contextmanager
def staged(folder: str | os.PathLike[str], *, last: str = INDEX) -> Iterator[Path]:
    """Build a folder's new content in a hidden temporary folder inside it, and move
    it into place when the block ends without an error: the old ``last`` (the index)
    is withdrawn first, every other file moved over the old one, ``last`` moved at the
    end. When the block is interrupted or fails, the temporary folder is removed and
    ``folder`` is left exactly as it was.

    Yields the temporary folder (on the same file system, so every move is a rename).

    Examples
    --------
    >>> import tempfile
    >>> out = Path(tempfile.mkdtemp())
    >>> with staged(out) as stage:
    ...     _ = (stage / "page.html").write_text("new")
    ...     _ = (stage / "index.html").write_text("index")
    >>> sorted(p.name for p in out.iterdir())
    ['index.html', 'page.html']
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=".partial-", dir=folder))
    try:
        yield stage
        files = sorted(p for p in stage.rglob("*") if p.is_file())
        withdraw(folder, last)
        for path in sorted(files, key=lambda p: p.relative_to(stage) == Path(last)):
            target = folder / path.relative_to(stage)
            target.parent.mkdir(parents=True, exist_ok=True)
            os.replace(path, target)
    finally:
        shutil.rmtree(stage, ignore_errors=True)
