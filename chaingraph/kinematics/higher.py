"""Higher pairs inside a linkage: cams and gear pairs as *derived inputs*.

A gear pair or a cam fixes the relative motion of one joint as a function of another's:

* a gear pair (links a, b in mesh, their axes held by the carrier c, teeth za, zb):
  Willis's equation ``(w_b - w_c) / (w_a - w_c) = -+ za / zb`` (minus for external
  teeth, plus for an annulus), integrated from the drawn pose: the rotation of b on
  its axis joint with c is ``ratio`` times that of a on its own;
* a disc cam turning on an R joint on a link F (the frame) and its follower sliding in
  a P joint on F, or swinging about an R joint on F: the follower's slide (or angle)
  from the drawn pose is the program's ``s(theta0 + theta) - s(theta0)``, theta the
  cam's turn on F from the drawn pose, theta0 where in its program the drawing shows the
  cam (the table's ``drawn``; 0, the start, the follower at its lowest, by default).

When the driving joint's motion is known (an input, or driven through other pairs), the
driven joint is one more input of the plan (a :class:`Derived`, its key ``"@derived:J"``
in pose and rate tables), whose value, rate and acceleration follow by the chain rule:
``f(x)``, ``f'(x) x'`` and ``f''(x) x'^2 + f'(x) x''``. The position kernel, the rates
and everything above them then move the mechanism as for any input.

When no input drives the pair, its driving member may be moved by the linkage (Watt's
sun and planet: the planet fixed to the connecting rod, the crank arm its carrier, the
sun on the crankshaft's pivot): the driving motion is then the rotation of the driving
link relative to the pair's link ``F`` (the carrier, the cam's frame) as the solve
places them (a Derived with ``after``), and the plan places the driven link after both.
A gear's angle follows exactly from Willis's equation integrated from the drawn pose,
``theta_b = theta_c + ratio (theta_a - theta_c)``, with ``theta_a - theta_c`` followed
continuously along the path (its whole turns count when the ratio is not whole).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike

from chaingraph._util.numbers import tidy
from chaingraph.errors import MechanismError
from chaingraph.geometry import rotate
from chaingraph.kinematics.cams import analyse_cam, follower_motion
from chaingraph.model.cams import Cam
from chaingraph.model.chain import Chain, Joint
from chaingraph.model.gears import GearPair

__all__ = ["Derived", "derived_inputs", "derived_options", "not_derived", "rise_at",
           "gear_cycle_turns", "CamFrame", "cam_frame", "HIGHER_KINDS",
           "cam_contact"]

#: the joint kinds a chain may have as higher pairs solved as derived inputs
HIGHER_KINDS = ("cam", "gear")


@dataclass(frozen=True)
class Derived:
    """A joint whose relative motion a higher pair derives from another joint's.

    ``joint`` (kind ``"R"`` or ``"P"``) between ``a`` and ``b``: its value is the
    rotation of b less a's (radians), or b's slide along a's guide, from the drawn
    pose. ``by`` is the table key of the driving joint's value (an input's or another
    derived joint's), ``by_sign`` turns it into the driving link's own motion (the cam's
    turn on F, the driving gear's rotation on the carrier). ``pair`` names the higher
    pair; ``ratio`` a gear pair's, or ``cam`` and ``sign`` (+1, or -1 where the P
    joint's guide is the follower) a cam's. ``after`` = (on, link), for a pair that no
    input drives: the driving motion is link's rotation less on's, as the solve places
    them (``by`` is then empty). ``inverse``: a follower driving its cam (the joint is
    the cam's, ``by`` the follower's), through the rise or fall the cam is drawn in,
    where the program is invertible; beyond it the joint has no value (NaN)."""

    joint: str
    kind: str
    a: str
    b: str
    pair: str
    by: str
    by_sign: float
    ratio: float | None = None
    cam: Cam | None = None
    sign: float = 1.0
    after: tuple[str, str] | None = None
    inverse: bool = False

    @property
    def key(self) -> str:
        """The derived joint's entry in pose and rate tables."""
        return "@derived:" + self.joint

    def driving(self, table: Mapping[str, tuple]) -> np.ndarray:
        """The driving link's motion (radians) from a table's entry of ``by`` (or the
        difference of the ``after`` links' entries: in a pose table, to whole turns)."""
        if self.after is not None:
            on, link = self.after
            return np.asarray(table[link][2], dtype=float) - \
                np.asarray(table[on][2], dtype=float)
        return self.by_sign * np.asarray(table[self.by][2], dtype=float)

    def ready(self, table: Mapping[str, object]) -> bool:
        """Whether ``table`` holds what the driving motion is read from."""
        if self.after is not None:
            return self.after[0] in table and self.after[1] in table
        return self.by in table

    def value(self, x: ArrayLike) -> np.ndarray:
        """The joint's value at the driving motion ``x`` (radians)."""
        x = np.asarray(x, dtype=float)
        if self.cam is None:
            return float(self.ratio or 0.0) * x
        if self.inverse:
            return _program_inverse(self.cam, self.sign * x) - self.cam.drawn
        # the places in the program, the drawn one first: one evaluation for both
        at = self.cam.drawn + np.concatenate([[0.0], np.ravel(x)])
        s = follower_motion(self.cam, at)[0]
        return self.sign * (s[1:] - s[0]).reshape(x.shape)

    def slopes(self, x: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """df/dx and d2f/dx2 at the driving motion ``x``."""
        x = np.asarray(x, dtype=float)
        if self.cam is None:
            return np.full(x.shape, float(self.ratio or 0.0)), np.zeros(x.shape)
        if self.inverse:           # x(u) of u = s(x): x' = 1 / s', x'' = -s'' / s'^3
            turn = self.cam.drawn + self.value(x)
            _, ds, dds, _ = follower_motion(self.cam, np.atleast_1d(turn))
            with np.errstate(divide="ignore", invalid="ignore"):
                d1, d2 = self.sign / ds, -dds / ds ** 3
            return d1.reshape(x.shape), d2.reshape(x.shape)
        _, ds, dds, _ = follower_motion(self.cam, self.cam.drawn + np.atleast_1d(x))
        return self.sign * ds.reshape(x.shape), self.sign * dds.reshape(x.shape)

    def velocity(self, pose: Mapping[str, tuple], vel: Mapping[str, tuple]) -> tuple:
        """The joint's velocity table entry, by the chain rule (the accelerations not
        yet known: a pair driven through the linkage, during the velocity solve)."""
        d1, _ = self.slopes(self.driving(pose))
        with np.errstate(invalid="ignore"):
            return (0.0, 0.0, d1 * self.driving(vel))

    def rates(self, pose: Mapping[str, tuple], vel: Mapping[str, tuple],
              acc: Mapping[str, tuple]) -> tuple[tuple, tuple]:
        """The joint's (velocity, acceleration) table entries, by the chain rule."""
        x = self.driving(pose)        # (to whole turns: a cam's program repeats each turn)
        xr, xa = self.driving(vel), self.driving(acc)
        d1, d2 = self.slopes(x)
        with np.errstate(invalid="ignore"):     # (a cam its follower drives, at the ends
            return (0.0, 0.0, d1 * xr), (0.0, 0.0, d2 * xr * xr + d1 * xa)   # of its rise)


def _r_joint(chain: Chain, one: str, other: str) -> Joint | None:
    return next((j for j in sorted(chain.joints, key=lambda j: j.id)
                 if j.kind == "R" and one in j.links and other in j.links), None)


def _pair(joint: str, a: str, b: str) -> tuple[str, frozenset[str]]:
    """The key of the pair of links a, b at ``joint`` among the known motions (a joint
    of several links may have several: the arm's on the frame, the sun's on the arm)."""
    return joint, frozenset((a, b))


def _entry(known: Mapping[tuple[str, frozenset[str]], tuple[str, str, str]], joint: Joint,
           on: str, link: str) -> tuple[str, float] | None:
    """(table key, sign) giving ``link``'s rotation on ``on`` at ``joint``, when the
    joint's motion is known (an input or derived between those two links)."""
    got = known.get(_pair(joint.id, on, link))
    if got is None:
        return None
    key, a, b = got
    if (a, b) == (on, link):
        return key, 1.0
    if (a, b) == (link, on):
        return key, -1.0
    return None


def _gear_axes(chain: Chain, g: GearPair, name: str) -> tuple[Joint, Joint, float]:
    """Each gear's R joint with the carrier, and the ratio (w_b - w_c) / (w_a - w_c)."""
    c = g.carrier
    a, b = g.links
    ja, jb = _r_joint(chain, a, c), _r_joint(chain, b, c)
    if ja is None or jb is None:
        raise MechanismError(f"the gear pair {g.id!r} needs each gear on an R joint with "
                             f"its carrier {c!r} to be solved", mechanism=name)
    return ja, jb, g.sign * g.teeth[0] / g.teeth[1]


def _gear(chain: Chain, g: GearPair, known, name: str) -> Derived | None:
    """The gear pair as a derived joint, once one of its gears' axis joints is known."""
    c = g.carrier
    a, b = g.links
    ja, jb, ratio = _gear_axes(chain, g, name)
    for (drive, driven, r) in ((ja, jb, ratio), (jb, ja, 1.0 / ratio)):
        by = _entry(known, drive, c, a if drive is ja else b)
        if by is None:
            continue
        if _pair(driven.id, c, b if driven is jb else a) in known:
            raise MechanismError(
                f"the gear pair {g.id!r} drives joint {driven.id!r}, whose motion is "
                "already an input or driven by another pair (a closed loop of gears, or "
                "one input too many)", mechanism=name)
        return Derived(driven.id, "R", c, b if driven is jb else a, g.id, by[0], by[1],
                       ratio=r)
    return None


def _cam_joints(chain: Chain, cam: Cam, name: str) -> tuple[Joint, Joint, str]:
    """The cam's R joint, the follower's joint on the same link F, and F."""
    for jc in sorted(chain.joints, key=lambda j: j.id):
        if jc.kind != "R" or cam.cam not in jc.links or cam.follower in jc.links \
                or len(jc.links) != 2:
            continue
        f = next(x for x in jc.links if x != cam.cam)
        for jf in sorted(chain.joints, key=lambda j: j.id):
            if jf.kind in ("R", "P") and set(jf.links) == {f, cam.follower}:
                return jc, jf, f
    raise MechanismError(f"the cam {cam.id!r}: the cam and the follower must turn, slide or "
                         "swing on one link (the frame) to be solved", mechanism=name)


def _cam(chain: Chain, cam: Cam, known, name: str) -> Derived | None:
    jc, jf, f = _cam_joints(chain, cam, name)
    by = _entry(known, jc, f, cam.cam)
    if by is None:
        return None
    if _pair(jf.id, f, cam.follower) in known:
        raise MechanismError(f"the cam {cam.id!r} drives joint {jf.id!r}, whose motion is "
                             "already an input or driven by another pair", mechanism=name)
    frame = cam_frame(chain, cam)         # (refuses a drawing the table disagrees with)
    if jf.kind == "R":
        return Derived(jf.id, "R", f, cam.follower, cam.id, by[0], by[1], cam=cam)
    up = (math.cos(math.radians(jf.axis or 0.0)), math.sin(math.radians(jf.axis or 0.0)))
    along = 1.0 if up[0] * frame.up[0] + up[1] * frame.up[1] > 0 else -1.0
    sign = along if jf.links[0] == f else -along
    return Derived(jf.id, "P", jf.links[0], jf.links[1], cam.id, by[0], by[1], cam=cam,
                   sign=sign)


def rise_at(cam: Cam, turn: float) -> tuple[float, float] | None:
    """The rise or fall of ``cam``'s program that the cam's ``turn`` (radians) lies
    strictly inside, as (its start, its end) in radians of cam turn, or None (in a
    dwell, or at a segment's end, where the follower stands still or may)."""
    start = 0.0
    for seg in cam.motion:
        end = start + seg.over
        if seg.kind != "dwell" and start < turn < end:
            return start, end
        start = end
    return None


def _program_inverse(cam: Cam, u: np.ndarray) -> np.ndarray:
    """The cam's turns (radians, inside the rise or fall it is drawn in) at which the
    follower stands ``u`` from where it is drawn (file units, or radians), by bisection
    on that segment (monotone there); NaN where the segment does not reach."""
    u = np.atleast_1d(np.asarray(u, dtype=float))
    seg = rise_at(cam, cam.drawn)
    assert seg is not None, "a cam driven by its follower is drawn inside a rise or fall"
    ends = follower_motion(cam, np.array([seg[0], seg[1] - 1e-15 * seg[1]]))[0]
    s0 = follower_motion(cam, np.array([cam.drawn]))[0][0]
    target = s0 + u
    up = 1.0 if ends[1] > ends[0] else -1.0
    lo, hi = np.full(u.shape, seg[0]), np.full(u.shape, seg[1])
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        below = up * (follower_motion(cam, mid)[0] - target) < 0
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    out = 0.5 * (lo + hi)
    reach = (target - min(ends)) * (target - max(ends)) <= 1e-12 * max(1.0, abs(s0))
    return np.where(reach, out, np.nan)


def _cam_by_follower(chain: Chain, cam: Cam, known, name: str) -> Derived | None:
    """The cam's turning joint driven by its follower's, when that is known and the
    cam is drawn inside a rise or fall (where the program has an inverse)."""
    jc, jf, f = _cam_joints(chain, cam, name)
    pair = (f, cam.follower) if jf.kind == "R" else tuple(jf.links)
    by = _entry(known, jf, *pair)
    if by is None or _pair(jc.id, f, cam.cam) in known:
        return None
    if rise_at(cam, cam.drawn) is None:
        raise MechanismError(
            f"the cam {cam.id!r} is drawn {math.degrees(cam.drawn):g} degrees into its "
            "program, in a dwell or at the end of a rise or fall, so its follower cannot "
            "drive it (the follower stands still there as the cam turns: the program has "
            "no inverse); draw it inside a rise or fall (its 'drawn') to drive it by the "
            "follower, or drive the cam", mechanism=name)
    forward = _cam(chain, cam, {_pair(jc.id, f, cam.cam): ("", f, cam.cam)}, name)
    assert forward is not None
    return Derived(jc.id, "R", f, cam.cam, cam.id, by[0], by[1], cam=cam,
                   sign=forward.sign, inverse=True)


def _early(chain: Chain, pairs: Sequence[GearPair | Cam], known: dict, name: str
           ) -> tuple[list[Derived], list[GearPair | Cam]]:
    """The pairs that follow from the ``known`` joints' motions (added to ``known``), in
    the order they follow, and the pairs left."""
    out: list[Derived] = []
    while pairs:
        left = []
        for p in pairs:
            d = _gear(chain, p, known, name) if isinstance(p, GearPair) else \
                _cam(chain, p, known, name) or _cam_by_follower(chain, p, known, name)
            if d is None:
                left.append(p)
            else:
                out.append(d)
                known[_pair(d.joint, d.a, d.b)] = (d.key, d.a, d.b)
        if len(left) == len(pairs):
            return out, left
        pairs = left
    return out, []


def _late(chain: Chain, p: GearPair | Cam, known: Mapping, name: str) -> list[Derived]:
    """The ways the pair ``p`` may be driven by its driving link's rotation as the solve
    places it (no input driving it): a gear pair either way, a cam by the cam."""
    if isinstance(p, Cam):
        jc, jf, f = _cam_joints(chain, p, name)
        if _pair(jf.id, f, p.follower) in known or not _moved_by_linkage(chain, p.cam, f):
            return []
        d = _cam(chain, p, {_pair(jc.id, f, p.cam): ("", f, p.cam)}, name)
        assert d is not None
        return [replace(d, by="", by_sign=1.0, after=(f, p.cam))]
    c = p.carrier
    a, b = p.links
    ja, jb, ratio = _gear_axes(chain, p, name)
    return [Derived(driven.id, "R", c, gear, p.id, "", 1.0, ratio=r, after=(c, other))
            for driven, gear, other, r in ((jb, b, a, ratio), (ja, a, b, 1.0 / ratio))
            if _pair(driven.id, c, gear) not in known and _moved_by_linkage(chain, other, c)]


def _moved_by_linkage(chain: Chain, link: str, on: str) -> bool:
    """Whether ``link`` has a lower pair with a link other than ``on`` (the pair's
    carrier or frame), through which the linkage may turn it: a driving gear or cam
    joined only to its axis is turned by nothing but the pair itself."""
    return any(j.kind in ("R", "P") and link in j.links and set(j.links) - {link, on}
               for j in chain.joints)


def _options(chain: Chain, pairs: Sequence[GearPair | Cam], known: dict, name: str
             ) -> list[tuple[Derived, ...]]:
    out, left = _early(chain, pairs, known, name)
    if not left:
        return [tuple(out)]
    found: list[tuple[Derived, ...]] = []
    for d in _late(chain, left[0], known, name):
        rest = _options(chain, left[1:], {**known, _pair(d.joint, d.a, d.b): (d.key, d.a, d.b)},
                        name)
        found.extend((*out, d, *r) for r in rest)
    return found


def _check_tables(chain: Chain, name: str) -> None:
    ids = {g.id for g in chain.gears} | {c.id for c in chain.cams}
    stray = [j.id for j in chain.joints if j.kind in HIGHER_KINDS and j.id not in ids]
    if stray:
        raise MechanismError(f"the higher pair {stray[0]!r} has no [[cams]] or [[gears]] "
                             "table saying how it moves", mechanism=name)


def derived_options(chain: Chain, inputs: Sequence[tuple[str, str, str, str]], name: str
                    ) -> list[tuple[Derived, ...]]:
    """Every way of deriving the higher pairs of ``chain`` (see :func:`derived_inputs`),
    those the inputs drive first: a pair no input drives is driven by its driving
    link's rotation as the solve places it (``Derived.after``), a gear pair either
    way (the plan takes the first way it can place). Empty when a pair can be driven
    neither way (its joints both inputs or driven)."""
    _check_tables(chain, name)
    known = {_pair(j, a, b): (key, a, b) for j, key, a, b in inputs}
    return _options(chain, [*chain.gears, *chain.cams], known, name)


def derived_inputs(chain: Chain, inputs: Sequence[tuple[str, str, str, str]], name: str
                   ) -> tuple[Derived, ...]:
    """Every higher pair of ``chain`` as a :class:`Derived` joint, in the order they
    follow from the ``inputs`` (each ``(joint, key, a, b)``: the joint, its table key,
    and the links whose relative motion it gives). Refuses a pair no input drives
    (:func:`derived_options` gives the ways the solve may drive it through the
    linkage)."""
    _check_tables(chain, name)
    known = {_pair(j, a, b): (key, a, b) for j, key, a, b in inputs}
    out, left = _early(chain, [*chain.gears, *chain.cams], known, name)
    if left:
        raise not_derived(left[0], name)
    return tuple(out)


def not_derived(p: GearPair | Cam, name: str, *, loop: bool = False) -> MechanismError:
    """The refusal of a higher pair that neither an input nor the links placed before
    it drive (``loop``: the links its driving motion needs are placed only with it)."""
    what = (f"the gear pair {p.id!r}: neither gear's joint with the carrier "
            f"{p.carrier!r} is an input or driven through another pair"
            if isinstance(p, GearPair) else
            f"the cam {p.id!r}: the cam's turning joint is neither an input nor "
            "driven through another pair, nor is the cam turned by the linkage, nor is "
            "the follower's joint an input (a follower drives its cam only as an input, "
            "the cam drawn inside a rise or fall: a program's dwells and the ends of its "
            "rises, where the follower stands still as the cam turns, have no inverse)")
    how = (", nor do the links placed before it turn its driving member (a closed loop "
           "through the pair, solved only with it)" if loop else "")
    return MechanismError(f"{what}{how}, so the pair's motion cannot be derived from the "
                          "inputs (the solver drives a higher pair from its driving "
                          "link: a cam from the cam, a gear from a gear)", mechanism=name)


def gear_cycle_turns(derived: Sequence[Derived]) -> int | None:
    """The turns of the driving motions after which every gear of a train whose higher
    pairs are all gear pairs is back where drawn: the least common multiple of the
    denominators of each gear's ratio to the motion that drives it through the train
    (the product of the ratios along the way: each ratio of teeth recovered exactly from
    its float by the nearest fraction of denominator at most a million, which is the
    teeth's own for any gears made). None when a cam is among the pairs, or no pair."""
    if not derived or any(d.cam is not None or d.ratio is None for d in derived):
        return None
    factor: dict[str, Fraction] = {}
    turns = 1
    for d in derived:
        r = Fraction(float(d.ratio or 0.0)).limit_denominator(10 ** 6) * \
            (1 if d.after is not None else factor.get(d.by, Fraction(1)))
        factor[d.key] = r
        turns = math.lcm(turns, r.denominator)
    return turns


# -- a cam's place in the drawing ------------------------------------------------------
@dataclass(frozen=True)
class CamFrame:
    """Where :mod:`chaingraph.kinematics.cams`' frame lies in the drawing: the cam's
    centre ``centre`` and the images ``right`` and ``up`` of its x and y axes (unit
    vectors: a point p of that frame is drawn at ``centre + p_x right + p_y up``); the
    link ``on`` (the frame) that the cam and the follower turn or slide on."""

    centre: tuple[float, float]
    right: tuple[float, float]
    up: tuple[float, float]
    on: str
    turn: float = 0.0

    def on_cam(self, p: ArrayLike) -> np.ndarray:
        """Points ``p`` (n x 2) of the cam's own frame (:func:`analyse_cam`'s, the cam at
        the start of its program), in the drawing: turned by ``turn``, where in its
        program the drawing shows the cam."""
        p = np.asarray(p, dtype=float).reshape(-1, 2)
        return self.drawn(_turned(p, np.full(len(p), self.turn)))

    def drawn(self, p: ArrayLike) -> np.ndarray:
        """Points ``p`` (n x 2) of the cam's frame, in the drawing."""
        p = np.asarray(p, dtype=float)
        return np.stack([self.centre[0] + p[..., 0] * self.right[0] + p[..., 1] * self.up[0],
                         self.centre[1] + p[..., 0] * self.right[1] + p[..., 1] * self.up[1]],
                        axis=-1)

    def vector(self, v: ArrayLike) -> np.ndarray:
        """Vectors ``v`` (n x 2) of the cam's frame, in the drawing."""
        v = np.asarray(v, dtype=float)
        return np.stack([v[..., 0] * self.right[0] + v[..., 1] * self.up[0],
                         v[..., 0] * self.right[1] + v[..., 1] * self.up[1]], axis=-1)


def cam_frame(chain: Chain, cam: Cam) -> CamFrame:
    """The cam's frame in the drawing (see :class:`CamFrame`): a translating follower
    slides along its P joint's axis, ``up`` pointing away from the cam's centre (to the
    follower's other joints), its line ``offset`` to the right of the centre; an
    oscillating follower's pivot lies at ``pivot`` from the centre, turned. Refuses a
    drawing whose follower's line or pivot does not agree with the ``[[cams]]`` table."""
    name = chain.source or chain.name
    jc, jf, f = _cam_joints(chain, cam, name)
    if jc.at is None or jf.at is None:
        raise MechanismError(f"the cam {cam.id!r}: its joints need positions to be solved",
                             mechanism=name)
    o = jc.at
    size = max(1.0, max(abs(v) for j in chain.joints if j.at for v in j.at))
    if jf.kind == "R":
        q = (jf.at[0] - o[0], jf.at[1] - o[1])
        px, py = cam.pivot or (0.0, 0.0)
        if abs(math.hypot(*q) - math.hypot(px, py)) > 1e-6 * size:
            raise MechanismError(
                f"the cam {cam.id!r}: the follower's pivot {jf.id!r} is drawn "
                f"{math.hypot(*q):g} from the cam's centre; its 'pivot' is "
                f"{math.hypot(px, py):g} from it", mechanism=name)
        turn = math.atan2(q[1], q[0]) - math.atan2(py, px)
        c, s = math.cos(turn), math.sin(turn)
        return _checked(chain, cam, CamFrame(o, (c, s), (-s, c), f, cam.drawn), size)
    u = (math.cos(math.radians(jf.axis or 0.0)), math.sin(math.radians(jf.axis or 0.0)))
    ahead = [j.at for j in chain.joints if cam.follower in j.links and j.at is not None
             and j.kind not in HIGHER_KINDS]
    reach = sum((p[0] - o[0]) * u[0] + (p[1] - o[1]) * u[1] for p in ahead)
    up = u if reach >= 0 else (-u[0], -u[1])
    right = (up[1], -up[0])
    offset = (jf.at[0] - o[0]) * right[0] + (jf.at[1] - o[1]) * right[1]
    if abs(offset - cam.offset) > 1e-6 * size:
        raise MechanismError(
            f"the cam {cam.id!r}: the follower's line {jf.id!r} is drawn "
            f"{tidy(offset, size):g} to the "
            f"right of the cam's centre (looking along the follower); its 'offset' is "
            f"{cam.offset:g}", mechanism=name)
    return _checked(chain, cam, CamFrame(o, right, up, f, cam.drawn), size)


def _checked(chain: Chain, cam: Cam, frame: CamFrame, size: float) -> CamFrame:
    """``frame``, once the drawn contact (the cam pair's joint) is where the program
    puts it at the cam's drawn place (``drawn``): as far from the cam's centre as the
    profile touches the follower there (else refused, naming both distances)."""
    k = next((j for j in chain.joints if j.id == cam.id and j.kind == "cam"), None)
    if k is None or k.at is None:
        return frame
    r = analyse_cam(cam, np.array([cam.drawn]))
    touch = float(np.hypot(*r.profile[0]))
    drawn = math.dist(k.at, frame.centre)
    if abs(drawn - touch) > 1e-6 * size:
        s = float(follower_motion(cam, np.array([cam.drawn]))[0][0])
        lift = f"{math.degrees(s):.6g} degrees" if cam.moves == "oscillating" else f"{s:.6g}"
        raise MechanismError(
            f"the cam {cam.id!r}: its contact {k.id!r} is drawn {tidy(drawn, size):g} from "
            f"the cam's centre, but {math.degrees(cam.drawn):g} degrees into its program "
            f"(its 'drawn'), the follower {lift} above its lowest, the cam touches it "
            f"{tidy(touch, size):g} from the centre", mechanism=chain.source or chain.name)
    return frame


def _turned(v: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Vectors ``v`` (n x 2) turned by ``angle`` (n)."""
    x, y = rotate(v.T, angle)
    return np.stack([x, y], axis=1)


def cam_contact(chain: Chain, cam: Cam, theta: ArrayLike, *,
                frame: CamFrame | None = None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """At the cam's turns ``theta`` (radians from the drawn pose, where the cam is
    ``cam.drawn`` into its program), in the drawing with
    the link F held where drawn: the contact point (n x 2), the common normal there
    (unit, from the cam towards the follower) and the follower's reference point (the
    roller's centre, the knife's tip, the flat face's foot). ``frame``: the cam's
    :func:`cam_frame`, when the caller has it already."""
    frame = frame or cam_frame(chain, cam)
    theta = cam.drawn + np.atleast_1d(np.asarray(theta, dtype=float))   # in the program
    r = analyse_cam(cam, theta)
    w, c = _turned(r.pitch, theta), _turned(r.profile, theta)   # the cam's frame, turned
    if cam.moves == "translating":
        up = np.tile([0.0, 1.0], (theta.size, 1))
    else:                                   # square to the arm, the way it swings
        arm = w - np.asarray(cam.pivot, dtype=float)
        up = np.stack([-arm[:, 1], arm[:, 0]], axis=1) / np.hypot(arm[:, 0], arm[:, 1])[:, None]
    normal = _turned(up, r.pressure)                  # up turned by the pressure angle
    return frame.drawn(c), frame.vector(normal), frame.drawn(w)
