"""The command line's output paths, checked before the work starts (a folder where a file
is wanted, no permission, an unknown picture format), and writes that fail midway
turned into one line naming the output."""

from __future__ import annotations

import os
from pathlib import Path
from types import TracebackType
from typing import Literal

from chaingraph.errors import ChainGraphError, OutputError

__all__ = ['write_text', 'Writing', 'output_file', 'output_folder', 'picture_file', 'svg_file']


def write_text(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` to ``path`` (checked first), or OutputError naming it."""
    output_file(path)
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    except OSError as e:
        raise OutputError(path, f"cannot be written ({e.strerror})") from None

class Writing:
    """Turn a write that fails midway (a full disk, a lost mount) into one line naming
    the output."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = path

    def __enter__(self) -> Writing:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> Literal[False]:
        if isinstance(error, OSError) and not isinstance(error, ChainGraphError):
            raise OutputError(error.filename or self.path,
                              f"cannot be written ({error.strerror or error})") from None
        return False

def _existing_folder_above(path: str | os.PathLike[str]) -> Path:
    """The nearest folder above ``path`` that exists, or OutputError when a file is in
    the way."""
    above = Path(os.path.abspath(path)).parent
    while not above.exists():
        above = above.parent
    if not above.is_dir():
        raise OutputError(path, f"{above} is a file, not a folder")
    return above

def output_file(path: str | os.PathLike[str], *, what: str = "output") -> Path:
    """Check a file to write before the work starts, and make its missing folders."""
    p = Path(path)
    if p.is_dir():
        raise OutputError(path, f"is a folder; give a file name for the {what}")
    above = _existing_folder_above(p)
    if not os.access(above, os.W_OK | os.X_OK):
        raise OutputError(path, f"no permission to write in {above}")
    if p.exists() and not os.access(p, os.W_OK):
        raise OutputError(path, "no permission to write it")
    p.parent.mkdir(parents=True, exist_ok=True)
    return p

def output_folder(path: str | os.PathLike[str], *, what: str = "output") -> Path:
    """Check a folder to write into before the work starts, and make it."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise OutputError(path, f"is a file; the {what} needs a folder")
    above = _existing_folder_above(p) if not p.exists() else p
    if not os.access(above, os.W_OK | os.X_OK):
        raise OutputError(path, f"no permission to write in {above}")
    p.mkdir(parents=True, exist_ok=True)
    return p

def picture_file(path: str | os.PathLike[str], *, what: str) -> Path:
    """An output picture: a known format (by the file's ending), then as output_file."""
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix:
        from matplotlib.backend_bases import FigureCanvasBase
        formats = FigureCanvasBase.get_supported_filetypes()
        if suffix not in formats:
            raise OutputError(path, f"unknown picture format '.{suffix}' for the {what}; "
                                    f"one of {', '.join('.' + f for f in sorted(formats))}")
    return output_file(path, what=what)


def svg_file(path: str | os.PathLike[str], *, what: str) -> Path:
    """An output drawn as SVG only: a ``.svg`` file, then as :func:`output_file`."""
    if not str(path).lower().endswith(".svg"):
        raise OutputError(path, f"the {what} are drawn as SVG: give a .svg file")
    return output_file(path, what="drawing")
