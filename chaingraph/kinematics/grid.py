"""A mechanism with two moving inputs over every pair of their values: the poses the
report's player needs to move its two sliders independently."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from chaingraph.errors import ChainGraphError
from chaingraph.kinematics.motion import Motion, solve
from chaingraph.model.chain import Chain, Input

__all__ = ["input_grid"]


def input_grid(chain: Chain, motion: Motion, *, size: int = 13) -> Motion | None:
    """For a mechanism whose two inputs move, its poses over every pair of input
    values (``size`` values of each over its sweep), as one motion whose rows run
    through the first input for each value of the second: what lets the player's two
    sliders move independently. None when the inputs are not two moving ones, or when
    some pair of values cannot be assembled."""
    if len(motion.inputs) != 2 or motion.plan.moving_inputs != 2:
        return None
    first, second = (np.asarray(motion.values[i.joint]) for i in motion.inputs)
    rows = []
    for value in np.linspace(second[0], second[-1], size):
        try:
            rows.append(solve(chain, inputs=[Input(motion.inputs[0].joint, float(first[0]),
                                                   float(first[-1])),
                                             Input(motion.inputs[1].joint, float(value),
                                                   float(value))],
                              steps=size - 1, summary=False))
        except ChainGraphError:
            return None
    return replace(rows[0].joined(*rows[1:]), name=motion.name, fixed=motion.fixed,
                   driver=None, omega=motion.omega, summary=None, units=motion.units,
                   inputs=motion.inputs)
