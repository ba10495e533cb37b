"""Motion generation over one mechanism family by the path optimiser
(:mod:`chaingraph.synthesis.optimiser`): the carrier's point passes the poses' points
and the carrier turns as the poses do.

The unknowns are the path synthesis's (the mechanism's drawn pose at the first pose and
the input's value at every other); each pose gives three equations: the point's two and
the carrier's turn from the first pose (``Family.rotation``). Starts come from the coarse
search, scored by the in-order distance from the poses' points to the traced path plus
the rms miss of the carrier's turn where the path comes nearest each; each start is
solved by least squares to rounding (two to five poses: fewer equations than unknowns
for a six- or eight-link family). Every fit is written as a chain file and certified by
:func:`~chaingraph.synthesis.certification.certify` with
:class:`~chaingraph.synthesis.certification.PoseTargets` at the input values it claims
(the pose met there, on the drawn circuit, in order, its transmission angle within
bounds, the error recomputed by the solver).
"""

from __future__ import annotations

import numpy as np

from chaingraph.synthesis.certification import Certified, PoseTargets, Rejected, certify
from chaingraph.synthesis.family import Family
from chaingraph.synthesis.optimiser import (
    MAX_RATIO,
    TaskFrame,
    coarse_search,
    fit_start,
    least_squares_fit,
)
from chaingraph.synthesis.path_generation import (
    EXACT,
    Budget,
    first_certified,
    into_bounds,
    least_transmission,
    screened_fits,
    slide_span,
)
from chaingraph.synthesis.result import Curve, Searched, Solution, Synthesis, ranked
from chaingraph.synthesis.task import MotionTask

__all__ = ["synthesise_motion"]

_STEPS = 96          # samples of a path over a turn
_CERTIFIED = 3       # candidates certified per solution asked for


def synthesise_motion(task: MotionTask, family: Family, *, solutions: int, budget: Budget,
                      rng: np.random.Generator) -> Synthesis:
    """Motion synthesis of a checked task over one mechanism family (see the module),
    searching as hard as ``budget`` says, from ``rng``: certified solutions, best first
    (exact; then the largest least transmission angle)."""
    points = [(x, y) for x, y, _ in task.poses]
    frame = TaskFrame.of(points)
    targets = frame.to_task(points)
    turns = np.radians([a - task.poses[0][2] for _, _, a in task.poses])
    starts, _ = coarse_search(family, targets, rng, count=budget.samples,
                              keep=budget.starts, steps=_STEPS,
                              min_transmission=task.min_transmission, turns=turns)
    posed, inputs = fit_start(family, starts, targets, steps=_STEPS)
    fits = []
    for p, th in zip(posed, inputs):
        if not np.all(np.isfinite(p)):
            continue
        fit = least_squares_fit(family, targets, p, th, exact=True, turns=turns)
        if fit is not None and fit.residual <= EXACT / 10:
            fits.append(fit)
    kept, rejected = screened_fits(family, fits)
    kept.sort(key=lambda f: -least_transmission(family, f))
    tried = _CERTIFIED * solutions
    # those to be certified moved along their set of solutions into the bounds where
    # they are out (a six-bar has unknowns to spare), the best first again
    kept[:tried] = sorted((into_bounds(family, targets, f, turns=turns,
                                       min_transmission=task.min_transmission)
                           for f in kept[:tried]), key=lambda f: -least_transmission(family, f))
    found = first_certified(kept, solutions, lambda f: _certified(task, family, frame, f),
                            rejected, tried=tried)
    return Synthesis(task, ranked(found, solutions, tolerance=EXACT * task.size),
                     dict(sorted(rejected.items())), Searched(1, 1, budget.samples))


def _certified(task, family, frame, fit):
    """Write, read back, solve and check one fitted mechanism at the input values it
    claims; a Solution or Rejected."""
    world = frame.to_world(fit.params)
    if family.link_ratio(world[None, :])[0] > MAX_RATIO:
        return Rejected("link ratio")
    dims = family.dimensions(world)
    sizes = ", ".join(f"{k} {v:.6g}" for k, v in dims.items())
    chain = family.chain(
        world, name=f"{family.title}: motion through "
                    f"{len(task.poses)} poses", units=task.units,
        span=slide_span(family, frame, fit),
        notes=f"Designed by chaingraph (motion generation, {family.name}): {sizes}; "
              f"drawn at the first pose; link {family.carrier} passes the poses in order "
              f"(its point {family.point}).", task=task.to_dict())
    ref = chain.reference_direction(family.carrier)
    angles = tuple(ref + a - task.poses[0][2] for _, _, a in task.poses)
    if family.sliding:      # the solver's slide from the drawn pose (the first target)
        claimed = tuple(float(v) for v in (fit.inputs - fit.inputs[0]) * frame.scale)
    else:
        claimed = tuple(float(v) for v in np.degrees(frame.input_to_world(fit.inputs)))
    result = certify(chain, PoseTargets(tuple((x, y) for x, y, _ in task.poses), angles,
                                        family.point, family.carrier, claimed),
                     min_transmission=task.min_transmission)
    if isinstance(result, Rejected):
        return result
    return _solution(result, dims)


def _solution(c: Certified, dims) -> Solution:
    xs, ys = c.curve
    return c.solution(curve=Curve(np.asarray(xs), np.asarray(ys), "x", "y"), dimensions=dims)
