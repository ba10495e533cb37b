"""The numbers and values of a chain file: what is accepted, and how a bad one is named
in a message (every reader of the format uses these)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NoReturn, TypeAlias

__all__ = ["LARGEST", "number", "type_name", "shown"]


LARGEST = 1e9

#: how a reader refuses a value: ``fail(message, where)`` raises
Fail: TypeAlias = Callable[[str, str], NoReturn]


def number(value: object, where: str, fail: Fail, *, positive: bool = False) -> float:
    """A finite number of at most :data:`LARGEST` in size (a float), or ``fail``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        fail(f"must be a number, got {type_name(value)}", where)
    if isinstance(value, float) and not math.isfinite(value):
        fail(f"must be a finite number, got {value}", where)
    if abs(value) > LARGEST:                 # (compares an integer of any size exactly)
        fail(f"{shown(value)} is too large: at most {LARGEST:g} in size", where)
    if positive and value <= 0:
        fail(f"a length must be positive, got {value:g}", where)
    return float(value)


def type_name(value: object) -> str:
    """What kind of TOML value ``value`` is, in words ("a string", "an array")."""
    return {bool: "a boolean", int: "an integer", float: "a number", str: "a string",
            list: "an array", dict: "a table"}.get(type(value), f"a {type(value).__name__}")


def shown(value: object) -> str:
    """A value as a message quotes it: short, and never a huge integer's digits."""
    if isinstance(value, int) and abs(value) > 10**30:
        # (no decimal text of a huge integer: Python refuses past 4,300 digits)
        return f"an integer of about {int(value.bit_length() * 0.30103) + 1:,} digits"
    if isinstance(value, list):
        text = "[" + ", ".join(shown(v) for v in value[:4]) + (", ...]" if len(value) > 4 else "]")
    else:
        text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."
