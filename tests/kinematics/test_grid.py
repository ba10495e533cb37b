"""The grid of a mechanism with two moving inputs: its poses over every pair of values."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph.kinematics.grid import input_grid
from chaingraph.naming.catalog import catalog_path

ROBOT = Path(__file__).parents[2] / "examples" / "five-bar-robot.toml"


def test_the_five_bar_robot_s_grid_holds_its_pose_at_every_pair_of_input_values():
    """Rows run through the first input for each value of the second; every row is the
    pose solved at that pair on its own."""
    chain = chaingraph.load(ROBOT)
    motion = chaingraph.solve(chain, steps=12)
    grid = input_grid(chain, motion, size=5)
    a, e = grid["input:A"], grid["input:E"]
    assert a.size == e.size == 25
    np.testing.assert_allclose(a.reshape(5, 5), np.tile(np.linspace(70.0, 130.0, 5), (5, 1)))
    np.testing.assert_allclose(e.reshape(5, 5).T, np.tile(np.linspace(110.0, 50.0, 5), (5, 1)))
    for k in (0, 7, 13, 24):
        one = chaingraph.solve(chain, inputs=[("A", a[k], a[k]), ("E", e[k], e[k])], steps=1,
                               summary=False)
        for key in ("x:pen", "y:pen", "x:C", "y:C"):
            assert grid[key][k] == pytest.approx(one[key][0], abs=1e-9)


def test_one_input_has_no_grid():
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    assert input_grid(chain, chaingraph.solve(chain, steps=12)) is None
