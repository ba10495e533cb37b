"""A synthesised mechanism's picture: targets small beside the mechanism are shown again,
enlarged, with the path of the point that passes through them."""

import math

import numpy as np

import chaingraph
from chaingraph.drawing.synthesis import draw_synthesis
from chaingraph.model.chain import Chain, Joint, Mechanism, Point


def _crank_rocker(crank):
    """Frame 70, coupler 60, rocker 50, the crank given; P on the coupler."""
    joints = (Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
              Joint("B", "R", ("crank", "coupler"), at=(crank, 0.0)),
              Joint("C", "R", ("coupler", "rocker"), at=(70.0 - 50.0 * math.cos(1.2),
                                                         50.0 * math.sin(1.2))),
              Joint("D", "R", ("rocker", "frame"), at=(70.0, 0.0)))
    return Chain("crank-rocker", joints, points=(Point("P", "coupler", (40.0, 60.0)),),
                 mechanism=Mechanism("frame", "crank", 1.0, "P"))


def _targets(chain, picks):
    m = chaingraph.solve(chain, steps=360, summary=False)
    return [(float(m["x:P"][k]), float(m["y:P"][k])) for k in picks]


def test_small_targets_get_an_enlarged_panel_with_the_path_through_them():
    chain = _crank_rocker(4.0)                       # a short crank: a small coupler curve
    targets = _targets(chain, [0, 60, 120, 180, 240, 300])
    fig = draw_synthesis(chain, at=0.0, targets=targets)
    assert len(fig.axes) == 2
    panel = fig.axes[1]
    (x0, x1), (y0, y1) = panel.get_xlim(), panel.get_ylim()
    for x, y in targets:                             # every target inside the panel
        assert x0 < x < x1 and y0 < y < y1
    path = next(line for line in panel.get_lines() if "path of P" in line.get_label())
    xs, ys = path.get_data()
    # the path drawn passes through every target (they were taken from it)
    for x, y in targets:
        assert np.hypot(np.asarray(xs) - x, np.asarray(ys) - y).min() <= 1e-9 * 70


def test_targets_the_size_of_the_mechanism_need_no_second_panel():
    chain = _crank_rocker(20.0)
    fig = draw_synthesis(chain, at=0.0, targets=_targets(chain, [0, 90, 180, 270]))
    assert len(fig.axes) == 1
