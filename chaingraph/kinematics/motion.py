"""Solving a mechanism over an input sweep: the :class:`Motion` and its summary.

:func:`solve` is what ``chaingraph solve`` runs. The plan (structure) is built once per
inversion; the motion (arrays) is the result. The summary describes the mechanism's
whole cycle, whatever rows were asked for: one full turn of a crank, or a rocking
driver's whole feasible range.
"""

from __future__ import annotations

import io
import math
import os
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from chaingraph._util.text import short_list, write_columns
from chaingraph.errors import AssemblyError, MechanismError, UnboundedRangeError
from chaingraph.kinematics.columns import csv_columns
from chaingraph.kinematics.equations import check_poses
from chaingraph.kinematics.plan import build_plan
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.summary import Summary, cycle_theta, motion_summary, straightness
from chaingraph.kinematics.sweep import Cycle, cycle, evaluate_near, evaluate_sweep
from chaingraph.model.chain import Input, chosen_inputs

__all__ = ["Motion", "solve", "full_turns", "full_turns_cost", "full_turns_drivers"]


def plan_of(chain, fixed, driver, inputs=None):
    # the file is part of the key: chains equal but for their file share no plan, whose
    # messages name the file
    return _cached_plan(chain, chain.source, fixed, driver, inputs)


@lru_cache(maxsize=256)
def _cached_plan(chain, source, fixed, driver, inputs):
    return build_plan(chain, fixed, driver, inputs=inputs)


@dataclass(frozen=True)
class LinkStates:
    """Every link's pose and rates along a solved sweep, as the solver holds them: the
    path parameters ``tau``, ``pose`` (link -> (x, y, phi, cos, sin) about the plan's
    origin), and ``velocity`` and ``acceleration`` (link -> (vx, vy, omega), (ax, ay,
    alpha) of its frame's origin; each input's rate under its key) at unit input
    speed, which scale with omega and omega squared."""

    tau: np.ndarray
    pose: dict
    velocity: dict
    acceleration: dict


@dataclass(frozen=True, eq=False)
class Motion:
    """A solved sweep: numpy arrays looked up by CSV column name, and the summary.

    ``motion["theta"]`` is the input angle (degrees; with inputs, the lead input's
    value, and ``motion["input:J"]`` each input's); ``motion["angle:crank"]``,
    ``motion["omega:crank"]``, ``motion["alpha:crank"]`` a link's direction (degrees),
    angular velocity and acceleration; ``motion["x:B"]``, ``"vx:B"``, ``"ax:B"``... a
    joint's or point's position, velocity, acceleration; ``motion["s:S"]``, ``"v:S"``,
    ``"a:S"`` a P joint's slide. Rates are at the constant input speed ``omega``; NaN
    at a dead centre.
    """

    name: str
    fixed: str
    driver: str | None
    omega: float
    columns: dict
    summary: Summary | None
    units: str | None = None
    plan: object = field(default=None, repr=False)
    inputs: tuple = ()            # the input joints, when not given as a driver
    links: object = field(default=None, repr=False, compare=False)   # LinkStates

    def __repr__(self):
        given = (f"inputs={[i.joint for i in self.inputs]!r}" if self.inputs
                 else f"driver={self.driver!r}")
        return (f"Motion({self.name!r}, fixed={self.fixed!r}, {given}, steps={self.steps}, "
                f"columns={short_list(self.columns)})")

    def to_frame(self):
        """The CSV's columns as a pandas DataFrame, one row per step (needs pandas:
        ``pip install chaingraph[notebook]``)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Motion.to_frame needs pandas: pip install "
                              "'chaingraph[notebook]' (or pandas)") from None
        return pandas.DataFrame({name: np.asarray(v) for name, v in self.columns.items()})

    def __getitem__(self, name) -> np.ndarray:
        return self.columns[name]

    def input_values(self, k=0):
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
            return [float(self.columns["input:" + i.joint][k]) for i in self.inputs]
        return float(self.columns["theta"][k])

    @property
    def theta(self) -> np.ndarray:
        return self.columns["theta"]

    @property
    def steps(self) -> int:
        return self.theta.size - 1

    def link(self, name) -> "LinkMotion":
        """A link's direction (degrees), angular velocity and acceleration over the sweep.

        Examples
        --------
        >>> import chaingraph
        >>> from chaingraph.naming.catalog import catalog_path
        >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=4)
        >>> m.link("crank").omega.tolist() == m["omega:crank"].tolist()
        True
        """
        self._known(name, "angle", "link")
        return LinkMotion(name, *(self.columns[f"{k}:{name}"] for k in ("angle", "omega", "alpha")))

    def point(self, name) -> "PointMotion":
        """A joint's or point's position, velocity and acceleration over the sweep."""
        self._known(name, "x", "joint or point")
        c = self.columns
        return PointMotion(name, c[f"x:{name}"], c[f"y:{name}"], c[f"vx:{name}"],
                           c[f"vy:{name}"], c[f"ax:{name}"], c[f"ay:{name}"])

    def slide(self, joint) -> "SlideMotion":
        """A P joint's slide from the drawn pose, its rate and acceleration."""
        self._known(joint, "s", "P joint")
        return SlideMotion(joint, *(self.columns[f"{k}:{joint}"] for k in ("s", "v", "a")))

    def _known(self, name, key, what):
        if f"{key}:{name}" not in self.columns:
            raise KeyError(f"{name!r} is no {what} of {self.name!r}")

    def to_csv(self, path=None) -> str | None:
        """Write the CSV (one row per step); returns the text when ``path`` is None.

        Numbers are written as Python writes them (the shortest text that reads back to
        the same float), ``nan`` where there is no value; the file is written in blocks
        of rows, so memory does not grow with the sweep."""
        if path is None:
            buf = io.StringIO()
            self._write_csv(buf)
            return buf.getvalue()
        with open(path, "w", encoding="utf-8", newline="") as f:
            self._write_csv(f)
        return None

    def _write_csv(self, out):
        write_columns(out, self.columns, self.steps + 1)

    def to_dict(self) -> dict:
        """The JSON of ``chaingraph solve --json``."""
        out = {"name": self.name, "fixed": self.fixed, "driver": self.driver}
        if self.inputs:
            out["inputs"] = [
                {"joint": i.joint, "kind": i.kind,
                 "from": float(self.columns["input:" + i.joint][0]),
                 "to": float(self.columns["input:" + i.joint][-1])} for i in self.inputs]
        out.update(steps=self.steps, summary=self.summary.to_dict() if self.summary else {})
        return out



def solve(mechanism, *, fixed=None, driver=None, inputs=None, start=None, stop=None,
          steps=360, omega=None, summary=True, output=None) -> Motion:
    """Solve a mechanism's motion over an input sweep.

    Parameters
    ----------
    mechanism : Chain
        A chain with a drawn pose; its ``[mechanism]`` gives the fixed link, inputs (or
        driver), output and input speed unless overridden here.
    fixed, driver : str, optional
        Choose the inversion and input link (turning about its R joint with the fixed
        link).
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
        Also work out the summary (stroke, time ratio, extremes, dead centres...) over
        the whole cycle (a :class:`Summary`); without it ``Motion.summary`` is None.
    output : str, optional
        What the summary is of, in place of the file's ``output``: a link (its slide on
        the fixed link, else its angle), a P joint (its slide: the block's travel along
        its guide), a point or an R joint (its travel along its path; the summary then
        adds how straight the path is over the sweep).

    Returns
    -------
    Motion

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
    >>> round(motion.summary["time_ratio"], 5), len(motion["theta"])
    (1.70995, 37)

    The engine driven by its piston's slide, limit to limit:

    >>> engine = chaingraph.load(catalog_path("reciprocating-engine"))
    >>> m = chaingraph.solve(engine, inputs=["S"], steps=4)
    >>> [round(float(v), 3) for v in m["input:S"]], round(m.summary["stroke"], 6)
    ([-56.205, -36.205, -16.205, 3.795, 23.795], 80.0)
    >>> m.summary["dead_centres"] == m.summary["input_range"]   # both ends of the stroke
    True
    """
    chain = mechanism
    if isinstance(steps, bool) or not isinstance(steps, int) or steps < 1:
        raise MechanismError(f"steps must be a positive whole number, got {steps!r}",
                             mechanism=chain.name, parameter="steps")
    m = chain.mechanism
    for value, what in ((start, "start"), (stop, "stop")):
        if value is not None:
            check_input_value(value, f"the sweep's {what}", chain.name)
    fixed, driver, items = chosen_inputs(chain, fixed, driver, as_inputs(inputs, chain))
    if items:
        first = items[0]
        if start is not None or stop is not None:
            first = Input(first.joint, start if start is not None else first.start,
                          stop if stop is not None else first.stop)
            start, stop = first.start, first.stop
        elif first.start is not None:
            start, stop = first.start, first.stop
        if (first.start is None) != (first.stop is None):
            if len(items) > 1 and any(i.start is not None for i in items[1:]):
                raise MechanismError(
                    f"the input {first.joint!r} has a sweep's start or stop but not both, "
                    "while other inputs move: give both", mechanism=chain.name)
            first = Input(first.joint)
        items = (first,) + tuple(items[1:])
        plan = plan_of(chain, fixed, None, items)
    else:
        plan = plan_of(chain, fixed, driver)
    _check_memory(plan, steps)
    if omega is None:
        omega = m.omega if m else 1.0
    if output is not None:
        names = set(chain.links) | {j.id for j in chain.joints} | {p.id for p in chain.points}
        if output not in names:
            raise MechanismError(f"the output {output!r} is no link, joint or point of the "
                                 "chain", mechanism=chain.source or chain.name,
                                 parameter="output")
    else:
        output = m.output if m else None
    lead = plan.inputs[plan.lead]
    if lead.sweep is not None:
        start, stop = lead.sweep
    explicit = start is not None and stop is not None
    c = None
    if summary or not explicit:
        try:
            c = cycle(plan)
        except UnboundedRangeError:
            if not explicit:
                raise
            # no whole cycle: the summary is of the sweep asked for
    lo = c.low if start is None else plan.tau(start)
    if stop is not None:
        theta = np.linspace(lo, plan.tau(stop), steps + 1)
    elif c.full_turn:
        theta = lo + 360.0 * np.arange(steps + 1) / steps    # as the summary's grid
    else:
        theta = np.linspace(lo, c.high, steps + 1)   # both ends exact (a rocker's limits)
    hi = float(theta[-1])
    ev = evaluate_sweep(plan, theta) if c is not None else evaluate_near(plan, theta)
    check_poses(plan, ev.pose, ev.feasible)
    # rates at unit input speed, scaled to omega: the summary can then use this sweep
    # when it is the summary's own grid
    vel, acc, measure = rates(plan, ev.pose, 1.0, theta.size, measure=summary)
    unit_columns = csv_columns(plan, theta, ev.pose, vel, acc)
    columns = _scaled(unit_columns, omega)
    if explicit and not plan.from_driver:
        # the values asked for, exactly (tau carries them to the last bit or so)
        for n, item in enumerate(plan.inputs):
            ends = (start, stop) if n == plan.lead else item.sweep
            if ends is not None and (n == plan.lead or plan.line[n][1] != 0):
                columns["input:" + item.joint] = np.linspace(ends[0], ends[1], steps + 1)
        columns["theta"] = columns["input:" + lead.joint]
    if c is not None and not c.full_turn:
        # a limit of the range is a fold: the inputs do not determine the rates there
        at_limit = (theta == c.low) | (theta == c.high)
        if at_limit.any():
            for key, values in list(columns.items()):
                if key.split(":")[0] in _RATE_COLUMNS and np.any(values != 0):
                    # (what is fixed keeps its zeros)
                    columns[key] = np.where(at_limit, np.nan, values)
    if plan.moving_inputs > 1 or (summary and c is None):   # summarize the sweep
        c = Cycle(None, min(lo, hi), max(lo, hi), ends="sweep")
    reuse = None
    if summary and c.ends == "limits" and np.array_equal(theta, cycle_theta(plan, c)):
        reuse = (ev, measure, unit_columns)
    summary = motion_summary(plan, output, omega, c, sweep=reuse) if summary else None
    if summary is not None and output is not None and output not in chain.links and not (
            output in chain._joint_index and chain.joint(output).kind == "P"):
        # a point's path: how straight it is over the sweep asked for
        summary = replace(summary, straightness=straightness(
            columns[f"x:{output}"], columns[f"y:{output}"]))
    return Motion(name=chain.name, fixed=plan.fixed, driver=plan.driver, omega=omega,
                  columns=columns, summary=summary, units=chain.units, plan=plan,
                  inputs=() if plan.from_driver else plan.inputs,
                  links=LinkStates(theta, ev.pose, vel, acc))


#: the largest input value a sweep may start or stop at
LARGEST_INPUT = 1e9
#: bytes a sweep holds per step and column (the columns and the working arrays, measured)
_BYTES_PER_VALUE = 24


def check_input_value(value, what, mechanism):
    """Refuse an input value (or speed) that is not a finite number or is past
    ``LARGEST_INPUT``; ``what`` names it in the message."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value):
        raise MechanismError(f"{what} must be a finite number, got {value}",
                             mechanism=mechanism)
    if abs(value) > LARGEST_INPUT:
        raise MechanismError(
            f"{what} {value:g} is too large: at most {LARGEST_INPUT:g} in size (beyond "
            "it a float cannot hold a thousandth of a degree or a millimetre)",
            mechanism=mechanism)


def memory_budget() -> int:
    """Bytes a sweep may take: half of this machine's memory, at most 8 GiB."""
    try:
        physical = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        physical = 4 << 30
    return int(min(physical // 2, 8 << 30))


def _check_memory(plan, steps):
    """Refuse up front a sweep that would not fit in memory, with what it would need."""
    chain = plan.chain
    columns = 10 * (len(chain.joints) + len(chain.points)) + 3 * len(chain.links) + 4
    need = (steps + 1) * columns * _BYTES_PER_VALUE
    budget = memory_budget()
    if need > budget:
        most = budget // (columns * _BYTES_PER_VALUE) - 1
        gib = -(-need // 2**30)                # integers: steps may have any size
        steps_text = f"{steps:,}" if steps < 10**15 else f"about 10^{len(str(steps)) - 1}"
        gib_text = f"{gib:,}" if gib < 10**15 else f"10^{len(str(gib)) - 1}"
        raise MechanismError(
            f"a sweep of {steps_text} steps would need about {gib_text} GiB of memory "
            f"({columns} columns); at most {most:,} steps fit in the {budget / 2**30:.1f} "
            "GiB a sweep may take here (half of this machine's memory, at most 8 GiB)",
            mechanism=chain.name)


_RATE_COLUMNS = {"omega", "alpha", "vx", "vy", "ax", "ay", "v", "a"}
_FIRST = {"omega", "vx", "vy", "v"}            # proportional to the input speed
_SECOND = {"alpha", "ax", "ay", "a"}           # to its square


def _scaled(columns, omega):
    """The columns at input speed ``omega`` from those at unit speed."""
    if omega == 1.0:
        return dict(columns)
    out = {}
    for key, values in columns.items():
        kind = key.split(":")[0]
        out[key] = values * omega if kind in _FIRST else \
            values * (omega * omega) if kind in _SECOND else values
    return out


def as_inputs(inputs, chain):
    """Inputs given to :func:`solve` as Input items (None when none are given)."""
    if inputs is None:
        return None
    if isinstance(inputs, (str, Input)):
        inputs = [inputs]
    out = []
    for item in inputs:
        if isinstance(item, Input):
            out.append(item)
        elif isinstance(item, str):
            out.append(Input(item))
        elif isinstance(item, dict) and "joint" in item:
            out.append(Input(item["joint"], item.get("from"), item.get("to")))
        elif isinstance(item, (tuple, list)) and len(item) == 3:
            out.append(Input(*item))
        else:
            raise MechanismError(f"an input must be a joint id, an Input or (joint, from, to), "
                                 f"got {item!r}", mechanism=chain.name)
    for item in out:
        for value in (item.start, item.stop):
            if value is not None and (isinstance(value, bool) or
                                      not isinstance(value, (int, float)) or
                                      not math.isfinite(value)):
                raise MechanismError(f"the input {item.joint!r} has a sweep value that is "
                                     f"not a finite number: {value!r}", mechanism=chain.name)
    if not out:
        raise MechanismError("no inputs given", mechanism=chain.name)
    return tuple(out)


def full_turns_drivers(chain, fixed):
    """The drivers :func:`full_turns` tries, in order."""
    m = chain.mechanism
    if m is not None and m.fixed == fixed and m.driver:
        return [m.driver]
    return [x for x in chain.links if x != fixed and any(
        j.kind == "R" and fixed in j.links and x in j.links for j in chain.joints)]


def full_turns_cost(chain, fixed, *, drivers=None) -> float:
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


def full_turns(chain, fixed):
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


@dataclass(frozen=True, eq=False)
class LinkMotion:
    """A link over a sweep: ``angle`` (degrees), ``omega`` (rad/s), ``alpha`` (rad/s^2)."""

    name: str
    angle: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray


@dataclass(frozen=True, eq=False)
class PointMotion:
    """A joint or point over a sweep: position, velocity, acceleration components."""

    name: str
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    ax: np.ndarray
    ay: np.ndarray


@dataclass(frozen=True, eq=False)
class SlideMotion:
    """A P joint over a sweep: ``s`` the slide from the drawn pose, ``v``, ``a``."""

    name: str
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
