"""Roots of smooth functions of the input, many brackets at once."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from numpy.typing import ArrayLike

import numpy as np

__all__ = ["bracketed_roots"]


def bracketed_roots(f: Callable[[np.ndarray], Any], a: ArrayLike, b: ArrayLike,
                    fa: ArrayLike, fb: ArrayLike, *, newton: bool = False,
                    tol: float = 1e-10, iterations: int = 60) -> np.ndarray:
    """Roots of f between a and b (arrays of brackets with fa, fb of opposite signs),
    all at once: Newton's step (``newton``: f returns the value and its derivative
    per degree) or the secant, kept inside the bracket, with a bisection every other
    step so that the bracket at least halves. Returns the roots."""
    a, b, fa, fb = (np.array(v, dtype=float) for v in (a, b, fa, fb))
    t = 0.5 * (a + b)
    value = slope = np.zeros_like(t)           # the first step is the secant's
    for it in range(iterations):
        with np.errstate(divide="ignore", invalid="ignore"):   # a zero slope: bisect
            if newton and it > 0:
                trial = t - value / slope
            else:
                trial = b - fb * (b - a) / (fb - fa)
        inside = np.isfinite(trial) & ((trial - a) * (trial - b) < 0)
        t = np.where(inside & (it % 2 == 0 or newton), trial, 0.5 * (a + b))
        out = f(t)
        value, slope = out if newton else (out, None)
        left = np.sign(value) == np.sign(fa)
        a, fa = np.where(left, t, a), np.where(left, value, fa)
        b, fb = np.where(left, b, t), np.where(left, fb, value)
        done = (np.abs(b - a) < tol) | (value == 0) | ~np.isfinite(value)
        if done.all():
            break
    return np.where(np.isfinite(t), t, 0.5 * (a + b))
