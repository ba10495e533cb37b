"""A mechanism's dimensions as the textbook gives them: link lengths, sliding lines, the
input's value in the drawn pose, and the assembly mode of each part that has two.

This module reads the dimension keys of a chain document (the ``[lengths]`` and
``[assembly]`` tables and the joints' ``offset``, ``angle``, ``near`` keys) into a
:class:`Dimensions` value, and turns one link's lengths into its shape: the positions
of its joints and points in the link's own frame. :mod:`chaingraph.kinematics.assembly` puts the
shapes together into the drawn pose.

A link's frame (used by the sliding lines' ``offset`` and ``angle``): its joints and
points in id order; the first is the origin and the reference line runs from it to the
second. A link with a single joint or point takes its first sliding pair's line (by
joint id) as its reference line; a link with none has its origin on that line. The
fixed link's frame is the drawing's.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Collection, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any, NoReturn

from chaingraph.geometry import Vec, rotate, sub
from chaingraph.model.chain import Joint
from chaingraph.model.values import Fail, number

__all__ = ["Dimensions", "LineSpec", "link_features", "link_shape", "parse_dimensions",
           "MODE_WORDS", "split_key"]

#: the words of an assembly mode: a joint placed from two known joints lies left or
#: right of the line through them; a joint placed on a sliding line lies ahead of or
#: behind the other known joint along the sliding direction
MODE_WORDS = {"left": 1, "right": -1, "ahead": 1, "behind": -1}

JOINT_KEYS = ("offset", "angle", "block_offset", "block_angle", "near")


@dataclass(frozen=True)
class LineSpec:
    """A sliding line on one link, in that link's frame: its direction ``angle``
    (degrees CCW from the link's reference line) and its signed distance ``offset``
    from the link's origin (positive to the left of the sliding direction)."""

    angle: float = 0.0
    offset: float = 0.0


@dataclass(frozen=True, eq=False)
class Dimensions:
    """The dimension keys of one chain document.

    Attributes
    ----------
    lengths : dict
        ``{link: {(a, b): distance, (a, b, c): angle at b in degrees}}`` as given.
    directions : dict
        ``{link: degrees}``: the direction of the reference line of a fixed link given
        by lengths.
    lines : dict
        ``{(joint, link): LineSpec}`` for the sliding lines given by offset and angle.
    modes : dict
        ``{joint: word}`` for dyads, ``{link: {joint or point: word}}`` for the side of a
        link's third joint; the words are those of :data:`MODE_WORDS`.
    values : dict
        ``{joint: value}``: each input's value in the drawn pose (degrees, or the slide
        in length units); the key ``None`` holds a ``driver``'s angle.
    typed : dict
        ``{joint or point: (x, y)}``: the coordinates the file gives (``at``).
    axes : dict
        ``{joint: degrees}``: the ``axis`` the file gives for P joints.
    near : dict
        ``{joint or point: (x, y)}``: rough positions that choose the assembly.
    """

    lengths: dict[str, dict[tuple[str, ...], float]] = field(default_factory=dict)
    directions: dict[str, float] = field(default_factory=dict)
    lines: dict[tuple[str, str], LineSpec] = field(default_factory=dict)
    modes: dict[str, str | dict[str, str]] = field(default_factory=dict)
    values: dict[str | None, float] = field(default_factory=dict)
    typed: dict[str, tuple[float, float]] = field(default_factory=dict)
    axes: dict[str, float] = field(default_factory=dict)
    near: dict[str, tuple[float, float]] = field(default_factory=dict)


def link_features(joints: Iterable[Joint], points: Iterable[tuple[str, str]], link: str,
                  ) -> list[str]:
    """The ids of the R joints and points on ``link``, in id order (the order that
    fixes the link's frame)."""
    ids = [j.id for j in joints if j.kind == "R" and link in j.links]
    ids += [p_id for p_id, p_link in points if p_link == link]
    return sorted(ids)


def split_key(key: str, features: Collection[str]) -> tuple[str, ...] | None:
    """The joints a ``[lengths]`` key names: ``"A-B"`` (a distance) or ``"A-B-C"`` (the
    angle at B), split where every part is one of ``features``; None when no split or
    more than one works.

    Examples
    --------
    >>> split_key("B-C", ["B", "C", "E"])
    ('B', 'C')
    >>> split_key("A-1-B", ["A-1", "B"])
    ('A-1', 'B')
    >>> split_key("C-B-E", ["B", "C", "E"])
    ('C', 'B', 'E')
    """
    parts = key.split("-")
    found: list[tuple[str, ...]] = []

    def walk(i: int, names: list[str]) -> None:
        if i == len(parts):
            if len(names) in (2, 3):
                found.append(tuple(names))
            return
        for k in range(i + 1, len(parts) + 1):
            name = "-".join(parts[i:k])
            if name in features:
                walk(k, names + [name])

    walk(0, [])
    return found[0] if len(found) == 1 else None


def _single_joint(link: str, joint: str, joints: Iterable[Joint],
                  points: Iterable[tuple[str, str]]) -> str:
    """Why one number cannot be the length of ``link``, which has a single joint or
    point, and the likely cause: another link of a single joint whose name looks like
    this one (a misspelling in some joint's ``links`` makes a link of its own)."""
    count: dict[str, list[str]] = {}
    for j in joints:
        for x in j.links:
            count.setdefault(x, []).append(j.id)
    for pid, plink in points:
        count.setdefault(plink, []).append(pid)
    lonely = [x for x, ids in count.items() if len(ids) == 1 and x != link]
    alike = difflib.get_close_matches(link, lonely, n=1, cutoff=0.6)
    text = (f"{link!r} has a single joint ({joint}), so it has no length to give: a link "
            "needs two joints or points")
    if alike:
        other = alike[0]
        text += (f"; {other!r} has a single joint too ({count[other][0]}) and looks like "
                 f"{link!r}: is it misspelt in the links of joint {count[other][0]!r}?")
    else:
        text += "; check the links of the joints (a misspelt name makes a link of its own)"
    return text


def parse_dimensions(doc: dict[str, Any], joints: Sequence[Joint],
                     points: Sequence[tuple[str, str]], fail: Fail) -> Dimensions:
    """Read the dimension keys of ``doc`` (a parsed chain document that has a
    ``[lengths]`` table). ``joints`` are the parsed joints (without coordinates),
    ``points`` ``(id, link)`` pairs; ``fail(problem, where)`` raises the file's error."""
    links = sorted({x for j in joints for x in j.links})
    point_ids = {pid for pid, _ in points}
    lengths: dict[str, dict[tuple[str, ...], float]] = {}
    directions: dict[str, float] = {}
    table = doc["lengths"]
    if not isinstance(table, dict):
        fail("'lengths' must be a table ([lengths]) of links", "[lengths]")
    for link, value in table.items():
        where = f"[lengths] {link!r}"
        if link not in links:
            fail(f"names no link of the chain (links: {', '.join(links)})", where)
        features = link_features(joints, points, link)
        if isinstance(value, dict):
            entries: dict[tuple[str, ...], float] = {}
            for key, x in value.items():
                if key == "direction":
                    directions[link] = number(x, f"{where} key 'direction'", fail)
                    fixed = doc.get("mechanism", {}).get("fixed") if isinstance(
                        doc.get("mechanism"), dict) else None
                    if link != fixed:
                        fail("'direction' places the fixed link's reference line; a moving "
                             "link's direction follows from the assembly", where)
                    continue
                names = split_key(key, features)
                if names is None or len(set(names)) != len(names):
                    fail(f"{key!r} names no pair of its joints 'A-B' (a distance) or "
                         f"triple 'A-B-C' (the angle at B, degrees) "
                         f"(its joints and points: {', '.join(features)})", where)
                # a tracer point may sit on a joint (a pen on its pin): its distance
                # may be zero; a distance between two joints is a length
                on_point = any(n in point_ids for n in names)
                entries[names] = number(x, f"{where} key {key!r}", fail,
                                         positive=len(names) == 2 and not on_point)
                if len(names) == 2 and on_point and entries[names] < 0:
                    fail(f"a distance must not be negative, got {entries[names]:g}",
                         f"{where} key {key!r}")
            lengths[link] = entries
        else:
            if len(features) == 1:
                fail(_single_joint(link, features[0], joints, points), where)
            if len(features) != 2:
                fail(f"one number is the length of a binary link, but {link!r} has "
                     f"{len(features)} joints and points ({', '.join(features)}): "
                     f"give a table of distances, e.g. {{{features[0]}-{features[1]} = ..., "
                     f"{features[1]}-{features[2]} = ..., {features[0]}-{features[2]} = ...}}"
                     if features else f"{link!r} has no R joint or point to measure",
                     where)
            lengths[link] = {tuple(features): number(value, where, fail, positive=True)}
    lines: dict[tuple[str, str], LineSpec] = {}
    for t, j in zip(doc.get("joints", []), joints):
        where = f"joint {j.id!r}"
        for key, role in (("offset", 0), ("angle", 0), ("block_offset", 1),
                          ("block_angle", 1)):
            if key in t and j.kind != "P":
                fail(f"'{key}' is only for P joints", where)
        if j.kind == "P":
            for role, (a_key, e_key) in enumerate((("angle", "offset"),
                                                   ("block_angle", "block_offset"))):
                if a_key in t or e_key in t:
                    angle = number(t.get(a_key, 0.0), f"{where} key '{a_key}'", fail)
                    offset = number(t.get(e_key, 0.0), f"{where} key '{e_key}'", fail)
                    lines[(j.id, j.links[role])] = LineSpec(angle, offset)
    modes = _modes(doc.get("assembly", {}), fail)
    values = _values(doc.get("mechanism", {}), fail)
    return Dimensions(lengths=lengths, directions=directions, lines=lines, modes=modes,
                      values=values)


def _modes(table: object, fail: Fail) -> dict[str, str | dict[str, str]]:
    where = "[assembly]"
    if not isinstance(table, dict):
        fail("'assembly' must be a table ([assembly]) of modes", where)

    def word(value: object, here: str) -> str:
        if not isinstance(value, str) or value not in MODE_WORDS:
            fail(f"an assembly mode is one of {', '.join(map(repr, MODE_WORDS))}, "
                 f"got {value!r}", here)
        return value

    modes: dict[str, str | dict[str, str]] = {}
    for key, value in table.items():
        here = f"{where} {key!r}"
        if isinstance(value, dict):
            modes[key] = {k: word(v, f"{here} {k!r}") for k, v in value.items()}
        else:
            modes[key] = word(value, here)
    return modes


def _values(table: object, fail: Fail) -> dict[str | None, float]:
    values: dict[str | None, float] = {}
    if not isinstance(table, dict):
        return values
    if "at" in table:
        values[None] = number(table["at"], "[mechanism] key 'at'", fail)
    items = table.get("inputs", [])
    if isinstance(items, list):
        for i, item in enumerate(items):
            if isinstance(item, dict) and "at" in item and isinstance(item.get("joint"), str):
                values[item["joint"]] = number(item["at"], f"[mechanism] inputs #{i + 1} "
                                                "key 'at'", fail)
    return values


# -- one link's shape ----------------------------------------------------------------
def _side_word(side: int) -> str:
    return "left" if side > 0 else "right"


def link_shape(link: str, features: Sequence[str], entries: dict[tuple[str, ...], float],
               sides: dict[str, int], fail: Callable[[str], NoReturn],
               ) -> tuple[dict[str, Vec], dict[str, tuple[str, str, int]]]:
    """The positions of ``link``'s joints and points in its own frame (origin at the
    first feature, reference line toward the second), from its lengths.

    ``entries`` are the link's ``[lengths]`` entries (see :func:`split_key`), ``sides``
    ``{feature: +1 or -1}`` the side of a feature placed from two others (+1: left of
    the line from the first to the second of them in id order). ``fail(problem)``
    raises. Returns ``(shape, placed)``: the positions, and for each feature placed
    from two others ``(a, b, side)``.

    Examples
    --------
    >>> shape, placed = link_shape("plate", ["B", "C", "E"],
    ...     {("B", "C"): 4.0, ("B", "E"): 3.0, ("C", "E"): 5.0}, {}, print)
    >>> [tuple(round(v, 12) for v in shape[f]) for f in "BCE"]
    [(0.0, 0.0), (4.0, 0.0), (0.0, 3.0)]
    >>> placed
    {'E': ('B', 'C', 1)}
    """
    if len(features) < 2:
        return {f: (0.0, 0.0) for f in features}, {}
    dist = {frozenset(k): v for k, v in entries.items() if len(k) == 2}
    angles = {k: v for k, v in entries.items() if len(k) == 3}

    def d(a: str, b: str) -> float | None:
        return dist.get(frozenset((a, b)))

    seed: tuple[str, ...] | None = ((features[0], features[1])
                                     if d(features[0], features[1]) else None)
    if seed is None:
        pairs = sorted(tuple(sorted(k)) for k in dist)
        if not pairs:
            fail(f"no length given for link {link!r} (joints and points: "
                 f"{', '.join(features)}): write its distances under [lengths], e.g. "
                 f"{_quote(link)} = {{{features[0]}-{features[1]} = ...}}")
        seed = pairs[0]
    pos: dict[str, tuple[float, float]] = {seed[0]: (0.0, 0.0),
                                           seed[1]: (dist[frozenset(seed)], 0.0)}
    placed: dict[str, tuple[str, str, int]] = {}
    while len(pos) < len(features):
        for f in features:
            if f in pos:
                continue
            p = _by_angle(f, pos, angles, d)
            if p is not None:
                pos[f] = p
                break
            known = [a for a in sorted(pos) if d(a, f) is not None]
            if len(known) >= 2:
                a, b = known[0], known[1]
                side = sides.get(f, 1)
                pos[f] = _triangle(link, f, a, b, pos, dist[frozenset((a, f))],
                                   dist[frozenset((b, f))], side, fail)
                placed[f] = (a, b, side)
                break
        else:
            missing = [f for f in features if f not in pos]
            fail(f"the lengths of link {link!r} do not fix {', '.join(missing)}: give "
                 f"each one's distances to two joints already fixed (or a distance and "
                 f"an angle 'A-B-C'), e.g. {_quote(link)} = "
                 f"{{{features[0]}-{missing[0]} = ..., {features[1]}-{missing[0]} = ...}}")
    scale = max(max(abs(v) for v in dist.values()), 1e-300)
    for k, v in entries.items():
        if len(k) == 2:
            got = math.dist(pos[k[0]], pos[k[1]])
            if abs(got - v) > 1e-9 * scale:
                fail(f"the lengths of link {link!r} disagree: {k[0]}-{k[1]} is given as "
                     f"{v:g} but the others make it {got:.6g}")
        else:
            got = _angle_at(pos, *k)
            if abs(math.remainder(got - v, 360.0)) > 1e-7:
                fail(f"the lengths of link {link!r} disagree: the angle {'-'.join(k)} is "
                     f"given as {v:g} degrees but the others make it {got:.6g}")
    origin, toward = pos[features[0]], pos[features[1]]
    if math.dist(origin, toward) <= 1e-12 * scale:
        fail(f"joints {features[0]} and {features[1]} of link {link!r} are at one place")
    turn = -math.atan2(toward[1] - origin[1], toward[0] - origin[0])
    return {f: rotate(sub(p, origin), turn) for f, p in pos.items()}, placed


def _quote(name: str) -> str:
    return name if name.replace("_", "").replace("-", "").isalnum() else f'"{name}"'


def _angle_at(pos: dict[str, tuple[float, float]], a: str, m: str, c: str) -> float:
    u, v = sub(pos[a], pos[m]), sub(pos[c], pos[m])
    return math.degrees(math.atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1]))


def _by_angle(f: str, pos: dict[str, tuple[float, float]],
              angles: dict[tuple[str, str, str], float], d: Callable[[str, str], float | None],
              ) -> tuple[float, float] | None:
    """Place ``f`` from an angle 'x-m-f' (or 'f-m-x') at a placed ``m`` with a placed
    ``x`` and the distance m-f; None when no such angle is given."""
    for (a, m, c), angle in angles.items():
        if m not in pos or d(m, f) is None:
            continue
        if c == f and a in pos:
            x, turn = a, math.radians(angle)
        elif a == f and c in pos:
            x, turn = c, -math.radians(angle)
        else:
            continue
        ray = sub(pos[x], pos[m])
        norm = math.hypot(*ray)
        if norm == 0:
            continue
        step = rotate((ray[0] / norm * d(m, f), ray[1] / norm * d(m, f)), turn)
        return (pos[m][0] + step[0], pos[m][1] + step[1])
    return None


def _triangle(link: str, f: str, a: str, b: str, pos: dict[str, tuple[float, float]],
              ra: float, rb: float, side: int, fail: Callable[[str], NoReturn],
              ) -> tuple[float, float]:
    """``f`` at distance ``ra`` from ``a`` and ``rb`` from ``b``, on ``side`` of a->b."""
    base = sub(pos[b], pos[a])
    ab = math.hypot(*base)
    if ab == 0:
        fail(f"joints {a} and {b} of link {link!r} are at one place")
    x = (ab * ab + ra * ra - rb * rb) / (2 * ab)
    h2 = ra * ra - x * x
    scale = max(ab, ra, rb)
    if h2 < -1e-12 * scale * scale:
        sides = sorted([(ab, f"{a}-{b}"), (ra, f"{a}-{f}"), (rb, f"{b}-{f}")])
        (s1, n1), (s2, n2), (s3, n3) = sides
        fail(f"the sides of link {link!r} violate the triangle inequality: {n3} = {s3:g} "
             f"is longer than {n1} + {n2} = {s1 + s2:g}" if s3 > s1 + s2 else
             f"the sides of link {link!r} cannot make a triangle: {n1} {s1:g}, "
             f"{n2} {s2:g}, {n3} {s3:g}")
    h = math.sqrt(max(h2, 0.0)) * side
    ux, uy = base[0] / ab, base[1] / ab
    return (pos[a][0] + x * ux - h * uy, pos[a][1] + x * uy + h * ux)
