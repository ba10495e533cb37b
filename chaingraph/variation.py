"""Behaviour over the dimensions: a mechanism solved once per value of one link's length.

:func:`vary` takes the mechanism by its lengths, as ``chaingraph measure`` writes it
(:func:`~chaingraph.kinematics.assembly.measured_document`: every link's lengths, every
sliding line, the input's value and every assembly mode),
changes the one length, assembles it again in the same modes and solves it, row by row;
a value where it cannot be assembled or solved is a row that says why.
:func:`length_values` is the range FROM, FROM + STEP, ... up to TO.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable
import math
from dataclasses import dataclass

from chaingraph.errors import ChainGraphError, MechanismError
from chaingraph.files import from_document
from chaingraph.kinematics import Summary, measured_document, solve
from chaingraph.model.chain import Chain

__all__ = ["VariationRow", "Variation", "length_values", "vary"]

#: the most values one variation solves
MAX_VALUES = 10_000


@dataclass(frozen=True)
class VariationRow:
    """One value of the length: the motion's ``summary`` there (a
    :class:`~chaingraph.kinematics.summary.Summary`), or ``error``, why there is none."""

    value: float
    summary: Summary | None = None
    error: str | None = None

    def to_dict(self) -> dict:
        return {"value": self.value,
                "summary": None if self.summary is None else self.summary.to_dict(),
                "error": self.error}


@dataclass(frozen=True)
class Variation:
    """A mechanism's summary for each value of one link's length (``chaingraph vary``)."""

    name: str
    link: str
    units: str | None
    rows: tuple[VariationRow, ...]

    def to_dict(self) -> dict:
        """The JSON of ``chaingraph vary --json``."""
        return {"name": self.name, "link": self.link,
                "rows": [r.to_dict() for r in self.rows]}

    def table(self) -> list[tuple]:
        """One row per value: (value, time ratio, stroke, transmission angle, input
        range), or the value and why it has none."""
        out = []
        for r in self.rows:
            if r.summary is None:
                out.append((f"{r.value:g}", "-", "-", "-", r.error or "-"))
                continue
            s = r.summary
            ta = s.transmission_angle
            stroke = "-" if s.stroke is None else f"{s.stroke:.6g} {s.stroke_unit or ''}".strip()
            ratio = "-" if s.time_ratio is None else f"{s.time_ratio:.6g}"
            angle = "-" if ta is None else f"{ta[0]:.4g} to {ta[1]:.4g}"
            span = ("without limits" if None in s.input_range else
                    "full turn" if s.full_turn else
                    f"{s.input_range[0]:.6g} to {s.input_range[1]:.6g}")
            out.append((f"{r.value:g}", ratio, stroke, angle, span))
        return out


def length_values(start: float, stop: float, step: float) -> tuple[float, ...]:
    """FROM, FROM + STEP, ... up to TO (TO included when the steps reach it to within
    1e-9 of a step).

    Examples
    --------
    >>> length_values(30, 120, 30)
    (30.0, 60.0, 90.0, 120.0)
    >>> length_values(120, 30, -45)
    (120.0, 75.0, 30.0)
    """
    for name, v in (("from", start), ("to", stop), ("step", step)):
        if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
            raise MechanismError(f"the length's {name} must be a finite number, got {v!r}",
                                 parameter="length")
    if step == 0:
        raise MechanismError("the length's step must not be 0", parameter="length")
    count = math.floor((stop - start) / step + 1e-9) + 1
    if count < 1:
        raise MechanismError(f"the range {start:g}:{stop:g}:{step:g} has no values (a step "
                             f"of {step:g} never goes from {start:g} to {stop:g})",
                             parameter="length")
    if count > MAX_VALUES:
        raise MechanismError(f"the range {start:g}:{stop:g}:{step:g} has {count} values, "
                             f"more than {MAX_VALUES}", parameter="length")
    return tuple(float(start + k * step) for k in range(count))


def vary(mechanism: Chain, link: str, values: Iterable[float], *, steps: int = 360,
         output: str | None = None) -> Variation:
    """The mechanism's summary for each value of ``link``'s length.

    Parameters
    ----------
    mechanism : Chain
        A mechanism with a drawn pose (coordinates or lengths).
    link : str
        A moving link whose dimensions are one length (a binary link; for a link that
        carries a slot, its arm to its pin).
    values : iterable of float
        Its lengths, in the file's units (see :func:`length_values`).
    steps, output
        As for :func:`chaingraph.solve`.

    Examples
    --------
    The lecture's slotted lever: with 300 mm between the centres, the time ratio falls
    towards 1 as the crank shortens.

    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> lever = chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))
    >>> v = vary(lever, "crank", [120, 90, 60, 30])
    >>> [round(r.summary.time_ratio, 3) for r in v.rows]
    [1.71, 1.481, 1.294, 1.136]
    """
    name = mechanism.source or mechanism.name
    if link not in mechanism.links:
        raise MechanismError(f"{link!r} is no link of the chain (links: "
                             f"{', '.join(mechanism.links)})", mechanism=name,
                             parameter="length")
    values = tuple(float(v) for v in values)
    if not values:
        raise MechanismError("no lengths to try", mechanism=name, parameter="length")
    doc = measured_document(mechanism)
    lengths = doc.get("lengths", {})
    fixed = mechanism.mechanism.fixed if mechanism.mechanism else None
    if link == fixed:
        raise MechanismError(f"{link!r} is the fixed link: its dimensions are its pivots' "
                             "coordinates, not a length", mechanism=name, parameter="length")
    if link not in lengths:
        raise MechanismError(f"link {link!r} has no length of its own (its joints are "
                             "placed by the links around it, as a block on a pin is)",
                             mechanism=name, parameter="length")
    if not isinstance(lengths[link], (int, float)):
        parts = ", ".join(lengths[link])
        raise MechanismError(f"link {link!r} is not given by a single length but by "
                             f"{len(lengths[link])} ({parts}); vary changes one number",
                             mechanism=name, parameter="length")
    rows = []
    for value in values:
        if not value > 0:
            rows.append(VariationRow(value, None, "a length must be greater than 0"))
            continue
        trial = copy.deepcopy(doc)
        trial["lengths"][link] = value
        try:
            chain = from_document(trial, source=f"{name} with {link} = {value:g}")
            motion = solve(chain, steps=steps, output=output)
        except ChainGraphError as e:
            rows.append(VariationRow(value, None, getattr(e, "problem", None) or str(e)))
        else:
            rows.append(VariationRow(value, motion.summary, None))
    return Variation(mechanism.name, link, mechanism.units, tuple(rows))
