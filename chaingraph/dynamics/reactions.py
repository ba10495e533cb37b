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
from dataclasses import dataclass, field
from typing import Any, overload

import numpy as np

from chaingraph._util.numbers import tidy
from chaingraph._util.text import csv_text, short_list
from chaingraph.dynamics.equilibrium import (
    UNIT_METRES,
    KinematicState,
    Solution,
    solve_equilibrium,
)
from chaingraph.errors import MechanismError
from chaingraph.kinematics import solve
from chaingraph.kinematics.columns import LinkStates
from chaingraph.kinematics.inputs import InputsGiven
from chaingraph.kinematics.motion import Motion
from chaingraph.kinematics.plan import Plan
from chaingraph.kinematics.pose import LinkState, PoseMotion, pose_motion
from chaingraph.model.chain import Chain

__all__ = ["Reaction", "Effort", "AppliedForce", "AppliedCouple", "PoseForces",
           "EffortStats", "ForcesSummary", "ReactionSeries", "EffortSeries", "SweepForces",
           "forces"]


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
        return {"min": self.min, "max": self.max, "mean": self.mean, "rms": self.rms}


@dataclass(frozen=True)
class ForcesSummary:
    """Over the sweep: ``efforts`` per input (:class:`EffortStats`), ``reactions`` the
    largest reaction per joint (N), and for a crank turning fully the
    ``energy_fluctuation`` (J: the largest swing of the work of its effort about the
    mean over a turn) and, given a ``speed_fluctuation``, the ``flywheel`` inertia
    (kg m^2) that holds the speed within it."""

    efforts: dict
    reactions: dict
    energy_fluctuation: float | None = None
    speed_fluctuation: float | None = None
    flywheel: float | None = None
    mean_speed: float | None = None

    def to_dict(self) -> dict:
        out: dict[str, Any] = {"efforts": {k: v.to_dict() for k, v in self.efforts.items()},
               "reactions": {k: {"max": v} for k, v in self.reactions.items()}}
        if self.energy_fluctuation is not None:
            out["energy_fluctuation"] = self.energy_fluctuation
        if self.flywheel is not None:
            out["flywheel"] = {"speed_fluctuation": self.speed_fluctuation,
                               "inertia": self.flywheel, "omega": self.mean_speed}
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

    def __repr__(self):
        return (f"SweepForces({self.name!r}, inputs={list(self.inputs)!r}, "
                f"steps={self.steps}, columns={short_list(list(self.columns))})")

    @property
    def columns(self) -> dict[str, np.ndarray]:
        """The CSV's columns, in its order."""
        out = {f"input:{joint}": v for joint, v in self.motion.values.items()}
        out["theta"] = self.motion.theta
        for r in self.reactions:
            name = f"{r.joint}:{r.on}" if len(r.by) > 1 else r.joint
            out[f"Fx:{name}"], out[f"Fy:{name}"] = r.fx, r.fy
        for r in self.reactions:
            if r.normal is not None and r.couple is not None:
                out[f"N:{r.joint}"], out[f"M:{r.joint}"] = r.normal, r.couple
        out.update((f"effort:{e.joint}", e.value) for e in self.efforts)
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
        if self.summary.energy_fluctuation is not None:
            out.append(("energy fluctuation", f"{self.summary.energy_fluctuation:.6g} J"))
        if self.summary.flywheel is not None:
            out.append(("flywheel", f"{self.summary.flywheel:.6g} kg m^2 for a speed "
                                    f"fluctuation of {self.summary.speed_fluctuation:g}"))
        return out


def _metres(chain):
    name = chain.source or chain.name
    if not chain.units:
        raise MechanismError("forces need the file's length 'units' (mm, cm, m or in) to "
                             "work in newtons and metres", mechanism=name)
    if chain.units not in UNIT_METRES:
        raise MechanismError(f"forces know the length units {', '.join(UNIT_METRES)}; the "
                             f"file's units are {chain.units!r}", mechanism=name)
    return UNIT_METRES[chain.units]


def _kinematic_state(chain: Chain, plan: Plan, states: LinkStates, omega, metres, *,
                     rates_known) -> KinematicState:
    """The :class:`KinematicState` of the solver's ``states`` at input speed ``omega``,
    in SI units: what the force solve needs, taken from the motion as it was solved."""
    n = states.tau.size
    w = 1.0 if float(omega) == states.speed else float(omega) / states.speed
    pose = states.pose
    vel = {k: tuple(np.asarray(c) * w for c in v) for k, v in states.velocity.items()}
    acc = {k: tuple(np.asarray(c) * w * w for c in v) for k, v in states.acceleration.items()}

    def arr(v, scale=1.0):
        return np.broadcast_to(np.asarray(v, dtype=float) * scale, (n,)).copy()
    links = {}
    for link in chain.links:
        p, v, a = pose[link], vel[link], acc[link]
        links[link] = LinkState(link, (arr(p[0], metres), arr(p[1], metres)), arr(p[2]),
                                (arr(v[0], metres), arr(v[1], metres)), arr(v[2]),
                                (arr(a[0], metres), arr(a[1], metres)), arr(a[2]))
    input_rates = {item.joint: arr(vel[item.key][2], 1.0 if item.kind == "R" else metres)
                   for item in plan.inputs}
    return KinematicState(n, links, input_rates, rates_known=rates_known)


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
    metres = _metres(mechanism)
    if speed_fluctuation is not None and not (isinstance(speed_fluctuation, (int, float))
                                              and 0 < speed_fluctuation < 2):
        raise MechanismError(f"the speed fluctuation must be a number between 0 and 2 "
                             f"(such as 0.02), got {speed_fluctuation!r}",
                             mechanism=mechanism.source or mechanism.name,
                             parameter="speed_fluctuation")
    if at is not None:
        state = pose_motion(mechanism, at=at, fixed=fixed, driver=driver, inputs=inputs,
                            omega=omega)
        return _forces_at(mechanism, state, static=static, metres=metres)
    motion = solve(mechanism, fixed=fixed, driver=driver, inputs=inputs, start=start,
                   stop=stop, steps=steps, omega=omega, summary=True)
    return _forces_over(mechanism, motion, static=static, metres=metres,
                        speed_fluctuation=speed_fluctuation)


def _forces_at(chain, state: PoseMotion, *, static, metres) -> PoseForces:
    """The forces at the solved pose ``state`` (its poses and rates as solved)."""
    plan = state.plan
    _check_masses(chain)
    assert state.states is not None               # (pose_motion keeps them)
    kin = _kinematic_state(chain, plan, state.states, state.omega, metres,
                           rates_known=False)
    sol = solve_equilibrium(chain, plan, kin, static=static, metres=metres)
    values = tuple(state.inputs.values()) if state.inputs else (state.input,)
    return _pose_forces(chain, plan, sol, 0, values, static)


def _forces_over(chain, motion: Motion, *, static, metres, speed_fluctuation) -> SweepForces:
    """The forces over the solved sweep ``motion`` (its poses and rates as solved)."""
    plan = motion.plan
    _check_masses(chain)
    assert motion.states is not None              # (solve keeps them)
    kin = _kinematic_state(chain, plan, motion.states, motion.omega, metres,
                           rates_known=True)
    sol = solve_equilibrium(chain, plan, kin, static=static, metres=metres)
    reactions = tuple(
        ReactionSeries(j.id, link, tuple(x for x in j.links if x != link),
                       sol.forces[(j.id, link)][0], sol.forces[(j.id, link)][1],
                       sol.normal[j.id] if j.kind == "P" else None,
                       sol.couple[j.id] if j.kind == "P" else None)
        for j in chain.joints for link in _on_links(j))
    efforts = tuple(EffortSeries(i.joint, sol.efforts[i.joint], "N m" if i.kind == "R" else "N")
                    for i in plan.inputs)
    return SweepForces(name=chain.name, fixed=plan.fixed,
                       inputs=tuple(i.joint for i in plan.inputs), static=static,
                       steps=motion.steps, reactions=reactions, efforts=efforts,
                       summary=_summary(chain, plan, motion, sol, speed_fluctuation),
                       notes=_notes(sol), motion=motion, solution=sol, chain=chain)


def _on_links(joint):
    """The links a joint's reactions are given on: each of a multiple joint's, else the
    first (the second's is its opposite)."""
    return joint.links if (joint.kind == "R" and len(joint.links) > 2) else joint.links[:1]


def _pose_forces(chain, plan, sol, k, at, static) -> PoseForces:
    """The forces at step ``k`` of the solution ``sol``, the inputs at ``at``."""
    metres = _metres(chain)
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
        power_balance=_num(one(sol.power)), notes=_notes(sol, k),
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
            normal = num(sol.normal[j.id][k]) if j.kind == "P" else None
            couple = num(sol.couple[j.id][k], size) if j.kind == "P" else None
            out.append(Reaction(j.id, link, by, (num(fx[k]), num(fy[k])), normal, couple))
    return tuple(out)


def _stats(v, unbounded):
    """Over the steps where ``v`` is determined; None throughout when it is unbounded
    somewhere (a dead centre) or nowhere determined."""
    v = np.asarray(v, dtype=float)
    v = v[np.isfinite(v)]
    if v.size == 0 or unbounded.any():
        return EffortStats(None, None, None, None)
    scale = float(np.abs(v).max())
    return EffortStats(float(v.min()), float(v.max()), tidy(float(v.mean()), scale),
                       float(np.sqrt(np.mean(v * v))))


def _filled(v):
    """``v`` with its undetermined steps (a slide at rest, a few steps) filled in
    linearly from their neighbours, for the work over a turn."""
    good = np.isfinite(v)
    if good.all() or good.sum() < 2:
        return v
    k = np.arange(v.size)
    return np.interp(k, k[good], v[good])


def _summary(chain, plan, motion, sol, speed_fluctuation):
    unbounded = sol.singular
    efforts = {i.joint: _stats(sol.efforts[i.joint], unbounded) for i in plan.inputs}
    reactions = {}
    for j in chain.joints:
        mags = [np.hypot(*sol.forces[(j.id, link)]) for link in _on_links(j)]
        worst = np.max(np.vstack(mags), axis=0)
        finite = worst[np.isfinite(worst)]
        reactions[j.id] = (float(finite.max()) if finite.size and not unbounded.any()
                           else None)
    energy = flywheel = None
    s = motion.summary
    lead = plan.inputs[plan.lead]
    theta = np.asarray(motion.theta, dtype=float)
    if (len(plan.inputs) == 1 and lead.kind == "R" and s is not None and s.full_turn
            and abs(abs(theta[-1] - theta[0]) - 360.0) < 1e-9):
        e = _filled(sol.efforts[lead.joint])
        if np.isfinite(e).all() and not unbounded.any():
            u = np.radians(theta)
            # over the turn, mean and RMS are integrals (the sweep's ends are one pose)
            span = u[-1] - u[0]
            mean_e = float(np.sum(0.5 * (e[1:] + e[:-1]) * np.diff(u)) / span)
            rms_e = math.sqrt(float(np.sum(0.5 * (e[1:] ** 2 + e[:-1] ** 2) * np.diff(u))
                                    / span))
            old = efforts[lead.joint]
            efforts[lead.joint] = EffortStats(old.min, old.max,
                                              tidy(mean_e, float(np.abs(e).max())), rms_e)
            # the work of the effort about its mean over the turn (trapezoid rule)
            work = np.concatenate([[0.0], np.cumsum(0.5 * (e[1:] + e[:-1]) * np.diff(u))])
            mean = work[-1] / (u[-1] - u[0])
            swing = work - mean * (u - u[0])
            energy = float(swing.max() - swing.min())
            if speed_fluctuation is not None:
                flywheel = energy / (motion.omega ** 2 * speed_fluctuation)
    return ForcesSummary(efforts, reactions, energy, speed_fluctuation if flywheel is not None
                         else None, flywheel, abs(motion.omega) if flywheel is not None else None)
