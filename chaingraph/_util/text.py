"""Small helpers shared by every layer (text for reprs)."""

from __future__ import annotations

__all__ = ["short_list"]


def short_list(items, keep=6) -> str:
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
