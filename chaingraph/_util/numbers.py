"""Figures as a reader expects them: rounding noise taken for what it is."""

from __future__ import annotations

import math
from typing import overload

__all__ = ["tidy"]


@overload
def tidy(value: float, scale: float) -> float: ...
@overload
def tidy(value: None, scale: float) -> None: ...
@overload
def tidy(value: float | None, scale: float) -> float | None: ...
def tidy(value: float | None, scale: float) -> float | None:
    """``value`` (a figure of magnitude up to about ``scale``) as the round number it
    is within rounding of (1e-12 of the scale): the nearest number with six
    significant digits at the scale's magnitude, where that is so near; else as it is
    (a figure that merely happens to lie so near a round number moves by at most 1e-12
    of the scale, far inside the solver's precision).
    The sweep's figures carry rounding that a reader would take for a digit
    (1.35704e-14 for 0, 179.9999999999999 for 180).

    Examples
    --------
    >>> tidy(1.3570374e-14, 360.0), tidy(179.9999999999999, 360.0), tidy(47.1563500001, 360.0)
    (0.0, 180.0, 47.1563500001)
    >>> tidy(1.7000000000000015, 1.0), tidy(None, 1.0)
    (1.7, None)
    """
    if value is None or not math.isfinite(value) or scale <= 0:
        return value
    digits = 6 - math.floor(math.log10(scale))
    near = round(value, digits) + 0.0          # + 0.0: no negative zero
    return near if abs(value - near) <= 1e-12 * scale else value
