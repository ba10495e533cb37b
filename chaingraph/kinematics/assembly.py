"""Assembling a mechanism's drawn pose from its dimensions.

:func:`assemble` takes a chain's structure (its joints and mechanism, without
coordinates) and its :class:`~chaingraph.model.dimensions.Dimensions` (lengths, sliding lines,
the inputs' values, assembly modes) and finds where every joint is, as a textbook
solution does with compass and ruler:

* each input joint welds its two links together at the input's value (the crank to the
  frame at its angle, a piston to its cylinder at its slide);
* a link joined to placed links at two points, or at one point with its direction known
  (through a sliding pair), is placed directly; links whose directions are all known are
  placed together by solving their (linear) equations;
* a dyad (two links joined to each other and each to a placed link) is placed in closed
  form: two circles (RRR), a circle and a line (RRP), or a line tangent to two circles
  (RPR); each has two assembly modes, chosen by ``[assembly]``, else by the typed or
  rough (``near``) positions of its joints, else by the default (``left``, ``ahead``);
* what is left (an Assur group of higher class, as in Stephenson's third inversion) is
  solved by Newton's method from the rough positions of its joints.

Every step is the position kernel's, as the sweep and the single pose take it
(:mod:`~chaingraph.kinematics.closed_form`, :mod:`~chaingraph.kinematics.equations`,
:func:`~chaingraph.kinematics.groups.newton`, on pose entries): this module chooses the
order of placement, the modes, and says what does not close.

:func:`measure` is the inverse: the dimensions of a drawn mechanism, written as a chain
file. :func:`chaingraph.model.snap.snap_to_lines` moves the joints of a coordinate file that lie within
drawing-level rounding of a sliding line onto it.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any, NoReturn

import numpy as np

from chaingraph._util.disjoint import DisjointSets
from chaingraph.errors import DimensionError, PoseAdjustedWarning
from chaingraph.geometry import (
    FIXED,
    PoseEntry,
    Vec,
    apply,
    compose,
    cross,
    dot,
    fit_frame,
    inverse,
    line_in,
    make_pose,
    normal,
    rotate,
    sub,
    turn_by,
    unit,
    unit_deg,
    world,
)
from chaingraph.kinematics.closed_form import dyad_roots, line_of, single_link
from chaingraph.kinematics.equations import (
    constraint_residuals,
    group_form,
    place_translations,
)
from chaingraph.kinematics.groups import newton
from chaingraph.kinematics.plan import Constraint, Step, build_plan
from chaingraph.kinematics.sweep import feasible_range
from chaingraph.model.chain import Chain, Joint, Point, chosen_inputs, line_direction
from chaingraph.model.chainfile import parse_document, toml_text
from chaingraph.model.dimensions import (
    MODE_WORDS,
    Dimensions,
    LineSpec,
    link_features,
    link_shape,
)
from chaingraph.model.snap import ROUNDING, SILENT, feature_label, size_of

__all__ = ["Assembly", "Mode", "assemble", "measure", "measured_document"]


@dataclass(frozen=True)
class Mode:
    """The assembly mode of one part: ``part`` (the joint a dyad places, or
    ``"LINK:JOINT"`` for the side of a link's joint), ``word`` (left, right, ahead,
    behind), ``reference`` (what the word is relative to), ``source`` ("given",
    "sketch" or "default")."""

    part: str
    word: str
    reference: str
    source: str


@dataclass(frozen=True, eq=False)
class Assembly:
    """The drawn pose found from a mechanism's dimensions: ``joints`` ``{id: (x, y)}``
    (for a P joint the block's reference point), ``axes`` ``{P joint: degrees}``,
    ``points`` ``{id: (x, y)}``; ``modes`` the assembly mode of every part that has two;
    ``groups`` the links solved by Newton's method; ``size`` the mechanism's size;
    ``links`` each link's pose entry ``(x, y, phi, cos phi, sin phi)``: the motion
    from the link's own frame (the one its lengths are drawn in) to the world."""

    joints: dict[str, tuple[float, float]]
    axes: dict[str, float]
    points: dict[str, tuple[float, float]]
    modes: tuple[Mode, ...]
    groups: tuple[tuple[str, ...], ...]
    size: float
    links: dict[str, PoseEntry]


class _DoesNotClose(Exception):
    """A part that cannot be assembled at the inputs' values (internal)."""

    def __init__(self, part, problem):
        self.part = part
        self.problem = problem
        super().__init__(problem)


def _fmt(x):
    return f"{x:.6g}"


# -- the model: links' frames, bodies welded by inputs, constraints -------------------------
class _Model:
    """Everything the assembly needs, built once per (structure, dimensions)."""

    def __init__(self, chain, points, dims, fail):
        self.chain, self.points, self.dims, self.fail = chain, points, dims, fail
        m = chain.mechanism
        if m is None:
            fail("a file with [lengths] needs [mechanism] (the fixed link and the input) "
                 "to be assembled", "[mechanism]")
        bad = [j.id for j in chain.joints if j.kind not in ("R", "P")]
        if bad:
            fail(f"only R and P joints can be given by lengths; {', '.join(bad)} "
                 f"{'is' if len(bad) == 1 else 'are'} not", f"joint {bad[0]!r}")
        self.fixed = m.fixed
        self.inputs = self._inputs()
        self.scale = self._scale()
        self.sides_used = set()
        self.shape_modes = []
        self.corrections = {}
        self.frames = {link: self._frame(link) for link in chain.links}
        self.sketch = dict(dims.near)
        self.sketch.update(dims.typed)

    # inputs ---------------------------------------------------------------------------
    def _inputs(self):
        chain, dims, fail = self.chain, self.dims, self.fail
        fixed, driver, inputs = chosen_inputs(chain)
        out = []
        if inputs:
            if None in dims.values:
                fail("'at' in [mechanism] is the driver's angle; with 'inputs', give each "
                     "input's value as 'at' in its table", "[mechanism]")
            for item in inputs:
                j = chain.joint(item.joint)
                if j.kind == "R":
                    a, b = ((fixed, next(x for x in j.links if x != fixed))
                            if fixed in j.links else (j.links[0], j.links[1]))
                else:
                    a, b = j.links
                out.append((j, a, b, dims.values.get(j.id, 0.0)))
        elif driver is not None:
            pivots = sorted(j.id for j in chain.joints
                            if j.kind == "R" and fixed in j.links and driver in j.links)
            if not pivots:
                fail(f"the driver {driver!r} is not pinned to the fixed link {fixed!r} by an "
                     "R joint", "[mechanism]")
            out.append((chain.joint(pivots[0]), fixed, driver, dims.values.get(None, 0.0)))
        else:
            fail("no driver or inputs: the lengths are assembled at the input's value, so "
                 "name the driver (or the inputs) and give 'at'", "[mechanism]")
        named = {j.id for j, *_ in out}
        for key in dims.values:
            if key is not None and key not in named:
                fail(f"'at' is given for {key!r}, which is not an input", "[mechanism]")
        return out

    def _scale(self):
        values = [abs(v) for e in self.dims.lengths.values() for k, v in e.items()
                  if len(k) == 2]
        values += [abs(s.offset) for s in self.dims.lines.values()]
        typed = list(self.dims.typed.values())
        if typed:
            xs, ys = [p[0] for p in typed], [p[1] for p in typed]
            values += [max(xs) - min(xs), max(ys) - min(ys)]
        return max(values + [1e-300])

    # one link's frame --------------------------------------------------------------------
    def _frame(self, link):
        """``(points, lines)`` of ``link`` in its frame: points ``{id: (x, y)}`` (R
        joints and points), lines ``{P joint: (angle rad, offset)}``."""
        chain, dims, fail = self.chain, self.dims, self.fail
        features = link_features(chain.joints, self.points, link)
        slides = sorted((j for j in chain.joints if j.kind == "P" and link in j.links),
                        key=lambda j: j.id)
        given = link in dims.lengths
        if link == self.fixed and not given:
            return self._fixed_frame(link, features, slides)
        if not given and len(features) >= 2:
            fail(f"no length given for link {link!r} (joints and points: "
                 f"{', '.join(features)}): add it under [lengths]",
                 f"[lengths] {link!r}")
        sides = dims.modes.get(link, {})
        if isinstance(sides, str):
            sides = {f: sides for f in features[2:]}
        for f in sides:
            if f not in features:
                fail(f"names no joint or point of link {link!r} "
                     f"({', '.join(features)})", f"[assembly] {link!r}")
        signs = {f: MODE_WORDS[w] for f, w in sides.items()}
        shape, placed = link_shape(link, features, dims.lengths.get(link, {}), signs,
                                   lambda problem: fail(problem, f"[lengths] {link!r}"))
        self.sides_used.add(link)
        for f, (a, b, side) in placed.items():
            self.shape_modes.append(Mode(f"{link}:{f}", "left" if side > 0 else "right",
                                         f"of the line {a}\u2192{b} on link {link!r}",
                                         "given" if f in sides else "default"))
        lines = {}
        for k, j in enumerate(slides):
            spec = dims.lines.get((j.id, link))
            where = f"joint {j.id!r}"
            if len(features) < 2 and k == 0:
                # this line is the link's reference line
                if spec is not None and spec.angle != 0:
                    fail(f"the sliding line is the reference line of {link!r} (a link "
                         "with fewer than two joints and points), so its angle on that "
                         "link is 0", where)
                if not features and spec is not None and spec.offset != 0:
                    fail(f"{link!r} has no R joint or point, so its origin is on this "
                         "sliding line: the offset on it is 0", where)
                lines[j.id] = (0.0, spec.offset if spec else 0.0)
            else:
                spec = spec or LineSpec()
                lines[j.id] = (math.radians(spec.angle), spec.offset)
        if link == self.fixed:
            return self._place_fixed_shape(link, features, shape, lines, slides)
        return shape, lines

    def _fixed_frame(self, link, features, slides):
        dims, fail = self.dims, self.fail
        shape, lines = {}, {}
        for f in features:
            if f not in dims.typed:
                fail(f"{f!r} is on the fixed link {link!r}: give its 'at' (or the fixed "
                     f"link's lengths under [lengths])", f"joint {f!r}")
            shape[f] = dims.typed[f]
        for j in slides:
            if (j.id, link) in dims.lines:
                fail("the fixed link is given by coordinates: give its sliding line by "
                     "'at' and 'axis'", f"joint {j.id!r}")
            if j.id not in dims.typed or j.id not in dims.axes:
                fail(f"the sliding line on the fixed link {link!r} needs 'at' (a point of "
                     "it) and 'axis' (its direction, degrees)", f"joint {j.id!r}")
            angle = math.radians(dims.axes[j.id])
            lines[j.id] = (angle, dot(normal(angle), dims.typed[j.id]))
        return shape, lines

    def _place_fixed_shape(self, link, features, shape, lines, slides):
        """A fixed link given by lengths: its first joint at its 'at' (else the
        origin), its reference line in the direction given (else +x)."""
        origin = self.dims.typed.get(features[0], (0.0, 0.0)) if features else (0.0, 0.0)
        pose = (math.radians(self.dims.directions.get(link, 0.0)), origin[0], origin[1])
        shape = {f: apply(pose, p) for f, p in shape.items()}
        out = {}
        for j in slides:
            if (j.id, link) in self.dims.lines or j.id not in self.dims.axes:
                out[j.id] = line_in(pose, lines[j.id])
            else:
                angle = math.radians(self.dims.axes[j.id])
                out[j.id] = (angle, dot(normal(angle), self.dims.typed[j.id]))
        return shape, out

    # directions that inputs are measured by -------------------------------------------------
    def _beta(self, link, joint):
        """The direction, in ``link``'s own frame, of the line an input at ``joint``
        is measured by (the rule of :meth:`Chain.reference_direction`); 0 on the
        fixed link. A sliding pair's point is not placed yet: it is first taken along
        its line, and the assembly corrects this once it is placed (see ``assemble``)."""
        if link == self.fixed:
            return 0.0
        shape, lines = self.frames[link]
        features = [(j.id, shape[j.id] if j.kind == "R" else None)
                    for j in self.chain.joints_of(link)]
        turn = line_direction(features, joint.id, tol=1e-12 * self.scale,
                              unplaced=lambda j: lines[j][0] + self.corrections.get(link, 0.0))
        return 0.0 if turn is None else turn


# -- the assembly at given input values -----------------------------------------------------
@dataclass(frozen=True)
class _Size:
    """What the kernel's Newton method reads of a plan: the size its tolerances are
    relative to."""

    size: float


class _Solver:
    """The pose at the inputs' values: the links welded by the inputs are bodies,
    each drawn in its own frame; the joints between bodies are the kernel's
    constraints (a joint's point, or sliding line, on each body); the bodies are placed
    in the order the lengths allow, each step by the position kernel (a single body,
    a dyad, bodies whose rotations are known, a group by Newton's method), on pose
    entries. What is the assembly's own: the order, the modes (``[assembly]``, else the
    rough positions, else the default) and the messages."""

    def __init__(self, model, values):
        self.model = model
        self.chain = model.chain
        self.values = values
        self.modes = []
        self.groups = []
        self.used_modes = set()
        self._bodies()
        self.pose = {model.fixed: FIXED}
        self.angle = {model.fixed: 0.0}
        self._constraints()

    def _bodies(self):
        """Weld links by the inputs; ``self.body[link] = (body, transform in body)``."""
        model = self.model
        body = {model.fixed: (model.fixed, (0.0, 0.0, 0.0))}
        welds: dict[str, list[tuple[Joint, str, str, float]]] = {}
        for (j, a, b, _), value in zip(model.inputs, self.values):
            welds.setdefault(a, []).append((j, a, b, value))
            welds.setdefault(b, []).append((j, a, b, value))
        order = [model.fixed] + [x for x in self.chain.links if x != model.fixed]
        self.loops, tree = [], set()
        for start in order:
            if start in body and start != model.fixed:
                continue
            if start not in body:
                body[start] = (start, (0.0, 0.0, 0.0))
            stack = [start]
            while stack:
                x = stack.pop()
                for j, a, b, value in welds.get(x, []):
                    y = b if x == a else a
                    rel = self._weld(j, a, b, value)     # b in a's frame
                    if x == b:
                        rel = inverse(rel)
                    if y in body:
                        if j.id not in tree:       # a weld that closes a loop of welds
                            self.loops.append((j, x, y, rel))
                        continue
                    tree.add(j.id)
                    body[y] = (body[x][0], compose(body[x][1], rel))
                    stack.append(y)
        self.body = body

    def _weld(self, joint, a, b, value):
        model = self.model
        (pa, la), (pb, lb) = model.frames[a], model.frames[b]
        if joint.kind == "R":
            phi = math.radians(value) - model._beta(b, joint) + model._beta(a, joint)
            r = rotate(pb[joint.id], phi)
            return (phi, pa[joint.id][0] - r[0], pa[joint.id][1] - r[1])
        (ag, eg), (ak, ek) = la[joint.id], lb[joint.id]
        phi = ag - ak
        ref_g = tuple(eg * v for v in normal(ag))
        ref_k = rotate(tuple(ek * v for v in normal(ak)), phi)
        u = unit(ag)
        return (phi, ref_g[0] + value * u[0] - ref_k[0], ref_g[1] + value * u[1] - ref_k[1])

    def _constraints(self):
        """The joints that are not inputs, as the kernel's constraints between bodies
        (``self.checked``, in the joints' order); ``self.constraints`` those between
        two bodies (the others lie within a body, which the welds must close)."""
        inputs = {j.id for j, *_ in self.model.inputs}
        fixed = self.model.fixed
        self.checked = []
        for j in self.chain.joints:
            if j.id in inputs:
                continue
            if j.kind == "R":
                base = fixed if fixed in j.links else j.links[0]
                self.checked += [self._constraint(j, base, x) for x in j.links if x != base]
            else:
                self.checked.append(self._constraint(j, *j.links))
        self.constraints = [c for c in self.checked if c.a != c.b]

    def _constraint(self, joint, a, b):
        """Joint ``joint`` between links a and b (for a P joint, the guide and the
        block) as a constraint between their bodies."""
        (ba, ta), (bb, tb) = self.body[a], self.body[b]
        (pa, la), (pb, lb) = self.model.frames[a], self.model.frames[b]
        if joint.kind == "R":
            return Constraint("R", joint.id, ba, bb, _xy(apply(ta, pa[joint.id])),
                              point_b=_xy(apply(tb, pb[joint.id])))
        (ga, ea), (gb, eb) = line_in(ta, la[joint.id]), line_in(tb, lb[joint.id])
        # each body's point on the line: its foot from the body's origin
        return Constraint("P", joint.id, ba, bb, (ea * normal(ga)[0], ea * normal(ga)[1]),
                          axis=math.degrees(ga), point_b=(eb * normal(gb)[0],
                                                          eb * normal(gb)[1]),
                          turn=ga - gb)

    # features in the world
    def world_point(self, link, name):
        body, t = self.body[link]
        return world(self.pose, body, apply(t, self.model.frames[link][0][name]))

    def world_line(self, link, name):
        body, t = self.body[link]
        return _line_at(self.pose[body], line_in(t, self.model.frames[link][1][name]))

    def _known(self, c, body):
        """Where the placed body of constraint ``c`` puts the joint's point."""
        other = c.other(body)
        return world(self.pose, other, c.at(other))

    def _place(self, placed):
        for body, entry in placed.items():
            self.pose[body] = (float(entry[0]), float(entry[1]), float(entry[2]),
                               float(entry[3]), float(entry[4]))
            self.angle[body] = self.pose[body][2]

    # the solve
    def run(self):
        bodies = {b for b, _ in self.body.values()}
        guard = 0
        while len(self.pose) < len(bodies):
            guard += 1
            if guard > 4 * len(bodies) + 8:
                break
            self._propagate_angles()
            if self._singles() or self._clusters() or self._dyads():
                continue
            self._group([b for b in sorted(bodies) if b not in self.pose])
        self._check()
        return self

    def _propagate_angles(self):
        """A sliding pair turns its two bodies together (by its ``turn`` apart)."""
        changed = True
        while changed:
            changed = False
            for c in self.constraints:
                if c.kind != "P":
                    continue
                if c.a in self.angle and c.b not in self.angle:
                    self.angle[c.b] = self.angle[c.a] + c.turn
                    changed = True
                elif c.b in self.angle and c.a not in self.angle:
                    self.angle[c.a] = self.angle[c.b] - c.turn
                    changed = True

    def _translate(self, bodies):
        """Bodies whose rotations are known, placed by the kernel's linear step; False
        where their joints do not fix them yet."""
        inside = set(bodies) | set(self.pose)
        cons = [c for c in self.constraints if (c.a in bodies or c.b in bodies)
                and c.a in inside and c.b in inside]
        trial = dict(self.pose)
        trial.update({b: make_pose(0.0, 0.0, self.angle[b]) for b in bodies})
        placed = place_translations(list(bodies), cons, trial)
        if placed is None:
            return False
        self._place(placed)
        return True

    def _singles(self):
        """Bodies placed from placed ones alone: two points, or directions known."""
        done = False
        scale = self.model.scale
        for b in sorted({x for x, _ in self.body.values()}):
            if b in self.pose:
                continue
            if b in self.angle:
                done = self._translate([b]) or done
                continue
            anchors = [c for c in self._to_placed(b) if c.kind == "R"]
            far = [c for c in anchors if math.dist(c.at(b), anchors[0].at(b)) > 1e-9 * scale]
            if anchors and far:
                c1, c2 = anchors[0], far[0]
                held = math.dist(c1.at(b), c2.at(b))
                apart = math.dist(self._known(c1, b), self._known(c2, b))
                if abs(held - apart) > 1e-9 * scale:
                    raise _DoesNotClose(c2.joint, f"joints {c1.joint} and {c2.joint} are "
                                                  f"{_fmt(apart)} apart, but the link "
                                                  f"{self._name(b)} holds them {_fmt(held)} "
                                                  "apart")
                self._place(single_link(Step("single", (b,), (c1, c2), "RR"), self.pose))
                done = True
        return done

    def _clusters(self):
        free = [b for b in self.angle if b not in self.pose]
        if len(free) < 2:
            return False
        # components of free bodies joined by constraints
        bodies = DisjointSets(free)
        for c in self.constraints:
            if c.a in bodies.parent and c.b in bodies.parent:
                bodies.join(c.a, c.b)
        return any(self._translate(sorted(g)) for g in bodies.blocks().values()
                   if len(g) > 1)

    def _name(self, body):
        links = [x for x, (b, _) in self.body.items() if b == body]
        return " + ".join(repr(x) for x in links)

    def _to_placed(self, b):
        return [c for c in self.constraints if b in (c.a, c.b) and c.other(b) in self.pose]

    def _between(self, b1, b2):
        return [c for c in self.constraints if {c.a, c.b} == {b1, b2}]

    def _dyads(self):
        free = sorted(b for b in {x for x, _ in self.body.values()} if b not in self.pose)
        for i, b1 in enumerate(free):
            for b2 in free[i + 1:]:
                link = self._between(b1, b2)
                one, two = self._to_placed(b1), self._to_placed(b2)
                if len(link) != 1 or len(one) != 1 or len(two) != 1:
                    continue
                kinds = one[0].kind + link[0].kind + two[0].kind
                turning = (b1 not in self.angle, b2 not in self.angle)
                if kinds in ("RRR", "RPR") and turning == (True, True):
                    step = Step("dyad", (b1, b2), (one[0], two[0], link[0]), kinds)
                    (self._rrr if kinds == "RRR" else self._rpr)(step)
                    return True
                if kinds == "RRP" and turning == (True, False):
                    self._rrp(Step("dyad", (b1, b2), (one[0], two[0], link[0]), "RRP"))
                    return True
                if kinds == "PRR" and turning == (False, True):
                    self._rrp(Step("dyad", (b2, b1), (two[0], one[0], link[0]), "RRP"))
                    return True
        return False

    def _choose(self, part, reference, candidates, words):
        """Pick one of two candidate placements ``{body: pose entry}``: the mode given
        in ``[assembly]``, else the one nearest the sketched positions, else the first."""
        given = self.model.dims.modes.get(part)
        self.used_modes.add(part)
        if isinstance(given, str):
            if given not in words:
                raise DimensionError(
                    f"the mode of {part} is {words[0]!r} or {words[1]!r} "
                    f"({reference}), got {given!r}", source=self.chain.source,
                    where=f"[assembly] {part!r}")
            k, source = words.index(given), "given"
        else:
            scores = [self._distance_to_sketch(c) for c in candidates]
            if None not in scores and scores[0] != scores[1]:
                k, source = int(np.argmin(scores)), "sketch"
            else:
                k, source = 0, "default"
        self.modes.append(Mode(part, words[k], reference, source))
        self._place(candidates[k])

    def _distance_to_sketch(self, placement):
        total, seen = 0.0, False
        sketch = self.model.sketch
        for link, (body, t) in self.body.items():
            if body not in placement:
                continue
            pts, lines = self.model.frames[link]
            for name, p in pts.items():
                if name in sketch:
                    total += math.dist(world(placement, body, apply(t, p)), sketch[name]) ** 2
                    seen = True
            for name, line in lines.items():
                axis = self.model.dims.axes.get(name)
                if axis is not None and self.chain.joint(name).links[0] == link:
                    angle = line[0] + t[0] + placement[body][2]
                    turn = math.remainder(angle - math.radians(axis), 2 * math.pi)
                    total += (turn * self.model.scale) ** 2
                    seen = True
        return total if seen else None

    def _roots(self, step):
        """The kernel's two placements of a dyad ``(build(+1), build(-1))``, their
        joint points (or rotations), and whether it closes."""
        keys, build, ok, _ = dyad_roots(step, self.pose, self.model.scale)
        return (build(1.0), build(-1.0)), keys, bool(ok)

    def _rrr(self, step):
        """Two bodies turning about placed joints, pinned to each other."""
        (b1, b2), (c1, c2, c12) = step.links, step.constraints
        w1, w2 = self._known(c1, b1), self._known(c2, b2)
        r1, r2 = math.dist(c1.at(b1), c12.at(b1)), math.dist(c2.at(b2), c12.at(b2))
        j, d = c12.joint, math.dist(w1, w2)
        if d == 0:
            raise _DoesNotClose(j, f"the dyad at joint {j}: its joints {c1.joint} and "
                                   f"{c2.joint} are at one place")
        placements, keys, ok = self._roots(step)
        if not ok:
            raise _DoesNotClose(j, f"the dyad of links {self._name(b1)} and {self._name(b2)} "
                                   f"at joint {j} does not close: {c1.joint} and {c2.joint} "
                                   f"are {_fmt(d)} apart, and the links reach from "
                                   f"{_fmt(abs(r1 - r2))} to {_fmt(r1 + r2)}")
        (ka, wa), (kb, wb) = sorted([(c1.joint, w1), (c2.joint, w2)])
        sides = [cross(sub(wb, wa), sub(k, wa)) for k in keys]
        left = 1 if sides[1] > sides[0] else 0
        self._choose(j, f"of the line {ka}\u2192{kb}", [placements[left], placements[1 - left]],
                     ("left", "right"))

    def _rrp(self, step):
        """b1 turns about a placed joint; b2 (direction known) slides on a placed line;
        they share an R joint. The kernel's first root is ahead along the line."""
        (b1, b2), (c1, c2, c12) = step.links, step.constraints
        placements, _, ok = self._roots(step)
        j = c12.joint
        if not ok:
            base, u, _ = line_of(self.pose, c2, b2, c12.at(b2))
            h = abs(cross(u, sub(self._known(c1, b1), base)))
            raise _DoesNotClose(j, f"the dyad of links {self._name(b1)} and {self._name(b2)} "
                                   f"at joint {j} does not close: {c1.joint} is {_fmt(h)} "
                                   f"from the line that {j} slides on, farther than "
                                   f"{_fmt(math.dist(c1.at(b1), c12.at(b1)))}")
        self._choose(j, f"of the foot of {c1.joint} along the sliding line of {c2.joint}",
                     list(placements), ("ahead", "behind"))

    def _rpr(self, step):
        """Two bodies joined by a sliding pair, each turning about a placed joint."""
        (b1, b2), (c1, c2, c12) = step.links, step.constraints
        A, B = self._known(c1, b1), self._known(c2, b2)
        d, j = math.dist(A, B), c12.joint
        if d == 0:
            raise _DoesNotClose(j, f"the sliding pair {j}: joints {c1.joint} and {c2.joint} "
                                   "are at one place")
        placements, _, ok = self._roots(step)
        if not ok:
            h1, h2 = (_off_line(c12, body, c.at(body)) for body, c in ((b1, c1), (b2, c2)))
            raise _DoesNotClose(j, f"the sliding pair {j} does not close: the line must pass "
                                   f"{_fmt(h1)} from {c1.joint} and {_fmt(h2)} from "
                                   f"{c2.joint}, which are only {_fmt(d)} apart")
        guide_first = c12.a == b1
        pins = sub(B, A) if guide_first else sub(A, B)
        ahead = sorted(placements, key=lambda p: -dot(
            pins, turn_by(p[c12.a], unit_deg(c12.axis))))
        guide, block = (c1.joint, c2.joint) if guide_first else (c2.joint, c1.joint)
        self._choose(j, f"of {guide} along the sliding line, for the pin {block}",
                     ahead, ("ahead", "behind"))

    def _guess(self, free):
        """Each free body's pose entry from the rough positions of its joints (and
        the placed joints it is pinned to)."""
        model = self.model
        guess, lacking = {}, []
        for b in free:
            pairs = []
            for link, (body, t) in self.body.items():
                if body != b:
                    continue
                for name, p in model.frames[link][0].items():
                    if name in model.sketch:
                        pairs.append((apply(t, p), model.sketch[name]))
            pairs += [(c.at(b), self._known(c, b)) for c in self._to_placed(b)
                      if c.kind == "R"]
            distinct = [pr for pr in pairs if math.dist(pr[0], pairs[0][0]) > 1e-9 * model.scale]
            if b in self.angle and pairs:
                r = rotate(pairs[0][0], self.angle[b])
                guess[b] = make_pose(pairs[0][1][0] - r[0], pairs[0][1][1] - r[1], self.angle[b])
            elif pairs and distinct:
                phi, x, y = fit_frame(pairs)
                guess[b] = make_pose(x, y, phi)
            else:
                lacking.append(b)
        if lacking:
            joints = sorted({n for link, (body, _) in self.body.items() if body in free
                             for n in model.frames[link][0] if n not in model.sketch
                             and link != model.fixed})
            raise DimensionError(
                f"links {', '.join(self._name(b) for b in free)} form a group that cannot "
                "be assembled dyad by dyad (an Assur group of higher class): give rough "
                f"positions of its joints ({', '.join(joints)}) with near = [x, y] to "
                "choose its assembly", source=self.chain.source, part=free[0])
        return guess

    def _group(self, free):
        """Bodies left after every closed-form step: the kernel's group, by Newton's
        method from the rough positions of their joints."""
        guess = self._guess(free)
        inside = set(free) | set(self.pose)
        cons = tuple(c for c in self.constraints if (c.a in free or c.b in free)
                     and c.a in inside and c.b in inside)
        step = Step("group", tuple(free), cons, f"group of {len(free)} links")
        form = group_form(step)
        q0 = np.array([[v for b in form.bodies for v in guess[b][:3]]])
        q, ok = newton(_Size(self.model.scale), step, self.pose, q0, iterations=60)
        if not ok[0]:
            raise _DoesNotClose(free[0], f"the group of links "
                                         f"{', '.join(self._name(b) for b in free)} does not "
                                         "close near the rough positions given")
        placed = form.complete(form.set_bodies(self.pose, q))
        self._place({b: tuple(np.asarray(v).reshape(-1)[0] for v in placed[b]) for b in free})
        self.groups.append(tuple(x for x, (body, _) in self.body.items() if body in free))
        self.modes.append(Mode("group " + "/".join(self._name(b) for b in free), "near",
                               "the rough positions given", "sketch"))

    def _check(self):
        scale = self.model.scale
        for c in self.checked:
            eqs = constraint_residuals(c, self.pose)
            off = max(abs(float(e)) * (scale if c.kind == "P" and k == 0 else 1.0)
                      for k, e in enumerate(eqs))
            if off > 1e-9 * scale:
                raise _DoesNotClose(c.joint, f"joint {c.joint} does not close (off by "
                                             f"{_fmt(off)})")
        for j, x, y, rel in self.loops:
            a = compose(self.body[x][1], rel)
            b = self.body[y][1]
            if (abs(math.remainder(a[0] - b[0], 2 * math.pi)) > 1e-9
                    or math.hypot(a[1] - b[1], a[2] - b[2]) > 1e-9 * self.model.scale):
                raise _DoesNotClose(j.id, f"the inputs close a loop that their values do not "
                                          f"fit (at input {j.id})")


def _line_at(entry, line):
    """A body's line ``(angle, offset)`` where its pose entry puts it."""
    angle = line[0] + entry[2]
    return (angle, line[1] + dot(normal(angle), (entry[0], entry[1])))


def _off_line(c, body, p):
    """How far the point ``p`` of ``body`` is from the sliding line of the P joint
    ``c`` on that body."""
    axis = math.radians(c.axis) - (0.0 if body == c.a else c.turn)
    return abs(cross(unit(axis), sub(p, c.at(body))))


# -- the public functions ----------------------------------------------------------------
def assemble(chain: Chain, points: Sequence[tuple[str, str]], dims: Dimensions) -> Assembly:
    """The drawn pose of a mechanism given by its dimensions.

    Parameters
    ----------
    chain : Chain
        The structure: joints (no coordinates needed) and ``[mechanism]``.
    points : sequence of (id, link)
        The tracer points, placed by their distances like joints.
    dims : Dimensions
        Lengths, sliding lines, the inputs' values, modes, typed and rough positions.

    Returns
    -------
    Assembly

    Raises
    ------
    DimensionError
        For lengths that give no pose: the message names the link, joint or dyad, and,
        for a mechanism that cannot be assembled at the input's value, the range of
        values where it can.

    Warns
    -----
    PoseAdjustedWarning
        When typed positions were off by drawing-level rounding (up to 1e-3 of the
        mechanism's size) and were moved.

    Examples
    --------
    >>> from chaingraph.files import loads
    >>> chain = loads('''
    ... name = "crank-rocker"
    ... [[joints]]
    ... id = "A"
    ... kind = "R"
    ... links = ["frame", "crank"]
    ... at = [0.0, 0.0]
    ... [[joints]]
    ... id = "B"
    ... kind = "R"
    ... links = ["crank", "coupler"]
    ... [[joints]]
    ... id = "C"
    ... kind = "R"
    ... links = ["coupler", "rocker"]
    ... [[joints]]
    ... id = "D"
    ... kind = "R"
    ... links = ["rocker", "frame"]
    ... at = [100.0, 0.0]
    ... [lengths]
    ... crank = 40.0
    ... coupler = 120.0
    ... rocker = 80.0
    ... [mechanism]
    ... fixed = "frame"
    ... driver = "crank"
    ... at = 90.0
    ... ''')
    >>> [round(v, 6) for v in chain.joint("C").at]
    [113.538447, 78.846119]
    """
    def fail(problem: str, where: str | None = None) -> NoReturn:
        raise DimensionError(problem, source=chain.source, where=where)

    model = _Model(chain, points, dims, fail)
    values = [v for *_, v in model.inputs]
    try:
        solver, result = _assembled(model, values)
    except _DoesNotClose as e:
        raise _unassemblable(model, values, e) from None
    _check_modes(model, solver)
    return _check_typed(model, result)


def _assembled(model, values):
    """(solver, Assembly) at the inputs' ``values``; _DoesNotClose where it fails."""
    for _ in range(6):
        solver = _Solver(model, values).run()
        result = _pose(model, solver)
        if not _correct_inputs(model, result):
            break
    return solver, result


def _solver_range(model, values):
    """The range of the first input's values that the solver reaches from the pose
    assembled at ``values`` (the others held): its exact limits, or None for a full
    turn."""
    _, result = _assembled(model, values)
    chain = model.chain
    joints = tuple(Joint(j.id, j.kind, j.links, at=result.joints[j.id],
                         axis=result.axes.get(j.id), closure=j.closure) for j in chain.joints)
    points = tuple(Point(pid, link, result.points[pid]) for pid, link in model.points)
    m = chain.mechanism
    kinds = {j.id: j.kind for j in chain.joints}
    values_of = {j.id: v for (j, *_), v in zip(model.inputs, values)}
    mechanism = replace(m, inputs=tuple(
        replace(item, start=None, stop=None,
                at=values_of.get(item.joint) if kinds.get(item.joint) == "P" else item.at)
        for item in m.inputs))
    plan = build_plan(replace(chain, joints=joints, points=points, mechanism=mechanism))
    return feasible_range(plan)


def _correct_inputs(model, result):
    """An input measured toward a sliding pair's reference point is known only once
    that point is placed: compare the direction the pose gives with the one the weld
    used and turn the link by the difference. True when something was corrected."""

    placed = None
    changed = False
    for j, a, b, value in model.inputs:
        if j.kind != "R":
            continue
        for link in (a, b):
            others = sorted((x for x in model.chain.joints_of(link) if x.id != j.id),
                            key=lambda x: x.id)
            if link == model.fixed or not others or others[0].kind == "R":
                continue
            if placed is None:
                placed = Chain(model.chain.name, tuple(
                    Joint(x.id, x.kind, x.links, at=result.joints[x.id],
                          axis=result.axes.get(x.id)) for x in model.chain.joints))
            got = math.radians(placed.reference_direction(link, joint=j.id))
            used = result.links[link][2] + model._beta(link, j)
            error = math.remainder(got - used, 2 * math.pi)
            if abs(error) > 1e-12:
                model.corrections[link] = model.corrections.get(link, 0.0) + error
                changed = True
    return changed


def _solves(model, values):
    try:
        _Solver(model, values).run()
    except _DoesNotClose:
        return False
    return True


def _unassemblable(model, values, error):
    """The error for a mechanism that does not close at the inputs' values, with the
    range of the first input's values where it does (the others held)."""
    joint, a, b, value = model.inputs[0]
    r_input = joint.kind == "R"
    what = (f"the driver {b!r} at {_fmt(value)} degrees" if r_input and a == model.fixed
            else f"input {joint.id} at {_fmt(value)}" + (" degrees" if r_input else ""))
    if r_input:
        grid = value + np.arange(-180.0, 180.0, 1.0)
    else:
        span = 4 * model.scale
        grid = value + np.linspace(-span, span, 801)

    def ok(v):
        return _solves(model, [v] + values[1:])

    good = [ok(v) for v in grid]
    runs, start = [], None
    for k, g in enumerate(good + [False]):
        if g and start is None:
            start = k
        if not g and start is not None:
            runs.append((start, k - 1))
            start = None
    # each run of the grid where it assembles: the solver's range from a pose in it
    ranges: list[tuple[float, float]] = []
    for s, e in runs:
        v = float(grid[(s + e) // 2])
        found = _solver_range(model, [v] + values[1:])
        lo, hi = found if found is not None else (float(grid[s]), float(grid[e]))
        same = [k for k, (a, b) in enumerate(ranges) if r_input
                and abs(math.remainder(a - lo, 360.0)) <= 1e-9
                and abs(math.remainder(b - hi, 360.0)) <= 1e-9]
        if same:               # the run at the grid's end that wraps round to its start
            ranges[same[0]] = max(ranges[same[0]], (lo, hi))
        elif (lo, hi) not in ranges:
            ranges.append((lo, hi))
    unit = " degrees" if r_input else ""
    if not ranges:
        where = "at any value of the input"
        tail = f"; it cannot be assembled {where}"
    else:
        said = " and ".join(f"from {_fmt(lo)} to {_fmt(hi)}{unit}" for lo, hi in ranges)
        where = ("[mechanism] at = VALUE" if r_input and a == model.fixed and
                 model.chain.mechanism.driver else
                 f"[mechanism] inputs = [{{joint = {joint.id!r}, at = VALUE}}, ...]".replace(
                     "'", '"'))
        tail = f"; it can be assembled {said} (its value is set by {where})"
    return DimensionError(f"cannot be assembled with {what}: {error.problem}{tail}",
                          source=model.chain.source, part=error.part,
                          feasible_range=ranges[0] if len(ranges) == 1 else ranges or None)


def _check_modes(model, solver):
    parts = solver.used_modes | model.sides_used
    for key in model.dims.modes:
        if key not in parts:
            named = sorted(parts)
            raise DimensionError(
                f"names no part with two assembly modes (the parts: "
                f"{', '.join(named) if named else 'none'}: a dyad by the joint it places, "
                "a link by its name)", source=model.chain.source,
                where=f"[assembly] {key!r}", part=key)


def _pose(model, solver):
    chain = model.chain
    joints, axes = {}, {}
    for j in chain.joints:
        if j.kind == "R":
            joints[j.id] = _xy(solver.world_point(j.links[0], j.id))
    for j in chain.joints:
        if j.kind != "P":
            continue
        guide, block = j.links
        angle, offset = solver.world_line(guide, j.id)
        axes[j.id] = math.degrees(math.remainder(angle, 2 * math.pi))
        n = normal(angle)
        # a sliding line on the fixed link is given by 'at' and 'axis'; its block's
        # reference point is that 'at', unless the (moving) block's pin is on the line
        ref = model.dims.typed.get(j.id)
        if ref is not None and model.fixed in j.links and block != model.fixed:
            pins = [x for x in model.chain.joints_of(block) if x.kind == "R"
                    and model.fixed not in x.links
                    and abs(dot(n, joints[x.id]) - offset) <= 1e-9 * model.scale]
            if pins:
                ref = joints[sorted(x.id for x in pins)[0]]
        if ref is None:
            ref = _reference(model, solver, j, joints)
        h = offset - dot(n, ref)
        # a pin on the line is the reference point itself, to the last digit
        joints[j.id] = _xy(ref if abs(h) <= 1e-12 * model.scale
                           else (ref[0] + h * n[0], ref[1] + h * n[1]))
    pts = {pid: _xy(solver.world_point(link, pid)) for pid, link in model.points}
    size = size_of({**joints, **pts})
    modes = tuple(model.shape_modes) + tuple(solver.modes)
    links: dict[str, PoseEntry] = {}
    for link, (body, t) in solver.body.items():
        w = world(solver.pose, body, (t[1], t[2]))
        links[link] = make_pose(w[0], w[1], solver.pose[body][2] + t[0])
    return Assembly(joints, axes, pts, modes, tuple(solver.groups), size, links)


def _xy(p: Vec) -> tuple[float, float]:
    return (float(p[0]), float(p[1]))


def _reference(model, solver, joint, placed):
    """Where a P joint's block reference point is drawn when the file does not say: at
    the block's R joint nearest the line (not one on the fixed link), else the guide's,
    else the block's origin."""
    guide, block = joint.links
    angle, offset = solver.world_line(guide, joint.id)
    n = normal(angle)
    for link in (block, guide):
        candidates = sorted((abs(dot(n, placed[j.id]) - offset), j.id)
                            for j in model.chain.joints_of(link)
                            if j.kind == "R" and model.fixed not in j.links)
        if candidates:
            return placed[candidates[0][1]]
    body, t = solver.body[block]
    return world(solver.pose, body, (t[1], t[2]))


def _check_typed(model, result):
    """Typed positions of joints the lengths place: within SILENT of the size, exact;
    within ROUNDING, moved with a warning; beyond, refused."""
    dims, chain = model.dims, model.chain
    fixed_by_coordinates = model.fixed not in dims.lengths
    worst = []
    for name, typed in dims.typed.items():
        try:
            j = chain.joint(name)
        except KeyError:
            j = None
        if j is not None and model.fixed in j.links and fixed_by_coordinates:
            continue
        if j is not None and j.kind == "P":
            angle = math.radians(result.axes[name])
            at = result.joints[name]
            d = abs(dot(normal(angle), sub(typed, at)))
            where = f"off the sliding line of {name} that the lengths give"
        else:
            at = result.joints[name] if j is not None else result.points[name]
            d = math.dist(typed, at)
            where = f"from where the lengths put it, ({_fmt(at[0])}, {_fmt(at[1])})"
        worst.append((d, name, where))
    for name, axis in dims.axes.items():
        j = chain.joint(name)
        if model.fixed in j.links and fixed_by_coordinates:
            continue
        turn = abs(math.remainder(axis - result.axes[name], 360.0))
        worst.append((math.radians(turn) * result.size, name,
                      f"(as a turn of its axis by {_fmt(turn)} degrees over the size) from "
                      f"the direction the lengths give, {_fmt(result.axes[name])} degrees"))
    if not worst:
        return result
    d, name, where = max(worst)
    size = result.size
    units = f" {chain.units}" if chain.units else ""
    if d > ROUNDING * size:
        raise DimensionError(
            f"typed at {_fmt(d)}{units} {where}: more than drawing-level rounding (1e-3 of "
            f"the mechanism's size {_fmt(size)}); correct its coordinates or the lengths, "
            "or leave out its 'at'", source=chain.source, where=feature_label(chain, name),
            part=name)
    if d > SILENT * size:
        others = sum(1 for x, *_ in worst if x > SILENT * size) - 1
        more = f" (and {others} other{'s' if others > 1 else ''} less)" if others > 0 else ""
        warnings.warn(PoseAdjustedWarning(
            f"{chain.source or chain.name}: {feature_label(chain, name)} was typed "
            f"{_fmt(d)}{units} {where}{more}: assembled to the consistent pose "
            f"(drawing-level rounding, {d / size:.1e} of the size)",
            joint=name, distance=d, size=size), stacklevel=4)
    return result


# -- the inverse: the dimensions of a drawn mechanism ---------------------------------------
def _frame_of(chain, link, fixed):
    """``(origin, direction in radians)`` of ``link``'s frame in the drawn pose."""
    if link == fixed:
        return (0.0, 0.0), 0.0
    points = [(p.id, p.link) for p in chain.points]
    features = link_features(chain.joints, points, link)
    where = {j.id: j.at for j in chain.joints}
    where.update({p.id: p.at for p in chain.points})
    if len(features) >= 2:
        o, t = where[features[0]], where[features[1]]
        return o, math.atan2(t[1] - o[1], t[0] - o[0])
    slides = sorted((j for j in chain.joints if j.kind == "P" and link in j.links),
                    key=lambda j: j.id)
    first = math.radians(slides[0].axis)
    if features:
        return where[features[0]], first
    origin = slides[0].at
    for other in slides[1:]:
        a2 = math.radians(other.axis)
        denom = math.sin(a2 - first)
        if abs(denom) > 1e-9:
            # where the second line crosses the first
            s = cross(sub(other.at, origin), unit(a2)) / denom
            origin = (origin[0] + s * math.cos(first), origin[1] + s * math.sin(first))
            break
    return origin, first


def measure(chain: Chain) -> str:
    """The dimensions of a drawn mechanism, as the text of a chain file with
    ``[lengths]`` that assembles to the same pose.

    Every moving link gets its lengths (a binary link one number, a link with more
    joints the distances from its first two joints to each other one), every sliding
    line its offset and angle on its moving links, the inputs their values in the drawn
    pose, and every part its assembly mode, written out.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> text = measure(chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism")))
    >>> print(text[text.index("[lengths]"):])
    [lengths]
    crank = 120.0
    <BLANKLINE>
    [assembly]
    S = "ahead"
    <BLANKLINE>
    [mechanism]
    fixed = "frame"
    driver = "crank"
    at = 0.0
    output = "slotted lever"
    <BLANKLINE>
    """
    return toml_text(measured_document(chain))


@dataclass(frozen=True)
class _Measures:
    """What a drawn mechanism's pose gives its chain file: ``lengths`` per moving link,
    ``sides`` the side of each further joint of a link with more than two (right only:
    left is the default), ``lines`` each P joint's angle and offset on its moving links,
    ``values`` each input's value (``None`` for the driver)."""

    lengths: dict[str, float | dict[tuple[str, str], float]]
    sides: dict[str, dict[str, str]]
    lines: dict[str, dict[str, float]]
    values: dict[str | None, float]


def measured_document(chain: Chain) -> dict[str, Any]:
    """The document (a dict, as a chain file reads) that :func:`measure` writes: the
    mechanism by its lengths, sliding lines, inputs' values and assembly modes."""
    if chain.mechanism is None:
        raise DimensionError("measuring needs [mechanism] (the fixed link and the input)",
                             source=chain.source, where="[mechanism]")
    if not chain.has_pose:
        raise DimensionError("measuring needs the drawn pose ('at' of every joint)",
                             source=chain.source)
    fixed = chain.mechanism.fixed
    # (every joint has its 'at': the chain has its drawn pose)
    where = {j.id: j.at for j in chain.joints if j.at is not None} | \
        {p.id: p.at for p in chain.points if p.at is not None}
    lengths, sides = _measured_lengths(chain, fixed, where)
    frames = {link: _frame_of(chain, link, fixed) for link in chain.links}
    measures = _Measures(lengths, sides, _measured_lines(chain, fixed, frames, where),
                         _measured_values(chain, fixed, frames))
    # assemble once with every moving joint as a rough position: that finds the modes,
    # the groups (which keep their rough positions) and the reference points to type
    moving = {j.id for j in chain.joints if fixed not in j.links}
    moving |= {p.id for p in chain.points if p.link != fixed}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        written = parse_document(_document(chain, measures, set(), moving, {}),
                                 source=chain.source or "<measure>")
        assert written.dimensions is not None          # a document with [lengths]
        pose = assemble(written.chain, [(p.id, p.link) for p in written.points],
                        written.dimensions)
    points = [(p.id, p.link) for p in chain.points]
    near = {n for group in pose.groups for link in group
            for n in link_features(chain.joints, points, link)} & moving
    modes = {mode.part: mode.word for mode in pose.modes
             if ":" not in mode.part and not mode.part.startswith("group ")}
    extra = {j.id for j in chain.joints if j.kind == "P" and fixed not in j.links
             and math.dist(pose.joints[j.id], where[j.id]) > 1e-9 * pose.size}
    return _document(chain, measures, extra, near, modes)


def _measured_lengths(chain, fixed, where):
    """Every moving link's lengths (one number for two joints or points, else the
    distances from the first two to each other one) and the sides of the others."""
    points = [(p.id, p.link) for p in chain.points]
    lengths: dict[str, float | dict[tuple[str, str], float]] = {}
    sides: dict[str, dict[str, str]] = {}
    for link in chain.links:
        if link == fixed:
            continue
        features = link_features(chain.joints, points, link)
        if len(features) < 2:
            if not any(j.kind == "P" and link in j.links for j in chain.joints):
                raise DimensionError(
                    f"{link!r} has {'a single joint' if features else 'no joint'} and no "
                    "sliding pair, so it has no dimensions to measure: every moving link "
                    "of a mechanism given by its lengths needs two joints or points, or a "
                    "sliding pair", source=chain.source, where=f"link {link!r}")
            continue
        f0, f1 = features[:2]
        if len(features) == 2:
            lengths[link] = math.dist(where[f0], where[f1])
            continue
        table = {(f0, f1): math.dist(where[f0], where[f1])}
        for f in features[2:]:
            table[(f0, f)] = math.dist(where[f0], where[f])
            table[(f1, f)] = math.dist(where[f1], where[f])
            if cross(sub(where[f1], where[f0]), sub(where[f], where[f0])) < 0:
                sides.setdefault(link, {})[f] = "right"
        lengths[link] = table
    return lengths, sides


def _measured_lines(chain, fixed, frames, where):
    """Each P joint's sliding line on its moving links: its angle and offset in the
    link's frame (the block's as ``block_angle``, ``block_offset``), where not zero."""
    out: dict[str, dict[str, float]] = {}
    for j in chain.joints:
        if j.kind != "P":
            continue
        psi = math.radians(j.axis)
        for role, link in enumerate(j.links):
            if link == fixed:
                continue
            origin, x = frames[link]
            angle = math.degrees(math.remainder(psi - x, 2 * math.pi))
            offset = dot(normal(psi), sub(j.at, origin))
            keys = ("angle", "offset") if role == 0 else ("block_angle", "block_offset")
            for key, value in zip(keys, (angle, offset)):
                if abs(value) > 1e-12 * size_of(where):
                    out.setdefault(j.id, {})[key] = value
    return out


def _measured_values(chain, fixed, frames):
    """Each input's value in the drawn pose (keyed by its joint), or the driver's angle
    (keyed None)."""
    _, driver, inputs = chosen_inputs(chain)
    values = {}
    for item in inputs or ():
        j = chain.joint(item.joint)
        if j.kind == "R" and fixed in j.links:
            b = next(x for x in j.links if x != fixed)
            values[j.id] = chain.reference_direction(b, joint=j.id)
        elif j.kind == "R":
            values[j.id] = math.remainder(
                chain.reference_direction(j.links[1], joint=j.id)
                - chain.reference_direction(j.links[0], joint=j.id), 360.0)
        else:
            u, n = unit(math.radians(j.axis)), normal(math.radians(j.axis))
            ref = []
            for link in j.links:
                origin = frames[link][0]
                h = dot(n, sub(j.at, origin))
                ref.append((origin[0] + h * n[0], origin[1] + h * n[1]))
            values[j.id] = dot(sub(ref[1], ref[0]), u)
    if inputs:
        return values
    pivots = sorted(j.id for j in chain.joints if j.kind == "R" and fixed in j.links
                    and driver in j.links)
    if not pivots:
        raise DimensionError(f"the driver {driver!r} is not pinned to the fixed link "
                             f"{fixed!r} by an R joint, so its angle cannot be measured",
                             source=chain.source, where="[mechanism] key 'driver'")
    return {None: chain.reference_direction(driver, joint=pivots[0])}


def _document(chain, measures, extra_at, near, modes):
    """The chain file's document: ``extra_at`` the moving joints that keep their
    'at', ``near`` those given as rough positions, ``modes`` the dyads' modes."""
    fixed = chain.mechanism.fixed
    doc = {"name": chain.name}
    for key in ("family", "units", "notes", "naming"):
        if getattr(chain, key) is not None:
            doc[key] = getattr(chain, key)
    joints = []
    for j in chain.joints:
        item = {"id": j.id, "kind": j.kind, "links": list(j.links)}
        if fixed in j.links or j.id in extra_at:
            item["at"] = list(j.at)
        if j.kind == "P" and (fixed in j.links or j.id in near):
            item["axis"] = j.axis
        item.update(measures.lines.get(j.id, {}))
        if j.id in near and j.kind == "R":
            item["near"] = list(j.at)
        joints.append(item)
    doc["joints"] = joints
    points_out = []
    for p in chain.points:
        item = {"id": p.id, "link": p.link}
        if p.link == fixed:
            item["at"] = list(p.at)
        if p.id in near:
            item["near"] = list(p.at)
        points_out.append(item)
    if points_out:
        doc["points"] = points_out
    doc["lengths"] = {link: ({"-".join(k): v for k, v in value.items()}
                             if isinstance(value, dict) else value)
                      for link, value in measures.lengths.items()}
    if modes or measures.sides:
        doc["assembly"] = {**modes, **measures.sides}
    doc["mechanism"] = _document_mechanism(chain, measures.values)
    return doc


def _document_mechanism(chain, values):
    """The document's ``[mechanism]``: the fixed link, the driver or the inputs at
    their values, the speed and the output."""
    m = chain.mechanism
    _, driver, inputs = chosen_inputs(chain)
    mech = {"fixed": m.fixed}
    if inputs:
        items = []
        for item in inputs:
            entry = {"joint": item.joint, "at": values[item.joint]}
            if item.start is not None:
                entry.update({"from": item.start, "to": item.stop})
            items.append(entry)
        mech["inputs"] = items
    else:
        mech.update(driver=driver, at=values[None])
    if m.omega != 1.0:
        mech["omega"] = m.omega
    if m.output is not None:
        mech["output"] = m.output
    return mech
