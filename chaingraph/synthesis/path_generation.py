"""Path generation: a four-bar whose coupler point passes through given points, in order.

The unknowns are the mechanism's drawn pose at the first target (its pivots, its moving
joints and the coupler point: so its lengths, the coupler point's place and the input
there) and the input's value at every other target; each target gives two equations,
``position(theta_i) = target_i`` (:mod:`chaingraph.synthesis.optimiser`, in the task's
own frame).

* Up to five points (not ``closed``) are passed **exactly**: fewer equations than
  unknowns (ten for five points, fourteen unknowns), so each start converges to a
  nearby solution. Starts come from a coarse search (random crank-rockers, turned and
  scaled onto the task, the best by their in-order distance to the targets), each
  solved by least squares (scipy's ``least_squares``, a finite-difference Jacobian) to
  rounding. With a ``timing`` the inputs are not unknowns: the input turns by the
  timing's steps from the first target to each other (its value at the first target is
  chosen, as in the textbooks' standard form), so five points with timing are ten
  equations in ten unknowns, solved directly the same way (not reduced to motion
  generation).
* More points, or a ``closed`` curve (the input turns fully and the path closes over its
  turn), are **fitted**: differential evolution (scipy, seeded from the coarse search,
  repeatable from ``seed``) on the in-order distance from each target to the traced
  path, then least squares from its best and from the coarse search's.

Every candidate is then written as a chain file and certified by
:func:`~chaingraph.synthesis.certification.certify` (assembled at every target, one circuit,
the targets in order as the input moves one way, the transmission angle, the error
recomputed: the largest and rms distance from the targets to the solved path).
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from chaingraph.errors import DesignError
from chaingraph.naming import identify
from chaingraph.synthesis.burmester import burmester_points
from chaingraph.synthesis.certification import Certified, PointTargets, Rejected, certify
from chaingraph.synthesis.family import FOUR_BAR, AtlasFamily, Family
from chaingraph.synthesis.optimiser import (
    MAX_RATIO,
    Fit,
    TaskFrame,
    coarse_search,
    fit_start,
    global_search,
    least_squares_fit,
    predicted_defect,
    timed_guides,
)
from chaingraph.synthesis.result import Searched, Solution, Synthesis, ranked
from chaingraph.synthesis.task import PathTask, check_options, drawn_seed, path_task

__all__ = ["path", "path_search_task", "EXACT", "synthesise_path", "Budget", "BUDGET",
           "screened_fits", "first_certified", "least_transmission", "slide_span",
           "spare_unknowns", "passing_fits", "within_bounds", "into_bounds", "MARGIN"]

#: a fit passes its points exactly when every distance is within this of the task's size
EXACT = 1e-9
_SAMPLES = {True: 2500, False: 4000}     # random mechanisms in the coarse search
_STARTS = {True: 40, False: 60}          # least-squares starts (exact; and DE's population)
_STEPS = {True: 96, False: 96}           # samples of a path over a turn
_FITTED = 8                              # fitted starts certified from, without exactness
_CERTIFIED = 3                           # candidates certified per solution asked for
_TIMING = 1e-6                           # degrees: a target's input against its timing
_PASSING_EVALUATIONS = 300               # least squares's, onto a family's set of solutions
#: degrees: an exact fit's transmission angle is sought within the bound by so much
#: where it has unknowns to spare (sampled more finely, the certification's may be a
#: little worse)
MARGIN = 2.0
_MOVE_EVALUATIONS = 200                  # least squares's, along a set into the bounds


def path(*, points: Iterable[tuple[float, float]],
         timing: Iterable[float] | None = None, closed: bool = False, kind: str = "four-bar",
         solutions: int = 5, seed: int | None = None, units: str = "mm",
         min_transmission: float = 30.0) -> Synthesis:
    """Synthesise a path generator: a four-bar whose coupler point passes through
    ``points`` in order.

    Parameters
    ----------
    points : sequence of (x, y)
        The targets, in order (two or more; three or more for a closed curve).
    timing : sequence of float, optional
        The input's value (degrees) at each target; the input's turn between targets is
        kept, its value at the first target is chosen (so ``reached_at`` may differ from
        the timing by one constant).
    closed : bool
        The targets lie on a closed curve traced over a full turn of the input.
    kind : {"four-bar"}
    solutions : int
        At most this many certified solutions, best first.
    seed : int, optional
        The random search's seed (the same seed, the same solutions); by default one is
        drawn and given in the task (``task.seed``).
    units : str
    min_transmission : float
        The transmission angle stays within [min, 180 - min] degrees between the first
        target and the last.

    Returns
    -------
    Synthesis
        Up to five points (not closed) passed exactly (to :data:`EXACT` of the task's
        size); more, or a closed curve, fitted; certified solutions best first.

    Raises
    ------
    DesignError
        For a bad task (``parameter`` names it).

    Examples
    --------
    >>> s = path(points=[(0, 0), (10, 4), (18, 12), (20, 22), (14, 30)], seed=1,
    ...          solutions=1)
    >>> s.solutions[0].error.max < 1e-9 * 36
    True
    """
    task = path_search_task(points=points, timing=timing, closed=closed, kind=kind,
                            solutions=solutions, seed=seed, units=units,
                            min_transmission=min_transmission)
    return synthesise_path(task, FOUR_BAR, solutions=solutions)


def path_search_task(*, points: Iterable[tuple[float, float]],
                     timing: Iterable[float] | None, closed: bool, kind: str,
                     solutions: int, seed: int | None, units: str,
                     min_transmission: float, slides: bool = False) -> PathTask:
    """The checked task of a path search (:func:`path`'s parameters, ``solutions``
    checked too), its seed drawn when None (:func:`~chaingraph.synthesis.task.drawn_seed`);
    ``slides``: the timing may be a sliding input's (see
    :func:`~chaingraph.synthesis.task.path_task`)."""
    task = path_task(points=points, timing=timing, closed=closed, kind=kind,
                     seed=drawn_seed(seed), units=units, min_transmission=min_transmission,
                     slides=slides)
    check_options(solutions=solutions, min_transmission=min_transmission, units=units,
                  kind="path")
    return task


@dataclass(frozen=True)
class Budget:
    """How hard the optimiser searches one family: random mechanisms in the coarse
    search (``samples``), least-squares starts and differential evolution's population
    (``starts``), fitted starts certified from (``fitted``), differential evolution's
    ``generations``; ``passing``: the most evaluations least squares makes from each
    start onto a family's set of solutions where it has spare unknowns
    (:func:`passing_fits`; 0: not tried, the targets fitted only)."""

    samples: int
    starts: int
    fitted: int = _FITTED
    generations: int = 100
    passing: int = _PASSING_EVALUATIONS


#: the four-bar's budget, exact (up to five points) and fitted
BUDGET = {True: Budget(_SAMPLES[True], _STARTS[True]), False: Budget(_SAMPLES[False],
                                                                        _STARTS[False])}


def synthesise_path(task: PathTask, family: Family, *, solutions: int,
                    budget: Budget | None = None,
                    rng: np.random.Generator | None = None) -> Synthesis:
    """Path synthesis of a checked task over one mechanism family (the optimiser is the
    family's: see :mod:`chaingraph.synthesis.family`), searching as hard as ``budget``
    says (by default :data:`BUDGET`), from ``rng`` (by default the task's seed)."""
    frame = TaskFrame.of(task.points)
    targets = frame.to_task(task.points)
    rng = np.random.default_rng(task.seed) if rng is None else rng
    exact = task.exact
    budget = BUDGET[exact] if budget is None else budget
    steps = _STEPS[exact]
    turns = None
    if task.timing is not None:     # a turn in degrees; a slide in file units
        turns = np.asarray(task.timing, dtype=float) - task.timing[0]
        turns = turns / frame.scale if family.sliding else np.radians(turns)
    common: dict[str, Any] = dict(steps=steps, min_transmission=task.min_transmission,
                                  timing=turns)
    starts, _ = coarse_search(family, targets, rng, count=budget.samples,
                              keep=budget.starts, **common)
    if turns is not None and family.sliding and exact and len(targets) == 5:
        # five targets timed in slides: seeds built as the textbooks build them
        starts = np.concatenate([timed_slider_seeds(family, targets, turns,
                                                    timed_guides(targets, turns)), starts])
    fits = []
    spare = spare_unknowns(family, len(targets), timed=True)
    if not exact and turns is not None and spare is not None and spare >= 0 and budget.passing:
        # as many unknowns as timed equations or more: the family passes them exactly
        fits = passing_fits(family, targets, starts, turns, steps=steps,
                            min_transmission=task.min_transmission, wanted=solutions,
                            evaluations=budget.passing)
    if not exact and len(fits) < solutions:
        best, _ = global_search(family, targets, starts, rng,
                                generations=budget.generations, **common)
        starts = np.concatenate([best[None, :], starts[:budget.fitted - 1]])
    elif not exact:             # passed exactly: nothing left to fit
        starts = starts[:0]
    if len(starts):
        fits += _fitted(task, family, targets, starts, turns, steps=steps)
    fits, rejected = screened_fits(family, fits)
    # the fits that pass the targets exactly first, the best transmission first; then
    # the others, the nearest first
    fits.sort(key=lambda f: (0.0, -least_transmission(family, f))
              if f.residual <= EXACT / 10 else (1.0, f.residual))
    found = first_certified(fits, solutions, lambda f: _certified(task, family, frame, f),
                            rejected, tried=_CERTIFIED * solutions)
    size = task.size
    return Synthesis(task, ranked(found, solutions,
                                  tolerance=EXACT * size if exact else 0.0),
                     dict(sorted(rejected.items())), Searched(1, 1, budget.samples))


def _fitted(task: PathTask, family: Family, targets: np.ndarray, starts: np.ndarray,
            turns: np.ndarray | None, *, steps: int) -> list[Fit]:
    """Least squares from each start: to rounding for an exact task (the fits that do
    not reach it dropped), else the least squares of the distances."""
    exact = task.exact
    posed, inputs = fit_start(family, starts, targets, steps=steps, timing=turns)
    fits = []
    for p, th in zip(posed, inputs):
        if not np.all(np.isfinite(p)):
            continue
        fit = least_squares_fit(family, targets, p, th, timing=turns, exact=exact,
                                min_transmission=task.min_transmission,
                                closed=task.closed)
        if fit is not None and (not exact or fit.residual <= EXACT / 10):
            fits.append(fit)
    return fits


def spare_unknowns(family: Family, count: int, *, timed: bool) -> int | None:
    """How many more unknowns than equations passing ``count`` targets exactly gives a
    family of turning pairs: its parameters (the drawn pose at the first target: its
    dimensions and the input there), and without a timing the input's ``count - 1``
    steps, against two equations per target. Zero or more: the targets can be passed
    exactly (by a set of mechanisms of that dimension, in general); the four-bar has 10
    parameters (five timed points), a six-bar 16 (eight). None for a family with
    sliding pairs (its drawn parameters hold more than its dimensions: a line's
    second point, a block's pair along its line)."""
    if any(j.kind != "R" for j in family.template):
        return None
    return family.size + (0 if timed else count - 1) - 2 * count


def passing_fits(family: Family, targets: np.ndarray, starts: np.ndarray,
                 timing: np.ndarray, *, steps: int, min_transmission: float,
                 wanted: int, evaluations: int = _PASSING_EVALUATIONS) -> list[Fit]:
    """Fits that pass timed ``targets`` to rounding (:data:`EXACT`), solved by least
    squares from each of ``starts`` (best first) with ``evaluations`` at most, for a
    family with spare unknowns (:func:`spare_unknowns`: its solutions a set,
    so that least squares converges onto it where the fitted search would stop near
    it); the search stops once ``wanted`` of them look right by the family's own
    kinematics (no predicted defect, the transmission angle and the link ratio within
    bounds)."""
    posed, inputs = fit_start(family, starts, targets, steps=steps, timing=timing)
    fits: list[Fit] = []
    good = 0
    for p, th in zip(posed, inputs):
        if not np.all(np.isfinite(p)):
            continue
        fit = within_bounds(family, targets, p, th, timing=timing,
                            min_transmission=min_transmission, evaluations=evaluations)
        if fit is None or fit.residual > EXACT / 10:
            continue
        fits.append(fit)
        good += predicted_defect(family, fit) is None and _in_bounds(family, fit,
                                                                    min_transmission)
        if good >= wanted:
            break
    return fits


def within_bounds(family: Family, targets: np.ndarray, params: np.ndarray,
                  inputs: np.ndarray, *, min_transmission: float,
                  timing: np.ndarray | None = None, turns: np.ndarray | None = None,
                  evaluations: int | None = None) -> Fit | None:
    """An exact fit (:func:`least_squares_fit`) from ``params`` and ``inputs``, moved
    :func:`into_bounds` where it passes the targets."""
    fit = least_squares_fit(family, targets, params, inputs, timing=timing, turns=turns,
                            exact=True, evaluations=evaluations)
    if fit is None or fit.residual > EXACT / 10:
        return fit
    return into_bounds(family, targets, fit, min_transmission=min_transmission,
                       timing=timing, turns=turns, evaluations=evaluations)


def into_bounds(family: Family, targets: np.ndarray, fit: Fit, *, min_transmission: float,
                timing: np.ndarray | None = None, turns: np.ndarray | None = None,
                evaluations: int | None = None) -> Fit:
    """An exact ``fit`` whose transmission angle or link ratio is out of bounds moved
    by least squares onto the same set of solutions where the bounds hold (by
    :data:`MARGIN`; a family with unknowns to spare can move along its set): that fit
    if it passes the targets still, else ``fit`` as it is (the certification judges it);
    a fit within bounds as it is."""
    if _in_bounds(family, fit, min_transmission):
        return fit
    moved = least_squares_fit(family, targets, fit.params, fit.inputs, timing=timing,
                              turns=turns, exact=True, bounded=True,
                              evaluations=max(evaluations or 0, _MOVE_EVALUATIONS),
                              min_transmission=min_transmission + MARGIN)
    return moved if moved is not None and moved.residual <= EXACT / 10 else fit


def _in_bounds(family: Family, fit: Fit, min_transmission: float) -> bool:
    """Whether a fit's transmission angle (by the family's kinematics, from the first
    target to the last) and its link ratio are within bounds."""
    return (least_transmission(family, fit) >= min_transmission
            and family.link_ratio(fit.params[None, :])[0] <= MAX_RATIO)


def _distinct(fits: list[Fit]) -> list[Fit]:
    """The fits, repeats dropped (parameters within 1e-6 of the task's size)."""
    out: list[Fit] = []
    for f in fits:
        if not any(np.max(np.abs(f.params - g.params)) <= 1e-6 for g in out):
            out.append(f)
    return out


def screened_fits(family: Family, fits: list[Fit]) -> tuple[list[Fit], Counter]:
    """The distinct fits the family's own kinematics predicts no defect for, and the
    others counted by the defect predicted."""
    rejected: Counter = Counter()
    kept = []
    for f in _distinct(fits):
        defect = predicted_defect(family, f)
        if defect is None:
            kept.append(f)
        else:
            rejected[defect] += 1
    return kept, rejected


def first_certified(fits: list[Fit], solutions: int,
                    certify_one: Callable[[Fit], Solution | Rejected], rejected: Counter,
                    *, tried: int) -> list[Solution]:
    """The first ``solutions`` of the fits (in their order, at most ``tried`` of them
    tried) that ``certify_one`` certifies; each rejected counted in ``rejected`` by its
    reason."""
    found: list[Solution] = []
    for fit in fits[:tried]:
        if len(found) >= solutions:
            break
        outcome = certify_one(fit)
        if isinstance(outcome, Rejected):
            rejected[outcome.reason] += 1
        else:
            found.append(outcome)
    return found


def timed_slider_seeds(family: Family, targets: np.ndarray, slides: np.ndarray,
                       guides: np.ndarray) -> np.ndarray:
    """Slider cranks driven by their slider through five targets at timed ``slides``,
    built as the textbooks reduce timed path generation to motion generation: each of
    the ``guides`` (:func:`~chaingraph.synthesis.optimiser.timed_guides`: the slide's
    direction, the block's pin and the point's circle about it) gives the coupler's
    five poses (the pin slid along the guide, the coupler turned about it to the
    target), and each of their Burmester points (an RR dyad,
    :func:`~chaingraph.synthesis.burmester.burmester_points`) a crank; rows of
    ``family``'s parameters drawn at the first target (none unless the family is the
    four-link chain driven by a slide on its fixed link, its carrier pinned to the
    block and to a crank turning about the fixed link). Five timed targets
    over-determine the slider crank by one, so its solutions are isolated: random
    seeds rarely find them, these do when the task has one."""
    parts = _slider_crank_joints(family)
    if parts is None or not isinstance(family, AtlasFamily):
        return np.zeros((0, family.size))
    pair, pin, crank, pivot = parts
    rows = []
    for phi, cx, cy, _ in guides:
        u = np.array([math.cos(phi), math.sin(phi)])
        q = targets - slides[:, None] * u[None, :]
        turn = np.arctan2(q[:, 1] - cy, q[:, 0] - cx)
        poses = [(cx + v * u[0], cy + v * u[1], t - turn[0]) for v, t in zip(slides, turn)]
        try:
            dyads = burmester_points(poses)
        except DesignError:
            continue
        for d in dyads:
            if d.kind != "RR" or d.centre is None or d.circle is None:
                continue
            at = {pair: (cx, cy), pin: (cx, cy), crank: d.circle, pivot: d.centre}
            row = family.params_of(at, {pair: phi}, tuple(targets[0]))
            if abs(math.remainder(float(family.slide_direction(row[None, :])[0]) - phi,
                                  2 * math.pi)) > 1.0:    # the block slides the other way
                row = family.params_of(at, {pair: phi + math.pi}, tuple(targets[0]))
            rows.append(row)
    return np.array(rows).reshape(-1, family.size)


def _slider_crank_joints(family: Family) -> tuple[str, str, str, str] | None:
    """The four-link chain driven by a slide on its fixed link, its carrier pinned to
    the block and to a crank about the fixed link: the joints' ids (the sliding pair,
    the block's pin, the crank's pin, the crank's pivot); else None."""
    joints = family.template
    if len(joints) != 4 or not isinstance(family, AtlasFamily) or not family.sliding:
        return None
    fixed, driver, carrier = family.fixed, family.driver, family.carrier

    def joint(a, b, kind):
        return next((j.id for j in joints if set(j.links) == {a, b} and j.kind == kind), None)
    crank = next((x for j in joints for x in j.links
                  if carrier in j.links and x not in (carrier, driver)), None)
    found = (joint(fixed, driver, "P"), joint(carrier, driver, "R"),
             joint(carrier, crank, "R"), joint(crank, fixed, "R"))
    if crank is None or None in found:
        return None
    return found


def least_transmission(family: Family, fit: Fit) -> float:
    """The transmission angle's worst (the least of mu and 180 - mu) between the first
    target and the last, by the family's own kinematics; -1 where unassembled."""
    lo, hi = fit.inputs[0], fit.inputs[-1]
    theta = np.linspace(lo, hi, 181)[None, :]
    mu = family.transmission(fit.params[None, :], theta)
    worst = np.minimum(mu, 180.0 - mu)
    return float(np.nanmin(worst)) if np.all(np.isfinite(worst)) else -1.0


def _certified(task, family, frame, fit):
    """Write, read back, solve and check one fitted mechanism; a Solution or Rejected."""
    world = frame.to_world(fit.params)
    if family.link_ratio(world[None, :])[0] > MAX_RATIO:
        return Rejected("link ratio")
    n = len(task.points)
    how = ("closed curve through" if task.closed else "path through") + f" {n} points"
    table = {k: v for k, v in task.to_dict().items() if v is not None}
    dims = family.dimensions(world)
    sizes = ", ".join(f"{k} {v:.6g}" for k, v in dims.items())
    chain = family.chain(world, name=f"{family.title}: {how}",
                         units=task.units, span=slide_span(family, frame, fit),
                         notes=f"Designed by chaingraph (path generation, {family.name}): "
                               f"{sizes}; drawn at the first target; the coupler point "
                               f"{family.point} passes the targets in order.", task=table)
    result = certify(chain, PointTargets(task.points, family.point, task.closed),
                     min_transmission=task.min_transmission)
    if isinstance(result, Rejected):
        return result
    if task.timing is not None and not _on_time(task, result, family.sliding):
        return Rejected("timing", "the targets are not met at the timing's input values")
    return _solution(result, dims)


def slide_span(family: Family, frame: TaskFrame, fit: Fit) -> tuple[float, float] | None:
    """A sliding input's sweep in the written file: from the first target (the drawn
    pose, 0) to the last, in file units; None for a turning input (its whole turn)."""
    if not family.sliding:
        return None
    return 0.0, float((fit.inputs[-1] - fit.inputs[0]) * frame.scale)


def _on_time(task, c: Certified, sliding: bool = False) -> bool:
    """Whether the targets are met at the timing's input values (up to one constant:
    the first's); a sliding input's are slides (file units), not angles."""
    got = np.asarray(c.reached_at) - c.reached_at[0]
    want = np.asarray(task.timing) - task.timing[0]
    if sliding:     # to rounding of the task's size (exact), or a thousandth of it
        tol = (1e3 * EXACT if task.exact else 1e-3) * task.size
        return bool(np.all(np.abs(got - want) <= tol))
    tol = _TIMING if task.exact else 1.0    # a fit meets its targets near its timing
    return bool(np.all(np.abs((got - want + 180.0) % 360.0 - 180.0) <= tol))


def _solution(c: Certified, dims) -> Solution:
    found = identify(c.chain)
    names = tuple(n for n in (found.chain, found.inversion) if n)
    return c.solution(names=names, dimensions=dims)

