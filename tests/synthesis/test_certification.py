"""The certification's transmission angle of a mechanism of more than four links: its
dyads' (the angle at each dyad's middle joint between its two links) and a group's
(at each turning pair between two of its links), measured on the solver's motion of
the written file, as the atlas families' screen measures them."""

import numpy as np
import pytest

import chaingraph
from chaingraph.naming.catalog import catalog_path
from chaingraph.synthesis.certification import (PointTargets, Rejected, certify,
                                                transmission_angles)


def angle_at(m, at, one, other):
    """The angle (degrees) at joint ``at`` between the lines to joints ``one`` and
    ``other``, from the motion's columns, by the cosine rule."""
    p = np.array([m[f"x:{at}"], m[f"y:{at}"]])
    u = np.array([m[f"x:{one}"], m[f"y:{one}"]]) - p
    v = np.array([m[f"x:{other}"], m[f"y:{other}"]]) - p
    cos = np.sum(u * v, axis=0) / np.linalg.norm(u, axis=0) / np.linalg.norm(v, axis=0)
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


@pytest.mark.parametrize("name, corners", [
    # two four-bars in series: the coupler and rocker at B, the second coupler and the
    # output at D
    ("watt-ii-mechanism", [("B", "A", "O2"), ("D", "C", "O3")]),
    # a group of four links (a triad and the rocker): at each pair between two of them,
    # each link's line to its first other joint
    ("stephenson-iii-mechanism", [("A", "E", "B"), ("B", "A", "G"), ("C", "E", "D"),
                                  ("D", "C", "G")]),
])
def test_a_six_bar_s_transmission_angle_is_its_dyads_or_its_group_s(name, corners):
    chain = chaingraph.load(catalog_path(name))
    m = chaingraph.solve(chain, steps=90, summary=False)
    mu = np.concatenate([angle_at(m, *c) for c in corners])
    assert transmission_angles(chain, [m]) == pytest.approx((mu.min(), mu.max()), abs=1e-9)


def test_a_six_bar_whose_transmission_leaves_the_bound_is_rejected():
    """The Watt II traced through four of its output joint's places: certified with
    its transmission angle, rejected where the bound asks more than its least."""
    chain = chaingraph.load(catalog_path("watt-ii-mechanism"))
    start = float(chaingraph.solve(chain, summary=False)["theta"][0])
    m = chaingraph.solve(chain, start=start, stop=start + 90.0, steps=3, summary=False)
    targets = PointTargets(tuple((float(x), float(y)) for x, y in zip(m["x:D"], m["y:D"])),
                           "D")
    found = certify(chain, targets, min_transmission=0.0)
    assert not isinstance(found, Rejected)
    low, high = found.transmission_angle
    assert 0.0 < low <= high < 180.0
    worst = min(low, 180.0 - high)
    assert not isinstance(certify(chain, targets, min_transmission=worst - 0.5), Rejected)
    refused = certify(chain, targets, min_transmission=worst + 0.5)
    assert isinstance(refused, Rejected) and refused.reason == "transmission angle"
