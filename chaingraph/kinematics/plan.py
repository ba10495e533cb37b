"""The solve plan of an inversion: which links are found from which, in what order.

Built once per (chain, fixed link, driver) and immutable. Coordinates: every link
carries a rigid motion (x, y, phi) from its drawn pose, so a point p of the drawing
moves to ``R(phi) p + (x, y)``; the drawn pose is all zeros. Constraints:

* an R joint of links a, b at point P: a's P and b's P coincide (a joint of k links
  gives k - 1 such pairs, each against the fixed link, else the driver, else the first);
* a P joint of guide g and block b at point A with direction u: equal rotations, and
  b's A stays on the line through g's A along g's u (the same line with either link
  as guide, since their rotations are equal).

Steps, in the order the graph allows: a *single* link joined to known links by two
constraints (RR, RP, PP); a *dyad* of two links, each joined to known links by one
constraint and to each other by one (RRR, RRP, PRR, RPR, PRP, RPP, PPR), both solved in
closed form; what is left is one *group* (an Assur group of higher class, such as the
triad of Stephenson's third inversion), solved by Newton's method.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import MechanismError

__all__ = ["Constraint", "Step", "Plan", "build_plan"]


@dataclass(frozen=True)
class Constraint:
    """One R pair (links a, b) or P joint (a the guide, b the block) at ``point``."""

    kind: str
    joint: str
    a: str
    b: str
    point: tuple[float, float]
    axis: float | None = None

    def other(self, link):
        return self.b if link == self.a else self.a


@dataclass(frozen=True)
class Step:
    """Links solved together: ``constraints`` lists attachments to known links first."""

    kind: str                 # "single", "dyad" or "group"
    links: tuple[str, ...]
    constraints: tuple[Constraint, ...]
    pattern: str


@dataclass(frozen=True)
class Plan:
    """How to solve one inversion."""

    chain: object
    fixed: str
    driver: str
    pivot: str                # the R joint about which the driver turns
    pivot_point: tuple[float, float]
    theta0: float             # input angle of the drawn pose, degrees
    steps: tuple[Step, ...]
    constraints: tuple[Constraint, ...]
    size: float               # the mechanism's size (for tolerances)
    mobility: int             # Kutzbach
    numeric_mobility: int     # coordinates minus rank of the constraint Jacobian
    origin: tuple[float, float] = (0.0, 0.0)   # the drawing's centre: see ``local``

    @property
    def moving(self):
        return tuple(x for x in self.chain.links if x != self.fixed)

    def local(self, p):
        """A drawn point in the plan's frame, centred on the drawing (so that precision
        does not depend on where the mechanism is drawn): the constraints, the pivot
        and every pose are in this frame."""
        return (p[0] - self.origin[0], p[1] - self.origin[1])


def _constraints(chain, fixed, driver, pivot, origin):
    def local(p):
        return (p[0] - origin[0], p[1] - origin[1])
    out = []
    for j in sorted(chain.joints, key=lambda j: j.id):
        if j.kind == "R":
            ref = fixed if fixed in j.links else driver if driver in j.links else j.links[0]
            for x in j.links:
                if x == ref or (j.id == pivot and {x, ref} == {fixed, driver}):
                    continue
                out.append(Constraint("R", j.id, ref, x, local(j.at)))
        else:
            out.append(Constraint("P", j.id, j.links[0], j.links[1], local(j.at), j.axis))
    return out


def _parallel(c1, c2):
    return abs(math.sin(math.radians(c1.axis - c2.axis))) < 1e-9


def _steps(chain, fixed, driver, constraints, closed_form=True):
    known = {fixed, driver}
    remaining = list(constraints)
    steps = []
    order = list(chain.links)
    while len(known) < len(order):
        unknown = [x for x in order if x not in known]

        def attachments(u):
            return [c for c in remaining if u in (c.a, c.b) and c.other(u) in known]
        step = None
        for u in (unknown if closed_form else []):
            att = attachments(u)
            if len(att) >= 2 and not (att[0].kind == att[1].kind == "P"
                                      and _parallel(att[0], att[1])):
                if att[0].kind == "P" and att[1].kind == "R":
                    att = [att[1], att[0]] + att[2:]
                step = Step("single", (u,), tuple(att), att[0].kind + att[1].kind)
                break
        if step is None:
            for a in (unknown if closed_form else []):
                att_a = attachments(a)
                if not att_a:
                    continue
                for c in remaining:
                    if a not in (c.a, c.b) or c.other(a) in known:
                        continue
                    b = c.other(a)
                    att_b = attachments(b)
                    pattern = att_a[0].kind + c.kind + att_b[0].kind if att_b else ""
                    if att_b and pattern != "PPP":
                        step = Step("dyad", (a, b), (att_a[0], att_b[0], c), pattern)
                        break
                if step is not None:
                    break
        if step is None:
            group = tuple(unknown)
            cons = tuple(c for c in remaining if c.a in group or c.b in group)
            step = Step("group", group, cons, "group of %d links" % len(group))
        steps.append(step)
        known |= set(step.links)
        used = set(step.constraints)
        remaining = [c for c in remaining if c not in used]
    return tuple(steps)


def build_plan(chain, fixed=None, driver=None, *, closed_form=True) -> Plan:
    """Check that an inversion can be solved and plan how.

    ``closed_form=False`` solves every link by Newton's method in one group (slower;
    the tests use it to check the closed forms and Newton against each other).

    Raises
    ------
    MechanismError
        For a higher pair or spatial joint, a joint without a position, a driver not
        pinned to the fixed link by an R joint, or a mobility other than 1 with this
        driver (the mobility found is said).
    """
    name = chain.source or chain.name
    m = chain.mechanism
    fixed = fixed or (m.fixed if m else None)
    driver = driver or (m.driver if m else None)
    if fixed is None:
        raise MechanismError("no fixed link: give [mechanism] fixed or --fixed", mechanism=name)
    if driver is None:
        raise MechanismError("no driver: give [mechanism] driver or --driver", mechanism=name)
    for role, link in (("fixed", fixed), ("driver", driver)):
        if link not in chain.links:
            raise MechanismError(f"the {role} link {link!r} is not a link of the chain "
                                 f"(links: {', '.join(chain.links)})", mechanism=name)
    if fixed == driver:
        raise MechanismError("the driver is the fixed link", mechanism=name)
    if chain.space != "planar":
        raise MechanismError("only planar chains can be solved; this one is spatial",
                             mechanism=name)
    for j in chain.joints:
        if j.kind not in ("R", "P"):
            raise MechanismError(
                f"a {j.pair.name} ({j.kind}) cannot be solved for motion: only R and P "
                "joints can (classification and inversions take every kind)",
                mechanism=name, where=f"joint {j.id!r}")
        if j.at is None:
            raise MechanismError("no position 'at': solving needs the drawn pose of every "
                                 "joint", mechanism=name, where=f"joint {j.id!r}")
    if len(chain.pieces) > 1:
        raise MechanismError("the chain is in several pieces that share no joint",
                             mechanism=name)
    pivots = sorted(j.id for j in chain.joints
                    if j.kind == "R" and fixed in j.links and driver in j.links)
    if not pivots:
        raise MechanismError(f"the driver {driver!r} is not pinned to the fixed link "
                             f"{fixed!r} by an R joint, so it cannot be turned as the input",
                             mechanism=name)
    pivot = chain.joint(pivots[0])
    others = [j for j in chain.joints_of(driver) if j.id != pivot.id]
    if not others:
        raise MechanismError(f"the driver {driver!r} has no joint besides its pivot",
                             mechanism=name)
    ref = others[0].at
    if math.dist(ref, pivot.at) == 0:
        far = [j for j in others if math.dist(j.at, pivot.at) > 0]
        ref = far[0].at if far else (pivot.at[0] + 1.0, pivot.at[1])
    theta0 = math.degrees(math.atan2(ref[1] - pivot.at[1], ref[0] - pivot.at[0]))
    points = [j.at for j in chain.joints] + [p.at for p in chain.points]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    size = max(max(xs) - min(xs), max(ys) - min(ys), 1e-300)
    origin = (0.5 * (max(xs) + min(xs)), 0.5 * (max(ys) + min(ys)))
    constraints = tuple(_constraints(chain, fixed, driver, pivot.id, origin))
    mobility = 3 * (len(chain.links) - 1) - 2 * sum(j.order - 1 for j in chain.joints)
    numeric = _numeric_mobility(chain, fixed, _constraints(chain, fixed, driver, "", origin),
                                size)
    # a drawn pose at a dead centre or change point loses rank there: that is no reason
    # to refuse a chain whose count says it moves (its range says where it can go)
    if numeric != 1 and not (mobility == 1 and numeric > 1):
        raise MechanismError(
            f"the mobility with driver {driver!r} and {fixed!r} fixed is {numeric} at the "
            f"drawn pose (Kutzbach: {mobility}); the driver must determine the motion "
            "(mobility 1)", mechanism=name, mobility=numeric)
    steps = _steps(chain, fixed, driver, constraints, closed_form)
    return Plan(chain=chain, fixed=fixed, driver=driver, pivot=pivot.id,
                pivot_point=(pivot.at[0] - origin[0], pivot.at[1] - origin[1]),
                theta0=theta0, steps=steps, constraints=constraints, size=size,
                mobility=mobility, numeric_mobility=numeric, origin=origin)


def _numeric_mobility(chain, fixed, constraints, size):
    """Coordinates (3 per moving link) minus the rank of all ``constraints`` (every
    joint's, the driver's pivot included) at the drawn pose.

    The constraints are about the drawing's centre; the Jacobian is taken in units of
    its size, so that its rank does not depend on where the mechanism is drawn or how
    large it is."""
    moving = [x for x in chain.links if x != fixed]
    col = {x: 3 * i for i, x in enumerate(moving)}
    rows = []
    for c in constraints:
        scaled = (c.point[0] / size, c.point[1] / size)
        for coeffs in _rows_at_drawn_pose(replace(c, point=scaled)):
            row = np.zeros(3 * len(moving))
            for link, vec in coeffs.items():
                if link != fixed:
                    row[col[link]:col[link] + 3] += vec
            rows.append(row)
    if not rows:
        return 3 * len(moving)
    rank = np.linalg.matrix_rank(np.array(rows), tol=1e-9)
    return 3 * len(moving) - int(rank)


def _rows_at_drawn_pose(c):
    px, py = c.point
    if c.kind == "R":
        return [{c.a: np.array([1.0, 0.0, -py]), c.b: np.array([-1.0, 0.0, py])},
                {c.a: np.array([0.0, 1.0, px]), c.b: np.array([0.0, -1.0, -px])}]
    a = math.radians(c.axis)
    nx_, ny_ = -math.sin(a), math.cos(a)
    # at the drawn pose d = 0, so the guide's rotation term n . perp(R A) cancels out
    perp_b = nx_ * -py + ny_ * px
    return [{c.b: np.array([0.0, 0.0, 1.0]), c.a: np.array([0.0, 0.0, -1.0])},
            {c.b: np.array([nx_, ny_, perp_b]), c.a: np.array([-nx_, -ny_, -perp_b])}]
