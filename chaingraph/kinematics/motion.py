"""Solving a mechanism over an input sweep: the :class:`Motion` and its summary.

:func:`solve` is what ``chaingraph solve`` runs. The plan (structure) is built once per
inversion; the motion (arrays) is the result. The summary describes the mechanism's
whole cycle, whatever rows were asked for: one full turn of a crank, or a rocking
driver's whole feasible range.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from chaingraph._util.text import csv_text, short_list
from chaingraph.errors import AssemblyError, MechanismError, UnboundedRangeError
from chaingraph.kinematics.columns import (
    LinkMotion,
    LinkStates,
    PointMotion,
    SlideMotion,
    Trajectories,
)
from chaingraph.kinematics.closed_form import closure_checks
from chaingraph.kinematics.equations import check_poses
from chaingraph.kinematics.inputs import Drive, InputsGiven, plan_of, sweep_drive
from chaingraph.kinematics.plan import InputJoint, Plan
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.summary import (
    CYCLE_STEPS,
    Summary,
    cycle_theta,
    motion_summary,
    straightness,
)
from chaingraph.kinematics.sweep import Cycle, cycle, evaluate_near, evaluate_sweep
from chaingraph.model.chain import Chain

__all__ = ["Motion", "LinkMotion", "PointMotion", "SlideMotion", "LinkStates", "solve",
           "full_turns", "full_turns_cost", "full_turns_drivers"]


@dataclass(frozen=True, eq=False, kw_only=True)
class Motion(Trajectories):
    """A solved sweep: every link's, joint's, point's and slide's arrays, typed and
    named (radians inside), and the summary.

    ``motion.link("crank")`` is a :class:`LinkMotion` (``angle`` in radians,
    ``angle_deg`` in degrees, ``omega``, ``alpha``); ``motion.joint("B")`` and
    ``motion.point("P")`` a :class:`PointMotion` (``x``, ``y``, ``vx``, ``vy``, ``ax``,
    ``ay``); ``motion.slide("S")`` a :class:`SlideMotion` (``s``, ``v``, ``a``);
    ``motion.theta`` the input angle (degrees; with inputs, the lead input's value, and
    ``motion.values[J]`` each input's). Rates are at the constant input speed
    ``omega``; NaN at a dead centre. ``motion["x:B"]``, :attr:`columns`,
    :meth:`to_csv` and :meth:`to_frame` are the CSV's view of them.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=4)
    >>> float(m.link("crank").angle_deg[1] - m.link("crank").angle_deg[0])
    90.0
    >>> m.joint("C").x.tolist() == m["x:C"].tolist()
    True
    """

    name: str
    fixed: str
    driver: str | None
    omega: float
    summary: Summary | None
    plan: Plan = field(repr=False)
    units: str | None = None
    inputs: tuple[InputJoint, ...] = ()    # the input joints, when not given as a driver
    states: LinkStates | None = field(default=None, repr=False)   # the solver's own

    def __repr__(self):
        given = (f"inputs={[i.joint for i in self.inputs]!r}" if self.inputs
                 else f"driver={self.driver!r}")
        return (f"Motion({self.name!r}, fixed={self.fixed!r}, {given}, steps={self.steps}, "
                f"columns={short_list(list(self.columns))})")

    @property
    def steps(self) -> int:
        """The sweep's intervals: ``steps + 1`` rows."""
        return self.theta.size - 1

    def link(self, name: str) -> LinkMotion:
        """A link's direction (radians; ``angle_deg`` degrees), angular velocity and
        acceleration over the sweep.

        Examples
        --------
        >>> import chaingraph
        >>> from chaingraph.naming.catalog import catalog_path
        >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=4)
        >>> m.link("crank").omega.tolist() == m["omega:crank"].tolist()
        True
        """
        return self._known(self.links, name, "link")

    def joint(self, name: str) -> PointMotion:
        """A joint's position, velocity and acceleration over the sweep (a P joint's
        block's reference point)."""
        return self._known(self.joints, name, "joint")

    def point(self, name: str) -> PointMotion:
        """A point's (or a joint's) position, velocity and acceleration over the sweep."""
        if name in self.joints:
            return self.joints[name]
        return self._known(self.points, name, "joint or point")

    def slide(self, joint: str) -> SlideMotion:
        """A P joint's slide from the drawn pose, its rate and acceleration."""
        return self._known(self.slides, joint, "P joint")

    def joined(self, *others: Trajectories) -> Motion:
        """This motion's steps followed by each of ``others``' (of the same mechanism),
        as one motion with this one's other fields (and no solver's states)."""
        return replace(super().joined(*others), states=None)

    def _known(self, group, name, what):
        if name not in group:
            raise KeyError(f"{name!r} is no {what} of {self.name!r}")
        return group[name]

    def input_values(self, k: int = 0) -> float | list[float]:
        """The inputs' values at row ``k``, as ``at`` takes them (``instant_centres``,
        ``forces``): the driver's angle, or one value per input.

        Examples
        --------
        >>> import chaingraph
        >>> from chaingraph.naming.catalog import catalog_path
        >>> engine = chaingraph.load(catalog_path("reciprocating-engine"))
        >>> chaingraph.solve(engine, steps=4).input_values(1)
        150.0
        """
        if self.inputs:
            return [float(self.values[i.joint][k]) for i in self.inputs]
        return float(self.theta[k])

    def rows(self) -> list[tuple[float, ...]]:
        """The CSV's rows: one tuple of its columns' values per step."""
        columns = [np.broadcast_to(v, self.theta.shape).tolist()
                   for v in self.columns.values()]
        return list(zip(*columns))

    def to_frame(self) -> Any:
        """The CSV's columns as a pandas DataFrame, one row per step (needs pandas:
        ``pip install chaingraph[notebook]``)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Motion.to_frame needs pandas: pip install "
                              "'chaingraph[notebook]' (or pandas)") from None
        return pandas.DataFrame({name: np.asarray(v) for name, v in self.columns.items()})

    def to_csv(self, path: str | os.PathLike | None = None) -> str | None:
        """Write the CSV (one row per step); returns the text when ``path`` is None.

        Numbers are written as Python writes them (the shortest text that reads back to
        the same float), ``nan`` where there is no value; the file is written in blocks
        of rows, so memory does not grow with the sweep."""
        return csv_text(self.columns, self.steps + 1, path)

    def to_dict(self) -> dict:
        """The JSON of ``chaingraph solve --json``."""
        out: dict[str, Any] = {"name": self.name, "fixed": self.fixed, "driver": self.driver}
        if self.inputs:
            out["inputs"] = [
                {"joint": i.joint, "kind": i.kind, "from": float(self.values[i.joint][0]),
                 "to": float(self.values[i.joint][-1])} for i in self.inputs]
        out.update(steps=self.steps, summary=self.summary.to_dict() if self.summary else {})
        return out


def solve(mechanism: Chain, *, fixed: str | None = None, driver: str | None = None,
          inputs: InputsGiven = None, start: float | None = None, stop: float | None = None,
          steps: int = 360, omega: float | None = None, summary: bool = True,
          output: str | None = None) -> Motion:
    """Solve a mechanism's motion over an input sweep.

    Parameters
    ----------
    mechanism : Chain
        A chain with a drawn pose; its ``[mechanism]`` gives the fixed link, inputs (or
        driver), output and input speed unless overridden here.
    fixed, driver : str, optional
        The inversion and input link (turning about its R joint with the fixed link).
    inputs : sequence, optional
        Input joints instead of a driver, one per degree of freedom: joint ids, or
        :class:`~chaingraph.Input` items (or ``(joint, from, to)`` tuples) with their
        sweeps. All move together, linearly, over the same steps; an input without a
        sweep stays at its drawn value.
    start, stop : float, optional
        The sweep of the (first) input: degrees for a driver or an R input (the
        driver's direction from its fixed pivot, CCW from +x), length units of slide
        from the drawn pose for a P input. By default one full turn from the drawn pose
        for an input that can turn fully, else its whole feasible range, limit to limit.
    steps : int
        Equal intervals of the sweep: ``steps + 1`` rows.
    omega : float, optional
        Constant speed of the (first) input: rad/s, or length units/s for a P input
        (default: the file's, else 1).
    summary : bool
        Also work out the :class:`Summary` (stroke, time ratio, extremes, dead
        centres...) over the whole cycle; without it ``Motion.summary`` is None.
    output : str, optional
        What the summary is of, in place of the file's ``output``: a link (its slide on
        the fixed link, else its angle), a P joint (its slide along its guide), a point
        or an R joint (its travel along its path, and how straight the path is).

    Raises
    ------
    MechanismError
        A mechanism that cannot be solved as asked (bad input, exit status 2).
    AssemblyError
        A sweep past the range that can be assembled (exit status 1); the message and
        ``feasible_range`` give the range.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> shaper = chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))
    >>> motion = chaingraph.solve(shaper, steps=36)
    >>> round(motion.summary["time_ratio"], 5), len(motion.theta)
    (1.70995, 37)

    The engine driven by its piston's slide, limit to limit:

    >>> engine = chaingraph.load(catalog_path("reciprocating-engine"))
    >>> m = chaingraph.solve(engine, inputs=["S"], steps=4)
    >>> [round(float(v), 3) for v in m.values["S"]], round(m.summary["stroke"], 6)
    ([-56.205, -36.205, -16.205, 3.795, 23.795], 80.0)
    >>> m.summary["dead_centres"] == m.summary["input_range"]   # both ends of the stroke
    True
    """
    chain = mechanism
    drive = sweep_drive(chain, fixed=fixed, driver=driver, inputs=inputs, start=start,
                        stop=stop, steps=steps, omega=omega)
    output, plan = _output(chain, output), drive.plan
    c, theta, ev, on_grid = _swept(drive, steps, summary)
    # rates at unit input speed, scaled to omega: the summary can then use this sweep
    # when it is the summary's own grid
    points: dict = {}
    vel, acc, measure = rates(plan, ev.pose, 1.0, theta.size, measure=summary, points=points)
    states = LinkStates(theta, ev.pose, vel, acc, points=points)
    unit = Motion.of_states(plan, states, name=chain.name, fixed=plan.fixed,
                            driver=plan.driver, omega=drive.omega, summary=None,
                            units=chain.units, plan=plan, states=states,
                            inputs=() if plan.from_driver else plan.inputs)
    motion = _as_asked(unit.scaled(drive.omega), drive, c, theta)
    if not summary:
        return motion
    return replace(motion, summary=_summary(unit, output, c, ev, measure, on_grid))


def _output(chain, output):
    """The output the summary is of: the one asked for (checked), else the file's."""
    if output is None:
        return chain.mechanism.output if chain.mechanism else None
    names = set(chain.links) | {j.id for j in chain.joints} | {p.id for p in chain.points}
    if output not in names:
        raise MechanismError(f"the output {output!r} is no link, joint or point of the "
                             "chain", mechanism=chain.source or chain.name,
                             parameter="output")
    return output


def _swept(drive: Drive, steps, summary):
    """(the cycle, or None when not needed or there is none; the path parameters of the
    sweep; its evaluation, checked; whether the path parameters are the summary's own
    grid, :func:`cycle_theta`, by construction: a crank's default turn in 3,600 steps)."""
    plan, start, stop = drive.plan, drive.start, drive.stop
    c, on_grid = None, False
    if summary or start is None or stop is None:
        try:
            c = cycle(plan)
        except UnboundedRangeError:
            if start is None or stop is None:
                raise
            # no whole cycle: the summary is of the sweep asked for
    if c is None:
        # no cycle was asked for or found: only when both ends of the sweep are given
        assert start is not None and stop is not None, "a sweep without a cycle has ends"
        theta = np.linspace(plan.tau(start), plan.tau(stop), steps + 1)
    else:
        lo = c.low if start is None else plan.tau(start)
        if stop is not None:
            theta = np.linspace(lo, plan.tau(stop), steps + 1)
        elif c.full_turn:
            theta = lo + 360.0 * np.arange(steps + 1) / steps    # as the summary's grid
            # (the same operations as cycle_theta's on the same numbers)
            on_grid = start is None and c.period == 360.0 and steps == CYCLE_STEPS
        else:
            theta = np.linspace(lo, c.high, steps + 1)   # both ends exact (a rocker's limits)
    ev = evaluate_sweep(plan, theta) if c is not None else evaluate_near(plan, theta)
    check_poses(plan, ev.pose, ev.feasible, constraints=closure_checks(plan))
    return c, theta, ev, on_grid


def _as_asked(motion: Motion, drive: Drive, c, theta) -> Motion:
    """The motion with the inputs' values exactly as asked for, and no rates at a
    limit of the range."""
    plan, start, stop = drive.plan, drive.start, drive.stop
    if start is not None and stop is not None and not plan.from_driver:
        # the values asked for, exactly (tau carries them to the last bit or so)
        values = dict(motion.values)
        for n, item in enumerate(plan.inputs):
            ends = (start, stop) if n == plan.lead else item.sweep
            if ends is not None and (n == plan.lead or plan.line[n][1] != 0):
                values[item.joint] = np.linspace(ends[0], ends[1], theta.size)
        motion = replace(motion, values=values, theta=values[plan.inputs[plan.lead].joint])
    if c is not None and not c.full_turn:
        # a limit of the range is a fold: the inputs do not determine the rates there
        at_limit = (theta == c.low) | (theta == c.high)
        if at_limit.any():
            motion = motion.rates_unknown_at(at_limit)
    return motion


def _summary(unit: Motion, output, c, ev, measure, on_grid=False) -> Summary:
    """The summary of the motion ``unit`` (at unit input speed) over the cycle ``c``, or
    over its own sweep when the cycle is not one input's (None: there is none).
    ``on_grid``: the sweep is the summary's own grid (else it is compared with it)."""
    plan, theta = unit.plan, ev.theta
    lo, hi = float(theta[0]), float(theta[-1])
    if plan.moving_inputs > 1 or c is None:          # summarize the sweep
        c = Cycle(None, min(lo, hi), max(lo, hi), ends="sweep")
    reuse = None
    if c.ends == "limits" and (on_grid or np.array_equal(theta, cycle_theta(plan, c))):
        reuse = (ev, measure, unit)
    summary = motion_summary(plan, output, unit.omega, c, sweep=reuse)
    if output is not None and output not in unit.links and output not in unit.slides:
        # a point's path: how straight it is over the sweep asked for
        path = unit.point(output)
        summary = replace(summary, straightness=straightness(path.x, path.y))
    return summary


def full_turns_drivers(chain: Chain, fixed: str) -> list[str]:
    """The drivers :func:`full_turns` tries, in order."""
    m = chain.mechanism
    if m is not None and m.fixed == fixed and m.driver:
        return [m.driver]
    return [x for x in chain.links if x != fixed and any(
        j.kind == "R" and fixed in j.links and x in j.links for j in chain.joints)]


def full_turns_cost(chain: Chain, fixed: str, *,
                    drivers: Sequence[str] | None = None) -> float:
    """An estimate, in seconds of one core, of :func:`full_turns` with ``fixed`` fixed:
    every candidate driver's cycle and sweep, from its plan (measured on 4- to 30-link
    chains of dyads and a rotary engine: a closed-form step about 15 ms; a group of
    higher class up to 1 s plus 0.9 s times (its coordinates / 36) ** 3.7, the cost of
    continuing its Newton's method along the path and solving its folds). 0 where
    nothing is solved. ``drivers``: only these candidates (by default every one).
    """
    total = 0.0
    for driver in full_turns_drivers(chain, fixed) if drivers is None else drivers:
        try:
            plan = plan_of(chain, fixed, driver)
        except MechanismError:
            continue
        for step in plan.steps:
            if step.kind == "group":
                total += 1.0 + 0.9 * (3 * len(step.links) / 36.0) ** 3.7
            else:
                total += 0.015
    return total


def full_turns(chain: Chain, fixed: str) -> tuple[frozenset[str], str] | None:
    """The links that make full turns relative to ``fixed``, from a solved cycle.

    The driver is the chain's own when its mechanism fixes ``fixed``, else each link
    pinned to ``fixed`` in turn until one turns fully (a rocking driver's range is used
    when none does). Returns (frozenset of links, driver) or None when the inversion
    cannot be solved (no pose, joints other than R and P, mobility other than 1).
    """
    drivers = full_turns_drivers(chain, fixed)
    fallback = None
    for driver in drivers:
        try:
            plan = plan_of(chain, fixed, driver)
        except MechanismError:
            continue
        try:
            c = cycle(plan)
            ev = evaluate_sweep(plan, cycle_theta(plan, c, 720))
        except AssemblyError:
            continue
        turning = set()
        for link in chain.links:
            if link == fixed:
                continue
            phi = np.unwrap(np.broadcast_to(ev.pose[link][2], ev.theta.shape))
            if np.ptp(phi) >= 2 * math.pi - 1e-9:
                turning.add(link)
        if c.full_turn:
            return frozenset(turning), driver
        fallback = fallback or (frozenset(turning), driver)
    return fallback
