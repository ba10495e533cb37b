"""Disc cams and their followers as data: ``[[cams]]`` in a chain file.

A :class:`Cam` is a disc cam turning about a frame pivot and a follower that slides
(``"translating"``, with an ``offset``) or swings (``"oscillating"``, about a ``pivot`` with
an ``arm``), touching the cam with a knife edge, a roller or a flat face. Its follower
program is a tuple of :class:`Segment` (rises, dwells and falls, each over an angle of cam
turn, the rises and falls by a named law). Angles are radians inside (an oscillating
follower's lift too); the file speaks degrees. The motion itself is
:mod:`chaingraph.kinematics.cams`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from chaingraph.model.values import Fail, number

__all__ = ["Cam", "Segment", "LAWS", "CONTACTS", "CAM_KEYS", "read_cam", "cam_entry"]

LAWS = ("uniform", "shm", "parabolic", "cycloidal", "poly345", "poly4567")
CONTACTS = ("knife", "roller", "flat")
CAM_KEYS = ("id", "cam", "follower", "contact", "roller", "base", "offset", "motion",
            "arm", "pivot", "drawn")
_TURN_TOLERANCE = 1e-9       # degrees: segments must sum to 360 within this
_LIFT_TOLERANCE = 1e-9       # relative: the program must come back to its start


@dataclass(frozen=True)
class Segment:
    """One piece of a follower program: ``kind`` is ``"rise"``, ``"fall"`` or ``"dwell"``;
    ``lift`` the follower's travel (file units, radians for an oscillating follower; 0 for a
    dwell); ``over`` the cam's turn it takes (radians); ``law`` the motion law (None for a
    dwell)."""

    kind: str
    lift: float
    over: float
    law: str | None = None

    @property
    def change(self) -> float:
        """The follower's travel over the segment: ``+lift`` for a rise, ``-lift`` for a
        fall, 0 for a dwell."""
        return {"rise": self.lift, "fall": -self.lift}.get(self.kind, 0.0)


@dataclass(frozen=True)
class Cam:
    """A disc cam and its follower (one ``[[cams]]`` table).

    ``moves`` is ``"translating"`` (the follower slides on a P joint, its line ``offset``
    from the cam's centre) or ``"oscillating"`` (it swings on an R joint at ``pivot``,
    measured from the cam's centre, the contact ``arm`` from it). ``base`` is the base
    circle's radius, ``roller`` the roller's (0 unless ``contact`` is ``"roller"``).
    ``drawn`` is where in its program the drawing shows the cam (radians of cam turn,
    0: at the start, the follower at its lowest).
    """

    id: str
    cam: str
    follower: str
    contact: str
    base: float
    motion: tuple[Segment, ...]
    moves: str = "translating"
    roller: float = 0.0
    offset: float = 0.0
    arm: float | None = None
    pivot: tuple[float, float] | None = None
    drawn: float = 0.0

    @property
    def stroke(self) -> float:
        """The follower's largest travel from its lowest place (file units, or radians)."""
        return max(itertools.accumulate((seg.change for seg in self.motion), initial=0.0))

    @property
    def prime(self) -> float:
        """The prime circle's radius: the base circle's plus the roller's."""
        return self.base + self.roller


def _segment(item: object, where: str, fail: Fail, oscillating: bool) -> Segment:
    if not isinstance(item, dict):
        fail("each motion segment is an inline table such as {rise = 30.0, over = 120.0, "
             "law = \"cycloidal\"} or {dwell = 60.0}", where)
    kinds = [k for k in ("rise", "fall", "dwell") if k in item]
    if len(kinds) != 1:
        fail("a motion segment has exactly one of 'rise', 'fall' or 'dwell'", where)
    kind = kinds[0]
    allowed = {"dwell"} if kind == "dwell" else {kind, "over", "law"}
    unknown = sorted(set(item) - allowed)
    if unknown:
        fail(f"unknown key '{unknown[0]}' in a {kind} (it takes {', '.join(sorted(allowed))})",
             where)
    if kind == "dwell":
        over = number(item["dwell"], where + " key 'dwell'", fail)
        if over <= 0:
            fail(f"a dwell's angle must be positive, got {over:g}", where + " key 'dwell'")
        return Segment("dwell", 0.0, math.radians(over))
    lift = number(item[kind], f"{where} key '{kind}'", fail)
    if lift <= 0:
        fail(f"a {kind}'s lift must be positive, got {lift:g}", f"{where} key '{kind}'")
    if "over" not in item:
        fail(f"a {kind} needs 'over' (the degrees of cam turn it takes)", where)
    over = number(item["over"], where + " key 'over'", fail)
    if over <= 0:
        fail(f"a {kind}'s angle must be positive, got {over:g}", where + " key 'over'")
    law = item.get("law")
    if law not in LAWS:
        fail(f"unknown law {law!r}: one of {', '.join(LAWS)}", where + " key 'law'")
    return Segment(kind, math.radians(lift) if oscillating else lift, math.radians(over), law)


def _program(value: object, where: str, fail: Fail, oscillating: bool) -> tuple[Segment, ...]:
    if not isinstance(value, list) or not value:
        fail("'motion' is a list of segments: rises, dwells and falls", where + " key 'motion'")
    motion = tuple(_segment(s, f"{where} motion #{i + 1}", fail, oscillating)
                   for i, s in enumerate(value))
    turn = math.degrees(sum(s.over for s in motion))
    if abs(turn - 360.0) > _TURN_TOLERANCE:
        fail(f"the segments take {turn:g} degrees of cam turn; they must sum to 360",
             where + " key 'motion'")
    level, scale = 0.0, max(s.lift for s in motion)
    for i, s in enumerate(motion):
        level += s.change
        if level < -_LIFT_TOLERANCE * scale:
            fail(f"motion #{i + 1} falls below the start (the base circle)",
                 where + " key 'motion'")
    if abs(level) > _LIFT_TOLERANCE * max(scale, 1e-300):
        fail(f"the rises and falls do not return to the start (they end "
             f"{math.degrees(level) if oscillating else level:g} above it)",
             where + " key 'motion'")
    return motion


def _moves(follower: str, cam: str, joints: Sequence[Any], where: str, fail: Fail) -> str:
    """How the follower moves on the frame, read from the chain's joints."""
    if not any(j.kind == "R" and cam in j.links for j in joints):
        fail(f"the cam {cam!r} turns about an R joint, and it has none", where + " key 'cam'")
    if any(j.kind == "P" and follower in j.links for j in joints):
        return "translating"
    if any(j.kind == "R" and follower in j.links and cam not in j.links for j in joints):
        return "oscillating"
    fail(f"the follower {follower!r} neither slides (a P joint) nor swings (an R joint)",
         where + " key 'follower'")


def read_cam(table: object, index: int, joints: Sequence[Any], fail: Fail) -> Cam:
    """One ``[[cams]]`` table as a :class:`Cam`, every key checked against the chain's
    ``joints`` (the cam turns on an R joint; the follower slides on a P or swings on an R)."""
    where = f"[[cams]] #{index + 1}"
    if not isinstance(table, dict):
        fail("each [[cams]] entry is a table", where)
    unknown = sorted(set(table) - set(CAM_KEYS))
    if unknown:
        fail(f"unknown key '{unknown[0]}' (a cam takes {', '.join(CAM_KEYS)})", where)
    for key in ("id", "cam", "follower", "contact", "base", "motion"):
        if key not in table:
            fail(f"missing required key '{key}'", where)
    names = {}
    for key in ("id", "cam", "follower", "contact"):
        if not isinstance(table[key], str) or not table[key]:
            fail("must be a non-empty string", f"{where} key '{key}'")
        names[key] = table[key]
    where = f"[[cams]] {names['id']!r}"
    links = {name for j in joints for name in j.links}
    for key in ("cam", "follower"):
        if names[key] not in links:
            fail(f"no link {names[key]!r} in the chain's joints", f"{where} key '{key}'")
    contact = names["contact"]
    if contact not in CONTACTS:
        fail(f"unknown contact {contact!r}: one of {', '.join(CONTACTS)}", where + " key 'contact'")
    moves = _moves(names["follower"], names["cam"], joints, where, fail)
    base = number(table["base"], where + " key 'base'", fail)
    if base <= 0:
        fail(f"the base circle's radius must be positive, got {base:g}", where + " key 'base'")
    roller = 0.0
    if contact == "roller":
        if "roller" not in table:
            fail("a roller follower needs 'roller' (its radius)", where)
        roller = number(table["roller"], where + " key 'roller'", fail)
        if roller <= 0:
            fail(f"the roller's radius must be positive, got {roller:g}", where + " key 'roller'")
        if roller >= base:
            fail(f"the roller ({roller:g}) must be smaller than the base circle ({base:g})",
                 where + " key 'roller'")
    elif "roller" in table:
        fail(f"'roller' is for a roller follower, not a {contact} one", where + " key 'roller'")
    offset = number(table.get("offset", 0.0), where + " key 'offset'", fail)
    if moves == "translating" and abs(offset) >= base + roller:
        fail(f"the offset ({offset:g}) must be less than the prime circle's radius "
             f"({base + roller:g})", where + " key 'offset'")
    arm, pivot = _swing(table, moves, contact, base + roller, where, fail)
    motion = _program(table["motion"], where, fail, moves == "oscillating")
    drawn = number(table.get("drawn", 0.0), where + " key 'drawn'", fail)
    if not 0.0 <= drawn < 360.0:
        fail(f"'drawn' is the cam's place in its program, from 0 to less than 360 degrees, "
             f"got {drawn:g}", where + " key 'drawn'")
    return Cam(names["id"], names["cam"], names["follower"], contact, base, motion,
               moves=moves, roller=roller, offset=offset, arm=arm, pivot=pivot,
               drawn=math.radians(drawn))


def _swing(table: dict[str, Any], moves: str, contact: str, prime: float, where: str,
           fail: Fail) -> tuple[float | None, tuple[float, float] | None]:
    """An oscillating follower's ``arm`` and ``pivot`` (None for a translating one), the
    arm reaching the prime circle of radius ``prime``."""
    if moves == "translating":
        for key in ("arm", "pivot"):
            if key in table:
                fail(f"'{key}' is for an oscillating follower; this one slides",
                     f"{where} key '{key}'")
        return None, None
    if contact == "flat":
        fail("a flat-faced oscillating follower is not analysed yet (knife or roller)",
             where + " key 'contact'")
    if "offset" in table:
        fail("'offset' is for a translating follower; this one swings", where + " key 'offset'")
    for key in ("arm", "pivot"):
        if key not in table:
            fail(f"an oscillating follower needs '{key}'", where)
    arm = number(table["arm"], where + " key 'arm'", fail)
    if arm <= 0:
        fail(f"the arm must be positive, got {arm:g}", where + " key 'arm'")
    p = table["pivot"]
    if not isinstance(p, list) or len(p) != 2:
        fail("'pivot' is [x, y] from the cam's centre", where + " key 'pivot'")
    pivot = (number(p[0], where + " key 'pivot'", fail), number(p[1], where + " key 'pivot'", fail))
    d = math.hypot(*pivot)
    if not abs(d - arm) < prime < d + arm:
        fail(f"an arm of {arm:g} from a pivot {d:g} from the cam's centre cannot reach the "
             f"prime circle (radius {prime:g})", where + " key 'arm'")
    return arm, pivot


def cam_entry(cam: Cam) -> dict[str, Any]:
    """A :class:`Cam` as its ``[[cams]]`` table (radians written as degrees)."""
    def degrees(v: float) -> float:
        return round(math.degrees(v), 9)
    lift = degrees if cam.moves == "oscillating" else (lambda v: v)
    motion: list[dict[str, Any]] = []
    for s in cam.motion:
        if s.kind == "dwell":
            motion.append({"dwell": degrees(s.over)})
        else:
            motion.append({s.kind: lift(s.lift), "over": degrees(s.over), "law": s.law})
    out: dict[str, Any] = {"id": cam.id, "cam": cam.cam, "follower": cam.follower,
                           "contact": cam.contact, "base": cam.base}
    if cam.contact == "roller":
        out["roller"] = cam.roller
    if cam.moves == "translating":
        out["offset"] = cam.offset
    else:
        out["arm"] = cam.arm
        out["pivot"] = list(cam.pivot or (0.0, 0.0))
    out["motion"] = motion
    if cam.drawn:
        out["drawn"] = degrees(cam.drawn)
    return out
