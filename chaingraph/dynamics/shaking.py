"""The shaking force and moment: what the moving links put on the frame.

By d'Alembert's principle the frame's forces on the moving links (its joints'
reactions and the inputs' efforts) balance their weights, the loads on them and their
inertia forces and couples; so the moving links put on the frame the sum of those,

    F_s = sum (m g + loads) - sum m a_G,
    M_s = sum r x (m g + loads - m a_G) + sum (load torques - I alpha),

the moment taken about the drawing's origin (the drawn coordinates' (0, 0)). The input's
effort is between the frame and a moving link, like a joint's reaction: it is part of
what the frame carries, not of what it is given. Friction, between links, is too.

:func:`shaking` takes these from the force solve's own applied forces and couples
(:class:`~chaingraph.dynamics.equilibrium.Solution`), so every kind of load the solve
knows is in it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from chaingraph.dynamics.equilibrium import Solution

__all__ = ["Shaking", "shaking", "largest_size", "INERTIA"]

#: the names of the applied forces and couples that are the links' inertia
INERTIA = ("inertia force", "inertia couple")


@dataclass(frozen=True, eq=False)
class Shaking:
    """The shaking force (``fx``, ``fy``, N) and moment (``moment``, N m, about the
    drawing's origin, counter-clockwise) the moving links put on the frame, per step
    (NaN where the motion is not determined)."""

    fx: np.ndarray
    fy: np.ndarray
    moment: np.ndarray

    @property
    def force(self) -> np.ndarray:
        """The shaking force's size per step (N)."""
        return np.hypot(self.fx, self.fy)

    def largest(self) -> tuple[float | None, float | None]:
        """The largest shaking force (N) and moment (N m, in size) over the steps where
        they are determined; None where nowhere."""
        return largest_size(self.force), largest_size(self.moment)


def largest_size(values: ArrayLike) -> float | None:
    """The largest size (absolute value) of ``values`` where they are finite; None
    where none is."""
    v = np.abs(np.asarray(values, dtype=float))
    v = v[np.isfinite(v)]
    return float(v.max()) if v.size else None


def shaking(solution: Solution, n: int, *, origin: tuple[float, float] = (0.0, 0.0),
            metres: float = 1.0, inertia_only: bool = False) -> Shaking:
    """The shaking force and moment of a force solve's ``solution`` at its ``n`` steps.

    Parameters
    ----------
    solution : Solution
        The force solve's (its ``applied`` forces in metres about the plan's origin).
    n : int
        The number of steps.
    origin : (float, float)
        The plan's origin in file units (the solve's points are about it); the moment is
        taken about the drawing's (0, 0).
    metres : float
        The file's length unit in metres.
    inertia_only : bool
        Only the links' inertia (minus the sum of m a_G and of I alpha): the part that
        counterweights change, without the weights and the loads.
    """
    fx, fy, m = np.zeros(n), np.zeros(n), np.zeros(n)
    ox, oy = origin[0] * metres, origin[1] * metres
    for _link, what, q, f in solution.applied:
        if what.startswith("effort") or (inertia_only and what not in INERTIA):
            continue
        gx, gy = np.asarray(f[0], dtype=float), np.asarray(f[1], dtype=float)
        fx = fx + gx
        fy = fy + gy
        m = m + (np.asarray(q[0]) + ox) * gy - (np.asarray(q[1]) + oy) * gx
    for _link, what, value in solution.couples:
        if what.startswith("effort") or (inertia_only and what not in INERTIA):
            continue
        m = m + np.asarray(value, dtype=float)
    shape = (n,)
    return Shaking(np.broadcast_to(fx, shape).copy(), np.broadcast_to(fy, shape).copy(),
                   np.broadcast_to(m, shape).copy())
