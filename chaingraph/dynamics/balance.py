"""Balance: counterweights that cancel the shaking force of a four-bar, or the primary
force of a slider crank, checked by solving the balanced mechanism again.

**Four-bar** (the method of linearly independent vectors, Berkof and Lowen): with the
crank O2-A, coupler A-B and rocker O4-B drawn as the complex vectors a, b, c (their
rotations from the drawn pose e2, e3, e4), and each link's centre of mass as an offset
g2 from O2, g3 from A, g4 from O4, the mass centre of the moving links is

    M G = const + (m2 g2 + m3 a) e2 + m3 g3 e3 + m4 g4 e4,

and the loop a e2 + b e3 - c e4 = O4 - O2 gives e3 in terms of e2 and e4, independent
as the mechanism moves. M G stands still (no shaking force at any speed) when both
coefficients vanish: the crank needs the mass times radius -(m2 g2 + m3 a (1 - g3/b))
and the rocker -(m4 g4 + m3 g3 c/b), each a complex number (size: kg times length, and
angle in the drawn pose).

**Slider crank**: the rod's centre G3 = (1 - l) A + l B with l = g3/b, so the rotating
masses are the crank's and (1 - l) of the rod's (at the crank pin), and the
reciprocating mass m_r = m4 + l m3 moves with the block. A counterweight against the
rotating masses and the ``fraction`` of m_r at the crank pin cancels the primary force
along the line of stroke (a fraction 1) and leaves the secondary force (the harmonics
of 2 theta and up) along it, and the counterweight's own primary force across it.

Each counterweight is placed at the radius of its link (the crank's or the rocker's
length) and added to the link's mass as a point mass (moving its centre and adding to
its inertia), and the mechanism is solved again over the same sweep: what remains is
that solve's shaking force and moment from inertia (the weights and the loads, which
no counterweight changes, left out).
"""

from __future__ import annotations

import cmath
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from chaingraph._util.numbers import tidy
from chaingraph.dynamics.reactions import SweepForces, forces, length_metres
from chaingraph.dynamics.shaking import Shaking, largest_size, shaking
from chaingraph.errors import MechanismError
from chaingraph.model.chain import Chain, LinkMass, mass_centre

__all__ = ["Counterweight", "Balance", "balance", "counterweights"]


@dataclass(frozen=True)
class Counterweight:
    """A counterweight on ``link``: ``mass`` (kg) centred at ``at`` (the drawn pose,
    file units), at ``radius`` (file units) from the link's pivot on the frame;
    ``mass_radius`` their product (kg times file units) and ``angle`` its direction in
    the drawn pose (degrees)."""

    link: str
    mass: float
    at: tuple[float, float]
    radius: float
    mass_radius: float
    angle: float

    def to_dict(self) -> dict:
        return {"link": self.link, "mass": self.mass, "at": list(self.at),
                "radius": self.radius, "mass_radius": self.mass_radius, "angle": self.angle}


@dataclass(frozen=True, eq=False)
class Balance:
    """The balance of a mechanism (:func:`balance`): its ``kind`` ("four-bar" or
    "slider crank"), the ``counterweights``, the balanced ``chain``, the shaking from
    inertia ``before`` and ``after`` (the balanced mechanism solved again over the same
    sweep), and for a slider crank the ``secondary`` force that remains along the line
    of stroke and the ``transverse`` force across it (largest, N)."""

    kind: str
    counterweights: tuple[Counterweight, ...]
    chain: Chain
    before: Shaking
    after: Shaking
    result: SweepForces
    secondary: float | None = None
    transverse: float | None = None
    notes: tuple[str, ...] = ()

    @property
    def remaining(self) -> tuple[float | None, float | None]:
        """The largest shaking force (N) and moment (N m) left by the counterweights
        (tidied at the scale of the unbalanced ones: rounding shows as 0)."""
        force, moment = self.after.largest()
        f0, m0 = self.before.largest()
        return (tidy(force, max(f0 or 0.0, force or 0.0)),
                tidy(moment, max(m0 or 0.0, moment or 0.0)))

    def to_dict(self) -> dict:
        """The ``"balance"`` of ``chaingraph forces --balance --json``."""
        force, moment = self.remaining
        f0, m0 = self.before.largest()
        remaining: dict[str, float | None] = {"force": force, "moment": moment}
        if self.kind == "slider crank":
            remaining.update(secondary=self.secondary, transverse=self.transverse)
        out: dict[str, Any] = {"kind": self.kind,
               "counterweights": [c.to_dict() for c in self.counterweights],
               "remaining": remaining, "unbalanced": {"force": f0, "moment": m0}}
        out["notes"] = list(self.notes)
        return out

    def rows(self) -> list[tuple[str, str]]:
        """(what, value) rows for the text output."""
        out = []
        for c in self.counterweights:
            out.append((f"counterweight on {c.link}",
                        f"{c.mass:.6g} kg at ({c.at[0]:.6g}, {c.at[1]:.6g}), radius "
                        f"{c.radius:.6g}, angle {c.angle:.6g} deg"))
        f0, m0 = self.before.largest()
        f1, m1 = self.remaining

        def num(v, unit):
            return "-" if v is None else f"{v:.6g} {unit}"
        out.append(("shaking force from inertia", f"{num(f0, 'N')} before, "
                                                  f"{num(f1, 'N')} after"))
        out.append(("shaking moment from inertia", f"{num(m0, 'N m')} before, "
                                                   f"{num(m1, 'N m')} after"))
        if self.kind == "slider crank":
            out.append(("remaining along the stroke (secondary)", num(self.secondary, "N")))
            out.append(("remaining across the stroke", num(self.transverse, "N")))
        return out


def _z(p) -> complex:
    return complex(p[0], p[1])


def _mass(chain: Chain, link: str) -> tuple[float, complex]:
    m = next((x for x in chain.masses if x.link == link), None)
    if m is None:
        return 0.0, 0j
    return m.mass, _z(mass_centre(chain, m))


def _shape(chain: Chain, fixed: str, crank: str):
    """("four-bar" or "slider crank", the crank's pivot, A, B, the coupler, the
    rocker or block, and the block's P joint), or a MechanismError."""
    name = chain.source or chain.name
    joints = chain.joints
    if len(chain.links) != 4 or len(joints) != 4 or any(len(j.links) != 2 for j in joints):
        raise MechanismError("balance is for a four-bar or a slider crank (four links, "
                             "four joints)", mechanism=name)
    pivot = next((j for j in joints if set(j.links) == {fixed, crank} and j.kind == "R"), None)
    if pivot is None:
        raise MechanismError("balance needs the input to be a crank turning on the frame",
                             mechanism=name)
    a = next(j for j in joints if crank in j.links and j is not pivot)
    coupler = next(x for x in a.links if x != crank)
    b = next(j for j in joints if coupler in j.links and j is not a)
    last = next(x for x in b.links if x != coupler)
    ground = next(j for j in joints if j not in (pivot, a, b))
    kinds = "".join(j.kind for j in (a, b, ground))
    if fixed in (coupler, last) or set(ground.links) != {fixed, last} or \
            kinds not in ("RRR", "RRP"):
        raise MechanismError("balance is for a four-bar (four R joints) or a slider crank "
                             "(its block sliding on the frame)", mechanism=name)
    kind = "four-bar" if kinds == "RRR" else "slider crank"
    return kind, pivot, a, b, coupler, last, ground


def counterweights(chain: Chain, *, fixed: str, crank: str, fraction: float = 1.0
                   ) -> tuple[str, list[tuple[str, complex, complex, float]], complex]:
    """The counterweights' mass times offset (complex, kg times file units, the drawn
    pose) of a four-bar or slider crank whose ``crank`` turns on ``fixed``: (kind,
    [(link, pivot, mass times offset, radius)], the block's axis as a unit complex, or
    0 for a four-bar). ``fraction``: of a slider crank's reciprocating mass."""
    kind, pivot, ja, jb, coupler, last, ground = _shape(chain, fixed, crank)
    p2, a0, b0 = _z(pivot.at), _z(ja.at), _z(jb.at)
    m2, c2 = _mass(chain, crank)
    m3, c3 = _mass(chain, coupler)
    m4, c4 = _mass(chain, last)
    a, b, g2, g3 = a0 - p2, b0 - a0, c2 - p2, c3 - a0
    if abs(b) == 0 or abs(a) == 0:
        raise MechanismError("balance needs a crank and a coupler of non-zero length",
                             mechanism=chain.source or chain.name)
    if kind == "four-bar":
        p4 = _z(ground.at)
        c, g4 = b0 - p4, c4 - p4
        need2 = -(m2 * g2 + m3 * a * (1 - g3 / b))
        need4 = -(m4 * g4 + m3 * g3 * c / b)
        return kind, [(crank, p2, need2, abs(a)), (last, p4, need4, abs(c))], 0j
    lam = g3 / b
    reciprocating = m4 + m3 * lam
    need2 = -(m2 * g2 + m3 * (1 - lam) * a) - fraction * reciprocating * a
    # the block does not turn: its guide's axis is the same in either link's frame
    return kind, [(crank, p2, need2, abs(a))], cmath.exp(1j * np.radians(ground.axis))


def _with_counterweight(chain: Chain, link: str, mass: float, at: complex) -> Chain:
    """``chain`` with a point mass ``mass`` at ``at`` added to ``link``'s mass."""
    old = next((x for x in chain.masses if x.link == link), None)
    if old is None:
        new = LinkMass(link, mass, (at.real, at.imag), 0.0)
        return replace(chain, masses=chain.masses + (new,))
    m0, g0 = old.mass, _z(mass_centre(chain, old))
    total = m0 + mass
    g = (m0 * g0 + mass * at) / total
    metres = length_metres(chain)
    inertia = old.inertia + (m0 * abs(g0 - g) ** 2 + mass * abs(at - g) ** 2) * metres ** 2
    new = LinkMass(link, total, (g.real, g.imag), inertia)
    return replace(chain, masses=tuple(new if x is old else x for x in chain.masses))


def balance(result: SweepForces, *, fraction: float = 1.0) -> Balance:
    """The counterweights that balance the mechanism of a sweep of forces, checked by
    solving the balanced mechanism again over the same sweep.

    Parameters
    ----------
    result : SweepForces
        A sweep of :func:`~chaingraph.dynamics.forces` of a four-bar or slider crank
        driven by its crank on the frame.
    fraction : float
        The share of a slider crank's reciprocating mass balanced at the crank pin
        (1: the whole primary force along the line of stroke).

    Returns
    -------
    Balance

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.dynamics.balance import balance
    >>> from chaingraph.naming.catalog import catalog_path
    >>> engine = chaingraph.load(catalog_path("reciprocating-engine"))
    >>> b = balance(chaingraph.forces(engine, steps=36, omega=100.0))
    >>> b.kind, [c.link for c in b.counterweights]
    ('slider crank', ['crank'])
    """
    if not (isinstance(fraction, (int, float)) and 0.0 <= fraction <= 1.0):
        raise MechanismError(f"the balanced fraction must be between 0 and 1, got {fraction!r}",
                             mechanism=result.chain.source or result.chain.name,
                             parameter="fraction")
    chain, motion = result.chain, result.motion
    plan = motion.plan
    name = chain.source or chain.name
    if len(plan.inputs) != 1 or plan.inputs[0].kind != "R" or plan.inputs[0].a != plan.fixed:
        raise MechanismError("balance needs one input, a crank turning on the frame",
                             mechanism=name)
    item = plan.inputs[0]
    kind, need, axis = counterweights(chain, fixed=plan.fixed, crank=item.b,
                                      fraction=fraction)
    balanced, weights = chain, []
    for link, pivot, mr, radius in need:
        if abs(mr) <= 1e-12 * max(radius, 1e-300) * max(
                [m.mass for m in chain.masses] + [1e-300]):
            continue                                   # already balanced
        mass = abs(mr) / radius
        at = pivot + mr / mass
        weights.append(Counterweight(link, float(mass), (at.real, at.imag), float(radius),
                                     float(abs(mr)), float(np.degrees(cmath.phase(mr)))))
        balanced = _with_counterweight(balanced, link, mass, at)
    theta = np.asarray(motion.theta, dtype=float)
    again = forces(balanced, fixed=plan.fixed, inputs=[(item.joint, float(theta[0]),
                                                        float(theta[-1]))],
                   steps=result.steps, omega=motion.omega, static=result.static)
    metres = length_metres(chain)
    n = result.steps + 1
    before = shaking(result.solution, n, origin=plan.origin, metres=metres, inertia_only=True)
    after = shaking(again.solution, n, origin=again.motion.plan.origin, metres=metres, inertia_only=True)
    notes = ["the shaking from inertia only: weights and loads, which no counterweight "
             "changes, are left out", "each counterweight is a point mass at its link's "
             "radius (its own inertia left out)"]
    secondary = transverse = None
    if kind == "slider crank":
        along = after.fx * axis.real + after.fy * axis.imag
        across = -after.fx * axis.imag + after.fy * axis.real
        secondary = largest_size(along)
        transverse = largest_size(across)
        if fraction:
            notes.append("the counterweight's primary force across the line of stroke "
                         "remains (balance a fraction of the reciprocating mass to share it)")
    return Balance(kind, tuple(weights), balanced, before, after, again, secondary,
                   transverse, tuple(notes))
