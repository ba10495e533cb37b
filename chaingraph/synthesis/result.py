"""What a synthesis returns: certified solutions, best first, and what was rejected.

:class:`Synthesis` (``task``, ``solutions``, ``rejected``, ``searched``) and each
:class:`Solution` are frozen dataclasses; ``to_dict()`` is the JSON of ``chaingraph
design function | path | motion --json`` (the contract's "Synthesis").
"""

from __future__ import annotations

from dataclasses import dataclass, field
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from chaingraph.model.chain import Chain
from chaingraph.model.chainfile import chain_document
from chaingraph.synthesis.task import FunctionTask, MotionTask, PathTask

__all__ = ["Error", "Curve", "Solution", "Searched", "Synthesis", "ranked"]


@dataclass(frozen=True)
class Error:
    """A solution's error, recomputed from its solved motion: ``max`` and ``rms`` (file
    units for points and poses, the output's units for a function), and a pose's
    ``angle`` error (degrees) when there are poses."""

    max: float
    rms: float
    angle: float | None = None

    def to_dict(self) -> dict:
        out: dict[str, float] = {"max": self.max, "rms": self.rms}
        if self.angle is not None:
            out["angle_error"] = self.angle
        return out


@dataclass(frozen=True, eq=False)
class Curve:
    """What a solution's drawing plots beside the mechanism: ``x`` and ``y`` arrays
    (for a function, the task's x and the structural error there) with their axes'
    labels, and the ``marks`` (the precision points' x)."""

    x: np.ndarray
    y: np.ndarray
    x_label: str
    y_label: str
    marks: tuple[float, ...] = ()


@dataclass(frozen=True, eq=False)
class Solution:
    """A certified mechanism: ``mechanism`` (a chain with its ``[task]``, as written),
    its ``error``, ``reached_at`` (the input at each target), ``transmission_angle``
    ``(min, max)`` between the first target and the last (None where the mechanism has
    no four-link loop at its output), ``grashof`` (a four-bar's Grashof words, else
    None), ``input`` (``"turns fully"``, ``"rocks"`` or, a sliding input,
    ``"slides"``: its ``reached_at`` are then slides, file units), ``names`` (catalog
    names of its structure), ``atlas`` (where a type synthesis found it, else None),
    ``curve`` (what its drawing plots) and ``dimensions`` (its lengths and starting
    values by name; not in the JSON, whose ``mechanism`` holds them all)."""

    rank: int
    mechanism: Chain
    error: Error
    reached_at: tuple[float, ...]
    transmission_angle: tuple[float, float] | None
    grashof: str | None
    input: str
    names: tuple[str, ...] = ()
    atlas: dict | None = None
    curve: Curve | None = field(default=None, repr=False)
    dimensions: dict[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict:
        ta = self.transmission_angle
        return {"rank": self.rank, "names": list(self.names), "atlas": self.atlas,
                "mechanism": chain_document(self.mechanism), "error": self.error.to_dict(),
                "reached_at": list(self.reached_at),
                "transmission_angle": None if ta is None else list(ta),
                "grashof": self.grashof, "input": self.input}


@dataclass(frozen=True)
class Searched:
    """The space a synthesis searched: chains, inversions and candidate mechanisms."""

    chains: int
    inversions: int
    candidates: int

    def to_dict(self) -> dict:
        return {"chains": self.chains, "inversions": self.inversions,
                "candidates": self.candidates}


@dataclass(frozen=True, eq=False)
class Synthesis:
    """A synthesis: its ``task``, the certified ``solutions`` best first, the
    ``rejected`` candidates counted by reason, and what was ``searched``."""

    task: FunctionTask | PathTask | MotionTask
    solutions: tuple[Solution, ...]
    rejected: dict[str, int]
    searched: Searched

    def to_dict(self) -> dict:
        """The JSON of ``chaingraph design ... --json``."""
        return {"task": self.task.to_dict(),
                "solutions": [s.to_dict() for s in self.solutions],
                "rejected": dict(self.rejected), "searched": self.searched.to_dict()}

    def __repr__(self) -> str:
        best = (f", best error {self.solutions[0].error.max:.4g}" if self.solutions else "")
        return (f"Synthesis({self.task.kind}, {len(self.solutions)} solutions{best}, "
                f"rejected={dict(self.rejected)})")


def ranked(solutions: Iterable[Solution], limit: int, *, tolerance: float = 0.0,
           key: Callable[[Solution], Any] | None = None) -> tuple[Solution, ...]:
    """Best first (smallest error, then largest least transmission angle; or by
    ``key``, a sort key of a solution, that refines this order), ranked 1, 2... and cut
    to ``limit``; errors within ``tolerance`` count as equal (every exact solution's
    error is rounding)."""
    def default(s):
        ta = s.transmission_angle
        worst = 0.0 if ta is None else min(ta[0], 180.0 - ta[1])
        return (max(s.error.max, tolerance), -worst)
    out = sorted(solutions, key=key or default)[:limit]
    return tuple(Solution(**{**s.__dict__, "rank": k + 1}) for k, s in enumerate(out))
