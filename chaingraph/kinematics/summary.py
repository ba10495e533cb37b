"""The summary of a motion over the mechanism's whole cycle: the output's stroke and
extremes, the time ratio, the transmission angle and the dead centres, each refined from
the sweep (not read off its grid).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from numpy.typing import ArrayLike

from chaingraph._util.numbers import tidy
from chaingraph.errors import UnboundedRangeError
from chaingraph.geometry import angle_between
from chaingraph.kinematics.columns import (
    LinkMotion,
    LinkStates,
    PointMotion,
    SlideMotion,
    Trajectories,
    link_of_states,
    point_of_states,
    slide_of_states,
)
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.roots import bracketed_roots
from chaingraph.kinematics.sweep import cycle, evaluate_near, evaluate_sweep
from chaingraph.kinematics.plan import Plan
from chaingraph.kinematics.sweep import Cycle
from chaingraph.kinematics.tracking import Evaluation, evaluate_at

if TYPE_CHECKING:                       # motion imports this module
    from chaingraph.kinematics.motion import Motion


class Columns(Protocol):
    """A sweep's columns by the CSV's names (``"x:B"``): a mapping, or the
    :class:`Trajectories` (a motion)."""

    def __getitem__(self, key: str, /) -> np.ndarray: ...

__all__ = ["CYCLE_STEPS", "Summary", "ExtremePosition", "Straightness", "straightness",
           "summary_rows", "path_direction", "output_signal", "OutputSignal"]


@dataclass(frozen=True)
class ExtremePosition:
    """One extreme of the output: the lead input's ``input`` value where it is, the
    output's ``value`` there (degrees for an angle, else a length), and its ``kind``,
    "max" or "min"."""

    input: float
    value: float
    kind: str

    def to_dict(self) -> dict:
        return {"input": self.input, "value": self.value, "kind": self.kind}


@dataclass(frozen=True)
class Summary:
    """The summary of a motion over the mechanism's whole cycle.

    ``output`` is what the stroke is of (None when the file names none); ``stroke`` in
    ``stroke_unit`` ("deg", the file's length unit, or None); ``time_ratio`` the forward
    stroke's input turn over the return's (``forward_deg``, ``return_deg``), for a
    crank with one maximum and one minimum; ``extremes`` the lead input's values at the
    lowest and highest output, ``extreme_positions`` every extreme in input order;
    ``transmission_angle`` ``(min, max)`` in degrees over the cycle, for a four-bar
    loop at the output; ``dead_centres`` the input values where the mechanism driven
    by its input is singular; ``input_range`` the values swept; ``full_turn`` whether
    the lead input turns fully; ``mobility`` Kutzbach's count and ``numeric_mobility``
    the rank count at the drawn pose; ``omega`` the input speed; ``note`` why a figure
    is missing; ``output_turns_fully`` when the output is a crank too.

    :meth:`to_dict` is the ``"summary"`` of ``solve --json``; ``summary["key"]`` reads
    the same keys.
    """

    output: str | None
    stroke: float | None
    stroke_unit: str | None
    time_ratio: float | None
    forward_deg: float | None
    return_deg: float | None
    extremes: tuple | None
    extreme_positions: tuple | None
    transmission_angle: tuple | None
    dead_centres: tuple
    input_range: tuple
    full_turn: bool
    mobility: int
    numeric_mobility: int
    omega: float
    note: str | None = None
    output_turns_fully: bool = False
    input_unit: str = "deg"
    straightness: Straightness | None = None     # a point's (or joint's) output

    def to_dict(self) -> dict:
        """The summary as JSON: the keys of ``solve --json``'s ``"summary"``."""
        ta = self.transmission_angle
        out = {"output": self.output, "stroke": self.stroke, "stroke_unit": self.stroke_unit,
               "time_ratio": self.time_ratio, "forward_deg": self.forward_deg,
               "return_deg": self.return_deg,
               "extremes": None if self.extremes is None else list(self.extremes),
               "extreme_positions": (None if self.extreme_positions is None else
                                     [e.to_dict() for e in self.extreme_positions]),
               "transmission_angle": None if ta is None else {"min": ta[0], "max": ta[1]},
               "dead_centres": None if self.dead_centres is None else list(self.dead_centres),
               "input_range": list(self.input_range),
               "full_turn": self.full_turn, "mobility": self.mobility,
               "numeric_mobility": self.numeric_mobility, "omega": self.omega,
               "note": self.note}
        if self.output_turns_fully:
            out["output_turns_fully"] = True
        if self.straightness is not None:
            out["straightness"] = self.straightness.to_dict()
        return out

    def __getitem__(self, key):
        """The JSON's figure ``key`` (``summary["time_ratio"]``), as :meth:`to_dict` has it."""
        return self.to_dict()[key]

    def rows(self) -> list:
        """The summary as (label, text) rows in the textbook's words.

        Examples
        --------
        >>> import chaingraph
        >>> from chaingraph.naming.catalog import catalog_path
        >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=12)
        >>> dict(m.summary.rows())["time ratio"]
        '1.0466'
        """
        def num(value, unit=""):
            if value is None or (isinstance(value, float) and not math.isfinite(value)):
                return "-"
            return f"{value:.6g}{unit}"
        unit = f" {self.stroke_unit}" if self.stroke_unit else ""
        ta = self.transmission_angle
        rows = [
            ("input range", "without limits" if None in self.input_range else
             " to ".join(f"{t:.6g}" for t in self.input_range) + f" {self.input_unit}"),
            ("output", self.output or "-"),
            ("stroke", num(self.stroke, unit)),
            ("time ratio", num(self.time_ratio)),
            ("forward / return", f"{num(self.forward_deg)} / {num(self.return_deg)} degrees"),
            ("extremes at", ", ".join(f"{t:.6g}" for t in self.extremes or ()) or "-"),
            ("every extreme", ", ".join(f"{e.kind} {e.value:.6g} at {e.input:.6g}"
                                        for e in self.extreme_positions or ()) or "-"),
            ("transmission angle", "-" if ta is None else
             f"{ta[0]:.6g} to {ta[1]:.6g} degrees"),
            ("dead centres", ", ".join(f"{t:.6g}" for t in self.dead_centres or ()) or "none"),
            ("mobility", f"{self.numeric_mobility} at the drawn pose "
                         f"(Kutzbach: {self.mobility})"),
        ]
        if self.straightness is not None:
            st = self.straightness
            rows.insert(-2, ("straightness", f"within {st.deviation:.6g}{unit} of a line over "
                                             f"{st.length:.6g}{unit}"))
        if self.note:
            rows.append(("note", self.note))
        return rows


def summary_rows(motion: Motion) -> list[tuple[str, str]]:
    """A motion's summary as (label, text) rows, for the command line, the report and
    the notebook: the fixed link and the inputs, then :meth:`Summary.rows`.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=12)
    >>> dict(summary_rows(m))["time ratio"]
    '1.0466'
    """
    s = motion.summary
    assert s is not None, "summary_rows is of a motion solved with its summary"
    plan = motion.plan
    how = "  (turns fully)" if s.full_turn else "  (rocks)"
    if motion.inputs and plan.moving_inputs > 1:
        how = "  (moving together)"
    if motion.inputs:
        lead = plan.inputs[plan.lead]
        how = how if lead.kind == "R" else "  (slides)"
        said = ("inputs", ", ".join(f"{i.joint} ({i.kind})" for i in motion.inputs)
                + (f"; {lead.joint} leads" if len(motion.inputs) > 1 else "") + how)
    else:
        assert motion.driver is not None, "a motion without inputs has its driver"
        said = ("driver", motion.driver + how)
    return [("fixed link", motion.fixed), said, *s.rows()]



# -- the summary -----------------------------------------------------------------------
@dataclass(frozen=True)
class Straightness:
    """How straight a point's path is over the sweep: ``deviation``, the largest
    distance of the path from its least-squares line (the line through the path's
    mean along its principal direction, which minimises the squared distances), and
    ``length``, the length of the path's projection on that line (file units)."""

    deviation: float
    length: float

    def to_dict(self) -> dict:
        return {"deviation": self.deviation, "length": self.length}


def straightness(x: ArrayLike, y: ArrayLike) -> Straightness | None:
    """The :class:`Straightness` of the path through the points (x, y) (the finite
    ones); None for fewer than two.

    Examples
    --------
    >>> s = straightness([0.0, 1.0, 2.0, 3.0], [0.0, 0.1, 0.1, 0.0])
    >>> round(s.deviation, 9), round(s.length, 9)
    (0.05, 3.0)
    """
    xy = np.column_stack([np.asarray(x, dtype=float), np.asarray(y, dtype=float)])
    xy = xy[np.isfinite(xy).all(axis=1)]
    if xy.shape[0] < 2:
        return None
    centred = xy - xy.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    along, across = centred @ vt[0], centred @ vt[1]
    length = float(along.max() - along.min())
    return Straightness(tidy(float(np.abs(across).max()), length), tidy(length, length))


@dataclass(frozen=True)
class OutputSignal:
    """How an output's position is measured along a sweep: a link's slide on the fixed
    link (``kind`` "slide", ``name`` the P joint), a link's angle ("angle", the link),
    or a point's travel along its path's main ``direction`` ("point", the joint or
    point; a link that neither slides nor turns is measured by its first joint).
    ``unit`` is "deg" for an angle, else the chain's length unit (None if it has none).
    """

    output: str
    kind: str
    name: str
    unit: str | None
    direction: tuple | None = None

    def values(self, columns: Columns) -> tuple[Any, Any, Any]:
        """(u, du/dt, d2u/dt2) along the sweep, from its columns (at unit input speed:
        per degree or length unit of the input, as the columns are)."""
        return self._of(lambda kind: columns[f"{kind}:{self.name}"])

    def of_states(self, plan: Plan, states: LinkStates) -> tuple[Any, Any, Any]:
        """(u, du/dt, d2u/dt2) from the solver's ``states`` (:class:`LinkStates`):
        :meth:`values` of their columns, working out the output's alone."""
        item: SlideMotion | LinkMotion | PointMotion
        if self.kind == "slide":
            item = slide_of_states(plan, states, self.name)
        elif self.kind == "angle":
            item = link_of_states(plan, states, self.name)
        else:
            item = point_of_states(plan, states, self.name)
        fields = {"angle": "angle_deg", "omega": "omega", "alpha": "alpha"}
        return self._of(lambda kind: getattr(item, fields.get(kind, kind)))

    def _of(self, column: Callable[[str], Any]) -> tuple[Any, Any, Any]:
        """(u, du/dt, d2u/dt2) from ``column(kind)``, the output's column of that kind."""
        if self.kind == "slide":
            return column("s"), column("v"), column("a")
        if self.kind == "angle":
            return column("angle"), np.degrees(column("omega")), np.degrees(column("alpha"))
        # output_signal gives every point's output its path's direction
        assert self.direction is not None, "a point's output has its path's direction"
        ux, uy = self.direction
        return (column("x") * ux + column("y") * uy, column("vx") * ux + column("vy") * uy,
                column("ax") * ux + column("ay") * uy)

    @property
    def label(self) -> str:
        """The output in words, for a plot's title."""
        if self.kind == "point":
            return f"point {self.name} (along its path's main direction)"
        if self.kind == "angle":
            return f"link {self.output} (angle)"
        return f"{self.output} (slide of joint {self.name})"


def output_signal(plan: Plan, output: str | None, columns: Columns, *,
                  closed: bool = False) -> OutputSignal | None:
    """How ``output`` (a link, point or joint, or None) moves along the sweep whose
    ``columns`` are given: the one definition the summary and the plots share (a P
    joint's is its slide, the block's travel along its guide; an R joint's its path). ``closed``: the
    columns are a whole cycle whose last row repeats the first (see
    :func:`path_direction`).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")), steps=8)
    >>> s = output_signal(m.plan, "crosshead", m.columns)
    >>> s.kind, s.name, s.unit
    ('slide', 'S', 'mm')
    """
    chain = plan.chain
    if output is None:
        return None
    units = chain.units
    if output in chain.links:
        for j in chain.joints:
            if j.kind == "P" and set(j.links) == {output, plan.fixed}:
                return OutputSignal(output, "slide", j.id, units)
        angle = columns[f"angle:{output}"]
        if np.max(angle) - np.min(angle) > 1e-9:      # (np.ptp's, at a third of its cost)
            return OutputSignal(output, "angle", output, "deg")
        name = chain.joints_of(output)[0].id
    elif output in chain._joint_index and chain.joint(output).kind == "P":
        # a sliding pair: its slide, the block's travel along its guide
        return OutputSignal(output, "slide", output, units)
    else:
        name = output
    return OutputSignal(output, "point", name, units,
                        path_direction(columns, name, closed=closed))


def path_direction(cols: Columns, name: str, *,
                   closed: bool = False) -> tuple[float, float]:
    """The main direction of point ``name``'s path (a unit vector), along which its
    stroke is measured: its sign points towards the path's point farthest from the
    path's mean, so that it turns with the drawing and does not depend on its frame.
    ``closed``: the samples are a whole cycle whose last repeats the first, which is
    counted once (twice, it would tilt the direction of a symmetric path)."""
    xy = np.column_stack([cols[f"x:{name}"], cols[f"y:{name}"]])
    if closed and xy.shape[0] > 2:
        xy = xy[:-1]
    centred = xy - xy.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    reach = np.hypot(centred[:, 0], centred[:, 1])
    along = centred[reach >= (1 - 1e-9) * reach.max()] @ vt[0]
    if along.max() > 0 > along.min():
        # farthest both ways (an ellipse's two ends): +x, else +y, decides
        ux, uy = vt[0]
        d = vt[0] if ux > 1e-12 or (abs(ux) <= 1e-12 and uy > 0) else -vt[0]
    else:
        d = vt[0] if along[np.argmax(np.abs(along))] >= 0 else -vt[0]
    return float(d[0]), float(d[1])


#: the summary's grid: steps per turn of :func:`cycle_theta`
CYCLE_STEPS = 3600


def cycle_theta(plan: Plan, c: Cycle, steps_per_turn: int = CYCLE_STEPS) -> np.ndarray:
    """The summary's grid: one period of a crank from the drawn pose, or a rocker's
    whole range, limits included exactly."""
    if c.period is not None:                   # a full turn
        n = int(round(steps_per_turn * c.period / 360.0))
        return c.low + c.period * np.arange(n + 1) / n
    theta = np.linspace(c.low, c.high, steps_per_turn + 1)
    theta[0], theta[-1] = c.low, c.high
    return theta


def _pointwise(plan, ev, k, t, *, measures=False):
    """The solver's states (:class:`LinkStates`) at angles ``t``, each continued from
    ev's point k, or with ``measures`` the step measures there (and no accelerations)."""
    pose, feasible, _ = evaluate_at(plan, t, ev.reference(k))
    vel, acc, measure = rates(plan, pose, 1.0, t.size, measure=measures,
                              accelerations=not measures)
    return LinkStates(t, pose, vel, acc), measure, feasible


def motion_summary(plan: Plan, output: str | None, omega: float, c: Cycle, *,
                   sweep: tuple[Evaluation, Any, Any] | None = None) -> Summary:
    """The :class:`Summary` over the cycle ``c``; ``sweep`` is (evaluation, step
    measures, columns at unit input speed, or the :class:`Trajectories`) on the cycle's own grid when the caller has
    them. Figures within rounding of a round number are that number (:func:`tidy`)."""
    s = _raw_summary(plan, output, omega, c, sweep=sweep)
    length = plan.size
    angle = 360.0
    lead = angle if plan.inputs[plan.lead].kind == "R" else length
    out = angle if s["stroke_unit"] == "deg" else length

    def tidied(values, scale):
        return None if values is None else tuple(tidy(v, scale) for v in values)
    positions = s["extreme_positions"]
    ta = s["transmission_angle"]
    return Summary(
        output=s["output"], stroke=tidy(s["stroke"], out), stroke_unit=s["stroke_unit"],
        time_ratio=tidy(s["time_ratio"], 1.0), forward_deg=tidy(s["forward_deg"], angle),
        return_deg=tidy(s["return_deg"], angle), extremes=tidied(s["extremes"], lead),
        extreme_positions=None if positions is None else tuple(
            ExtremePosition(tidy(e["input"], lead), tidy(e["value"], out), e["kind"])
            for e in positions),
        transmission_angle=None if ta is None else (tidy(ta["min"], angle),
                                                    tidy(ta["max"], angle)),
        dead_centres=tidied(s["dead_centres"], lead), input_range=tidied(s["input_range"], lead),
        full_turn=bool(s["full_turn"]), mobility=s["mobility"],
        numeric_mobility=s["numeric_mobility"], omega=s["omega"], note=s["note"],
        output_turns_fully=bool(s.get("output_turns_fully")), input_unit=plan.lead_unit)


def _raw_summary(plan, output, omega, c, *, sweep=None):
    if sweep is None:
        theta = cycle_theta(plan, c)
        try:
            ev = evaluate_sweep(plan, theta)
        except UnboundedRangeError:            # a sweep of a slide without limits
            ev = evaluate_near(plan, theta)
        points: dict = {}
        vel, acc, measure = rates(plan, ev.pose, 1.0, theta.size, points=points)
        cols = Trajectories.of_states(plan, LinkStates(theta, ev.pose, vel, acc, points=points))
    else:
        ev, measure, cols = sweep
        theta = ev.theta
    summary = {"output": output, "stroke": None, "stroke_unit": None, "time_ratio": None,
               "forward_deg": None, "return_deg": None, "extremes": None,
               "extreme_positions": None,
               "transmission_angle": _transmission(plan, cols, output),
               "dead_centres": _dead_centres(plan, ev, measure, c),
               "input_range": _input_range(plan, theta, c),
               "full_turn": c.full_turn,
               "mobility": plan.mobility, "numeric_mobility": plan.numeric_mobility,
               "omega": omega, "note": None}
    signal = output_signal(plan, output, cols, closed=c.full_turn)
    if signal is None:
        summary["note"] = "no output is named, so there is no stroke or time ratio"
        return summary
    kind = signal.kind
    u, du, ddu = signal.values(cols)
    summary["stroke_unit"] = signal.unit
    if kind == "angle" and c.full_turn and abs(u[-1] - u[0]) > 180.0:
        summary["output_turns_fully"] = True
        summary["note"] = "the output turns fully, so it has no stroke or time ratio"
        return summary
    # np.nanmax(np.abs(du)), and u's range without NaN (fmax and fmin skip NaN, as
    # nanmax and nanmin do, at a tenth of their cost)
    scale = max(np.fmax.reduce(du), -np.fmin.reduce(du))
    if not np.isfinite(scale) or np.fmax.reduce(u) - np.fmin.reduce(u) <= 1e-12 * max(
            plan.size if kind != "angle" else 360.0, 1e-300):
        summary.update(stroke=0.0, note="the output does not move")
        return summary
    extremes = _output_extremes(plan, ev, signal, u, du, ddu, scale, c)
    # the highest and the lowest, the first in input order among equals (to rounding:
    # a toggle's two equal maxima are not told apart by their last bits)
    values = np.array([e["value"] for e in extremes])
    same = 1e-12 * (360.0 if kind == "angle" else plan.size)
    hi_e = extremes[int(np.argmax(values >= values.max() - same))]
    lo_e = extremes[int(np.argmax(values <= values.min() + same))]
    summary["stroke"] = hi_e["value"] - lo_e["value"]
    summary["extremes"] = [_turn(plan, lo_e["input"], c), _turn(plan, hi_e["input"], c)]
    summary["extreme_positions"] = [dict(e, input=_turn(plan, e["input"], c))
                                    for e in extremes]
    if c.ends == "sweep":
        summary["note"] = ("the inputs move together over the sweep given, so there is no "
                           "time ratio")
        return summary
    if not c.full_turn:
        summary["note"] = ("the input rocks, so there is no time ratio"
                           if plan.inputs[plan.lead].kind == "R" else
                           "the input slides to and fro, so there is no time ratio")
        return summary
    maxima = sum(e["kind"] == "max" for e in extremes)
    if maxima != 1:
        summary["note"] = (f"the output reaches {maxima} maxima and {len(extremes) - maxima} "
                           "minima in a cycle, so no single forward and return stroke "
                           "(and no time ratio) is defined")
        return summary
    lo_in, lo_out = _dwell(theta, u, lo_e, summary["stroke"], c.period)
    hi_in, hi_out = _dwell(theta, u, hi_e, summary["stroke"], c.period)
    a = (hi_in - lo_out) % c.period                  # from the minimum to the maximum
    b = (lo_in - hi_out) % c.period                  # and back
    if (lo_in, hi_in) != (lo_out, hi_out):
        summary["note"] = (f"the output dwells at its extremes ({(lo_out - lo_in) % c.period:.6g} "
                           f"and {(hi_out - hi_in) % c.period:.6g} {plan.lead_unit} of the "
                           "input): the strokes are taken between the dwells")
    forward, back = max(a, b), min(a, b)
    summary.update(forward_deg=forward, return_deg=back,
                   time_ratio=forward / back if back > 0 else None)
    return summary


def _dwell(theta, u, extreme, stroke, period):
    """Where the output arrives at the ``extreme`` and where it leaves it (input
    values, in the sweep's terms): the ends of a dwell, the run of the sweep's points
    at the extreme's value (to 1e-9 of the stroke) round it, three points or more (a
    smooth extreme is that flat over a single point of a fine grid); else the
    extreme's input twice."""
    at = extreme["input"]
    flat = np.abs(u - extreme["value"]) <= 1e-9 * stroke
    if np.count_nonzero(flat) < 3:       # no run of three (a smooth extreme): no dwell
        return at, at
    k = int(np.argmin(np.abs((theta - at + 0.5 * period) % period - 0.5 * period)))
    n = theta.size - 1 if abs(theta[-1] - theta[0] - period) < 1e-9 else theta.size
    if n < 3 or not flat[k] or flat[:n].all():
        return at, at
    lo = hi = k
    while flat[(lo - 1) % n] and (k - lo) < n:
        lo -= 1
    while flat[(hi + 1) % n] and (hi - k) < n:
        hi += 1
    if hi - lo < 2:
        return at, at
    start = theta[lo % n] + period * (lo // n)
    end = theta[hi % n] + period * (hi // n)
    return float(start), float(end)


def _input_range(plan, theta, c):
    """The lead input's values that can be assembled: the summary's own range, or, for
    a sweep of several inputs, the range along their line."""
    if c.ends == "sweep":
        try:
            whole = cycle(plan)
        except UnboundedRangeError:
            return [None, None]                  # no limit either way
        ends = ((whole.low, whole.low + whole.period) if whole.period is not None  # a turn
                else (whole.low, whole.high))
        return [float(plan.value(t)) for t in ends]
    return [float(plan.value(theta[0])), float(plan.value(theta[-1]))]


def _output_extremes(plan, ev, signal, u, du, ddu, scale, c):
    """Every extreme of the output over the cycle, in input order: stationary points,
    and for a rocker the values at the input's limits. Each {"input", "value", "kind"}.

    A stationary point is first placed from what the sweep already has (the root of the
    cubic through the rate and its slope at the two samples around it, accurate to the
    fourth power of the grid's step). On a fine grid it is finished from the samples
    too, where the estimated error is within rounding (:func:`_interpolated_extremes`);
    else one Newton step on the exact rate there finishes it, and where that step does
    not land inside the bracket, Newton's method safeguarded by bisection takes over
    (:func:`_finished_extremes`)."""
    theta = ev.theta
    sign = np.sign(du)
    sign[~(np.abs(du) > 1e-9 * scale)] = 0.0        # (and where NaN)
    if not c.full_turn and sign.size > 2:
        # a limit of the range is a fold, where the rate is infinite and its computed
        # sign means nothing: the samples inside say which way the output goes there
        sign[[0, -1]] = 0.0
    # the rate's sign changes between significant samples (a dwell's rounding noise and
    # exact zeros on the grid are skipped over, not counted); a crank's cycle closes on
    # itself, so a change across its seam counts too, one period on
    first: int | None
    if sign.size and sign.all():          # (every sample counts: no gathering)
        ka = np.flatnonzero(sign[:-1] != sign[1:])
        kb = ka + 1
        first, last = 0, sign.size - 1
    else:
        idx = np.nonzero(sign)[0]
        ka, kb = idx[:-1], idx[1:]
        change = sign[ka] != sign[kb]
        ka, kb = ka[change], kb[change]
        first, last = (int(idx[0]), int(idx[-1])) if idx.size else (None, -1)
    tb = theta[kb]
    if c.full_turn and first is not None and sign[last] != sign[first]:
        ka, kb = np.append(ka, last), np.append(kb, first)
        tb = np.append(tb, theta[first] + c.period)
    found = []
    if ka.size:
        ta = theta[ka]
        slope_a, slope_b = ddu[ka] * plan.rate_scale, ddu[kb] * plan.rate_scale
        guess = _cubic_roots(ta, tb, du[ka], du[kb], slope_a, slope_b)
        scales = (360.0 if plan.inputs[plan.lead].kind == "R" else plan.size,
                  360.0 if signal.kind == "angle" else plan.size)
        t, value, sure = _interpolated_extremes(theta, u, du, ddu, ka, kb, guess,
                                                plan.rate_scale, scales)
        if not sure.all():
            rest = np.flatnonzero(~sure)
            t[rest], value[rest] = _finished_extremes(plan, ev, signal, ka[rest], kb[rest],
                                                      ta[rest], tb[rest], guess[rest], du)
        if signal.kind == "angle":      # the same turn as the sweep's own values
            value = u[ka] + np.remainder(value - u[ka] + 180.0, 360.0) - 180.0
        found = [{"input": float(ti), "value": float(vi), "kind": "max" if sign[k] > 0 else "min"}
                 for ti, vi, k in sorted(zip(t, value, ka))]
    if not c.full_turn and first is not None:
        found.insert(0, {"input": float(theta[0]), "value": float(u[0]),
                         "kind": "min" if sign[first] > 0 else "max"})
        found.append({"input": float(theta[-1]), "value": float(u[-1]),
                      "kind": "max" if sign[last] > 0 else "min"})
    return found or [{"input": float(theta[int(np.argmax(u))]), "value": float(np.max(u)),
                      "kind": "max"},
                     {"input": float(theta[int(np.argmin(u))]), "value": float(np.min(u)),
                      "kind": "min"}]


def _finished_extremes(plan, ev, signal, ka, kb, ta, tb, guess, du):
    """The stationary points (inputs, values) in the brackets [ta, tb] finished on the
    mechanism itself: one Newton step on the exact rate at the ``guess``, and where that
    does not land inside the bracket, Newton's method safeguarded by bisection."""
    states, _, _ = _pointwise(plan, ev, ka, guess)
    at_guess, rate, second = signal.of_states(plan, states)
    with np.errstate(divide="ignore", invalid="ignore"):   # (checked below)
        step = -rate / (second * plan.rate_scale)
        t = guess + step
        # u moves by -rate^2 / (2 second) on the way to the root (rate = du / d input)
        value = at_guess - 0.5 * rate * rate / second
    good = (np.isfinite(t) & np.isfinite(value) & ((t - ta) * (t - tb) <= 0)
            & (np.abs(step) <= 1e-3 * np.abs(tb - ta)))
    if not good.all():
        bad = np.nonzero(~good)[0]
        kbad = ka[bad]
        t[bad] = bracketed_roots(
            lambda tt: _rate_and_slope(plan, ev, kbad, tt, signal),
            ta[bad], tb[bad], du[kbad], du[kb[bad]], newton=True)
        redo, _, _ = _pointwise(plan, ev, kbad, t[bad])
        value[bad] = signal.of_states(plan, redo)[0]
    return t, value


_SURE = 1e-13       # an interpolated extreme is kept within this of its scales (x 10)


def _interpolated_extremes(theta, u, du, ddu, ka, kb, guess, rate_scale, scales):
    """The stationary points in the brackets between the samples ``ka`` and ``kb`` from
    the sweep's own values, rates and accelerations, where its grid is fine enough:
    (inputs, values, sure), starting from the rate's cubic roots ``guess``.

    With h the step and dNu the output's N-th derivative along the path: the rate's
    cubic (Hermite) is off the rate by h^4 d5u s^2 (1 - s)^2 / 24 across the bracket,
    which the third difference of the accelerations at the four samples round it
    (~ h^3 d5u) corrects, leaving about h^5 |d6u| / 384; two Newton steps on the
    corrected cubic place the extreme, off by that over |d2u| (the rates alone: the
    values' rounding would move it more). The value is the quintic's through the value,
    rate and acceleration at both samples, off by at most h^6 |d6u| / 46080 (an error in
    the place moves it by its square only). h^4 d6u is estimated by the fourth
    difference of the accelerations at the six samples round the bracket. An extreme is
    *sure* where both errors, ten times over, are within 1e-13 of the input's and the
    output's ``scales`` (360 degrees, or the chain's size): a fine sweep's extremes to
    rounding without solving the mechanism again. Only a bracket of consecutive samples
    on an even grid, two samples more either side, is judged, and only up to
    ``_FEW_BRACKETS`` of them (in floats, one by one); the rest, and every bracket of a
    coarse grid or near a fold, are finished on the mechanism (:func:`_finished_extremes`)."""
    t, value = guess.copy(), np.full(ka.size, np.nan)
    sure = np.zeros(ka.size, dtype=bool)
    if ka.size > _FEW_BRACKETS:
        return t, value, sure
    for i, (k, k1, at) in enumerate(zip(ka.tolist(), kb.tolist(), guess.tolist())):
        if k1 == k + 1 and k >= 2 and k1 + 2 < u.size:
            t[i], value[i], sure[i] = _interpolated_extreme(
                theta[k - 2:k + 4].tolist(), float(u[k]), float(u[k1]), float(du[k]),
                float(du[k1]), (ddu[k - 2:k + 4] * (rate_scale * rate_scale)).tolist(),
                at, rate_scale, scales)
    return t, value, sure


def _interpolated_extreme(theta, u0, u1, du0, du1, g, at, rate_scale, scales):
    """:func:`_interpolated_extremes` of one bracket, in floats: ``theta`` and ``g``
    (the accelerations per unit of the path squared) at the six samples round it."""
    h = theta[3] - theta[2]
    if not all(abs(theta[i + 1] - theta[i] - h) <= 1e-9 * abs(h) for i in range(5)):
        return at, math.nan, False
    fourth = max(abs(g[i] - 4 * g[i + 1] + 6 * g[i + 2] - 4 * g[i + 3] + g[i + 4])
                 for i in (0, 1))                                    # ~ h^4 d6u
    bend = min(abs(g[2]), abs(g[3]))
    if not (bend > 0 and 10.0 * h * fourth / 384.0 <= _SURE * scales[0] * bend
            and 10.0 * h * h * fourth / 46080.0 <= _SURE * scales[1]):
        return at, math.nan, False
    r0, r1 = du0 * rate_scale, du1 * rate_scale
    b0, b1, b2, b3 = _hermite_cubic(0.0, 1.0, r0, r1, g[2] * h, g[3] * h)
    bump = h * (g[4] - 3 * g[3] + 3 * g[2] - g[1]) / 24.0   # ~ h^4 d5u / 24
    s = (at - theta[2]) / h
    for _ in range(2):
        q = s * (1.0 - s)
        rate = b0 + s * (b1 + s * (b2 + s * b3)) + bump * q * q
        slope = b1 + s * (2 * b2 + 3 * s * b3) + bump * 2 * q * (1.0 - 2 * s)
        s = s - _ratio(rate, slope)
    # the quintic past u0, in s across the bracket: d the values' difference
    m0, m1, c0, c1, d = r0 * h, r1 * h, g[2] * h * h, g[3] * h * h, u1 - u0
    a3 = 10 * d - 6 * m0 - 4 * m1 - 1.5 * c0 + 0.5 * c1
    a4 = -15 * d + 8 * m0 + 7 * m1 + 1.5 * c0 - c1
    a5 = 6 * d - 3 * m0 - 3 * m1 - 0.5 * c0 + 0.5 * c1
    value = u0 + s * (m0 + s * (0.5 * c0 + s * (a3 + s * (a4 + s * a5))))
    if not (math.isfinite(value) and 0.0 <= s <= 1.0):
        return at, math.nan, False
    return theta[2] + s * h, value, True


_FEW_BRACKETS = 8     # up to so many brackets, the cubics are solved one by one in floats


def _cubic_roots(t0, t1, f0, f1, g0, g1):
    """The root in each bracket [t0, t1] (f0, f1 of opposite signs) of the cubic with
    values f and slopes g at its ends (Hermite): Newton's method from the secant's
    root, and bisection where it does not settle inside the bracket. No evaluation of
    the mechanism, only of the cubic. (A few brackets, as a cycle has, are solved in
    Python floats, the same operations without an array's cost per operation.)"""
    if np.size(t0) <= _FEW_BRACKETS:
        return np.array([_cubic_root(*(float(x) for x in v))
                         for v in zip(t0, t1, f0, f1, g0, g1)], dtype=float)
    h, (a0, a1, a2, a3) = t1 - t0, _hermite_cubic(t0, t1, f0, f1, g0, g1)

    def cubic(s):
        return a0 + s * (a1 + s * (a2 + s * a3))
    with np.errstate(divide="ignore", invalid="ignore"):
        s = f0 / (f0 - f1)
        for _ in range(6):
            last, s = s, np.clip(s - cubic(s) / (a1 + s * (2 * a2 + 3 * s * a3)), 0.0, 1.0)
            if np.array_equal(s, last):       # settled: the steps left would change nothing
                break
    settled = np.isfinite(s) & (np.abs(cubic(s)) <= 1e-13 * (np.abs(f0) + np.abs(f1)))
    if not settled.all():                   # bisection, where Newton's did not settle
        lo, hi = np.zeros_like(h), np.ones_like(h)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            left = np.sign(cubic(mid)) == np.sign(f0)
            lo, hi = np.where(left, mid, lo), np.where(left, hi, mid)
        s = np.where(settled, s, 0.5 * (lo + hi))
    return t0 + s * h


def _hermite_cubic(t0, t1, f0, f1, g0, g1):
    """The coefficients (a0, a1, a2, a3) of p(s) = a0 + a1 s + a2 s^2 + a3 s^3 on
    s in [0, 1] with values f and slopes g (per unit of t) at t0 and t1 (floats or
    arrays alike)."""
    h = t1 - t0
    return f0, g0 * h, 3 * (f1 - f0) - (2 * g0 + g1) * h, 2 * (f0 - f1) + (g0 + g1) * h


def _ratio(a, b):
    """a / b as numpy divides floats: infinite or NaN where b is 0."""
    if b != 0.0:
        return a / b
    return math.nan if a == 0.0 or a != a else math.copysign(math.inf, a) * math.copysign(1.0, b)


def _cubic_root(t0, t1, f0, f1, g0, g1):
    """:func:`_cubic_roots` of one bracket, in floats."""
    h, (a0, a1, a2, a3) = t1 - t0, _hermite_cubic(t0, t1, f0, f1, g0, g1)

    def cubic(s):
        return a0 + s * (a1 + s * (a2 + s * a3))
    s = _ratio(f0, f0 - f1)
    for _ in range(6):
        last = s
        s = min(max(s - _ratio(cubic(s), a1 + s * (2 * a2 + 3 * s * a3)), 0.0), 1.0)
        if s == last:                         # settled (never for NaN, as np.array_equal)
            break
    if not (math.isfinite(s) and abs(cubic(s)) <= 1e-13 * (abs(f0) + abs(f1))):
        lo, hi = 0.0, 1.0                     # bisection, where Newton's did not settle
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            v = cubic(mid)
            if ((v > 0) - (v < 0)) == ((f0 > 0) - (f0 < 0)) and v == v:
                lo = mid
            else:
                hi = mid
        s = 0.5 * (lo + hi)
    return t0 + s * h


def _rate_and_slope(plan, ev, k, t, signal):
    """The output's rate and its derivative per degree of input at angles t."""
    states, _, _ = _pointwise(plan, ev, k, t)
    _, d1, d2 = signal.of_states(plan, states)
    return d1, d2 * plan.rate_scale        # d2 per unit of input squared, t in tau


def _transmission(plan, cols, out):
    """Transmission angle range of the four-bar loop (RRR dyad) at the output ``out``
    (else the first such loop), if any, from the sweep's joint positions ``cols``."""
    dyads = [s for s in plan.steps if s.kind == "dyad" and s.pattern == "RRR"]
    if not dyads:
        return None
    step = next((s for s in dyads if out in s.links), dyads[0])
    ca, cb, cj = step.constraints
    x = cols[f"x:{cj.joint}"], cols[f"y:{cj.joint}"]        # the joint between the two
    ax, ay = cols[f"x:{ca.joint}"] - x[0], cols[f"y:{ca.joint}"] - x[1]
    bx, by = cols[f"x:{cb.joint}"] - x[0], cols[f"y:{cb.joint}"] - x[1]
    # the angle between a and b, atan2(|a x b|, a . b), falls as a . b rises (|a| and |b|
    # are the links' own lengths): the extremes of a . b are its, the angle worked out
    # at them and their neighbours only
    dot = ax * bx
    dot += ay * by

    def angle_near(k):
        near = slice(max(int(k) - 1, 0), int(k) + 2)
        a, b = (ax[near], ay[near]), (bx[near], by[near])
        return _refined_extreme(angle_between(a, b), min(int(k), 1))
    return {"min": angle_near(np.argmax(dot)), "max": angle_near(np.argmin(dot))}


def _refined_extreme(y, k):
    """A sampled extreme refined by the parabola through its neighbours."""
    k = int(k)
    if 0 < k < y.size - 1:
        y0, y1, y2 = y[k - 1], y[k], y[k + 1]
        den = y0 - 2 * y1 + y2
        if den != 0:
            return float(y1 - 0.125 * (y2 - y0) ** 2 / den)
    return float(y[k])


def _dead_centres(plan, ev, measure, c):
    """Input angles where the driven mechanism is singular: where a step's signed,
    normalized determinant changes sign (refined all at once), where a dyad's two
    modes touch (a change point), and a rocker's limits."""
    theta = ev.theta
    # where a dyad's modes touch, and a rocker's limits, are known precisely; a root of
    # a determinant near one (where positions carry the square root of the rounding
    # error) is the same dead centre
    exact = [t for ts in ev.switches.values() for t in ts]
    folds = not c.full_turn and c.ends == "limits"
    if folds:
        exact += [c.low, c.high]
    # a rocker's limits are folds, where a determinant is zero with no meaningful
    # sign: the samples there are left out of the search
    inner = np.ones(theta.size, dtype=bool)
    if folds:
        inner[[0, -1]] = False
    roots = []
    for i, m in enumerate(measure):
        if np.ndim(m) == 0 and m != 0 and math.isfinite(m):
            continue                     # (an input's weld: never singular)
        m = np.asarray(m, dtype=float)
        valid = inner & np.isfinite(m) & (m != 0)
        if valid.all():                  # (as below, without gathering the samples)
            negative = m < 0
            ka = np.flatnonzero(negative[1:] != negative[:-1])
            kb = ka + 1
        else:
            idx = np.nonzero(valid)[0]
            change = np.sign(m[idx[:-1]]) != np.sign(m[idx[1:]])
            ka, kb = idx[:-1][change], idx[1:][change]
            roots += [float(theta[k]) for k in np.nonzero(inner & (m == 0))[0]]
        if ka.size:
            def f(t, ka=ka, i=i):
                _, mm, _ = _pointwise(plan, ev, ka, t, measures=True)
                return mm[i]
            roots += list(bracketed_roots(f, theta[ka], theta[kb], m[ka], m[kb]))
    found = exact + [t for t in roots if all(abs(t - x) > 1e-5 for x in exact)]
    if c.ends == "sweep":
        found = [t for t in found if c.low - 1e-9 <= t <= c.high + 1e-9]
    found = sorted(_turn(plan, t, c) for t in found)
    merged = [t for i, t in enumerate(found) if i == 0 or t - found[i - 1] > _SAME_ANGLE]
    if c.full_turn and len(merged) > 1 and merged[0] + 360.0 - merged[-1] <= _SAME_ANGLE:
        merged.pop()
    return merged


_SAME_ANGLE = 1e-7     # degrees: how precisely change points and limits are found


def _turn(plan, t, c):
    """The lead input's value at tau = t: an angle of a full-turn cycle in [0, 360)
    (within ``_SAME_ANGLE`` of 360 is 0); a rocking or sliding input's as it is."""
    t = float(plan.value(t))
    if not c.full_turn:
        return t
    t = float(t % 360.0)
    return 0.0 if t > 360.0 - _SAME_ANGLE else t
