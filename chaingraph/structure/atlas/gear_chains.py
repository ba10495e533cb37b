"""A chain file for each train of the gear-train atlas: its links, its turning pairs
placed on their axes and its gear pairs with teeth, made so that the geometry holds.

The turning pairs of one axis (one *level* of :func:`~chaingraph.structure.atlas.gears.
train_levels`: the links that turn about one line) are one R joint holding all the links
on that axis (a multiple joint of k links counts k - 1 turning pairs, the first link
holding the others, so the tree of turning pairs keeps its axes: where the links of an
axis form a star in the atlas's tree, the file's pairs are the atlas's). The axes are
parallel and drawn in one plane, each at a height, 36 mm apart, in the order that keeps
the meshing axes nearest (:func:`_heights`). Every gear pair is external, of module 2 mm: its centre distance, the distance
between the two axes, is the sum of the pitch radii, ``m (z_a + z_b) / 2``, so the teeth
add up to the distance in millimetres (36 for neighbouring axes), split in a proportion
that varies from pair to pair (never below 12 teeth, the least an involute pinion of
20 degrees takes with a little undercut) and changed where the numbers made the train
degenerate (two equations dependent, or two links turning together).

The fixed link is the one the atlas's graph hangs from (the link that holds most
turning pairs, the lowest number first: the frame of a textbook train); the driver the
first link journalled on it whose speed, with the fixed link's, fixes the train's (for
F degrees of freedom the file names one driver and its notes the F links to drive).
"""

from __future__ import annotations

import itertools
from collections import deque
from collections.abc import Iterable
from fractions import Fraction

from chaingraph.model.chain import Chain, Joint, Mechanism
from chaingraph.model.chainfile import dumps
from chaingraph.model.gears import GearPair
from chaingraph.structure.atlas.gears import GearEntry, drivers, gear_axes

__all__ = ["gear_chain", "gear_chain_text", "MODULE", "AXIS_STEP", "MIN_TEETH"]

#: the module of every gear (mm): a pitch radius is teeth * MODULE / 2
MODULE = 2.0
#: the distance between neighbouring axes (mm)
AXIS_STEP = 36
#: the fewest teeth a gear of the atlas's files has
MIN_TEETH = 12
#: the most axes whose every order is tried for the nearest gear pairs
_ORDERED_UP_TO = 6

#: the share of a pair's teeth its first gear takes, tried in turn pair by pair
_SHARES = (Fraction(1, 3), Fraction(4, 9), Fraction(5, 12), Fraction(7, 18),
           Fraction(5, 9), Fraction(3, 8), Fraction(11, 24), Fraction(2, 7))


def _heights(levels: tuple[int, ...], axes: list[tuple[int, int]],
             turning: tuple[tuple[int, int], ...]) -> dict[int, int]:
    """Each axis's height (mm), one step apart: in the order that puts the gear pairs'
    axes nearest (the least sum of the steps between them, then the least largest
    step: the smallest wheels), the axes taken first as a breadth-first walk over the
    gear pairs meets them from the axis that holds most links (that walk's order alone
    beyond :data:`_ORDERED_UP_TO` axes)."""
    count = max(levels) + 1
    holds: list[set[int]] = [set() for _ in range(count)]
    for (a, b), level in zip(turning, levels):
        holds[level] |= {a, b}
    start = max(range(count), key=lambda x: (len(holds[x]), -x))
    order, queue, seen = [], deque([start]), {start}
    while queue:
        x = queue.popleft()
        order.append(x)
        for y in sorted({q for p in axes if x in p for q in p} - seen):
            seen.add(y)
            queue.append(y)
    order += [x for x in range(count) if x not in seen]
    if count <= _ORDERED_UP_TO:
        def cost(p: Iterable[int]) -> tuple[int, int]:
            place = {x: i for i, x in enumerate(p)}
            steps = [abs(place[a] - place[b]) for a, b in axes]
            return sum(steps), max(steps)
        order = list(min(itertools.permutations(order), key=cost))
    return {x: AXIS_STEP * i for i, x in enumerate(order)}


def _teeth(total: int, k: int) -> tuple[int, int]:
    """Two numbers of teeth adding up to ``total``, split by share ``k``."""
    first = round(total * _SHARES[k % len(_SHARES)])
    first = min(max(first, MIN_TEETH), total - MIN_TEETH)
    return first, total - first


def _fixed(entry: GearEntry) -> int:
    """The link the atlas's graph hangs from: the one in most turning pairs."""
    return max(range(entry.links), key=lambda v: (sum(v in p for p in entry.turning), -v))


def gear_chain(entry: GearEntry, dof: int = 1) -> Chain:
    """The train ``entry`` as a chain (module text): links ``L1`` .. ``LN`` as the
    atlas numbers them, an R joint per axis (``A``, ``B``, ... as the graph's level
    letters) at its height, a ``[[gears]]`` pair per gear pair (``G1``, ...) with its
    carrier and teeth, and the fixed link and driver in ``[mechanism]``.

    Examples
    --------
    >>> from chaingraph.structure.atlas.gears import gear_atlas
    >>> chain = gear_chain(gear_atlas(4, 1)[0])
    >>> [(j.id, j.links, j.at) for j in chain.joints if j.kind == "R"]
    ... # doctest: +NORMALIZE_WHITESPACE
    [('A', ('L1', 'L2'), (0.0, 0.0)), ('B', ('L1', 'L3'), (0.0, 72.0)),
     ('C', ('L1', 'L4'), (0.0, 36.0))]
    >>> [(g.links, g.teeth, g.carrier) for g in chain.gears]
    [(('L2', 'L4'), (12, 24), 'L1'), (('L3', 'L4'), (16, 20), 'L1')]
    >>> chain.mechanism.fixed, chain.mechanism.driver
    ('L1', 'L2')
    """
    n, name = entry.links, (lambda v: f"L{v + 1}")
    levels, axes = gear_axes(n, entry.turning, entry.gears)
    height = _heights(levels, axes, entry.turning)
    fixed = _fixed(entry)
    near = sorted(range(n), key=lambda v: (not any({v, fixed} == set(p)
                                                   for p in entry.turning), v))
    near.remove(fixed)
    for attempt in range(4 * len(_SHARES)):
        teeth = [_teeth(abs(height[la] - height[lb]) * 2 // int(MODULE), k + attempt)
                 for k, (la, lb) in enumerate(axes)]
        ratios = [Fraction(-zb, za) for za, zb in teeth]
        driven = drivers(n, entry.gears, ratios, fixed, near)
        if driven is not None:
            break
    else:                                   # not met in the atlas up to eight links
        raise ValueError(f"no numbers of teeth found that keep train {entry.key} "
                         "non-degenerate")
    joints = []
    for level in range(max(levels) + 1):
        pairs = [p for p, x in zip(entry.turning, levels) if x == level]
        held = sorted({v for p in pairs for v in p})
        hub = max(held, key=lambda v: (sum(v in p for p in pairs), -v))
        held.remove(hub)
        joints.append(Joint("ABCDEFGHIJ"[level], "R", tuple(map(name, [hub, *held])),
                            at=(0.0, float(height[level]))))
    gears = [GearPair(f"G{k + 1}", (name(a), name(b)), z, False, name(c))
             for k, ((a, b, c), z) in enumerate(zip(entry.gears, teeth))]
    run = " ".join(f"--speed {name(v)}=1" for v in driven)
    notes = (f"Gear train {entry.id} of the atlas of {n} links and {dof} degree"
             f"{'s' if dof != 1 else ''} of freedom, gear pairs {entry.key} (a-b/c: links "
             f"a and b mesh, c carries them). Axes {AXIS_STEP} mm apart, every gear pair "
             f"external, module {MODULE:g} mm (teeth add up to twice the centre distance "
             f"over the module). Run: chaingraph gears FILE"
             + ("" if dof == 1 else f" {run}") + ".")
    return Chain(f"Gear train {entry.id} of {n} links", tuple(joints), family="gear train",
                 units="mm", notes=notes, mechanism=Mechanism(name(fixed), name(driven[0])),
                 gears=tuple(gears))


def gear_chain_text(entry: GearEntry, dof: int = 1) -> str:
    """The chain file (TOML) of :func:`gear_chain`."""
    return dumps(gear_chain(entry, dof))
