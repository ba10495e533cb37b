"""What a dimensioned inversion does: which links turn fully relative to the fixed one.

Closed forms for the four-link loops of turning and sliding pairs:

* four turning pairs (four-bar): Grashof's law. With s the shortest link, l the longest
  and p, q the others: s + l < p + q, the shortest link turns fully relative to every
  other link (shortest fixed: double crank; shortest next to the fixed link:
  crank-rocker; shortest opposite: double rocker); s + l = p + q, change point, with the
  parallelogram (opposite links equal: double crank), deltoid (equal adjacent links, a
  longer one fixed) and Galloway (equal adjacent links, a shorter one fixed) cases;
  s + l > p + q, no link turns fully: triple rocker.
* one sliding pair (single slider crank chain): with the crank a (the link pinned to the
  guide's link), the rod b, and the offset e of the crank's pivot from the line of the
  block's pin: a turns fully relative to the guide and block when a + e <= b; b does
  when b + e <= a; a and b turn fully relative to each other when |b - a| >= e.
* two adjacent sliding pairs (double slider crank chain, guides not parallel): the bar
  between the two sliders turns fully relative to the others; the sliders and the
  guides' link keep their directions.

Lengths come from the drawn pose (distances between a link's joints). Other chains
of R and P joints with a drawn pose and mobility 1 (six- and eight-bars...) are solved
over a cycle (:func:`chaingraph.kinematics.full_turns`) and the links that make a net turn
relative to the fixed link are reported. Otherwise None.
"""

from __future__ import annotations

import math
from functools import lru_cache

from chaingraph.geometry import distance
from chaingraph.model.chain import Chain, Joint
from chaingraph.kinematics.motion import full_turns, full_turns_cost, full_turns_drivers

__all__ = ["turning_links", "behaviour", "behaviour_key", "behaviour_cost", "four_link_loop"]

_TOL = 1e-9


def four_link_loop(chain: Chain) -> tuple[tuple[str, ...], tuple[Joint, ...]] | None:
    """The chain's links and joints in loop order, when it is a single loop of four
    binary links on four binary R or P joints; else None.

    Returns
    -------
    tuple (links, joints) or None
        ``joints[i]`` joins ``links[i]`` and ``links[(i + 1) % 4]``.
    """
    if len(chain.links) != 4 or len(chain.joints) != 4:
        return None
    if any(j.kind not in ("R", "P") or j.order != 2 for j in chain.joints):
        return None
    if any(len(chain.joints_of(x)) != 2 for x in chain.links):
        return None
    links: list[str] = [chain.links[0]]
    joints: list[Joint] = []
    while len(joints) < 4:
        here = links[-1]
        j = next(j for j in chain.joints_of(here) if j not in joints)
        joints.append(j)
        nxt = j.links[1] if j.links[0] == here else j.links[0]
        if len(joints) < 4:
            if nxt in links:
                return None
            links.append(nxt)
    return tuple(links), tuple(joints)




def _four_bar(links, joints, fixed):
    length = {links[i]: distance(joints[i - 1].at, joints[i].at) for i in range(4)}
    values = sorted(length.values())
    s, p, q, l = values
    scale = max(values)
    grashof = s + l - (p + q)
    opposite = links[(links.index(fixed) + 2) % 4]
    shortest = [x for x in links if length[x] - s <= _TOL * scale]
    if grashof > _TOL * scale:
        return "triple rocker", frozenset()
    if fixed in shortest:
        turning = frozenset(x for x in links if x != fixed)
    else:
        turning = frozenset(shortest)
    if abs(grashof) <= _TOL * scale:
        eq = lambda a, b: abs(length[a] - length[b]) <= _TOL * scale  # noqa: E731
        if eq(links[0], links[2]) and eq(links[1], links[3]):
            return "double crank, parallelogram", turning
        for k in (0, 1):  # a kite: two disjoint pairs of equal adjacent links
            if eq(links[k], links[k + 1]) and eq(links[k + 2], links[(k + 3) % 4]):
                other = next(x for x in links if not eq(x, fixed))
                kind = "deltoid" if length[fixed] > length[other] else "Galloway"
                return "change point, " + kind, turning
        return "change point", turning
    if fixed in shortest:
        return "double crank", turning
    if opposite in shortest:
        return "double rocker", turning
    return "crank-rocker", turning


def _line_offset(point, through, axis_deg):
    """Distance from ``point`` to the line through ``through`` at ``axis_deg``."""
    a = math.radians(axis_deg)
    dx, dy = point[0] - through[0], point[1] - through[1]
    return abs(-math.sin(a) * dx + math.cos(a) * dy)


def _single_slider(links, joints, fixed):
    k = next(i for i, j in enumerate(joints) if j.kind == "P")
    # rotate the loop so that joints = (R G-a, R a-b, R b-B, P B-G)
    links = links[k + 1:] + links[:k + 1]
    joints = joints[k + 1:] + joints[:k + 1]
    guide_side, a, b, block_side = links
    pivot, pin, block_pin, slide = joints
    r = distance(pivot.at, pin.at)
    l_ = distance(pin.at, block_pin.at)
    e = _line_offset(pivot.at, block_pin.at, slide.axis)
    scale = max(r, l_, e, 1e-300)
    tol = _TOL * scale
    a_full = r + e <= l_ + tol
    b_full = l_ + e <= r + tol
    ab_full = abs(l_ - r) >= e - tol
    if fixed in (guide_side, block_side):
        turning = {x for x, ok in ((a, a_full), (b, b_full)) if ok}
    elif fixed == a:
        turning = ({guide_side, block_side} if a_full else set()) | ({b} if ab_full else set())
    else:
        turning = ({guide_side, block_side} if b_full else set()) | ({a} if ab_full else set())
    return frozenset(turning)


def _double_slider(links, joints, fixed):
    k = next(i for i in range(4) if joints[i].kind == "P" and joints[i - 1].kind == "P")
    axes = [joints[k - 1].axis, joints[k].axis]
    if abs(math.sin(math.radians(axes[0] - axes[1]))) < 1e-9:
        return None  # parallel guides: the bar cannot turn, the chain is not this one
    bar = links[(k + 2) % 4]
    others = [x for x in links if x != bar]
    return frozenset(others) if fixed == bar else frozenset({bar})


def turning_links(chain: Chain, fixed: str) -> frozenset[str] | None:
    """The links that make full turns relative to ``fixed``, or None where unknown.

    Known (closed form) for four-link loops of R and P joints with a drawn pose.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> c = chaingraph.load(catalog_path("single-slider-crank-chain"))
    >>> sorted(turning_links(c, "frame")), sorted(turning_links(c, "crank"))
    (['crank'], ['crosshead', 'frame', 'rod'])
    """
    found = _analyse(chain, fixed)
    return None if found is None else found[1]


def behaviour(chain: Chain, fixed: str) -> str | None:
    """What the inversion with ``fixed`` fixed does, in words; None without dimensions.

    Four-bars get Grashof's words; other chains the links that turn fully.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> c = chaingraph.load(catalog_path("four-bar-chain"))
    >>> [behaviour(c, x) for x in c.links]
    ['crank-rocker', 'double crank', 'crank-rocker', 'double rocker']
    """
    found = _analyse(chain, fixed)
    return None if found is None else found[0]


def behaviour_key(chain: Chain, fixed: str) -> tuple[str, object] | None:
    """What two inversions must share to be the same named mechanism, or None.

    For a four-bar, Grashof's category (``"double crank"`` for a parallelogram too);
    for other chains, the set of links that turn fully (compare it through a link
    mapping).
    """
    found = _analyse(chain, fixed)
    if found is None:
        return None
    words, turning = found
    if four_link_loop(chain) and all(j.kind == "R" for j in chain.joints):
        return ("four-bar", words.split(",")[0])
    return ("full turns", turning)


def _solvable(chain):
    """Whether a chain that is no four-link loop has its behaviour solved numerically."""
    return (chain.has_pose and chain.space == "planar" and len(chain.pieces) == 1
            and all(j.kind in ("R", "P") for j in chain.joints))


def behaviour_cost(chain: Chain, fixed: str, *, spent: bool = False) -> float:
    """An estimate, in seconds of one core, of working out the behaviour of the
    inversion with ``fixed`` fixed (:func:`~chaingraph.kinematics.full_turns_cost`): 0
    for a closed form (four-link loops) or where there is nothing to solve; else the
    cycle of the first candidate driver, the least it takes, or, with ``spent`` (once
    it is worked out), of the drivers it tried (those up to one that turns fully, every
    one where none does)."""
    if four_link_loop(chain) is not None or not _solvable(chain):
        return 0.0
    drivers = full_turns_drivers(chain, fixed)
    if not spent:
        return full_turns_cost(chain, fixed, drivers=drivers[:1])
    found = _analyse(chain, fixed, with_driver=True)
    if found is not None and found[2] in found[1]:
        # full_turns stopped at this driver, which turned fully: the ones after it untried
        drivers = drivers[:drivers.index(found[2]) + 1]
    return full_turns_cost(chain, fixed, drivers=drivers)


def _numeric(chain, fixed):
    if not _solvable(chain):
        return None
    found = full_turns(chain, fixed)
    if found is None:
        return None
    turning, driver = found
    order = {x: i for i, x in enumerate(chain.links)}
    words = ", ".join(sorted(turning, key=order.__getitem__))
    return ("full turns: " + words if turning else "no link turns fully"), turning, driver


def _analyse(chain, fixed, *, with_driver=False):
    """(words, turning links) of the inversion, or None; solved once per chain and
    fixed link (behaviour, its key and the turning links all ask for it); with
    ``with_driver``, the driver solved too (None for a closed form)."""
    try:
        found = _analysed(chain, fixed)
    except TypeError:                    # a chain that cannot be hashed: not cached
        found = _analysed.__wrapped__(chain, fixed)
    if found is None:
        return None
    return found if with_driver else found[:2]


@lru_cache(maxsize=1024)
def _analysed(chain, fixed):
    if not chain.has_pose or chain.space != "planar":
        return None
    loop = four_link_loop(chain)
    if loop is None:
        return _numeric(chain, fixed)
    links, joints = loop
    kinds = "".join(j.kind for j in joints)
    n_p = kinds.count("P")
    if n_p == 0:
        return _four_bar(links, joints, fixed) + (None,)
    if n_p == 1:
        turning = _single_slider(links, joints, fixed)
    elif n_p == 2 and ("PP" in kinds or (kinds[0] == "P" and kinds[-1] == "P")):
        turning = _double_slider(links, joints, fixed)
        if turning is None:
            return None
    else:
        return None
    order = {x: i for i, x in enumerate(chain.links)}
    words = ", ".join(sorted(turning, key=order.__getitem__))
    return ("full turns: " + words if turning else "no link turns fully"), turning, None
