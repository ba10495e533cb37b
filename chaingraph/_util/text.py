"""Small helpers shared by every layer (text for reprs)."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import TextIO

from numpy.typing import ArrayLike

import csv
import io

import numpy as np

__all__ = ["counted", "freedom", "short_list", "write_columns", "csv_text"]


def counted(n: int, singular: str, plural: str | None = None) -> str:
    """``n`` (with thousands separated) and the noun, singular for one:
    ``counted(1, "degree of freedom", "degrees of freedom")``; the plural is the
    singular with an ``s`` unless given.

    Examples
    --------
    >>> counted(1, "degree of freedom", "degrees of freedom"), counted(2, "chain")
    ('1 degree of freedom', '2 chains')
    >>> counted(0, "sliding pair"), counted(3107, "chain")
    ('0 sliding pairs', '3,107 chains')
    """
    return f"{n:,} {singular if n == 1 else plural or singular + 's'}"


def freedom(dof: int) -> str:
    """``dof`` degrees of freedom, in words: singular for one.

    Examples
    --------
    >>> freedom(1), freedom(2)
    ('1 degree of freedom', '2 degrees of freedom')
    """
    return counted(dof, "degree of freedom", "degrees of freedom")


def short_list(items: Sequence[object], keep: int = 6) -> str:
    """``[a, b, c, ... (N)]``: a list cut to ``keep`` items for a repr.

    Examples
    --------
    >>> short_list(["theta", "x:A", "y:A"], keep=2)
    "['theta', 'x:A', ... (3)]"
    """
    items = list(items)
    if len(items) <= keep:
        return repr(items)
    return "[" + ", ".join(repr(x) for x in items[:keep]) + f", ... ({len(items)})]"


def write_columns(out: TextIO, columns: Mapping[str, ArrayLike], rows: int, *,
                  block: int = 20_000) -> None:
    """Named columns (arrays of ``rows`` values) to ``out`` as CSV: a header, then one
    line per row; numbers as Python writes them (the shortest text that reads back to
    the same float), ``nan`` where there is no value; in blocks of rows, so memory does
    not grow with the length."""
    names = list(columns)
    header = io.StringIO()
    csv.writer(header, lineterminator="\n").writerow(names)
    out.write(header.getvalue())
    arrays = [np.broadcast_to(np.asarray(columns[n], dtype=float), (rows,)) for n in names]
    for s in range(0, rows, block):
        texts = []
        for column in arrays:
            part = column[s:s + block]
            text = list(map(repr, part.tolist()))
            if not np.isfinite(part).all():
                for i in np.flatnonzero(~np.isfinite(part)):
                    text[i] = "nan"
            texts.append(text)
        out.write("".join(",".join(row) + "\n" for row in zip(*texts)))


def csv_text(columns: Mapping[str, ArrayLike], rows: int,
             path: str | os.PathLike[str] | None = None) -> str | None:
    """:func:`write_columns` to the file ``path``, or, when ``path`` is None, to a
    string that is returned (a result's ``to_csv``)."""
    if path is None:
        buf = io.StringIO()
        write_columns(buf, columns, rows)
        return buf.getvalue()
    with open(path, "w", encoding="utf-8", newline="") as f:
        write_columns(f, columns, rows)
    return None
