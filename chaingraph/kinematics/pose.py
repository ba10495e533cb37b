"""A mechanism at one input value: every link's position, velocity and acceleration.

This is what the graphical constructions start from (structure and dimensions in, one
pose's rigid-body motions out): :func:`pose_motion` solves the mechanism at the input
value asked for, in the assembly mode of the drawn pose, exactly as ``solve`` does
along a sweep, and keeps each link's whole motion (a reference point's velocity and
acceleration with the link's angular velocity and acceleration), from which the velocity
and acceleration of any point of the link follow.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from chaingraph.errors import AssemblyError
from chaingraph.geometry import turn_by
from chaingraph.kinematics.columns import LinkStates, Trajectories, reference_link
from chaingraph.kinematics.closed_form import closure_checks
from chaingraph.kinematics.equations import check_poses
from chaingraph.kinematics.inputs import Drive, InputsGiven, pose_drive
from chaingraph.kinematics.plan import Plan
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.sweep import evaluate_near
from chaingraph.model.chain import Chain

__all__ = ["LinkState", "Slide", "PoseMotion", "AtOneValue", "pose_motion"]


@dataclass(frozen=True)
class LinkState:
    """One link's planar rigid-body motion at an instant, in the drawing's frame.

    ``point`` is a reference point of the link (any: the link's frame origin), with
    its ``velocity`` and ``acceleration``; ``omega`` and ``alpha`` the link's angular
    velocity and acceleration (rad/s, rad/s^2, counter-clockwise positive); ``angle``
    the rotation of the link from its drawn pose (radians). The fields may as well be
    arrays, one value per step of a sweep (``chaingraph.dynamics`` holds them so)."""

    link: str
    point: tuple[float, float]
    angle: float
    velocity: tuple[float, float]
    omega: float
    acceleration: tuple[float, float]
    alpha: float

    @cached_property
    def turn(self) -> tuple[float, float]:
        """(cos, sin) of ``angle``, worked out once (a sweep's are arrays)."""
        c, s = np.cos(self.angle), np.sin(self.angle)
        if not isinstance(self.angle, np.ndarray):
            c, s = float(c), float(s)
        return c, s

    def moved(self, offset: tuple[float, float]) -> tuple[float, float]:
        """Where the link's point is now that was drawn at ``offset`` from where
        ``point`` was drawn: point + R(angle) offset."""
        r = turn_by((0.0, 0.0, self.angle, *self.turn), offset)
        return (self.point[0] + r[0], self.point[1] + r[1])

    def velocity_at(self, p: tuple[float, float]) -> tuple[float, float]:
        """Velocity of the link's point now at ``p``: v_O + omega k x (p - O)."""
        r = (p[0] - self.point[0], p[1] - self.point[1])
        return (self.velocity[0] - self.omega * r[1], self.velocity[1] + self.omega * r[0])

    def acceleration_at(self, p: tuple[float, float]) -> tuple[float, float]:
        """Acceleration of the link's point now at ``p``:
        a_O + alpha k x (p - O) - omega^2 (p - O)."""
        r = (p[0] - self.point[0], p[1] - self.point[1])
        w2 = self.omega * self.omega
        return (self.acceleration[0] - self.alpha * r[1] - w2 * r[0],
                self.acceleration[1] + self.alpha * r[0] - w2 * r[1])


@dataclass(frozen=True)
class Slide:
    """A P joint at the instant: ``at`` the block's reference point, ``axis`` the unit
    vector of the sliding line (turned with the guide), ``speed`` and ``acceleration``
    the block's slide along it relative to the guide (the CSV's ``v:S`` and ``a:S``),
    ``slide`` its slide from the drawn pose (``s:S``)."""

    joint: str
    guide: str
    block: str
    at: tuple
    axis: tuple
    speed: float
    acceleration: float
    slide: float = 0.0


@dataclass(frozen=True, eq=False)
class PoseMotion:
    """A mechanism solved at one input value (a result: numbers, no drawing).

    Attributes
    ----------
    name, fixed, units : str
    input : float
        The lead input's value (degrees for a driver or an R input, slide for a P one).
    inputs : dict
        Each input joint's value, when the mechanism is given by inputs (else empty).
    driver : str or None
    omega : float
        The lead input's speed.
    links : dict
        link -> :class:`LinkState` (the fixed link's all zeros).
    positions : dict
        joint or point id -> (x, y); a P joint's is its block's reference point.
    slides : dict
        P joint id -> :class:`Slide`.
    finite_rates : bool
        False at a dead centre, where the inputs do not determine the rates (NaN).
    chain, plan
        The chain solved and its solve plan.
    states : LinkStates
        The solver's own poses and rates (at ``omega``), from which the rest follows
        (and the forces are solved).
    """

    name: str
    fixed: str
    driver: str | None
    input: float
    inputs: dict
    omega: float
    units: str | None
    links: dict[str, LinkState]
    positions: dict[str, tuple[float, float]]
    slides: dict[str, Slide]
    finite_rates: bool
    chain: Chain
    plan: Plan
    states: LinkStates | None = field(default=None, repr=False)

    def input_text(self, symbol: str = "theta", unit: str = " degrees") -> str:
        """The input's value in words: "theta = 60 degrees", or each input's
        "A = 80, E = 100"."""
        if self.inputs:
            return ", ".join(f"{j} = {v:.6g}" for j, v in self.inputs.items())
        return f"{symbol} = {self.input:.6g}{unit}"

    @property
    def speed_text(self) -> str:
        """The input's speed in words: "crank at 10 rad/s", "S at 5 mm/s"."""
        lead = self.plan.inputs[self.plan.lead]
        unit = "rad/s" if lead.kind == "R" else f"{self.units or 'length units'}/s"
        who = self.driver if self.driver and not self.inputs else lead.joint
        return f"{who} at {self.omega:g} {unit}"

    def link_of(self, name: str) -> str:
        """The link whose motion a joint's or point's CSV columns follow."""
        chain = self.chain
        if name in {j.id for j in chain.joints}:
            return reference_link(chain.joint(name), self.fixed, chain=chain)
        return chain.point(name).link

    def velocity(self, name: str) -> tuple[float, float]:
        """A joint's or point's velocity (the solver's)."""
        return self.links[self.link_of(name)].velocity_at(self.positions[name])

    def acceleration(self, name: str) -> tuple[float, float]:
        """A joint's or point's acceleration (the solver's)."""
        return self.links[self.link_of(name)].acceleration_at(self.positions[name])


class AtOneValue:
    """What the results at one input value share: they keep their solved ``state``."""

    state: PoseMotion

    @property
    def name(self) -> str:
        """The mechanism's name."""
        return self.state.name

    @property
    def input(self) -> float:
        """The lead input's value."""
        return self.state.input


def _first(value) -> float:
    """The one step's value of a column (an array of one, or a constant)."""
    return float(np.asarray(value).reshape(-1)[0])


def pose_motion(chain: Chain, *, at: float | Sequence[float] | None = None,
                fixed: str | None = None, driver: str | None = None,
                inputs: InputsGiven = None, omega: float | None = None) -> PoseMotion:
    """Solve a mechanism at one input value, keeping every link's motion.

    Parameters
    ----------
    chain : Chain
        A chain with a drawn pose and a mechanism (or ``fixed`` and ``driver``/``inputs``).
    at : float or sequence of float, optional
        The input value: the driver's angle (degrees, as ``solve``'s ``theta``), or
        the lead input's value; with several inputs either the lead's value (the others
        where the sweep puts them) or one value per input. By default the drawn pose.
    fixed, driver, inputs, omega
        As for :func:`chaingraph.solve`. With several inputs, they move at the rates
        of their sweeps (the lead at ``omega``); an input without a sweep is held.

    Raises
    ------
    MechanismError
        No mechanism, no pose, or a bad input value (exit status 2).
    AssemblyError
        An input value outside the range that can be assembled (exit status 1): the
        message gives the range.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> shaper = chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))
    >>> state = pose_motion(shaper, at=90.0)
    >>> round(state.links["slotted lever"].omega, 6)      # 120 mm/s across AB = 420 mm
    0.285714
    """
    drive = pose_drive(chain, at=at, fixed=fixed, driver=driver, inputs=inputs,
                       omega=omega)
    plan, omega = drive.plan, float(drive.omega)
    theta = np.array([drive.tau])
    ev = _assembled(drive, theta, chain.source or chain.name)
    check_poses(plan, ev.pose, ev.feasible, constraints=closure_checks(plan))
    vel, acc, _ = rates(plan, ev.pose, omega, 1, measure=False)
    states = LinkStates(theta, ev.pose, vel, acc, speed=omega)
    now = Trajectories.of_states(plan, states)
    ox, oy = plan.origin
    links = {}
    for link in chain.links:
        x, y, phi = (_first(c) for c in ev.pose[link][:3])
        v = [_first(c) for c in vel[link]]
        a = [_first(c) for c in acc[link]]
        links[link] = LinkState(link, (x + ox, y + oy), phi, (v[0], v[1]), v[2],
                                (a[0], a[1]), a[2])
    positions = {name: (_first(p.x), _first(p.y))
                 for name, p in (*now.joints.items(), *now.points.items())}
    slides = {}
    for j in chain.joints:
        if j.kind == "P":                         # the solver's slide rates (the CSV's)
            guide, block = j.links
            axis = math.radians(j.axis or 0.0)    # (a P joint's is always given)
            x, y, phi, c, sin = map(_first, ev.pose[guide])
            ux, uy = turn_by((x, y, phi, c, sin), (math.cos(axis), math.sin(axis)))
            s = now.slides[j.id]
            slides[j.id] = Slide(j.id, guide, block, positions[j.id], (float(ux), float(uy)),
                                 _first(s.v), _first(s.a), _first(s.s))
    finite = all(math.isfinite(c) for m in links.values()
                 for c in (*m.velocity, m.omega, *m.acceleration, m.alpha))
    return PoseMotion(name=chain.name, fixed=plan.fixed, driver=plan.driver,
                      input=_first(now.theta),
                      inputs={k: _first(v) for k, v in now.values.items()},
                      omega=omega, units=chain.units, links=links, positions=positions,
                      slides=slides, finite_rates=finite, chain=chain, plan=plan,
                      states=states)


def _assembled(drive: Drive, theta, name):
    """The pose at the path parameters ``theta`` (one), or the range it leaves."""
    plan = drive.plan
    try:
        return evaluate_near(plan, theta)
    except AssemblyError as e:
        rng = e.feasible_range
        if rng is None:
            raise
        value = _first(plan.value(theta))
        verb = "turn" if plan.inputs[plan.lead].kind == "R" else "slide"
        raise AssemblyError(
            f"the input value {value:g} {plan.lead_unit} cannot be assembled: "
            f"{plan.describe()} can {verb} only from {rng[0]:.6f} to {rng[1]:.6f} "
            f"{plan.lead_unit}", mechanism=name, feasible_range=rng) from None
