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


def test_a_sliding_dyad_s_angle_is_its_rod_s_to_the_guide_s_normal():
    """A four-bar driving a slider through a rod from its coupler-rocker pin B (six
    links, a multiple joint): the four-bar's angle at B, and the rod's (B to D) angle
    to the normal of the slider's fixed guide (along x: its normal is y), within
    [0, 90] as the certification measures a slider crank's. Over the crank's 84 to 132
    degrees the least is the rod's, so that the sliding dyad is seen measured."""
    chain = chaingraph.load(catalog_path("crank-rocker-with-slider"))
    m = chaingraph.solve(chain, start=84.0, stop=132.0, steps=24, summary=False)
    at_b = angle_at(m, "B", "A", "O4")
    rod_x, rod_y = m["x:D"] - m["x:B"], m["y:D"] - m["y:B"]
    to_normal = np.degrees(np.arccos(np.abs(rod_y) / np.hypot(rod_x, rod_y)))
    assert to_normal.min() < at_b.min() - 1.0
    mu = np.concatenate([at_b, to_normal])
    assert transmission_angles(chain, [m]) == pytest.approx((mu.min(), mu.max()), abs=1e-9)


def test_a_shaper_s_angles_are_its_slotted_lever_s_and_its_ram_s():
    """The crank and slotted lever with its ram (two dyads with sliding pairs, no
    four-link loop): the block's dyad (RPR) measures the line through the crank pin B
    and the lever's pivot A against the slot's normal, 90 degrees all the way (the slot
    runs through A); the ram's (RRP) the link (P to R) against the normal of the ram's
    guide (along x)."""
    chain = chaingraph.load(catalog_path("shaper-crank-and-slotted-lever"))
    m = chaingraph.solve(chain, steps=90, summary=False)
    link_x, link_y = m["x:R"] - m["x:P"], m["y:R"] - m["y:P"]
    ram = np.degrees(np.arccos(np.abs(link_y) / np.hypot(link_x, link_y)))
    assert ram.max() < 90.0 - 1e-3          # (so its 90 is the slotted lever's)
    assert transmission_angles(chain, [m]) == pytest.approx((ram.min(), 90.0), abs=1e-9)
