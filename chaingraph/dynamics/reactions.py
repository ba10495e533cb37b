"""Forces of a mechanism: every joint's reaction and the effort each input needs, at
one pose or over a sweep, kinetostatic (inertia at the input speed, gravity, loads,
friction) or static.

:func:`forces` solves (the motion once: the pose's or the sweep's, whose solved states
the force solve takes as they are); :class:`PoseForces` and :class:`SweepForces` hold
the results, with ``to_dict`` (the JSON of ``chaingraph forces --json``), ``rows`` and,
for a sweep, its typed arrays (:class:`ReactionSeries`, :class:`EffortSeries`), the
CSV's view of them (``to_csv``, ``to_frame``, ``sweep["Fx:A"]``) and any of its steps as
a :class:`PoseForces` (:meth:`SweepForces.pose`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field, replace
from typing import Any, overload

import numpy as np

from chaingraph._util.numbers import tidy
from chaingraph._util.text import csv_text, short_list
from chaingraph.dynamics.cycle import CycleEfforts, kinematic_state
from chaingraph.dynamics.equilibrium import (
    UNIT_METRES,
    KinematicState,
    Solution,
    solve_equilibrium,
)
from chaingraph.dynamics.shaking import Shaking, largest_size, shaking
from chaingraph.errors import AssemblyError, MechanismError
from chaingraph.kinematics import feasible_range, solve
from chaingraph.kinematics.inputs import InputsGiven, sweep_drive
from chaingraph.kinematics.motion import Motion
from chaingraph.kinematics.plan import Plan
from chaingraph.kinematics.pose import PoseMotion, pose_motion
from chaingraph.model.chain import Chain

__all__ = ["Reaction", "Effort", "AppliedForce", "AppliedCouple", "PoseForces",
           "EffortStats", "Flywheel", "ForcesSummary", "ReactionSeries", "EffortSeries",
           "SweepForces", "forces", "load_cycle"]


@dataclass(frozen=True)
class Reaction:
    """A joint's reaction on one of its links: ``force`` (Fx, Fy) in N, the force that
    ``by`` (the joint's other link; for a multiple joint, the others) exerts on ``on``;
    for a P joint also ``normal`` (N, the force across the guide) and ``couple`` (N m,
    the couple the guide carries), else None. None values where not determined."""

    joint: str
    on: str
    by: tuple[str, ...]
    force: tuple[float | None, float | None]
    normal: float | None = None
    couple: float | None = None

    def to_dict(self) -> dict:
        return {"joint": self.joint, "on": self.on,
                "by": self.by[0] if len(self.by) == 1 else list(self.by),
                "force": list(self.force), "normal": self.normal, "couple": self.couple}


@dataclass(frozen=True)
class Effort:
    """What input ``joint`` needs, in its positive sense: a torque (``unit`` "N m")
    for an R input, a force ("N") for a P input; None where it is unbounded (a dead
    centre) or not determined."""

    joint: str
    value: float | None
    unit: str

    def to_dict(self) -> dict:
        return {"joint": self.joint, "value": self.value, "unit": self.unit}


def _num(v):
    v = float(v)
    return v if math.isfinite(v) else None


@dataclass(frozen=True)
class AppliedForce:
    """A force on a link other than a joint's reaction: a ``what`` ("weight", "inertia
    force", "load", "effort J") of ``force`` (N) through ``at`` (the drawing's
    coordinates, file units)."""

    link: str
    what: str
    at: tuple[float, float]
    force: tuple[float, float]


@dataclass(frozen=True)
class AppliedCouple:
    """A couple on a link (N m, counter-clockwise): an inertia couple, a load's torque,
    an R input's effort."""

    link: str
    what: str
    value: float | None


@dataclass(frozen=True)
class PoseForces:
    """The forces at one pose (``chaingraph forces --at``). ``points`` gives each
    joint's point at the pose (file units; a P joint's block reference point), and
    ``applied`` and ``couples`` the other forces and couples on the links: with the
    reactions, every link's free body."""

    name: str
    fixed: str
    inputs: tuple[str, ...]
    at: tuple[float, ...]
    static: bool
    reactions: tuple[Reaction, ...]
    efforts: tuple[Effort, ...]
    power_balance: float | None
    notes: tuple[str, ...] = ()
    units: str | None = None
    dyads: tuple[tuple[str, str], ...] = ()   # the solver's dyads, for the force polygons
    points: dict[str, tuple[float, float]] = field(default_factory=dict, repr=False,
                                                   compare=False)
    applied: tuple[AppliedForce, ...] = field(default=(), repr=False)
    couples: tuple[AppliedCouple, ...] = field(default=(), repr=False)
    chain: Chain = field(kw_only=True, repr=False, compare=False)   # the mechanism solved

    def effort(self, joint: str | None = None) -> float | None:
        """The effort of input ``joint`` (default: the first input)."""
        joint = joint or self.inputs[0]
        return next(e.value for e in self.efforts if e.joint == joint)

    def reaction(self, joint: str, on: str | None = None) -> Reaction:
        """The reaction of ``joint`` on link ``on`` (default: its first link)."""
        return next(r for r in self.reactions if r.joint == joint and (on is None or r.on == on))

    def to_dict(self) -> dict:
        """The JSON of ``chaingraph forces --at ... --json``."""
        return {"name": self.name, "fixed": self.fixed, "inputs": list(self.inputs),
                "at": list(self.at), "static": self.static,
                "joints": [r.to_dict() for r in self.reactions],
                "efforts": [e.to_dict() for e in self.efforts],
                "power_balance": self.power_balance, "notes": list(self.notes)}

    def rows(self) -> list[tuple]:
        """(joint, on, by, Fx, Fy, |F|, normal, couple) per reaction."""
        def f(v):
            return "-" if v is None else f"{v:.6g}"
        out = []
        for r in self.reactions:
            fx, fy = r.force
            mag = None if fx is None or fy is None else math.hypot(fx, fy)
            out.append((r.joint, r.on, ", ".join(r.by), f(fx), f(fy), f(mag), f(r.normal),
                        f(r.couple)))
        return out


@dataclass(frozen=True)
class EffortStats:
    """An input's effort over the sweep: min, max, mean and RMS (None when it is not
    determined at some step)."""

    min: float | None
    max: float | None
    mean: float | None
    rms: float | None

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class Flywheel:
    """The flywheel that holds the speed within ``speed_fluctuation`` ((omega_max -
    omega_min) / omega) at the mean speed ``omega`` (rad/s): its ``inertia`` (kg m^2),
    I = dE / (omega^2 CS)."""

    speed_fluctuation: float
    inertia: float
    omega: float

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class ForcesSummary:
    """Over the sweep's regular poses (the dead centres left out, and listed apart in
    ``dead_centres``, the lead input's values there): ``efforts`` per input
    (:class:`EffortStats`), ``reactions`` the largest reaction per joint (N); for a
    crank turning through its whole cycle (a turn, or a load's ``cycle``) the
    ``mean_effort`` (the lead input's, N m: its integral over the cycle divided by the
    cycle), the ``energy_fluctuation`` (J: the largest swing of the work of its effort
    about the mean, its extremes found where the effort crosses the mean) and, given a
    speed fluctuation, the ``flywheel`` (:class:`Flywheel`); these integrals are exact,
    not read off the sweep's grid (:mod:`chaingraph.dynamics.cycle`)."""

    efforts: dict
    reactions: dict
    energy_fluctuation: float | None = None
    flywheel: Flywheel | None = None
    mean_effort: float | None = None
    dead_centres: tuple[float, ...] = ()
    shaking: tuple[float | None, float | None] | None = None   # largest force N, moment N m

    @property
    def speed_fluctuation(self) -> float | None:
        return None if self.flywheel is None else self.flywheel.speed_fluctuation

    def to_dict(self) -> dict:
        out: dict[str, Any] = {"efforts": {k: v.to_dict() for k, v in self.efforts.items()},
               "reactions": {k: {"max": v} for k, v in self.reactions.items()},
               "dead_centres": list(self.dead_centres)}
        if self.mean_effort is not None:
            out["mean_effort"] = self.mean_effort
        if self.energy_fluctuation is not None:
            out["energy_fluctuation"] = self.energy_fluctuation
        if self.flywheel is not None:
            out["flywheel"] = self.flywheel.to_dict()
        if self.shaking is not None:
            out["shaking"] = {"force": {"max": self.shaking[0]},
                              "moment": {"max": self.shaking[1]}}
        return out


@dataclass(frozen=True, eq=False)
class ReactionSeries:
    """A joint's reaction on one of its links over a sweep (NaN where not determined):
    ``fx``, ``fy`` (N) the force that ``by`` (the joint's other link; for a multiple
    joint, the others) exerts on ``on``; for a P joint also ``normal`` (N, across the
    guide) and ``couple`` (N m, carried by the guide), else None."""

    joint: str
    on: str
    by: tuple[str, ...]
    fx: np.ndarray
    fy: np.ndarray
    normal: np.ndarray | None = None
    couple: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class EffortSeries:
    """What input ``joint`` needs over a sweep, in its positive sense: ``value`` a
    torque (``unit`` "N m") for an R input, a force ("N") for a P input; NaN where it is
    unbounded (a dead centre) or not determined."""

    joint: str
    value: np.ndarray
    unit: str


@dataclass(frozen=True, eq=False)
class SweepForces:
    """The forces over a sweep (``chaingraph forces``): ``reactions`` (one
    :class:`ReactionSeries` per joint, per link of a multiple joint), ``efforts`` (one
    :class:`EffortSeries` per input), the ``summary``, and the ``motion`` they are of.

    ``sweep["Fx:J"]``, :attr:`columns`, :meth:`to_csv` and :meth:`to_frame` are the
    CSV's view of them: the input columns of ``solve``, then ``Fx:J``, ``Fy:J`` per
    joint (``Fx:J:LINK`` per link of a multiple joint), ``N:J``, ``M:J`` per P joint,
    ``effort:J`` per input. :meth:`pose` gives one step as a :class:`PoseForces`.
    """

    name: str
    fixed: str
    inputs: tuple[str, ...]
    static: bool
    steps: int
    reactions: tuple[ReactionSeries, ...] = field(repr=False)
    efforts: tuple[EffortSeries, ...] = field(repr=False)
    summary: ForcesSummary = field(repr=False)
    motion: Motion = field(repr=False)
    solution: Solution = field(repr=False)       # the force solve's own, every step
    chain: Chain = field(repr=False)
    notes: tuple[str, ...] = ()
    shaking: Shaking | None = field(default=None, repr=False)   # on the frame, per step
    #: the steady torque of a ``torque = "mean"`` load (N m, on its link), else None
    load_torque: float | None = None

    def __repr__(self):
        return (f"SweepForces({self.name!r}, inputs={list(self.inputs)!r}, "
                f"steps={self.steps}, columns={short_list(list(self.columns))})")

    @property
    def columns(self) -> dict[str, np.ndarray]:
        """The CSV's columns, in its order."""
        out = {f"input:{joint}": v for joint, v in self.motion.values.items()}
        plan = self.motion.plan
        if plan.inputs[plan.lead].kind == "R" or not out:
            out["theta"] = self.motion.theta     # (a P input's slide: its input: column)
        for r in self.reactions:
            name = f"{r.joint}:{r.on}" if len(r.by) > 1 else r.joint
            out[f"Fx:{name}"], out[f"Fy:{name}"] = r.fx, r.fy
        for r in self.reactions:
            if r.normal is not None and r.couple is not None:
                out[f"N:{r.joint}"], out[f"M:{r.joint}"] = r.normal, r.couple
        out.update((f"effort:{e.joint}", e.value) for e in self.efforts)
        if self.shaking is not None:
            out.update({"shaking:Fx": self.shaking.fx, "shaking:Fy": self.shaking.fy,
                        "shaking:M": self.shaking.moment})
        return out

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def reaction(self, joint: str, on: str | None = None) -> ReactionSeries:
        """The reaction of ``joint`` on link ``on`` (default: its first link)."""
        return next(r for r in self.reactions if r.joint == joint and (on is None or r.on == on))

    def effort(self, joint: str | None = None) -> EffortSeries:
        """The effort of input ``joint`` (default: the first input)."""
        joint = joint or self.inputs[0]
        return next(e for e in self.efforts if e.joint == joint)

    def pose(self, k: int = 0) -> PoseForces:
        """The forces at step ``k`` of the sweep, as :func:`forces` gives them at one
        pose, from the sweep's own solution (nothing is solved again)."""
        plan = self.motion.plan
        at = self.motion.input_values(k)
        return _pose_forces(self.chain, plan, self.solution, k,
                            at if isinstance(at, list) else [at], self.static)

    def to_dict(self) -> dict:
        """The JSON of ``chaingraph forces --json`` over a sweep."""
        return {"name": self.name, "fixed": self.fixed, "inputs": list(self.inputs),
                "static": self.static, "steps": self.steps,
                "summary": self.summary.to_dict(), "notes": list(self.notes)}

    def to_csv(self, path: str | os.PathLike | None = None) -> str | None:
        """Write the CSV (one row per step); returns the text when ``path`` is None."""
        return csv_text(self.columns, self.steps + 1, path)

    def to_frame(self) -> Any:
        """The CSV's columns as a pandas DataFrame (needs the notebook extra)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("SweepForces.to_frame needs pandas: pip install "
                              "'chaingraph[notebook]' (or pandas)") from None
        return pandas.DataFrame({k: np.asarray(v) for k, v in self.columns.items()})

    def rows(self) -> list[tuple]:
        """The summary as (what, value) rows."""
        out = []
        def f(v, unit):
            return "unbounded or not determined" if v is None else f"{v:.6g} {unit}"
        for e in self.efforts:
            s, u = self.summary.efforts[e.joint], e.unit
            out.append((f"effort {e.joint}", f"min {f(s.min, u)}, max {f(s.max, u)}, "
                                             f"mean {f(s.mean, u)}, RMS {f(s.rms, u)}"))
        for joint, v in self.summary.reactions.items():
            out.append((f"largest reaction {joint}", "-" if v is None else f"{v:.6g} N"))
        if self.summary.mean_effort is not None:
            unit = self.efforts[0].unit
            out.append(("mean effort", f"{self.summary.mean_effort:.6g} {unit} over the cycle"))
        if self.summary.energy_fluctuation is not None:
            out.append(("energy fluctuation", f"{self.summary.energy_fluctuation:.6g} J"))
        if self.summary.flywheel is not None:
            fw = self.summary.flywheel
            out.append(("flywheel", f"{fw.inertia:.6g} kg m^2 for a speed fluctuation of "
                                    f"{fw.speed_fluctuation:g} at {fw.omega:g} rad/s"))
        if self.summary.dead_centres:
            out.append(("dead centres", ", ".join(f"{v:g}" for v in self.summary.dead_centres)
                        + " (left out of the figures above)"))
        if self.summary.shaking is not None:
            for what, v, unit in zip(("force", "moment"), self.summary.shaking, ("N", "N m")):
                out.append((f"largest shaking {what}", "-" if v is None else f"{v:.6g} {unit}"))
        return out


def length_metres(chain: Chain) -> float:
    """The chain's length unit in metres; a MechanismError when it has none, or one
    forces do not know."""
    name = chain.source or chain.name
    if not chain.units:
        raise MechanismError("forces need the file's length 'units' (mm, cm, m or in) to "
                             "work in newtons and metres", mechanism=name)
    if chain.units not in UNIT_METRES:
        raise MechanismError(f"forces know the length units {', '.join(UNIT_METRES)}; the "
                             f"file's units are {chain.units!r}", mechanism=name)
    return UNIT_METRES[chain.units]


def _notes(solution, k=None):
    """What is not determined (at step k, or at which steps of the sweep)."""
    def hit(mask):
        return bool(mask[k]) if k is not None else bool(np.any(mask))

    def where(mask):
        if k is not None:
            return ""
        n = int(np.sum(mask))
        return f" (at {n} step{'s' if n != 1 else ''}, NaN in the CSV)"
    out = []
    if solution.indeterminate:
        out.append("a redundant constraint leaves the reactions statically indeterminate: "
                   "they are the least-norm share that balances the links (the efforts "
                   "are determined)")
    if hit(solution.singular):
        out.append("a dead centre: the inputs do not hold the mechanism there, so the "
                   f"effort is unbounded{where(solution.singular)}")
    for joint, mask in solution.at_rest.items():
        if hit(mask):
            out.append(f"the slide of {joint} is at rest: its friction is indeterminate "
                       "within its cone, so the reactions and efforts are not determined"
                       + where(mask))
    if hit(solution.jammed):
        out.append("no direction of the friction forces is consistent: the friction "
                   f"locks the mechanism{where(solution.jammed)}")
    return tuple(out)


def _leaving(chain, solution, values, unit, k=None):
    """Where a cam's contact force would have to pull (the pair is unclosed: it can only
    push): the follower would leave the cam there; at step ``k``, or over the sweep as
    runs of the input's ``values`` (in ``unit``)."""
    out = []
    for cam in chain.cams:
        f = np.asarray(solution.normal[cam.id], dtype=float)
        finite = f[np.isfinite(f)]
        scale = float(np.abs(finite).max()) if finite.size else 0.0
        pull = np.isfinite(f) & (f < -1e-9 * scale)
        said = (f"the contact force of cam {cam.id!r} would have to pull its follower "
                f"{cam.follower!r} onto the cam")
        hold = ("the pair is unclosed, so the follower leaves the cam (a stronger spring "
                "or load, a slower speed, or a closed cam would hold it)")
        if k is not None:
            if pull[k]:
                out.append(f"{said} ({f[k]:.6g} N): {hold}")
            continue
        idx = np.flatnonzero(pull)
        if idx.size:
            runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
            at = ", ".join(f"{values[r[0]]:.6g} to {values[r[-1]]:.6g}" for r in runs)
            out.append(f"{said} at {at} {unit} (least {f[idx].min():.6g} N): {hold}")
    return tuple(out)


def _check_masses(chain):
    name = chain.source or chain.name
    if chain.masses or chain.loads or chain.gravity:
        return
    raise MechanismError("the mechanism has no masses, loads or gravity: add [[links]] "
                         "with masses, [[loads]] or [forces] gravity", mechanism=name)


@overload
def forces(mechanism: Chain, *, at: None = None, static: bool = False,
           fixed: str | None = None, driver: str | None = None, inputs: InputsGiven = None,
           start: float | None = None, stop: float | None = None, steps: int = 360,
           omega: float | None = None, speed_fluctuation: float | None = None
           ) -> SweepForces: ...
@overload
def forces(mechanism: Chain, *, at: float | Sequence[float], static: bool = False,
           fixed: str | None = None, driver: str | None = None, inputs: InputsGiven = None,
           start: float | None = None, stop: float | None = None, steps: int = 360,
           omega: float | None = None, speed_fluctuation: float | None = None
           ) -> PoseForces: ...
def forces(mechanism: Chain, *, at: float | Sequence[float] | None = None,
           static: bool = False, fixed: str | None = None, driver: str | None = None,
           inputs: InputsGiven = None, start: float | None = None,
           stop: float | None = None, steps: int = 360, omega: float | None = None,
           speed_fluctuation: float | None = None) -> PoseForces | SweepForces:
    """The joints' reactions and the inputs' efforts of a mechanism.

    Parameters
    ----------
    mechanism : Chain
        A mechanism with a drawn pose, ``units``, and masses (``[[links]]``), loads
        (``[[loads]]``), gravity (``[forces]``) and friction on its P joints.
    at : float or sequence of float, optional
        One pose: the input value (as for :func:`chaingraph.instant_centres`); gives a
        :class:`PoseForces`. By default the sweep of :func:`chaingraph.solve`
        (``start``, ``stop``, ``steps``), a :class:`SweepForces`.
    static : bool
        Leave out the links' inertia (gravity, loads and friction only).
    fixed, driver, inputs, omega
        As for :func:`chaingraph.solve`; ``omega`` is the input speed the inertia forces
        are worked out at (rad/s, or length units/s for a P input).
    speed_fluctuation : float, optional
        For a crank turning fully, the coefficient of fluctuation of speed
        (omega_max - omega_min) / omega the flywheel must hold: the summary then gives
        the flywheel's inertia I = dE / (omega^2 CS).

    Returns
    -------
    PoseForces or SweepForces

    Examples
    --------
    A slider crank held by a 1 kN load on its piston towards the crank, crank at 90
    degrees: the load would turn the crank on (counter-clockwise) with the load times the
    crank radius (50 mm), so the crank holds it with -50 N m; the guide takes F tan(phi)
    (the piston presses down on it).

    >>> import chaingraph
    >>> from chaingraph.model.chain import Chain, Joint, Load, Mechanism
    >>> engine = Chain("engine", (
    ...     Joint("O", "R", ("frame", "crank"), at=(0.0, 0.0)),
    ...     Joint("A", "R", ("crank", "rod"), at=(0.0, 50.0)),
    ...     Joint("B", "R", ("rod", "piston"), at=(193.6492, 0.0)),
    ...     Joint("S", "P", ("frame", "piston"), at=(193.6492, 0.0), axis=0.0)),
    ...     units="mm", mechanism=Mechanism("frame", driver="crank"),
    ...     loads=(Load("piston", "B", (-1000.0, 0.0)),))
    >>> f = chaingraph.forces(engine, at=90.0, static=True)
    >>> round(f.effort(), 6)                                  # N m: 1000 N x 0.05 m
    -50.0
    >>> round(f.reaction("S").normal, 3)                      # 1000 tan(phi), phi = 14.48
    -258.199
    """
    metres = length_metres(mechanism)
    if speed_fluctuation is not None and not (isinstance(speed_fluctuation, (int, float))
                                              and 0 < speed_fluctuation < 2):
        raise MechanismError(f"the speed fluctuation must be a number between 0 and 2 "
                             f"(such as 0.02), got {speed_fluctuation!r}",
                             mechanism=mechanism.source or mechanism.name,
                             parameter="speed_fluctuation")
    how: dict[str, Any] = dict(fixed=fixed, driver=driver, inputs=inputs, omega=omega)
    if at is not None:
        state = pose_motion(mechanism, at=at, **how)
        return _forces_at(mechanism, state, static=static, metres=metres, how=how)
    cycle = load_cycle(mechanism)
    _check_loads(mechanism, sweep_drive(mechanism, steps=steps, **how).plan)
    if cycle is not None and start is None and stop is None:
        start, stop = 0.0, cycle          # a load's cycle: swept from 0, as the textbook
    # the motion's summary is not the forces': only whether the input turns fully is
    # (:func:`_full_turn`), which the cycle says without the summary's cost
    motion = solve(mechanism, start=start, stop=stop, steps=steps, summary=False, **how)
    return _forces_over(mechanism, motion, static=static, metres=metres,
                        speed_fluctuation=speed_fluctuation, how=how)


def load_cycle(chain: Chain) -> float | None:
    """The input's cycle in degrees of the loads tabulated against it with a ``cycle``
    (720 for a four-stroke engine), or None when none gives one."""
    cycles = [math.degrees(x.cycle) for x in chain.loads if x.cycle is not None]
    return float(round(max(cycles), 9)) if cycles else None


def _lead_angle(plan: Plan, values) -> np.ndarray | None:
    """The lead input's value in radians (None for a P input)."""
    lead = plan.inputs[plan.lead]
    return np.radians(np.asarray(values, dtype=float)) if lead.kind == "R" else None


def _check_loads(chain, plan):
    """Loads that need what the inputs do not give."""
    lead = plan.inputs[plan.lead]
    for load in chain.loads:
        if load.against == "input" and lead.kind != "R":
            raise MechanismError(f"the load on {load.on!r} is tabulated against the input's "
                                 f"value in degrees: it needs an R input (a crank), not the "
                                 f"P input {lead.joint!r}", mechanism=chain.source or chain.name)
    if any(x.mean_torque and x.on == plan.fixed for x in chain.loads):
        raise MechanismError(f"the steady torque equal to the mean effort (torque = \"mean\") "
                             f"acts on the fixed link {plan.fixed!r}, which takes it without "
                             "moving: put it on a moving link (the crank)",
                             mechanism=chain.source or chain.name)
    if sum(x.mean_torque for x in chain.loads) > 1:
        raise MechanismError("only one load may be the steady torque equal to the mean "
                             "effort (torque = \"mean\")", mechanism=chain.source or chain.name)


def _cycle_loads(chain, plan, metres, static, how, sweep=None) -> CycleEfforts:
    """The loads' cycle quantities (the strokes' directions, the steady mean torque),
    from ``sweep`` ((motion, state) of the sweep solved) when it is the whole cycle,
    else from a sweep of the cycle solved here."""
    resist = [i for i, x in enumerate(chain.loads) if x.resist is not None]
    mean = any(x.mean_torque for x in chain.loads)
    key: tuple | None = (chain, chain.source, metres, static, repr(sorted(how.items())))
    try:
        if key in _CYCLES:
            return _CYCLES[key]
    except TypeError:                   # (a chain holding lists: not kept)
        key = None
    if not resist and not mean:
        omega = solve_omega(chain, how) if sweep is None else sweep[0].omega
        efforts = CycleEfforts(chain, plan, metres, static, omega)
    else:
        span = load_cycle(chain) or 360.0
        whole = sweep is not None and _whole_cycle(sweep[0], span)
        efforts = _cycle_efforts(chain, plan, metres, static, how, sweep if whole else None,
                                 span, resist, mean)
    if len(_CYCLES) > 32:
        _CYCLES.clear()
    if key is not None:
        _CYCLES[key] = efforts
    return efforts


#: the loads' cycle quantities of the mechanisms solved lately (exact, so whatever grid
#: they were found on), by chain, units, statics and inputs
_CYCLES: dict = {}


def solve_omega(chain: Chain, how: dict) -> float:
    """The lead input's speed a solve of ``chain`` takes with ``how``'s inputs."""
    return sweep_drive(chain, **how).omega


def _cycle_efforts(chain, plan, metres, static, how, sweep, span, resist, mean):
    """:func:`_cycle_loads`'s work, from ``sweep`` (the whole cycle) or solved here."""
    if sweep is None:
        try:
            motion = solve(chain, start=0.0, stop=span, steps=int(round(span)), **how)
        except AssemblyError:                       # a rocking input: its own range
            motion = solve(chain, steps=360, **how)
        sweep = (motion, None)
    motion, kin = sweep
    if kin is None:
        kin = kinematic_state(chain, plan, motion.states, motion.omega, metres,
                              rates_known=True, angle=_lead_angle(plan, motion.theta))
    directions = {i: _stroke_direction(chain, plan, kin, metres, i) for i in resist}
    strokes = {i: d for i, d in directions.items() if chain.loads[i].stroke}
    efforts = CycleEfforts(chain, plan, metres, static, motion.omega, strokes, directions)
    if not mean:
        return efforts
    if not _whole_cycle(motion, span):
        raise MechanismError("a steady torque equal to the mean effort (torque = \"mean\") "
                             "needs a crank that turns through its whole cycle",
                             mechanism=chain.source or chain.name)
    return efforts.with_torque(_mean_torque(efforts, np.asarray(motion.theta, dtype=float)))


def _full_turn(motion: Motion) -> bool:
    """Whether the motion's lead input turns fully (its cycle a whole turn), from the
    motion's summary when it has one, else from the cycle (found once per plan)."""
    if motion.summary is not None:
        return bool(motion.summary.full_turn)
    plan = motion.plan
    if plan.moving_inputs > 1:
        return False
    try:
        return feasible_range(plan) is None
    except AssemblyError:             # no cycle: the input neither returns nor stops
        return False


def _whole_cycle(motion, span):
    theta = np.asarray(motion.theta, dtype=float)
    return (_full_turn(motion) and theta.size > 1
            and abs(abs(theta[-1] - theta[0]) - span) < 1e-9)


def _stroke_direction(chain, plan, kin, metres, i):
    """The direction load ``i``'s point moves in during its stroke: the line of its
    motion (the principal direction of its positions over the cycle), in the sense it
    moves for the longer part of the input's cycle (the forward stroke), reversed for
    the return stroke."""
    load = chain.loads[i]
    state = kin.links[load.on]
    origin = plan.origin
    p = (chain.joint(load.at).at if load.at in {j.id for j in chain.joints}
         else chain.point(load.at).at)
    q = state.moved(((p[0] - origin[0]) * metres, (p[1] - origin[1]) * metres))
    xy = np.column_stack(q)
    xy = xy - xy.mean(axis=0)
    d = np.linalg.svd(xy, full_matrices=False)[2][0]
    v = state.velocity_at(q)
    u = v[0] * d[0] + v[1] * d[1]
    sense = 1.0 if np.sum(u > 0) >= np.sum(u < 0) else -1.0
    if load.stroke == "return":
        sense = -sense
    return (float(sense * d[0]), float(sense * d[1]))


def _mean_torque(efforts: CycleEfforts, grid: np.ndarray) -> float:
    """The steady torque of the ``torque = "mean"`` load that makes the lead input's
    mean effort over the cycle zero (the secant method: exact in one step without
    friction, where the effort is linear in the torque)."""
    breaks = efforts.breaks(_partition(grid))
    t0, f0 = 0.0, efforts.mean(breaks)
    if not math.isfinite(f0):
        return math.nan
    t1 = f0 if f0 else 1.0
    f1 = efforts.with_torque(t1).mean(breaks)
    for _ in range(30):
        if not math.isfinite(f1) or f1 == f0 or abs(f1) <= 1e-14 * max(abs(t1), 1e-300):
            break
        t0, f0, t1 = t1, f1, t1 - f1 * (t1 - t0) / (f1 - f0)
        f1 = efforts.with_torque(t1).mean(breaks)
    return t1


def _forces_at(chain, state: PoseMotion, *, static, metres, how) -> PoseForces:
    """The forces at the solved pose ``state`` (its poses and rates as solved)."""
    plan = state.plan
    _check_masses(chain)
    _check_loads(chain, plan)
    assert state.states is not None               # (pose_motion keeps them)
    cyc = _cycle_loads(chain, plan, metres, static, how)
    kin = kinematic_state(chain, plan, state.states, state.omega, metres,
                           rates_known=False, angle=_lead_angle(plan, [state.input]),
                           strokes=cyc.strokes)
    sol = solve_equilibrium(chain, plan, kin, static=static, metres=metres,
                            mean_torque=cyc.mean_torque)
    values = tuple(state.inputs.values()) if state.inputs else (state.input,)
    return _pose_forces(chain, plan, sol, 0, values, static)


def _forces_over(chain, motion: Motion, *, static, metres, speed_fluctuation,
                 how) -> SweepForces:
    """The forces over the solved sweep ``motion`` (its poses and rates as solved)."""
    plan = motion.plan
    _check_masses(chain)
    _check_loads(chain, plan)
    assert motion.states is not None              # (solve keeps them)
    kin = kinematic_state(chain, plan, motion.states, motion.omega, metres,
                           rates_known=True, angle=_lead_angle(plan, motion.theta))
    cyc = _cycle_loads(chain, plan, metres, static, how, sweep=(motion, kin))
    kin = replace(kin, strokes=cyc.strokes)
    sol = solve_equilibrium(chain, plan, kin, static=static, metres=metres,
                            mean_torque=cyc.mean_torque)
    shaken = shaking(sol, kin.n, origin=plan.origin, metres=metres)
    reactions = tuple(
        ReactionSeries(j.id, link, tuple(x for x in j.links if x != link),
                       sol.forces[(j.id, link)][0], sol.forces[(j.id, link)][1],
                       sol.normal.get(j.id) if j.kind != "R" else None,
                       sol.couple[j.id] if j.kind == "P" else None)
        for j in chain.joints for link in _on_links(j))
    efforts = tuple(EffortSeries(i.joint, sol.efforts[i.joint], "N m" if i.kind == "R" else "N")
                    for i in plan.inputs)
    summary, notes = _summary(chain, plan, motion, sol, speed_fluctuation, cyc)
    summary = replace(summary, shaking=shaken.largest())
    steady = next((x for x in chain.loads if x.mean_torque), None)
    if steady is not None:
        notes = (f"the steady load torque on {steady.on} (torque = \"mean\"), equal to the "
                 f"mean effort over the cycle: {tidy(cyc.mean_torque, 1.0):.6g} N m",) + notes
    return SweepForces(name=chain.name, fixed=plan.fixed,
                       inputs=tuple(i.joint for i in plan.inputs), static=static,
                       steps=motion.steps, reactions=reactions, efforts=efforts,
                       summary=summary, motion=motion,
                       notes=_notes(sol) + _leaving(chain, sol, motion.theta, plan.lead_unit)
                       + notes,
                       solution=sol, chain=chain, shaking=shaken,
                       load_torque=cyc.mean_torque if steady is not None else None)


def _on_links(joint):
    """The links a joint's reactions are given on: each of a multiple joint's, else the
    first (the second's is its opposite)."""
    return joint.links if (joint.kind == "R" and len(joint.links) > 2) else joint.links[:1]


def _pose_forces(chain, plan, sol, k, at, static) -> PoseForces:
    """The forces at step ``k`` of the solution ``sol``, the inputs at ``at``."""
    metres = length_metres(chain)
    ox, oy = plan.origin

    def one(v):
        v = np.asarray(v, dtype=float).reshape(-1)
        return float(v[k if v.size > 1 else 0])

    def back(q):
        return (one(q[0]) / metres + ox, one(q[1]) / metres + oy)
    return PoseForces(
        name=chain.name, fixed=plan.fixed,
        inputs=tuple(i.joint for i in plan.inputs), at=tuple(float(v) for v in at),
        static=static, reactions=_reactions(chain, sol, k, plan.size * metres),
        efforts=tuple(Effort(i.joint, _num(one(sol.efforts[i.joint])),
                             "N m" if i.kind == "R" else "N") for i in plan.inputs),
        power_balance=_num(one(sol.power)),
        notes=_notes(sol, k) + _leaving(chain, sol, at, plan.lead_unit, k),
        units=chain.units, points={name: back(q) for name, q in sol.points.items()},
        dyads=tuple(tuple(step.links) for step in plan.steps if step.kind == "dyad"),
        applied=tuple(AppliedForce(link, what, back(q), (_num(one(f[0])), _num(one(f[1]))))
                      for link, what, q, f in sol.applied),
        couples=tuple(AppliedCouple(link, what, _num(one(v))) for link, what, v in sol.couples),
        chain=chain)


def _reactions(chain, sol, k, size):
    """The reactions at step k, each figure tidied at the scale of the largest (so
    that rounding shows as 0, not 5.6e-15); ``size`` the mechanism's size in m."""
    mags = [abs(float(c[k])) for f in sol.forces.values() for c in f if np.isfinite(c[k])]
    scale = max(mags + [0.0])

    def num(v, unit=1.0):
        v = _num(v)
        return None if v is None else tidy(v, scale * unit)
    out = []
    for j in chain.joints:
        for link in _on_links(j):
            fx, fy = sol.forces[(j.id, link)]
            by = tuple(x for x in j.links if x != link)
            normal = num(sol.normal[j.id][k]) if j.kind != "R" else None
            couple = num(sol.couple[j.id][k], size) if j.kind == "P" else None
            out.append(Reaction(j.id, link, by, (num(fx[k]), num(fy[k])), normal, couple))
    return tuple(out)


def _stats(v, regular):
    """Over the regular steps where ``v`` is determined; None throughout when it is
    determined at none."""
    v = np.asarray(v, dtype=float)
    v = v[regular & np.isfinite(v)]
    if v.size == 0:
        return EffortStats(None, None, None, None)
    scale = float(np.abs(v).max())
    return EffortStats(float(v.min()), float(v.max()), tidy(float(v.mean()), scale),
                       float(np.sqrt(np.mean(v * v))))


def _summary(chain, plan, motion, sol, speed_fluctuation, efforts_at: CycleEfforts):
    """The :class:`ForcesSummary` over the regular poses, and notes on what it leaves
    out; ``efforts_at`` the lead input's effort anywhere in its cycle, for the integrals
    over the cycle."""
    regular = ~sol.singular
    theta = np.asarray(motion.theta, dtype=float)
    efforts = {i.joint: _stats(sol.efforts[i.joint], regular) for i in plan.inputs}
    reactions = {}
    for j in chain.joints:
        mags = [np.hypot(*sol.forces[(j.id, link)]) for link in _on_links(j)]
        reactions[j.id] = largest_size(np.max(np.vstack(mags), axis=0)[regular])
    dead = tuple(float(v) for v in theta[sol.singular])
    notes: list[str] = []
    lead = plan.inputs[plan.lead]
    span = load_cycle(chain) or 360.0
    energy = mean = flywheel = None
    cycle = _one_cycle(plan, motion, span)
    if isinstance(cycle, str):
        if speed_fluctuation is not None or (len(plan.inputs) == 1 and lead.kind == "R"
                                             and _full_turn(motion)):
            notes.append(cycle)
    else:
        e = sol.efforts[lead.joint][cycle]
        if not sol.singular[cycle].any() and not sol.jammed[cycle].any():
            e = e[np.isfinite(e)]
            mean, rms2, energy = _cycle_figures(efforts_at, theta[cycle])
            rms = math.sqrt(rms2)
            old = efforts[lead.joint]
            mean = tidy(mean, float(np.abs(e).max()))
            efforts[lead.joint] = EffortStats(old.min, old.max, mean, rms)
            if speed_fluctuation is not None:
                flywheel = Flywheel(speed_fluctuation,
                                    energy / (motion.omega ** 2 * speed_fluctuation),
                                    abs(motion.omega))
        else:
            notes.append("the energy fluctuation and flywheel are not determined: the "
                         "effort is unbounded or not determined over part of the cycle")
    return (ForcesSummary(efforts, reactions, energy, flywheel, mean, dead), tuple(notes))


def _cycle_figures(efforts_at: CycleEfforts, theta: np.ndarray):
    """The mean effort, its mean square and the energy fluctuation over the cycle
    ``theta`` spans: exact, so kept with ``efforts_at`` for the next sweep of the same
    cycle."""
    key = ("figures", float(theta[0]), float(theta[-1]))
    if key not in efforts_at.solved:
        breaks = efforts_at.breaks(_partition(theta))
        mean = efforts_at.mean(breaks)
        efforts_at.solved[key] = (mean, efforts_at.mean(breaks, power=2),
                                  efforts_at.energy_fluctuation(breaks, mean))
    return efforts_at.solved[key]


def _partition(theta: np.ndarray) -> np.ndarray:
    """The cycle's span (from the sweep's first angle to its last, increasing) cut in
    pieces of at most 5 degrees (Gauss-Legendre's 8 points on each: exact to rounding
    for an effort of up to some tens of harmonics), the same whatever the sweep's
    steps."""
    lo, hi = sorted((float(theta[0]), float(theta[-1])))
    return np.linspace(lo, hi, max(int(math.ceil((hi - lo) / 5.0)), 4) + 1)


def _one_cycle(plan, motion, span):
    """The steps of the sweep's first whole cycle of ``span`` degrees (a slice), or why
    there is none (a note)."""
    lead = plan.inputs[plan.lead]
    theta = np.asarray(motion.theta, dtype=float)
    if len(plan.inputs) != 1 or lead.kind != "R" or not _full_turn(motion):
        return ("no energy fluctuation or flywheel: they are for a single crank turning "
                "fully")
    swept = abs(theta[-1] - theta[0])
    turns = swept / span
    per = (theta.size - 1) / turns if turns else 0.0
    if turns < 1 - 1e-9 or abs(per - round(per)) > 1e-6:
        return (f"no energy fluctuation or flywheel: they are over a whole cycle of the "
                f"input ({span:g} degrees), and the sweep covers {swept:g} degrees"
                + ("" if turns < 1 else ", whose steps do not end a cycle (sweep a whole "
                                        "number of cycles)"))
    return slice(0, int(round(per)) + 1)


def _energy_swing(spline, u, mean):
    """The largest swing of the work of the effort about its mean over the cycle: the
    work W(u) = int e du - mean (u - u0) at its extremes (where the effort crosses the
    mean, the spline's roots) and at the cycle's ends."""
    work = spline.antiderivative()
    roots = np.asarray(spline.solve(mean, extrapolate=False), dtype=float)
    at = np.concatenate([[u[0], u[-1]], roots[np.isfinite(roots)]])
    swing = work(at) - work(u[0]) - mean * (at - u[0])
    return float(swing.max() - swing.min())
