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
from dataclasses import dataclass

import numpy as np

from ..chain import Input
from ..errors import AssemblyError, MechanismError
from ..kinematics.equations import check_poses
from ..kinematics.geometry import rotate
from ..kinematics.motion import LARGEST_INPUT, _as_inputs, _plan
from ..kinematics.plan import chosen_inputs
from ..kinematics.rates import rates
from ..kinematics.sweep import _evaluate_near

__all__ = ["LinkMotion", "PoseMotion", "AtOneValue", "pose_motion"]


def perp(v):
    """The vector turned a quarter turn counter-clockwise (k x v)."""
    return (-v[1], v[0])


@dataclass(frozen=True)
class LinkMotion:
    """One link's planar rigid-body motion at an instant, in the drawing's frame.

    ``point`` is a reference point of the link (any: the link's frame origin), with
    its ``velocity`` and ``acceleration``; ``omega`` and ``alpha`` the link's angular
    velocity and acceleration (rad/s, rad/s^2, counter-clockwise positive); ``angle``
    the rotation of the link from its drawn pose (radians)."""

    link: str
    point: tuple
    angle: float
    velocity: tuple
    omega: float
    acceleration: tuple
    alpha: float

    def velocity_at(self, p):
        """Velocity of the link's point now at ``p``: v_O + omega k x (p - O)."""
        r = (p[0] - self.point[0], p[1] - self.point[1])
        return (self.velocity[0] - self.omega * r[1], self.velocity[1] + self.omega * r[0])

    def acceleration_at(self, p):
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
    the block's slide along it relative to the guide (the CSV's ``v:S`` and ``a:S``)."""

    joint: str
    guide: str
    block: str
    at: tuple
    axis: tuple
    speed: float
    acceleration: float


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
        link -> :class:`LinkMotion` (the fixed link's all zeros).
    positions : dict
        joint or point id -> (x, y); a P joint's is its block's reference point.
    slides : dict
        P joint id -> :class:`Slide`.
    finite_rates : bool
        False at a dead centre, where the inputs do not determine the rates (NaN).
    """

    name: str
    fixed: str
    driver: str | None
    input: float
    inputs: dict
    omega: float
    units: str | None
    links: dict
    positions: dict
    slides: dict
    finite_rates: bool
    chain: object
    plan: object

    @property
    def speed_text(self) -> str:
        """The input's speed in words: "crank at 10 rad/s", "S at 5 mm/s"."""
        lead = self.plan.inputs[self.plan.lead]
        unit = "rad/s" if lead.kind == "R" else f"{self.units or 'length units'}/s"
        who = self.driver if self.driver and not self.inputs else lead.joint
        return f"{who} at {self.omega:g} {unit}"

    def link_of(self, name):
        """The link whose motion a joint's or point's CSV columns follow."""
        chain = self.chain
        if name in chain._joint_index:
            j = chain.joint(name)
            if j.kind == "P":
                return j.block
            rank = {self.fixed: 0}
            return min(j.links, key=lambda x: rank.get(x, 1))
        return chain.point(name).link

    def velocity(self, name):
        """A joint's or point's velocity (the solver's)."""
        return self.links[self.link_of(name)].velocity_at(self.positions[name])

    def acceleration(self, name):
        """A joint's or point's acceleration (the solver's)."""
        return self.links[self.link_of(name)].acceleration_at(self.positions[name])


class AtOneValue:
    """What the results at one input value share: they keep their solved ``state``."""

    @property
    def name(self):
        """The mechanism's name."""
        return self.state.name

    @property
    def input(self):
        """The lead input's value."""
        return self.state.input


def _check_value(value, what, name):
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value):
        raise MechanismError(f"{what} must be a finite number, got {value!r}", mechanism=name)
    if abs(value) > LARGEST_INPUT:
        raise MechanismError(f"{what} {value:g} is too large: at most {LARGEST_INPUT:g} in "
                             "size", mechanism=name)


def pose_motion(chain, *, at=None, fixed=None, driver=None, inputs=None,
                omega=None) -> PoseMotion:
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
    >>> from chaingraph.catalog import catalog_path
    >>> shaper = chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))
    >>> state = pose_motion(shaper, at=90.0)
    >>> round(state.links["slotted lever"].omega, 6)      # 120 mm/s across AB = 420 mm
    0.285714
    """
    name = chain.source or chain.name
    if not chain.has_pose:
        raise MechanismError("the chain has no drawn pose (joint positions or lengths): "
                             "instant centres and polygons need its dimensions",
                             mechanism=name)
    values = None
    if at is not None:
        values = [at] if isinstance(at, (int, float)) else list(at)
        if not values:
            raise MechanismError("no input value given", mechanism=name)
        for v in values:
            _check_value(v, "the input value", name)
    if omega is not None:
        _check_value(omega, "the input speed omega", name)
    fixed, driver, items = chosen_inputs(chain, fixed, driver, _as_inputs(inputs, chain))
    if items:
        plan = _plan(chain, fixed, None, items)
        if values is not None and len(values) > 1 or at is None:
            plan = _plan(chain, fixed, None, _items_at(plan, values))
    else:
        if not driver and not fixed:
            raise MechanismError("the chain has no mechanism: name its fixed link and its "
                                 "driver or inputs ([mechanism])", mechanism=name)
        plan = _plan(chain, fixed, driver)
    if values is not None and len(values) != 1 and len(values) != len(plan.inputs):
        raise MechanismError(f"{len(values)} input values given for {len(plan.inputs)} "
                             f"inputs: give one per input, or the first input's alone",
                             mechanism=name)
    lead = plan.inputs[plan.lead]
    if values is None:
        tau = plan.tau(lead.value0) if plan.from_driver or lead.kind == "R" else \
            plan.tau(0.0)
    else:
        tau = plan.tau(values[plan.lead] if len(values) > 1 else values[0])
    if omega is None:
        omega = chain.mechanism.omega if chain.mechanism else 1.0
    theta = np.array([float(tau)])
    try:
        ev = _evaluate_near(plan, theta)
    except AssemblyError as e:
        rng = e.feasible_range
        if rng is None:
            raise
        value = float(np.asarray(plan.value(theta)).reshape(-1)[0])
        verb = "turn" if lead.kind == "R" else "slide"
        raise AssemblyError(
            f"the input value {value:g} {plan.lead_unit} cannot be assembled: "
            f"{plan.describe()} can {verb} only from {rng[0]:.6f} to {rng[1]:.6f} "
            f"{plan.lead_unit}", mechanism=chain.source or name, feasible_range=rng) from None
    check_poses(plan, ev.pose, ev.feasible)
    vel, acc, _ = rates(plan, ev.pose, float(omega), 1, measure=False)
    ox, oy = plan.origin
    links = {}
    for link in chain.links:
        e = ev.pose[link]
        x, y, phi = (float(np.asarray(e[k]).reshape(-1)[0]) for k in range(3))
        v = [float(np.asarray(c).reshape(-1)[0]) for c in vel[link]]
        a = [float(np.asarray(c).reshape(-1)[0]) for c in acc[link]]
        links[link] = LinkMotion(link, (x + ox, y + oy), phi, (v[0], v[1]), v[2],
                                 (a[0], a[1]), a[2])
    pose0 = {link: tuple(float(np.asarray(c).reshape(-1)[0]) for c in ev.pose[link])
             for link in chain.links}

    def world(link, p):
        if link == plan.fixed:                    # as drawn, to the last digit
            return (float(p[0]), float(p[1]))
        r = rotate(pose0[link], plan.local(p))
        return (r[0] + pose0[link][0] + ox, r[1] + pose0[link][1] + oy)
    positions = {}
    for j in chain.joints:
        on = j.block if j.kind == "P" else \
            (plan.fixed if plan.fixed in j.links else j.links[0])
        positions[j.id] = world(on, j.at)
    for p in chain.points:
        positions[p.id] = world(p.link, p.at)
    slides = {}
    for j in chain.joints:
        if j.kind != "P":
            continue
        g, b = j.guide, j.block
        u = rotate(pose0[g], (math.cos(math.radians(j.axis)), math.sin(math.radians(j.axis))))
        p = positions[j.id]
        lg, lb = links[g], links[b]
        dv = np.subtract(lb.velocity_at(p), lg.velocity_at(p))
        # the block's acceleration relative to the guide's coincident point, less the
        # Coriolis term 2 omega k x v_rel, is the slide's acceleration along the line
        da = np.subtract(lb.acceleration_at(p), lg.acceleration_at(p))
        coriolis = 2.0 * lg.omega * np.array(perp(dv))
        slides[j.id] = Slide(j.id, g, b, p, u, float(dv @ u), float((da - coriolis) @ u))
    inputs_now = {}
    if not plan.from_driver:
        for item, value in zip(plan.inputs, plan.values(theta)):
            inputs_now[item.joint] = float(np.asarray(value).reshape(-1)[0])
    finite = all(math.isfinite(c) for m in links.values()
                 for c in (*m.velocity, m.omega, *m.acceleration, m.alpha))
    return PoseMotion(name=chain.name, fixed=plan.fixed, driver=plan.driver,
                      input=float(np.asarray(plan.value(theta)).reshape(-1)[0]),
                      inputs=inputs_now, omega=float(omega), units=chain.units,
                      links=links, positions=positions, slides=slides,
                      finite_rates=finite, chain=chain, plan=plan)


def _items_at(plan, values):
    """Inputs that pass through ``values`` (one per input; None: the drawn pose), each
    moving at its sweep's rate (an input without a sweep is held)."""
    items = []
    for n, item in enumerate(plan.inputs):
        value = item.value0 if values is None else values[n]
        _, k = plan.line[n]
        extent = 0.0
        if k != 0 and item.sweep is not None:
            extent = item.sweep[1] - item.sweep[0]
        elif n == plan.lead:
            extent = 1.0
        items.append(Input(item.joint, float(value), float(value) + extent))
    return tuple(items)
