"""Type synthesis through the atlas: a path or motion task searched over every 1-dof
chain of a given number of links, every inversion and every link that can carry the
point or pose, with the same optimiser as the four-bar's.

The space (:func:`atlas_space`): the chains of the atlas with ``links`` links (with
``prismatic`` sliding pairs: the sliding atlas's), each chain's inversions (the orbits of
its links under its automorphisms, as the atlas counts them; the first link of each
orbit fixed), each inversion's drivers (a link turning about the fixed link on a
turning pair, or sliding on it on a sliding pair: a *sliding input*, its value a slide
in file units; one per orbit of (fixed, driver) pairs) and carriers (every link not
jointed to the fixed link: a link turning about a fixed pivot traces circles only, one
sliding on it lines). A
(chain, fixed, driver, carrier) choice is a *family*: an
:class:`~chaingraph.synthesis.family.AtlasFamily` when its chain is solved dyad by dyad
from its fixed link and driver in closed form (every Watt inversion, the Stephenson I,
the Stephenson II driven by a ternary link; with sliding pairs, every dyad kind RRR,
RRP, PRR, RPR, PRP, RPP, PPR), a :class:`~chaingraph.synthesis.family.LoopFamily` when
the group beyond its driver is a triad (the Stephenson III, the Stephenson II driven by
its binary link, with or without sliding pairs: Newton's method, continued along the
input, on a smaller budget, :data:`NEWTON_BUDGETS`). Both are screens: every solution is
certified by the kernel's solver from its written file. A sliding input's families are
solved alike, dyad by dyad or by Newton's method continued both ways from the drawn
slide, their path swept over the slides that assemble, from limit to limit
(:meth:`~chaingraph.synthesis.family.Family.sweep`). A family neither class solves (a
joint of three or more links: not in the atlases of single joints searched here) would
be counted in ``rejected`` as :data:`UNSOLVED`. A
closed curve needs a turning input (a slide does not come back by going on): for a
``closed`` task the families driven by a slide are not searched, the inversions that
have them counted under :data:`SLIDING_CLOSED`.

Each family is one independent job (:func:`search_family`: the coarse search, the
global search and least squares of :mod:`chaingraph.synthesis.optimiser` on a budget,
then the best fits certified from their written files); jobs run on local processes or
a Dask cluster through the atlas's runners (:func:`chaingraph._util.parallel.process_runner`,
:class:`~chaingraph.structure.atlas.DaskRunner`), each from its own random stream
(the task's seed and the family's number), so the result does not depend on how many
workers ran it.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from chaingraph._util.parallel import Runner, serial
from chaingraph.errors import DesignError
from chaingraph.model.chain import Chain
from chaingraph.naming.atlas import atlas_names
from chaingraph.structure.atlas import atlas
from chaingraph.structure.isomorphism import (
    automorphism_orbits,
    link_joint_orbits,
    pair_orbits,
)
from chaingraph.synthesis.family import (
    AtlasFamily,
    CylinderDyads,
    CylinderFamily,
    LoopFamily,
    cylinder_joints,
    cylinder_plan,
    dyad_plan,
    input_kind,
)
from chaingraph.synthesis.motion_generation import motion as four_bar_motion
from chaingraph.synthesis.path_generation import Budget, path_search_task, synthesise_path
from chaingraph.synthesis.path_generation import path as four_bar_path
from chaingraph.synthesis.pose_search import synthesise_motion
from chaingraph.synthesis.result import Searched, Solution, Synthesis, ranked
from chaingraph.synthesis.task import MotionTask, PathTask, check_options, drawn_seed, motion_task

__all__ = ["path", "motion", "LINKS", "Choice", "Space", "atlas_space", "search_family",
           "path_types", "check_links", "BUDGETS", "NEWTON_BUDGETS", "CYLINDER_BUDGETS",
           "UNSOLVED", "TRIADS_SKIPPED", "NOT_CHOSEN", "UNDRIVEN", "SLIDING_CLOSED"]

#: the sizes a synthesis searches (4: the four-bar; 6 and 8: through the atlas)
LINKS = (4, 6, 8)
#: the reason a family whose motion neither family class finds is counted under
UNSOLVED = "families not solved"
#: the reason a triad family is counted under when ``triads`` is False (a quicker search)
TRIADS_SKIPPED = "triads not searched"
#: the reason an inversion with no binary turning or sliding pair on its fixed link (no
#: input) is counted under
UNDRIVEN = "inversions with no input"
#: the reason the inversions searched only through a sliding input are counted under for a
#: closed curve (its families, driven by a slide, are not searched)
SLIDING_CLOSED = "inversions with a sliding input: a closed curve needs a turning input"
#: the reason a family left out by ``families`` (see :func:`path_types`) is counted under
NOT_CHOSEN = "families not chosen"
#: how hard one family is searched, exact (up to five points) and fitted
BUDGETS = {True: Budget(samples=1500, starts=24), False: Budget(samples=2000, starts=30,
                                                                  fitted=4, generations=40)}
#: how hard a family solved by Newton's method (slower) is searched (its least squares
#: onto a set of solutions not tried: each evaluation continues Newton's method, and 300
#: from each start made such a family five times as slow)
NEWTON_BUDGETS = {True: Budget(samples=200, starts=4, fitted=2, generations=5, passing=0),
                  False: Budget(samples=200, starts=6, fitted=1, generations=5, passing=0)}
#: how hard a family driven by a cylinder (Newton's method over every moving link, its
#: continuation both ways along the slide: the slowest) is searched
CYLINDER_BUDGETS = {True: Budget(samples=60, starts=1, fitted=1, generations=5, passing=0),
                    False: Budget(samples=60, starts=6, fitted=1, generations=5, passing=0)}
_KEPT = 2         # certified solutions kept per family


@dataclass(frozen=True)
class Choice:
    """One family of the space: the atlas's ``chain`` (number ``chain_id`` from 1 in the
    atlas's order), its inversion ``inversion`` (from 1, in the order of its orbits),
    ``fixed``, ``driver`` and ``carrier`` links, the catalog's ``names`` (the chain's,
    then the inversion's) and how its motion is found: ``method`` ``"dyads"`` (closed
    form, :class:`~chaingraph.synthesis.family.AtlasFamily`), ``"newton"`` (a triad,
    :class:`~chaingraph.synthesis.family.LoopFamily`) or ``""`` (not searched, counted
    under :data:`UNSOLVED`). ``cylinder``: the input is this sliding pair between two
    moving links (a hydraulic cylinder, ``driver`` its block;
    :class:`~chaingraph.synthesis.family.CylinderFamily`, by Newton's method), not the
    driver's pair with the fixed link."""

    chain: Chain
    chain_id: int
    inversion: int
    fixed: str
    driver: str
    carrier: str
    names: tuple[str, ...]
    method: str
    cylinder: str = ""

    @property
    def solvable(self) -> bool:
        """Whether the family is searched (its motion found by dyads or by Newton)."""
        return bool(self.method)

    @property
    def sliding(self) -> bool:
        """Whether the driver slides on the fixed link (a sliding input: its values are
        slides, in file units) rather than turning about it."""
        return not self.cylinder and input_kind(self.chain, self.fixed, self.driver) == "P"

    @property
    def slides(self) -> bool:
        """Whether the input is a sliding pair (on the fixed link, or a cylinder's):
        its values are slides, its path open."""
        return self.sliding or bool(self.cylinder)


@dataclass(frozen=True)
class Space:
    """The space a type synthesis searches: ``links``, ``prismatic``, the atlas's
    ``chains`` and ``inversions`` (counts), the ``choices`` and the number of
    inversions with no family (``undriven``: no binary turning or sliding pair on the
    fixed link)."""

    links: int
    prismatic: int
    chains: int
    inversions: int
    choices: tuple[Choice, ...]
    undriven: int = 0


def check_links(links: object, prismatic: object, *, kind: str) -> None:
    """Refuse a number of links not in :data:`LINKS` (and a ``prismatic`` that is not a
    whole number 0 or more, or "all")."""
    if isinstance(links, bool) or links not in LINKS:
        raise DesignError(f"links must be 4, 6 or 8, got {links!r}", kind=kind,
                          parameter="links")
    if prismatic is not None and prismatic != "all" and (
            isinstance(prismatic, bool) or not isinstance(prismatic, int) or prismatic < 0):
        raise DesignError(f"prismatic must be a whole number, 0 or more, or 'all', got "
                          f"{prismatic!r}", kind=kind, parameter="prismatic")


def atlas_space(links: int, prismatic: int | str | None = None) -> Space:
    """Every chain of ``links`` links (1 dof; with ``prismatic`` sliding pairs), every
    inversion, driver and carrier (see the module).

    Examples
    --------
    >>> s = atlas_space(6)
    >>> s.chains, s.inversions, len(s.choices), sum(c.solvable for c in s.choices)
    (2, 5, 23, 23)
    >>> s = atlas_space(6, 1)       # one sliding pair
    >>> s.chains, s.inversions, len(s.choices), sum(c.method == "newton" for c in s.choices)
    (6, 25, 182, 68)
    >>> cylinders = [c.method for c in s.choices if c.cylinder]   # driven by a cylinder
    >>> len(cylinders), cylinders.count("dyads")
    (43, 15)
    >>> sliding = [c.method for c in s.choices if c.sliding]   # driven by a slide
    >>> len(sliding), sliding.count("dyads")
    (23, 15)
    >>> atlas_space(6, "all").undriven      # every fixed link has a turning or sliding pair
    0
    """
    chains = list(atlas(links=links, prismatic=prismatic))
    choices: list[Choice] = []
    sliding: list[Choice] = []
    cylinders: list[Choice] = []
    inversions = 0
    for number, chain in enumerate(chains, 1):
        named = atlas_names(chain)
        by_link = {x: tuple(i["names"]) for i in named["inversions"] for x in i["links"]}
        orbits = automorphism_orbits(chain, oriented=False)
        inversions += len(orbits)
        for k, orbit in enumerate(orbits, 1):
            fixed = orbit[0]
            names = tuple(named["chain"]) + by_link.get(fixed, ())
            choices += _choices(chain, number, k, fixed, names, "R")
            sliding += _choices(chain, number, k, fixed, names, "P")
            cylinders += _cylinder_choices(chain, number, k, fixed, names)
    # the sliding inputs' families after every turning input's, the cylinders' last, so
    # that each of these keeps its number (its random stream) in the space
    choices += sliding + cylinders
    p = 0 if prismatic is None else (-1 if prismatic == "all" else int(prismatic))
    driven = len({(c.chain_id, c.inversion) for c in choices})
    return Space(links, p, len(chains), inversions, tuple(choices), inversions - driven)


def _choices(chain, number, inversion, fixed, names, kind) -> list[Choice]:
    """An inversion's families driven through a pair of ``kind`` on the fixed link (R: a
    link turning about it; P: sliding on it, a sliding input): one driver per orbit of
    (fixed, driver) pairs under the automorphisms that keep the fixed link, every
    carrier not jointed to the fixed link. The orbits are the whole group's, of every
    ordered pair of links joined by a binary pair of ``kind`` (those of one fixed link
    alone are joined only by the generators that happen to keep it): a pair's orbit
    under the fixed link's stabiliser is the members of its orbit with that link
    first."""
    joined = [(a, b) for j in chain.joints if len(j.links) == 2 and j.kind == kind
              for a, b in (j.links, j.links[::-1])]
    drivers = [b for a, b in joined if a == fixed]
    kept = []
    for orbit in pair_orbits(chain, list(dict.fromkeys(joined)), oriented=False):
        mine = [d for f, d in orbit if f == fixed]
        if mine:
            kept.append(min(mine, key=drivers.index))
    kept.sort(key=drivers.index)
    grounded = {x for j in chain.joints if fixed in j.links for x in j.links}
    carriers = [x for x in chain.links if x not in grounded]
    return [Choice(chain, number, inversion, fixed, d, c, names, _method(chain, fixed, d))
            for d in kept for c in carriers]


def _cylinder_choices(chain, number, inversion, fixed, names) -> list[Choice]:
    """An inversion's families driven by a cylinder: each sliding pair between two
    moving links (one per orbit of (fixed, pair) under the automorphisms that keep the
    fixed link: :func:`~chaingraph.structure.isomorphism.link_joint_orbits`), every carrier not jointed to the fixed
    link; solved dyad by dyad where the cylinder's links as one leave dyads of turning
    pairs (:func:`~chaingraph.synthesis.family.cylinder_plan`), else by Newton's
    method."""
    joints = set(cylinder_joints(chain, fixed))
    kept = []
    for orbit in link_joint_orbits(chain, oriented=False):
        mine = [j for f, j in orbit if f == fixed and j in joints]
        if mine:
            kept.append(mine[0])
    kept.sort(key=[j.id for j in chain.joints].index)
    grounded = {x for j in chain.joints if fixed in j.links for x in j.links}
    carriers = [x for x in chain.links if x not in grounded]
    return [Choice(chain, number, inversion, fixed, chain.joint(j).links[1], c, names,
                   "dyads" if cylinder_plan(chain, fixed, j) else "newton", cylinder=j)
            for j in kept for c in carriers]


def _method(chain, fixed, driver) -> str:
    """How a family's motion is found (see :class:`Choice`), for a turning or a
    sliding input alike."""
    if dyad_plan(chain, fixed, driver) is not None:
        return "dyads"
    if input_kind(chain, fixed, driver) is not None:
        return "newton"
    return ""


@dataclass(frozen=True)
class _Job:
    task: Any
    choice: Choice
    number: int
    links: int
    prismatic: int
    solutions: int
    triads: bool = True
    budget: Budget | None = None


def search_family(job: _Job) -> tuple[list[Solution], dict[str, int], int]:
    """One family searched (module docstring): its certified solutions (``atlas`` and
    ``names`` filled), its rejected candidates by reason, and the random mechanisms it
    sampled."""
    c = job.choice
    if not c.solvable:
        return [], {UNSOLVED: 1}, 0
    if c.method == "newton" and not job.triads:
        return [], {TRIADS_SKIPPED: 1}, 0
    name = c.names[-1] if len(c.names) > 1 else None    # None: the family's own
    if c.cylinder:
        cylinder = CylinderDyads if c.method == "dyads" else CylinderFamily
        family: AtlasFamily = cylinder(c.chain, c.fixed, c.cylinder, c.carrier, name=name)
    else:
        kind = AtlasFamily if c.method == "dyads" else LoopFamily
        family = kind(c.chain, c.fixed, c.driver, c.carrier, name=name)
    rng = np.random.default_rng([job.task.seed, job.number])
    budgets = BUDGETS if c.method == "dyads" else (CYLINDER_BUDGETS if c.cylinder
                                                   else NEWTON_BUDGETS)
    budget = job.budget or budgets[_exact(job.task)]
    search = synthesise_motion if job.task.kind == "motion" else synthesise_path
    kept = _KEPT if c.method == "dyads" else 1      # a triad's certification is slow
    found = search(job.task, family, solutions=min(job.solutions, kept), budget=budget,
                   rng=rng)
    where = {"links": job.links, "prismatic": job.prismatic, "chain": c.chain_id,
             "inversion": c.inversion}
    out = [replace(s, names=c.names, atlas=where) for s in found.solutions]
    return out, dict(found.rejected), budget.samples


def path(*, points: Iterable[tuple[float, float]], timing: Iterable[float] | None = None,
         closed: bool = False, kind: str = "four-bar",
         solutions: int = 5, seed: int | None = None, units: str = "mm",
         min_transmission: float = 30.0, links: int = 4,
         prismatic: int | str | None = None, runner: Runner | None = None,
         triads: bool = True, families: Callable[[Choice], bool] | None = None,
         budget: Budget | None = None) -> Synthesis:
    """Synthesise a path generator: a point of one link passes through ``points`` in
    order. With ``links`` 4 (and no ``prismatic``), the four-bar
    (:func:`chaingraph.synthesis.path_generation.path`, whose parameters these are);
    with 6 or 8, every chain of the atlas of that size (with ``prismatic`` sliding
    pairs), every inversion and every link that can carry the point
    (:func:`path_types`), its families searched on ``runner`` (a runner of
    :mod:`chaingraph._util.parallel`, or :class:`~chaingraph.structure.atlas.DaskRunner`;
    by default one after another here); ``triads``, ``families`` and ``budget`` narrow
    the search (:func:`path_types`).

    Examples
    --------
    >>> def watt_ii(c):         # one of the 23 families: a Watt II, its point on L2
    ...     return c.names[-1] == "Watt II six-bar mechanism" and (c.driver, c.carrier) == ("L1", "L2")
    >>> s = path(points=[(0, 0), (10, 4), (18, 12), (20, 22), (14, 30)], seed=1,
    ...          solutions=1, links=6, families=watt_ii)
    >>> s.solutions[0].atlas, s.solutions[0].error.max < 1e-9 * 36
    ({'links': 6, 'prismatic': 0, 'chain': 1, 'inversion': 2}, True)
    >>> s.searched.chains, s.searched.inversions, s.rejected["families not chosen"]
    (2, 5, 22)
    """
    check_links(links, prismatic, kind="path")
    if links == 4 and prismatic in (None, 0):
        return four_bar_path(points=points, timing=timing, closed=closed, kind=kind,
                             solutions=solutions, seed=seed, units=units,
                             min_transmission=min_transmission)
    task = path_search_task(points=points, timing=timing, closed=closed, kind=kind,
                            solutions=solutions, seed=seed, units=units,
                            min_transmission=min_transmission,
                            slides=prismatic not in (None, 0))
    return path_types(task, links=links, prismatic=prismatic, solutions=solutions,
                      runner=runner, triads=triads, families=families, budget=budget)


def motion(*, poses: Iterable[tuple[float, float, float]], solutions: int = 5, units: str = "mm",
           min_transmission: float = 30.0,
           circle_points: Sequence[Sequence[float]] | None = None, links: int = 4, prismatic: int | str | None = None,
           seed: int | None = None, runner: Runner | None = None,
           triads: bool = True, families: Callable[[Choice], bool] | None = None,
           budget: Budget | None = None) -> Synthesis:
    """Synthesise a motion generator: one link passes through ``poses`` (x, y, degrees)
    in order. With ``links`` 4 (and no ``prismatic``), the four-bar and slider crank by
    the classical constructions and Burmester theory
    (:func:`chaingraph.synthesis.motion_generation.motion`, whose parameters these are);
    with 6 or 8, every chain of the atlas of that size, every inversion and every link
    that can carry the pose (:func:`path_types`, the carrier's point at x, y and its
    angle), each family searched by the path optimiser with the carrier's turn as
    further equations (:func:`chaingraph.synthesis.pose_search.synthesise_motion`), on
    ``runner``, repeatably from ``seed``; ``triads``, ``families`` and ``budget`` narrow
    the search (:func:`path_types`).

    Examples
    --------
    >>> s = motion(poses=[(0, 0, 0), (40, 10, 20), (70, 40, 50)], solutions=1, links=6,
    ...            seed=1)  # doctest: +SKIP
    >>> s.solutions[0].atlas["links"], s.solutions[0].error.angle < 1e-6  # doctest: +SKIP
    (6, True)

    (skipped here: a minute of search; tests/synthesis/test_type_synthesis.py runs one)
    """
    check_links(links, prismatic, kind="motion")
    if links == 4 and prismatic in (None, 0):
        return four_bar_motion(poses=poses, solutions=solutions, units=units,
                               min_transmission=min_transmission, circle_points=circle_points)
    task = motion_task(poses=poses, units=units, min_transmission=min_transmission,
                       seed=drawn_seed(seed))
    check_options(solutions=solutions, min_transmission=min_transmission, units=units,
                  kind="motion")
    return path_types(task, links=links, prismatic=prismatic, solutions=solutions,
                      runner=runner, triads=triads, families=families, budget=budget)


def path_types(task: PathTask | MotionTask, *, links: int, prismatic: int | str | None = None,
               solutions: int = 5, runner: Runner | None = None,
               progress: Callable[[int, int], None] | None = None,
               triads: bool = True, families: Callable[[Choice], bool] | None = None,
               budget: Budget | None = None) -> Synthesis:
    """Type synthesis of a checked path or motion task over the atlas's chains of ``links`` links
    (6 or 8; with ``prismatic`` sliding pairs), every family searched on ``runner`` (by
    default here, one after another); the certified solutions of every family ranked
    together. ``progress(done, total)`` is called as families finish. ``triads`` False
    leaves the families solved by Newton's method unsearched (counted under
    :data:`TRIADS_SKIPPED`): a quicker search of the dyad families only. ``families``
    (a test of a :class:`Choice`) searches only the families it accepts, the others
    counted under :data:`NOT_CHOSEN`; ``budget`` searches every family on that budget
    instead of :data:`BUDGETS` (:data:`NEWTON_BUDGETS` for the triads). Each family
    keeps its number in the space (its random stream), so a family searched alone finds
    what the whole search finds in it."""
    space = atlas_space(links, prismatic)
    task = replace(task, mechanism=_mechanism(links, prismatic))
    closed = getattr(task, "closed", False)
    jobs = [_Job(task, c, k, links, space.prismatic, solutions, triads, budget)
            for k, c in enumerate(space.choices) if (families is None or families(c))
            and not (closed and c.slides)]
    # a closed curve: the families driven by a slide are left out, counted by inversion
    sliding_only = _sliding_inversions(space.choices) if closed else 0
    left_out = len(space.choices) - len(jobs) - (
        sum(c.slides for c in space.choices) if closed else 0)
    results: dict[int, tuple] = {}
    # the slow families (Newton's) first, so that workers do not wait on one at the end
    order = sorted(range(len(jobs)), key=lambda i: jobs[i].choice.method != "newton")

    def done(i, result):
        results[order[i]] = result
        if progress is not None:
            progress(len(results), len(jobs))
    (runner or serial)(search_family, [jobs[i] for i in order], done)
    found: list[Solution] = []
    rejected: Counter = Counter()
    sampled = 0
    for i in range(len(jobs)):          # in the space's order, however they ran
        sols, why, n = results[i]
        found += sols
        rejected.update(why)
        sampled += n
    if left_out:
        rejected[NOT_CHOSEN] += left_out
    if sliding_only:
        rejected[SLIDING_CLOSED] += sliding_only
    if space.undriven:
        rejected[UNDRIVEN] += space.undriven
    tolerance = 1e-9 * task.size if _exact(task) else 0.0
    return Synthesis(task, ranked(found, solutions, tolerance=tolerance),
                     dict(sorted(rejected.items())),
                     Searched(space.chains, space.inversions, sampled))


def _sliding_inversions(choices: Sequence[Choice]) -> int:
    """The inversions with families driven by a sliding input (or a cylinder)."""
    return len({(c.chain_id, c.inversion) for c in choices if c.slides})


def _exact(task) -> bool:
    """Whether a task's targets are met exactly (two to five poses always are)."""
    return isinstance(task, MotionTask) or task.exact


def _mechanism(links: int, prismatic) -> str:
    """The task's mechanism: what was searched."""
    if prismatic in (None, 0):
        return f"{links}-link chains"
    if prismatic == "all":
        return f"{links}-link chains, any sliding pairs"
    return f"{links}-link chains, {prismatic} sliding pair{'' if prismatic == 1 else 's'}"
