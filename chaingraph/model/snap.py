"""Drawing-level rounding in a file of coordinates: joints typed a hair off the sliding
line they move on are put on it, with a warning; the thresholds that tell rounding from
an offset drawn on purpose.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from chaingraph.errors import DegenerateDrawingError, PoseAdjustedWarning
from chaingraph.geometry import dot, normal, sub

if TYPE_CHECKING:                       # the chain imports this module
    from chaingraph.model.chain import Chain

__all__ = ["snap_to_lines", "check_link_sizes", "size_of", "feature_label", "SILENT", "ROUNDING"]

#: typed positions within this fraction of the mechanism's size are taken as exact
SILENT = 1e-6
#: up to this fraction of the size a typed position is drawing-level rounding: moved to
#: the consistent pose with a warning; beyond it, refused
ROUNDING = 1e-3


def size_of(where: Mapping[str, Sequence[float]]) -> float:
    """The mechanism's size, as the solver takes it: the longer side of the box round
    its joints and points."""
    xs = [p[0] for p in where.values()]
    ys = [p[1] for p in where.values()]
    return max(max(xs) - min(xs), max(ys) - min(ys), 1e-300)


def feature_label(chain: Chain, name: str) -> str:
    """How a message names a joint or point of the chain."""
    return (f"joint {name!r}" if any(j.id == name for j in chain.joints)
            else f"point {name!r}")


def _figure(x):
    return f"{x:.6g}"


def _listed(names):
    quoted = [repr(x) for x in names]
    return quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " and " + quoted[-1]


# -- a drawing that gives a link no size -------------------------------------------------------
def check_link_sizes(chain: Chain) -> None:
    """Refuse a drawn pose in which a link has zero length: a link turned by two or more
    R joints (and set in direction by no sliding pair) whose joints are all drawn at one
    point (within 1e-12 of the mechanism's size): its direction is undefined, and no
    analysis of the drawing means anything. Raises
    :class:`~chaingraph.errors.DegenerateDrawingError` naming the link, its joints and
    the point (the first such link; all the joints at one point are said to be so).

    Examples
    --------
    >>> from chaingraph.model.chain import Chain, Joint
    >>> chain = Chain("four-bar", (
    ...     Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
    ...     Joint("B", "R", ("crank", "coupler"), at=(30.0, 40.0)),
    ...     Joint("C", "R", ("coupler", "rocker"), at=(30.0, 40.0)),
    ...     Joint("D", "R", ("rocker", "frame"), at=(100.0, 0.0))))
    >>> check_link_sizes(chain)
    Traceback (most recent call last):
    ...
    chaingraph.errors.DegenerateDrawingError: four-bar: link 'coupler' has zero length: joints 'B' and 'C' are both drawn at (30, 40)
    """
    if not chain.has_pose:
        return
    where = chain.positions()
    tol = 1e-12 * size_of(where)
    everything = all(math.dist(at, where[chain.joints[0].id]) <= tol for at in where.values())
    for link in chain.links:
        joints = chain.joints_of(link)
        turning = [j for j in joints if j.kind == "R"]
        if len(turning) < 2 or any(j.kind == "P" for j in joints):
            continue
        at = where[turning[0].id]
        if all(math.dist(where[j.id], at) <= tol for j in turning[1:]):
            names = [j.id for j in turning]
            point = f"({_figure(at[0] + 0.0)}, {_figure(at[1] + 0.0)})"
            both = "both" if len(names) == 2 else "all"
            problem = (f"link {link!r} has zero length: joints {_listed(names)} are {both} "
                       f"drawn at {point}")
            if everything:
                problem += (" (every joint of the chain is drawn there: draw the "
                            "mechanism in a pose, or give its lengths)")
            raise DegenerateDrawingError(problem, source=chain.source or chain.name,
                                         link=link, joints=names, at=tuple(at))


# -- drawing-level rounding in a file of coordinates -------------------------------------------
def snap_to_lines(chain: Chain) -> Chain:
    """The chain with every joint or point that lies within drawing-level rounding of a
    sliding line it moves on (an R joint or point of the pair's guide or block, up to
    1e-3 of the mechanism's size off) put on it exactly: the nearest such pose (least
    movement of the typed coordinates, lines included). A joint farther off is an
    offset slider, as drawn.

    Warns with :class:`~chaingraph.errors.PoseAdjustedWarning` when something moved by
    more than 1e-6 of the size; returns the chain itself when nothing moved.

    Examples
    --------
    >>> import warnings
    >>> from chaingraph.model.chain import Chain, Joint
    >>> from chaingraph.model.chain import Mechanism
    >>> engine = Chain("engine", (
    ...     Joint("O", "R", ("frame", "crank"), at=(0.0, 0.0)),
    ...     Joint("A", "R", ("crank", "rod"), at=(20.0, 34.64)),
    ...     Joint("B", "R", ("rod", "piston"), at=(176.2, 0.01)),
    ...     Joint("S", "P", ("frame", "piston"), at=(150.0, 0.0), axis=0.0)),
    ...     mechanism=Mechanism("frame", "crank"))
    >>> with warnings.catch_warnings(record=True) as said:
    ...     warnings.simplefilter("always")
    ...     snapped = snap_to_lines(engine)
    >>> snapped.joint("B").at
    (176.2, 0.0)
    >>> print(said[0].message)  # doctest: +ELLIPSIS
    engine: joint 'B' was 0.01 off the sliding line of S: moved onto it (taken as drawing-level rounding: ...)
    """
    if not chain.has_pose:
        return chain
    where = chain.positions()
    size = size_of(where)
    on = _near_lines(chain, where, size)
    if not any(d > 1e-12 * size for *_, d in on):
        return chain
    # the nearest pose: the typed axes and the fixed link's joints stay as drawn; the
    # other joints and points and the lines' points move as little as they can
    fixed = chain.mechanism.fixed if chain.mechanism else None
    anchored = {x.id for x in chain.joints if fixed in x.links}
    anchored |= {p.id for p in chain.points if p.link == fixed}
    features = sorted(({name for _, name, _ in on} | {p for p, _, _ in on}) - anchored)
    if not features:
        return chain
    index = {name: 2 * i for i, name in enumerate(features)}
    x0 = np.array([v for name in features for v in where[name]])
    x = _nearest_pose(chain, on, index, x0, where)
    if max(abs(dot(normal(math.radians(_axis(chain, p))),
                   _position(name, x, index, where) - _position(p, x, index, where)))
           for p, name, _ in on) > 1e-12 * size:
        return chain      # the fixed link's joints themselves disagree: leave it as drawn
    moved = sorted(((math.dist(x[index[f]:index[f] + 2], x0[index[f]:index[f] + 2]), f)
                    for f in features), reverse=True)
    joints = [replace(j, at=(float(x[index[j.id]]), float(x[index[j.id] + 1])))
              if j.id in index else j for j in chain.joints]
    points = [replace(p, at=(float(x[index[p.id]]), float(x[index[p.id] + 1])))
              if p.id in index else p for p in chain.points]
    snapped = replace(chain, joints=tuple(joints), points=tuple(points))
    if moved[0][0] > SILENT * size:
        _warn_moved(chain, on, moved, size)
    return snapped


def _axis(chain: Chain, joint: str) -> float:
    """A drawn P joint's axis (degrees): validation gives one to every P joint drawn."""
    axis = chain.joint(joint).axis
    assert axis is not None, f"the P joint {joint!r} is drawn without an axis"
    return axis


def _near_lines(chain, where, size):
    """(P joint, feature, distance) for every R joint or point of a sliding pair's
    guide or block within drawing-level rounding of its sliding line."""
    on = []
    for j in chain.joints:
        if j.kind != "P":
            continue
        n = normal(math.radians(j.axis))
        names = {x.id for link in j.links for x in chain.joints_of(link) if x.kind == "R"}
        names |= {p.id for p in chain.points if p.link in j.links}
        for name in sorted(names):
            d = abs(dot(n, sub(where[name], j.at)))
            if d <= ROUNDING * size:
                on.append((j.id, name, d))
    return on


def _position(name, x, index, where):
    """A feature's position: from the coordinates ``x`` if it moves, else as drawn."""
    return x[index[name]:index[name] + 2] if name in index else np.array(where[name])


def _nearest_pose(chain, on, index, x0, where):
    """The moving features' coordinates nearest ``x0`` that put each feature of ``on``
    on its line. Each constraint n . (feature - line point) = 0 is linear in the
    positions (the axes stay), so one minimum-norm step lands on it."""
    rows, res = [], []
    for p, name, _ in on:
        n = np.array(normal(math.radians(chain.joint(p).axis)))
        row = np.zeros(len(x0))
        for f, sign in ((name, 1.0), (p, -1.0)):
            if f in index:
                row[index[f]:index[f] + 2] += sign * n
        rows.append(row)
        res.append(float(n @ (_position(name, x0, index, where) - _position(p, x0, index, where))))
    J, r = np.array(rows), np.array(res)
    return x0 - J.T @ np.linalg.lstsq(J @ J.T, r, rcond=None)[0]


def _warn_moved(chain, on, moved, size):
    """Say what moved most, from how far off its line, and how many others moved."""
    far = max((d, p, name) for p, name, d in on)
    others = sum(1 for d, _ in moved[1:] if d > SILENT * size)
    more = f" (and {others} other{'s' if others > 1 else ''} less)" if others else ""
    units = f" {chain.units}" if chain.units else ""
    d, p, name = far
    how = ("moved onto it" if moved[0][1] == name else
           f"{feature_label(chain, moved[0][1])} moved {_figure(moved[0][0])}{units} to put it on it")
    warnings.warn(PoseAdjustedWarning(
        f"{chain.source or chain.name}: {feature_label(chain, name)} was {_figure(d)}{units} off "
        f"the sliding line of {p}: {how}{more} (taken as drawing-level rounding: up to "
        f"1e-3 of the size {_figure(size)}; an offset slider is drawn farther off)",
        joint=moved[0][1], distance=moved[0][0], size=size), stacklevel=4)
