"""Dimensional synthesis of quick return drives: from a time ratio and a stroke to sizes.

Crank and slotted lever (the shaper's drive), the ram's line through the extreme
positions of the lever's end: the lever's extremes are tangent to the crank circle, so
with the return angle ``a = 360 / (R + 1)`` (the time ratio R = (360 - a) / a), the
centre distance is ``crank / cos(a / 2)`` and the stroke ``2 lever cos(a / 2)``.

Whitworth (the slotter's drive), the ram's line through the lever's pivot: the ram is at
its extremes when the lever lies along that line, so the block is on it too, and with the
return angle ``b = 360 / (R + 1)`` the centre distance is ``crank cos(b / 2)``; the
stroke is twice the lever arm.

Each design also returns a complete six-link mechanism (frame, crank, block, lever,
connecting link, ram) that :func:`chaingraph.solve` reproduces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from chaingraph.errors import DesignError
from chaingraph.model.chain import Chain, Joint, Mechanism
from chaingraph.model.values import LARGEST

__all__ = ["Design", "slotted_lever", "whitworth", "KINDS"]


@dataclass(frozen=True)
class Design:
    """A designed drive: its dimensions and the mechanism built from them."""

    kind: str
    time_ratio: float
    crank: float
    stroke: float
    centre_distance: float
    forward_deg: float
    return_deg: float
    lever: float | None = None          # slotted lever: pivot to the lever's end
    lever_arm: float | None = None      # Whitworth: pivot to the connecting rod's pin
    link: float = 0.0                   # lever end to ram (the connecting link or rod)
    mechanism: Chain = field(kw_only=True)   # the mechanism built from the dimensions

    def to_dict(self) -> dict:
        d = {"kind": self.kind, "time_ratio": self.time_ratio, "crank": self.crank,
             "stroke": self.stroke, "centre_distance": self.centre_distance}
        if self.lever is not None:
            d["lever"] = self.lever
        if self.lever_arm is not None:
            d["lever_arm"] = self.lever_arm
        d.update(link=self.link, forward_deg=self.forward_deg, return_deg=self.return_deg)
        return d


def _check(kind, time_ratio, crank, stroke):
    for name, value in (("time_ratio", time_ratio), ("crank", crank), ("stroke", stroke)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise DesignError(f"{name} must be a finite number, got {value!r}", kind=kind,
                              parameter=name)
        if abs(value) > LARGEST:
            raise DesignError(f"{name} {value:g} is too large: at most {LARGEST:g} (larger "
                              "values overflow)", kind=kind, parameter=name)
    if time_ratio <= 1:
        raise DesignError(f"the time ratio must be above 1 (the forward stroke is the slower "
                          f"one), got {time_ratio:g}", kind=kind, parameter="time_ratio")
    for name, value in (("crank", crank), ("stroke", stroke)):
        if value <= 0:
            raise DesignError(f"{name} must be a positive length, got {value:g}", kind=kind,
                              parameter=name)


def _angles(time_ratio):
    back = 360.0 / (time_ratio + 1.0)
    return 360.0 - back, back


def _joint(joint_id, kind, links, at, axis=None):
    return Joint(joint_id, kind, tuple(links), at=(float(at[0]), float(at[1])),
                 axis=None if axis is None else float(axis))


def _drive(name, centre, pin, slot_axis, pivot, lever_end, link, ram, units, notes):
    """The six-link quick return drive: crank about ``centre``; a block on the crank pin
    ``pin`` (id, position) slides in the slotted lever (slot along ``slot_axis``), which
    turns about ``pivot`` (id, position); the lever's end drives the ram along x through
    ``link``."""
    (pin_id, pin_at), (pivot_id, pivot_at) = pin, pivot
    return Chain(name, (
        _joint("C", "R", ["frame", "crank"], centre),
        _joint(pin_id, "R", ["crank", "block"], pin_at),
        _joint("S", "P", ["slotted lever", "block"], pin_at, slot_axis),
        _joint(pivot_id, "R", ["slotted lever", "frame"], pivot_at),
        _joint("P", "R", ["slotted lever", link], lever_end),
        _joint("R", "R", [link, "ram"], ram), _joint("G", "P", ["frame", "ram"], ram, 0.0)),
        family="six-link quick return mechanism", units=units, notes=notes,
        mechanism=Mechanism("frame", "crank", 1.0, "ram"))


def slotted_lever(*, time_ratio: float, crank: float, stroke: float,
                  units: str = "mm") -> Design:
    """Design a crank and slotted lever quick return drive.

    Parameters
    ----------
    time_ratio : float
        Forward (working) over return crank rotation, above 1.
    crank : float
        Crank radius.
    stroke : float
        Stroke of the ram, whose line passes through the lever end's extreme positions.

    Returns
    -------
    Design
        ``centre_distance`` (crank centre to lever pivot), ``lever`` (pivot to the
        lever's end), the crank angles, and the mechanism.

    Raises
    ------
    DesignError
        For a time ratio not above 1, a length not positive, or a stroke too short for
        the crank and ratio (the block would run off the lever's end).

    Examples
    --------
    The textbook's worked example (crank 30 mm, time ratio 1.7, stroke 120 mm):

    >>> d = slotted_lever(time_ratio=1.7, crank=30, stroke=120)
    >>> round(d.centre_distance, 1), round(d.lever, 1), round(d.return_deg, 2)
    (75.7, 151.5, 133.33)
    """
    kind = "slotted-lever"
    _check(kind, time_ratio, crank, stroke)
    forward, back = _angles(time_ratio)
    half = math.radians(back / 2)
    centres = crank / math.cos(half)
    lever = stroke / (2 * math.cos(half))
    reach = centres + crank
    if lever <= reach:
        raise DesignError(
            f"no crank and slotted lever can meet this: a stroke of {stroke:g} with a crank of "
            f"{crank:g} at time ratio {time_ratio:g} needs a lever of {lever:.6g}, but the "
            f"block on the crank pin reaches {reach:.6g} from the lever's pivot (centre "
            f"distance {centres:.6g} plus the crank), so it would run off the lever's end; "
            f"ask for a stroke above {2 * reach * math.cos(half):.6g}", kind=kind,
            parameter="stroke")
    # the drawing: lever pivot A at the origin, crank centre C above it, crank along +x
    A, C = (0.0, 0.0), (0.0, centres)
    B = (crank, centres)
    unit = (B[0] / math.hypot(*B), B[1] / math.hypot(*B))
    P = (lever * unit[0], lever * unit[1])
    y_ram = lever * math.sin(half)                 # through the lever end's extremes
    link = max(0.25 * lever, 1.5 * (lever - y_ram))
    R = (P[0] + math.sqrt(link ** 2 - (y_ram - P[1]) ** 2), y_ram)
    axis = math.degrees(math.atan2(unit[1], unit[0]))
    mech = _drive(
        f"Crank and slotted lever: time ratio {time_ratio:g}, stroke {stroke:g}",
        C, ("B", B), axis, ("A", A), P, "link", R, units,
        notes=f"Designed by chaingraph: crank {crank:g}, centre distance {centres:.6g}, slotted "
              f"lever {lever:.6g}, link {link:.6g}; the ram's line passes through the extreme "
              f"positions of the lever's end, so the stroke is {stroke:g} and the time ratio "
              f"{time_ratio:g} (crank turns {forward:.6g} forward, {back:.6g} back).")
    return Design(kind=kind, time_ratio=time_ratio, crank=crank, stroke=stroke,
                  centre_distance=centres, forward_deg=forward, return_deg=back, lever=lever,
                  link=link, mechanism=mech)


def whitworth(*, time_ratio: float, crank: float, stroke: float,
              units: str = "mm") -> Design:
    """Design a Whitworth quick return drive (the ram's line through the lever's pivot).

    Returns
    -------
    Design
        ``centre_distance`` (crank centre to lever pivot), ``lever_arm`` (pivot to the
        connecting rod's pin: half the stroke), the crank angles, and the mechanism.

    Examples
    --------
    The textbook's assignment (stroke 150 mm, crank 40 mm, time ratio 2):

    >>> d = whitworth(time_ratio=2, crank=40, stroke=150)
    >>> round(d.centre_distance, 6), d.lever_arm, d.forward_deg, d.return_deg
    (20.0, 75.0, 240.0, 120.0)
    """
    kind = "whitworth"
    _check(kind, time_ratio, crank, stroke)
    forward, back = _angles(time_ratio)
    centres = crank * math.cos(math.radians(back / 2))
    arm = stroke / 2
    rod = 2 * arm
    # the drawing: lever pivot D at the origin, crank centre C below it, crank upright
    D, C = (0.0, 0.0), (0.0, -centres)
    A = (0.0, crank - centres)
    P = (0.0, -arm)
    R = (math.sqrt(rod ** 2 - arm ** 2), 0.0)
    mech = _drive(
        f"Whitworth drive: time ratio {time_ratio:g}, stroke {stroke:g}",
        C, ("A", A), 90.0, ("D", D), P, "connecting rod", R, units,
        notes=f"Designed by chaingraph: crank {crank:g}, centre distance {centres:.6g}, lever "
              f"arm {arm:.6g}, connecting rod {rod:.6g}; the ram's line passes through the "
              f"lever's pivot, so the stroke is twice the arm, {stroke:g}, and the time ratio "
              f"{time_ratio:g} (crank turns {forward:.6g} forward, {back:.6g} back).")
    return Design(kind=kind, time_ratio=time_ratio, crank=crank, stroke=stroke,
                  centre_distance=centres, forward_deg=forward, return_deg=back,
                  lever_arm=arm, link=rod, mechanism=mech)


KINDS = {"slotted-lever": slotted_lever, "whitworth": whitworth}
