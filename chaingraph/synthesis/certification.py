"""Certification: a candidate mechanism written as a chain file, read back and solved by
chaingraph's own solver, then checked against its task.

A candidate is certified when, solved from its written file in the assembly mode of
its drawn pose (the first target): it assembles at every target; every target is
reached on that one circuit (the solver, tracking the drawn pose's circuit, passes it:
no circuit defect), and in the given order as the input moves one way, without passing
a limit of the input between them (no branch or order defect); its transmission angle
stays within ``[min, 180 - min]`` from the first target to the last; and its error is
recomputed from the solved motion. :func:`certify` returns a :class:`Certified` or a
:class:`Rejected` with its reason, one of :data:`REASONS`.

The targets are one of :class:`FunctionTargets` (the input's values and the output's
there), :class:`PointTargets` (points a tracer passes through) and
:class:`PoseTargets` (a tracer's points and its link's angles).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial

import numpy as np
from scipy.optimize import minimize_scalar  # type: ignore[import-untyped]

from chaingraph.errors import AssemblyError, PoseAdjustedWarning
from chaingraph.files import dumps, loads
from chaingraph.geometry import angle_between
from chaingraph.kinematics import Motion, build_plan, solve
from chaingraph.kinematics.behaviour import behaviour, four_link_loop, turning_links
from chaingraph.model.chain import Chain
from chaingraph.synthesis.result import Curve, Error, Solution

__all__ = ["FunctionTargets", "PointTargets", "PoseTargets", "Certified", "Rejected",
           "certify", "Targets", "REASONS", "transmission_angles", "output_values", "reached_in_order"]

#: why a candidate is not listed
REASONS = {
    "negative length": "a length came out negative",
    "impossible length": "no real length fits (a coupler's squared length not positive)",
    "singular": "the targets give no unique mechanism",
    "link ratio": "the longest link over the shortest is too large",
    "offset at rounding": "a pin or point off a sliding line by drawing-level rounding (a "
                          "chain file would put it on the line)",
    "does not assemble": "the mechanism cannot be assembled at a target",
    "circuit defect": "a target lies on the other circuit from the first",
    "branch defect": "the input meets a limit between the targets",
    "order defect": "the targets are not reached in order as the input moves one way",
    "transmission angle": "the transmission angle leaves [min, 180 - min]",
    "timing": "the targets are not met at the timing's input values",
}
_SWEEP = 720          # steps over a function's range
_CYCLE = 1440         # steps over a cycle, for points and poses


@dataclass(frozen=True)
class FunctionTargets:
    """A function generator's targets: the input's values ``inputs`` (degrees) and the
    output's values ``outputs`` there as the design claims them (the output's angle in
    degrees, or a slide's position along its guide); ``output`` names the output (a
    link turning about the fixed link, or a P joint on it); ``span`` the input's
    ``(start, end)`` over the task's range and ``wanted`` the output the task asks for
    at an input value (for the structural error)."""

    inputs: tuple[float, ...]
    outputs: tuple[float, ...]
    output: str
    span: tuple[float, float]
    wanted: Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class PointTargets:
    """Points a tracer (``point``, a point or joint) passes through, in order."""

    points: tuple[tuple[float, float], ...]
    point: str
    closed: bool = False


@dataclass(frozen=True)
class PoseTargets:
    """Poses of a link: its tracer ``point`` at ``points`` and the link's angle (the
    solver's ``angle:LINK``, degrees) ``angles`` there, in order. ``inputs``, when
    given, are the input's values at the poses as the design claims them (exact
    synthesis): the solver is then asked there, instead of searching the whole cycle
    for where the tracer passes."""

    points: tuple[tuple[float, float], ...]
    angles: tuple[float, ...]
    point: str
    link: str
    inputs: tuple[float, ...] | None = None


@dataclass(frozen=True, eq=False)
class Certified:
    """A certified candidate: the chain as read back from its file, the error
    (``max``, ``rms``, and ``angle`` for poses), ``reached_at``, the transmission
    angle's range, Grashof's words, the input's turn, and ``curve`` ((x, y) of its
    error or its traced path)."""

    chain: Chain
    error_max: float
    error_rms: float
    reached_at: tuple[float, ...]
    transmission_angle: tuple[float, float] | None
    grashof: str | None
    input: str
    curve: tuple[np.ndarray, np.ndarray]
    angle_error: float | None = None

    def solution(self, *, names: tuple[str, ...] = (), curve: Curve | None = None,
                 dimensions: dict[str, float] | None = None) -> Solution:
        """The certified candidate as a synthesis's :class:`~chaingraph.synthesis.result.Solution`
        (rank 0 until ranked), with its catalog ``names``, drawn ``curve`` and
        ``dimensions``."""
        return Solution(0, self.chain, Error(self.error_max, self.error_rms, self.angle_error),
                        self.reached_at, self.transmission_angle, self.grashof, self.input,
                        names, None, curve, dict(dimensions or {}))


@dataclass(frozen=True)
class Rejected:
    """A candidate that is not certified, and why (a key of :data:`REASONS`, and the
    detail)."""

    reason: str
    detail: str = ""


#: what a candidate is checked against
Targets = FunctionTargets | PointTargets | PoseTargets


def certify(candidate: Chain, targets: Targets, *,
            min_transmission: float = 30.0) -> Certified | Rejected:
    """Write ``candidate`` as a chain file, read it back, solve it and check it.

    Parameters
    ----------
    candidate : Chain
        A mechanism drawn at its first target, with ``driver`` (the input) and
        ``output``; its ``task`` table is written with it.
    targets : FunctionTargets, PointTargets or PoseTargets
    min_transmission : float
        The transmission angle must stay within ``[min, 180 - min]`` degrees.

    Returns
    -------
    Certified or Rejected
    """
    if candidate.mechanism is None or (candidate.mechanism.driver is None
                                       and not candidate.mechanism.inputs):
        raise ValueError(f"the candidate {candidate.name!r} needs a [mechanism] with a "
                         "driver or an input")
    with warnings.catch_warnings():
        # a joint a hair off a sliding line is put on it as the file is read: the chain
        # certified (and listed) is the one read, as solve reads the written file
        warnings.simplefilter("ignore", PoseAdjustedWarning)
        chain = loads(dumps(candidate), source=f"<{candidate.name}>")
    try:
        if isinstance(targets, FunctionTargets):
            found = _function(chain, targets)
        elif isinstance(targets, PoseTargets) and targets.inputs is not None:
            found = _posed(chain, targets)
        else:
            found = _traced(chain, targets)
    except AssemblyError as e:
        return Rejected("does not assemble", str(e))
    if isinstance(found, Rejected):
        return found
    reached, error, curve, rows, angle = found
    ta = transmission_angles(chain, rows)
    if ta is not None and (ta[0] < min_transmission or ta[1] > 180.0 - min_transmission):
        return Rejected("transmission angle", f"{ta[0]:.4g} to {ta[1]:.4g} degrees")
    m = candidate.mechanism
    turning = turning_links(chain, m.fixed)
    four = four_link_loop(chain)
    grashof = (behaviour(chain, m.fixed) if four is not None
               and all(j.kind == "R" for j in chain.joints) else None)
    how = ("slides" if _slides(chain) else
           "turns fully" if turning and m.driver in turning else "rocks")
    return Certified(chain, float(np.max(error)), float(np.sqrt(np.mean(np.square(error)))),
                     tuple(float(v) for v in reached), ta, grashof, how, curve, angle)


def _slides(chain) -> bool:
    """Whether a mechanism's (one) input is a sliding pair: its values are slides, in
    file units, and it does not come round."""
    m = chain.mechanism
    return (m.driver is None and len(m.inputs) == 1
            and chain.joint(m.inputs[0].joint).kind == "P")


def _function(chain, t: FunctionTargets):
    """Solve over the task's range and at each target; the structural error."""
    fixed = chain.mechanism.fixed
    turns = next(j for j in chain.joints_of(t.output) if fixed in j.links).kind == "R"
    out_tol = 1e-6 if turns else 1e-8 * _size(chain)
    first, last = t.inputs[0], t.inputs[-1]
    try:
        at_targets = [solve(chain, start=v, stop=v, steps=1, summary=False)
                      for v in t.inputs]
    except AssemblyError as e:
        return Rejected("does not assemble", str(e))
    got = [float(output_values(chain, m, t.output, near=o)[0])
           for m, o in zip(at_targets, t.outputs)]
    for k, (g, want) in enumerate(zip(got, t.outputs)):
        if not abs(g - want) <= out_tol:
            return Rejected("circuit defect", f"target {k + 1}: the solver's output is "
                            f"{g:.6g}, the design's {want:.6g}")
    try:                        # from the first target to the last, the input one way
        inner = solve(chain, start=first, stop=last, steps=_SWEEP, summary=False)
    except AssemblyError as e:
        return Rejected("branch defect", str(e))
    try:
        whole = solve(chain, start=t.span[0], stop=t.span[1], steps=_SWEEP, summary=False)
    except AssemblyError as e:
        return Rejected("does not assemble", f"over the task's range: {e}")
    theta = whole["theta"]
    out = output_values(chain, whole, t.output, near=t.outputs[0])
    error = out - t.wanted(theta)
    return (tuple(t.inputs), np.abs(error), (theta, error), [inner] + at_targets, None)


def _posed(chain, t: PoseTargets):
    """Solve at the input's claimed value at each pose; the poses met there, on the
    drawn pose's circuit, in order as the input moves one way, with no limit between
    the first and the last."""
    assert t.inputs is not None
    tol = 1e-6 * _size(chain)
    rows = [solve(chain, start=v, stop=v, steps=1, summary=False) for v in t.inputs]
    dist = np.array([math.hypot(float(m[f"x:{t.point}"][0]) - p[0],
                                float(m[f"y:{t.point}"][0]) - p[1])
                     for m, p in zip(rows, t.points)])
    turn = np.array([float(m[f"angle:{t.link}"][0]) for m in rows]) - np.asarray(t.angles)
    turn = np.abs((turn + 180.0) % 360.0 - 180.0)
    missed = [k + 1 for k in range(len(rows)) if not (dist[k] <= tol and turn[k] <= 1e-6)]
    steps = np.diff(t.inputs)
    one_way = bool(np.all(steps > 0) or np.all(steps < 0))
    if not one_way:
        k = int(np.argmax(np.sign(steps[1:]) != np.sign(steps[0]))) + 2
        return Rejected("branch defect" if missed else "order defect",
                        f"the input turns back at target {k} "
                        f"({', '.join(f'{v:.6g}' for v in t.inputs)})")
    if missed:
        return Rejected("circuit defect", f"target {missed[0]}: the solver's pose there is "
                        f"{dist[missed[0] - 1]:.3g} and {turn[missed[0] - 1]:.3g} degrees "
                        "from the design's")
    first, last = t.inputs[0], t.inputs[-1]
    try:
        inner = solve(chain, start=first, stop=last, summary=False,
                      steps=max(2, min(720, int(abs(last - first) * 2))))
    except AssemblyError as e:
        return Rejected("branch defect", str(e))
    return (tuple(t.inputs), dist, (inner[f"x:{t.point}"], inner[f"y:{t.point}"]),
            [inner] + rows, float(np.max(turn)))


def _traced(chain, t):
    """Solve the input's whole cycle; where the tracer passes each target, in order."""
    whole = solve(chain, steps=_CYCLE, summary=False)
    theta = whole["theta"]
    xs, ys = whole[f"x:{t.point}"], whole[f"y:{t.point}"]
    size = _size(chain)
    full = abs(theta[-1] - theta[0]) >= 360.0 - 1e-9 and not _slides(chain)
    if getattr(t, "closed", False) and not full:
        return Rejected("branch defect", "the input does not turn fully: no closed curve "
                        "over its turn")
    candidates = []
    for target in t.points:
        d = np.hypot(xs - target[0], ys - target[1])
        near = [k for k in range(d.size) if d[k] <= d.min() + 1e-3 * size and
                (k == 0 or d[k] <= d[k - 1]) and (k == d.size - 1 or d[k] <= d[k + 1])]
        candidates.append([_refined(chain, t.point, target, theta, k) for k in near])
    reached = reached_in_order([[v for v, _ in c] for c in candidates], theta, full)
    if reached is None:
        return Rejected("order defect", "the targets are passed, but not in the given order "
                        "as the input moves one way")
    dist = np.array([dict(c)[v] for c, v in zip(candidates, reached)])
    angle = None
    rows = [solve(chain, start=v, stop=v, steps=1, summary=False) for v in reached]
    if isinstance(t, PoseTargets):
        got = np.array([float(m[f"angle:{t.link}"][0]) for m in rows])
        angle = float(np.max(np.abs((got - np.asarray(t.angles) + 180.0) % 360.0 - 180.0)))
    lo, hi = min(reached[0], reached[-1]), max(reached[0], reached[-1])
    if lo < hi:
        rows.append(solve(chain, start=reached[0], stop=reached[-1],
                          steps=max(2, int(abs(reached[-1] - reached[0]) * 2)),
                          summary=False))
    return reached, dist, (xs, ys), rows, angle


def _refined(chain, point, target, theta, k):
    """(input, distance) of the tracer's closest approach to ``target`` near step k:
    the squared distance (smooth) minimised over the input's offset from step k (small,
    so that the minimiser's relative tolerance does not hide the last digits)."""
    here = float(theta[k])
    lo = float(theta[max(k - 1, 0)]) - here
    hi = float(theta[min(k + 1, theta.size - 1)]) - here

    def squared(u):
        v = here + u
        m = solve(chain, start=v, stop=v, steps=1, summary=False)
        return ((float(m[f"x:{point}"][0]) - target[0]) ** 2
                + (float(m[f"y:{point}"][0]) - target[1]) ** 2)
    if lo == hi:
        return here, math.sqrt(squared(0.0))
    found = minimize_scalar(squared, bounds=(min(lo, hi), max(lo, hi)), method="bounded",
                            options={"xatol": 1e-12})
    return here + float(found.x), math.sqrt(max(float(found.fun), 0.0))


def reached_in_order(candidates: Sequence[Sequence[float]], theta: np.ndarray,
                     full_turn: bool) -> list[float] | None:
    """The input values, one per target, at which the targets are met in the given
    order as the input moves one way from the first (for an input that turns fully,
    within one turn); None when there are none. ``candidates[i]`` are the input values
    where target i is passed."""
    span = 360.0 if full_turn else None
    for direction in (1.0, -1.0):
        for start in candidates[0]:
            out, here, travelled = [start], start, 0.0
            for options in candidates[1:]:
                ahead = []
                for v in options:
                    step = (v - here) * direction
                    if span is not None:
                        step %= span
                    if step > 0 or (step == 0 and v != here):
                        ahead.append((step, v))
                if not ahead:
                    break
                step, v = min(ahead)
                travelled += step
                out.append(v)
                here = v
            else:
                if span is None or travelled < span:
                    return out
    return None


def output_values(chain: Chain, motion: Motion, output: str, *,
                  near: float | None = None) -> np.ndarray:
    """A function generator's output over a solved motion: for a link turning about the
    fixed link, the angle (degrees, CCW from +x, unwrapped, within a half turn of
    ``near`` at the first row) of the line from its pivot to its other joint; for a link
    sliding on the fixed link, its other joint's position along the guide (measured from
    the origin's foot on the guide's line)."""
    if chain.mechanism is None:
        raise ValueError(f"{chain.name!r} has no [mechanism]: no fixed link to measure from")
    fixed = chain.mechanism.fixed
    pivot = next(j for j in chain.joints_of(output) if fixed in j.links)
    other = next(j for j in chain.joints_of(output) if j.id != pivot.id)
    x, y = motion[f"x:{other.id}"], motion[f"y:{other.id}"]
    if pivot.kind == "P":
        a = math.radians(pivot.axis or 0.0)      # a drawn P joint has its axis
        return x * math.cos(a) + y * math.sin(a)
    angle = np.degrees(np.unwrap(np.arctan2(y - motion[f"y:{pivot.id}"],
                                            x - motion[f"x:{pivot.id}"])))
    if near is not None:
        angle = angle + 360.0 * np.round((near - angle[0]) / 360.0)
    return angle


def transmission_angles(chain: Chain,
                        motions: Sequence[Motion]) -> tuple[float, float] | None:
    """The transmission angle's range (degrees) over the rows of ``motions``, at the
    output dyad of a four-link loop (the joint between the two links that are neither
    fixed nor the input link, a driver or the link its input joint moves): the angle
    between the coupler and the rocker (four-bar); where a sliding pair makes the dyad,
    within [0, 90], the angle to the normal of the guide: of the coupler, for a block on
    a fixed guide (slider crank); of the line from the block's fixed pivot to the
    coupler's pin, for a coupler sliding in a block that turns about a fixed pivot; of
    the rocker, for a coupler sliding in the input link, or the angle between the
    rocker and the axis of a cylinder driving it (a sliding input between two moving
    links: the force's line) (each 0 where the input meets a limit); for a mechanism of
    more than four links, its dyads' and groups' (:func:`_dyads_transmission`); None
    for other mechanisms."""
    m = chain.mechanism
    loop = four_link_loop(chain)
    lead = _input_link(chain)
    if m is None or lead is None:
        return None
    if loop is None:
        return _dyads_transmission(chain, motions)
    free = [x for x in loop[0] if x not in (m.fixed, lead)]
    joint = next(j for j in chain.joints if set(j.links) == set(free))
    coupler = next(x for x in free if any(lead in j.links for j in chain.joints_of(x)))
    rocker = next(x for x in free if x != coupler)
    back = next(j for j in chain.joints_of(coupler) if j.id != joint.id)
    ahead = next(j for j in chain.joints_of(rocker) if j.id != joint.id)
    cylinder = (m.driver is None and bool(m.inputs) and back.id == m.inputs[0].joint
                and m.fixed not in back.links)
    values = []
    for motion in motions:
        def xy(j):
            return motion[f"x:{j.id}"], motion[f"y:{j.id}"]
        if joint.kind == "R" and back.kind == "R" and ahead.kind == "R":
            mu = _angle_at(motion, joint.id, back.id, ahead.id)
        elif joint.kind == "R" and ahead.kind == "P" and m.fixed in ahead.links:
            mu = _to_normal(np.subtract(xy(back), xy(joint)), _guide(chain, motion, ahead))
        elif joint.kind == "P" and ahead.kind == "R" and m.fixed in ahead.links:
            mu = _to_normal(np.subtract(xy(back), xy(ahead)), _guide(chain, motion, joint))
        elif joint.kind == "R" and back.kind == "P" and ahead.kind == "R":
            mu = _to_normal(np.subtract(xy(ahead), xy(joint)), _guide(chain, motion, back))
            if cylinder:        # the force's line is the cylinder's axis, not its normal
                mu = 90.0 - mu
        else:
            return None
        values.append(np.asarray(mu, dtype=float).reshape(-1))
    mu = np.concatenate(values)
    return float(np.min(mu)), float(np.max(mu))


def _dyads_transmission(chain: Chain,
                        motions: Sequence[Motion]) -> tuple[float, float] | None:
    """The transmission angles' range (degrees) of a mechanism of more than four links
    (a six- or eight-bar), over the rows of ``motions``, as the atlas families measure
    them for their screen: at the middle joint of each dyad its solution places
    (:func:`build_plan`), the angle between its two links (their lines to the joints
    that carry them); with a sliding pair (within [0, 90]), the angle between the
    turning link and the guide's normal (RRP), between the line through the two pivots
    and the guide's normal (RPR), or between the two guides (PRP, RPP); at each turning
    pair between two links of a group solved together (a triad), the angle between the
    two links' lines to another of their joints (the first in the chain's order). None
    where nothing is measured."""
    plan = build_plan(chain)
    measures: list[Callable[[Motion], np.ndarray]] = []
    for step in plan.steps:
        if step.kind == "dyad":
            measures.append(_dyad_angle(chain, step.pattern, *step.constraints))
        elif step.kind == "group":
            inside = set(step.links)
            for j in chain.joints:
                if j.kind == "R" and set(j.links) <= inside and len(j.links) == 2:
                    ends = [next(k.id for k in chain.joints if x in k.links and k.id != j.id)
                            for x in j.links]
                    measures.append(partial(_angle_at, at=j.id, one=ends[0], other=ends[1]))
    if not measures:
        return None
    mu = np.concatenate([np.asarray(f(m), dtype=float).reshape(-1)
                         for m in motions for f in measures])
    return float(np.min(mu)), float(np.max(mu))


def _dyad_angle(chain: Chain, pattern: str, ca, cb, cj) -> Callable[[Motion], np.ndarray]:
    """One dyad's transmission angle over a motion (see :func:`_dyads_transmission`):
    ``ca`` and ``cb`` attach its links to known ones, ``cj`` joins them."""
    if pattern in ("PRR", "PPR"):           # (the R-first form, as the solver mirrors it)
        ca, cb, pattern = cb, ca, pattern[::-1]
    first, middle, second = (chain.joint(c.joint) for c in (ca, cj, cb))

    def xy(m, j):
        return np.array([m[f"x:{j.id}"], m[f"y:{j.id}"]])
    if pattern == "RRR":
        return lambda m: _angle_at(m, middle.id, first.id, second.id)
    if pattern == "RRP":
        return lambda m: _to_normal(xy(m, first) - xy(m, middle), _guide(chain, m, second))
    if pattern == "RPR":
        return lambda m: _to_normal(xy(m, second) - xy(m, first), _guide(chain, m, middle))
    one = first if pattern == "PRP" else middle          # PRP, RPP: the two guides

    def guides(m):
        between = _guide(chain, m, one) - _guide(chain, m, second)
        return np.degrees(np.arccos(np.clip(np.abs(np.cos(between)), 0.0, 1.0)))
    return guides


def _angle_at(motion: Motion, at: str, one: str, other: str) -> np.ndarray:
    """The angle (degrees) at joint ``at`` between the lines to joints ``one`` and
    ``other`` over a motion."""
    cx, cy = motion[f"x:{at}"], motion[f"y:{at}"]
    return angle_between((motion[f"x:{one}"] - cx, motion[f"y:{one}"] - cy),
                         (motion[f"x:{other}"] - cx, motion[f"y:{other}"] - cy))


def _input_link(chain) -> str | None:
    """The link the input moves: the driver, or the moving link of the first input
    joint."""
    m = chain.mechanism
    if m is None:
        return None
    if m.driver is not None:
        return m.driver
    if not m.inputs:
        return None
    links = chain.joint(m.inputs[0].joint).links
    return next((x for x in links if x != m.fixed), None)


def _guide(chain, motion, joint) -> np.ndarray:
    """A sliding pair's guide direction (radians) over a solved motion."""
    link = joint.links[0]
    turn = motion[f"angle:{link}"] - chain.reference_direction(link)
    return np.radians(joint.axis + np.asarray(turn, dtype=float))


def _to_normal(u, guide) -> np.ndarray:
    """The angle (degrees, [0, 90]) between the vectors ``u`` (rows x, y) and the
    normal of the guide at ``guide`` radians."""
    nx, ny = -np.sin(guide), np.cos(guide)
    cos = np.abs(u[0] * nx + u[1] * ny) / np.hypot(u[0], u[1])
    return np.degrees(np.arccos(np.clip(cos, 0.0, 1.0)))


def _size(chain):
    pts = np.array([j.at for j in chain.joints] + [p.at for p in chain.points], dtype=float)
    return float(max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1]), 1e-300))
