"""Function generation: a four-bar or a slider crank whose output follows y = f(x).

Four-bar (input crank about A at the origin, output rocker about D at (d, 0), d =
:data:`FRAME`): with the crank a at theta and the rocker c at psi, the coupler b closes
the loop when (Freudenstein's equation)

    R1 cos(psi) - R2 cos(theta) + R3 = cos(theta - psi),
    R1 = d / a,  R2 = d / c,  R3 = (a^2 - b^2 + c^2 + d^2) / (2 a c),

linear in R1, R2, R3: three precision points (theta_j, psi_j) give them by one linear
solve, then a = d / R1, c = d / R2, b^2 = a^2 + c^2 + d^2 - 2 a c R3.

Slider crank (crank r about the origin, the block's pin at (s, e) on a guide along +x):
the rod l closes the loop when

    2 r s cos(theta) + 2 e r sin(theta) + (l^2 - r^2 - e^2) = s^2,

linear in K1 = 2 r, K2 = 2 e r, K3 = l^2 - r^2 - e^2: r = K1 / 2, e = K2 / K1,
l^2 = K3 + r^2 + e^2.

More than three points are fitted over the whole range, the largest structural error
(the output's departure from the task, over every x of the range, not only at the points)
made small (minimax, by scipy's Nelder-Mead from the three-point solutions at Chebyshev's
points). Without a start, the input's and output's starting values are searched (a
coarse grid, then local refinement of the best). Every candidate is then certified by
:func:`~chaingraph.synthesis.certification.certify` from its written chain file.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt
from scipy.optimize import minimize  # type: ignore[import-untyped]

from chaingraph.errors import DesignError
from chaingraph.geometry import angle_between, circle_circle, circle_line
from chaingraph.model.chain import Chain, Joint, Mechanism
from chaingraph.naming import identify
from chaingraph.kinematics import solve
from chaingraph.synthesis.certification import (
    Certified,
    FunctionTargets,
    certify,
    output_values,
)
from chaingraph.synthesis.result import Curve, Searched, Solution, Synthesis, ranked
from chaingraph.synthesis.task import FunctionTask, check_options, function_task, precision_x

__all__ = ["function", "FRAME", "MAX_RATIO", "FunctionDesign", "freudenstein",
           "slider_crank_closed_form", "design_error", "structural_error"]

#: the four-bar's frame length (file units); a function generator's size is free
FRAME = 100.0
#: the longest link over the shortest, at most
MAX_RATIO = 20.0
_GRID = 10.0          # degrees: the coarse grid of starting angles
_OFFSETS = np.linspace(-3.0, 3.0, 25)    # a slider's start, in output swings
_SAMPLES = 241        # structural error samples while designing
_REFINED = 6          # grid designs refined locally
_ZOOMS = 4            # ever finer grids about a start
_FITTED = 61          # samples of the structural error in a fit
_FITTED_SEEDS = 2     # designs fitted from, without a task's start
_BAD = 1e9
_CERTIFIED = 3        # candidates certified, at most, per solution asked for


@dataclass(frozen=True)
class FunctionDesign:
    """A designed function generator before certification: ``kind``, ``lengths``
    (four-bar: a crank, b coupler, c rocker, d frame; slider crank: r crank, l rod, e
    offset), ``start`` (the input's angle and the output's value at x = A), ``mode``
    (+1 or -1: the assembly at the first precision point) and ``predicted`` (the
    largest structural error over the range, by the closed form)."""

    kind: str
    lengths: tuple[float, ...]
    start: tuple[float, float]
    mode: int
    predicted: float


def freudenstein(theta: npt.ArrayLike, psi: npt.ArrayLike) -> np.ndarray:
    """R1, R2, R3 of Freudenstein's equation through three (theta, psi) pairs (radians,
    arrays of shape (..., 3)); NaN where the three give no unique solution.

    Examples
    --------
    The four-bar a = 40, b = 120, c = 80, d = 100 at three poses gives back d/a, d/c:

    >>> import numpy as np
    >>> from chaingraph.geometry import circle_circle
    >>> t = np.radians([40.0, 70.0, 100.0])
    >>> (mx, my), (nx, ny), raw = circle_circle((40 * np.cos(t), 40 * np.sin(t)), 120.0,
    ...                                         (100.0, 0.0), 80.0)
    >>> psi = np.arctan2(my + np.sqrt(raw) * ny, mx + np.sqrt(raw) * nx - 100.0)
    >>> [round(float(v), 9) for v in freudenstein(t, psi)][:2]
    [2.5, 1.25]
    """
    theta, psi = np.asarray(theta, dtype=float), np.asarray(psi, dtype=float)
    m = np.stack([np.cos(psi), -np.cos(theta), np.ones_like(theta)], axis=-1)
    rhs = np.cos(theta - psi)
    det = np.linalg.det(m)
    ok = np.abs(det) > 1e-12
    safe = np.where(ok[..., None, None], m, np.eye(3))
    r = np.linalg.solve(safe, rhs[..., None])[..., 0]
    return np.where(ok[..., None], r, np.nan)


def slider_crank_closed_form(theta: npt.ArrayLike, s: npt.ArrayLike) -> np.ndarray:
    """(r, l squared, e) of the slider crank through three (theta, s) pairs (theta in
    radians, s the block's pin along the guide; arrays of shape (..., 3)); NaN where the
    three give no unique solution.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.radians([10.0, 50.0, 90.0])
    >>> s = 30 * np.cos(t) + np.sqrt(100.0 ** 2 - (8.0 - 30 * np.sin(t)) ** 2)
    >>> [round(float(v), 9) for v in slider_crank_closed_form(t, s)]
    [30.0, 10000.0, 8.0]
    """
    theta, s = np.asarray(theta, dtype=float), np.asarray(s, dtype=float)
    m = np.stack([s * np.cos(theta), np.sin(theta), np.ones_like(theta)], axis=-1)
    det = np.linalg.det(m)
    ok = np.abs(det) > 1e-12 * np.maximum(np.max(np.abs(s), axis=-1), 1.0)
    safe = np.where(ok[..., None, None], m, np.eye(3))
    k = np.linalg.solve(safe, (s * s)[..., None])[..., 0]
    r = k[..., 0] / 2
    with np.errstate(all="ignore"):
        e = k[..., 1] / k[..., 0]
    out = np.stack([r, k[..., 2] + r * r + e * e, e], axis=-1)
    return np.where(ok[..., None], out, np.nan)


# -- the designs' own closed-form motion ---------------------------------------------
def _four_bar_output(a, b, c, d, theta, mode):
    """The rocker's angle (radians) and the transmission angle (degrees) at crank angles
    theta, in assembly ``mode``; NaN where it cannot be assembled."""
    bx, by = a * np.cos(theta), a * np.sin(theta)
    (mx, my), (nx, ny), raw = circle_circle((bx, by), b, (d, 0.0), c)
    root = mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
    cx, cy = mx + root * nx, my + root * ny
    psi = np.arctan2(cy, cx - d)
    return psi, angle_between((bx - cx, by - cy), (d - cx, -cy))


def _slider_output(r, l, e, theta, mode):
    """The block's pin along the guide and the transmission angle (degrees)."""
    bx, by = r * np.cos(theta), r * np.sin(theta)
    (fx, _), _, raw = circle_line((bx, by), l, (0.0, e), (1.0, 0.0))
    s = fx + mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
    with np.errstate(all="ignore"):
        mu = np.degrees(np.arccos(np.clip(np.abs(e - by) / l, 0.0, 1.0)))
    return s, mu


def _wrap(deg):
    return (deg + 180.0) % 360.0 - 180.0


def design_error(task: FunctionTask, kind: str, lengths: Sequence[npt.ArrayLike],
                 start: Sequence[npt.ArrayLike], mode: npt.ArrayLike,
                 xs: npt.ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The structural error (output's units) of a design at ``xs`` (default: the
    range, densely) and its transmission angles there (degrees), by the design's closed
    form. ``lengths``, ``start`` and ``mode`` may hold one value or arrays of M designs
    (the results are then (M, len(xs)))."""
    at = (np.linspace(task.x[0], task.x[1], _SAMPLES) if xs is None
          else np.asarray(xs, dtype=float))
    sizes = [np.asarray(v, dtype=float)[..., None] for v in lengths]
    first, out0 = (np.asarray(v, dtype=float)[..., None] for v in start)
    modes = np.asarray(mode)[..., None]
    theta = np.radians(first + task.input_at(at))
    wanted = out0 + task.output_at(at)
    with np.errstate(all="ignore"):
        if kind == "four-bar":
            got, mu = _four_bar_output(sizes[0], sizes[1], sizes[2], sizes[3], theta, modes)
            err = _wrap(np.degrees(got) - wanted)
        else:
            got, mu = _slider_output(sizes[0], sizes[1], sizes[2], theta, modes)
            err = got - wanted
    return err, mu


def _scores(task, lengths, starts, modes, xs_targets):
    """The largest structural error over the range of each of M designs (``lengths``
    (M, n), ``starts`` (M, 2), ``modes`` (M,)), and why a design fails (None where it
    does not): an analytic screen; the solver certifies afterwards."""
    lengths, starts = np.atleast_2d(lengths), np.atleast_2d(starts)
    err, mu = design_error(task, task.mechanism, lengths.T, starts.T, modes)
    at, _ = design_error(task, task.mechanism, lengths.T, starts.T, modes, xs_targets)
    reasons = np.full(len(starts), None, dtype=object)
    lo, hi = min(xs_targets[0], xs_targets[-1]), max(xs_targets[0], xs_targets[-1])
    xs = np.linspace(task.x[0], task.x[1], _SAMPLES)
    inside = mu[:, (xs >= lo) & (xs <= hi)]
    mt = task.min_transmission
    reasons[np.any((inside < mt) | (inside > 180 - mt), axis=1)] = "transmission angle"
    if task.points == 3:
        tol = 1e-6 * (1.0 if task.mechanism == "four-bar" else abs(task.swing[1]))
        reasons[~np.all(np.abs(at) <= tol, axis=1)] = "circuit defect"
    reasons[~np.all(np.isfinite(err), axis=1)] = "does not assemble"
    with np.errstate(invalid="ignore"):
        score = np.where(reasons == None, np.max(np.abs(err), axis=1), _BAD)  # noqa: E711
    return score, reasons


# -- three points, exactly -----------------------------------------------------------
def _three_points(task, xs, starts):
    """Designs through the precision points ``xs`` (three) for each start (rows of
    ``starts``, degrees): (lengths (M, 3 or 4), starts (M, 2), modes (M,), reasons (M,)
    or None).

    A negative crank or rocker out of the equations is the link pointing the other way
    along its line (the textbooks' reading of the sign: an angle is a line's, the sign
    of a length says which way along it): the link's length is made positive and its
    start turned by half a turn; the mechanism is the same."""
    starts = np.array(starts, dtype=float)
    theta = np.radians(starts[:, :1] + task.input_at(xs)[None, :])
    out = starts[:, 1:] + task.output_at(xs)[None, :]
    reasons = np.full(len(starts), None, dtype=object)
    with np.errstate(all="ignore"):
        if task.mechanism == "four-bar":
            psi = np.radians(out)
            r = freudenstein(theta, psi)
            d = FRAME
            a, c = d / r[:, 0], d / r[:, 1]
            b2 = a * a + c * c + d * d - 2 * a * c * r[:, 2]
            bx, by = a * np.cos(theta[:, 0]), a * np.sin(theta[:, 0])
            cx, cy = d + c * np.cos(psi[:, 0]), c * np.sin(psi[:, 0])
            modes = np.where((d - bx) * (cy - by) - (0 - by) * (cx - bx) >= 0, 1, -1)
            starts[:, 0] += np.where(a < 0, 180.0, 0.0)
            starts[:, 1] += np.where(c < 0, 180.0, 0.0)
            lengths = np.stack([np.abs(a), np.sqrt(np.abs(b2)), np.abs(c),
                                np.full_like(a, d)], axis=1)
            impossible = b2 <= 0
        else:
            k = slider_crank_closed_form(theta, out)
            r, l2, e = k[:, 0], k[:, 1], k[:, 2]
            foot = r * np.cos(theta[:, 0])
            modes = np.where(out[:, 0] - foot >= 0, 1, -1)
            starts[:, 0] += np.where(r < 0, 180.0, 0.0)
            lengths = np.stack([np.abs(r), np.sqrt(np.abs(l2)), e], axis=1)
            impossible = l2 <= 0
    singular = ~np.all(np.isfinite(lengths), axis=1)
    reasons[impossible] = "impossible length"
    reasons[singular] = "singular"
    positive = np.abs(lengths[:, :4 if task.mechanism == "four-bar" else 2])
    with np.errstate(all="ignore"):
        ratio = positive.max(axis=1) / positive.min(axis=1)
    reasons[(reasons == None) & ~(ratio <= MAX_RATIO)] = "link ratio"  # noqa: E711
    return lengths, starts, modes, reasons


def _grid_starts(task):
    """The coarse grid of starts: every input angle, with every output angle (four-bar)
    or every offset of the slide (slider crank)."""
    thetas = np.arange(0.0, 360.0, _GRID)
    outs = (np.arange(0.0, 360.0, _GRID) if task.mechanism == "four-bar"
            else _OFFSETS * abs(task.swing[1]))
    return np.array([(t, o) for t in thetas for o in outs])


def _designs_at(task, starts, rejected):
    """Three-point designs at Chebyshev's (or the task's) points for each start, the
    failures counted in ``rejected``; [(predicted, FunctionDesign)] in the grid's order."""
    xs = task.precision_x() if task.points == 3 else precision_x(task.x, 3, "chebyshev")
    lengths, starts, modes, reasons = _three_points(task, xs, starts)
    ok = reasons == None  # noqa: E711
    score, why = _scores(task, lengths[ok], starts[ok], modes[ok], task.precision_x())
    reasons[ok] = why
    for reason in reasons[reasons != None]:  # noqa: E711
        rejected[reason] += 1
    keep = np.nonzero(ok)[0][why == None]  # noqa: E711
    kept = score[why == None]  # noqa: E711
    return [FunctionDesign(task.mechanism, tuple(float(v) for v in lengths[k]),
                           (float(starts[k][0]), float(starts[k][1])), int(modes[k]),
                           float(v)) for k, v in zip(keep, kept)]


def _refine_start(task, design):
    """A three-point design with its start refined locally: grids ever finer about the
    best start so far (the points stay exact; the largest error over the range is
    made small)."""
    xs = task.precision_x()
    best = design
    step = np.array([_GRID, _GRID if task.mechanism == "four-bar"
                     else (_OFFSETS[1] - _OFFSETS[0]) * abs(task.swing[1])])
    offsets = np.linspace(-1.0, 1.0, 11)
    for _ in range(_ZOOMS):
        starts = np.array([(best.start[0] + u * step[0], best.start[1] + v * step[1])
                           for u in offsets for v in offsets])
        lengths, starts, modes, reasons = _three_points(task, xs, starts)
        ok = (reasons == None) & (modes == best.mode)  # noqa: E711
        if ok.any():
            score, _ = _scores(task, lengths[ok], starts[ok], modes[ok], xs)
            k = int(np.argmin(score))
            if score[k] < best.predicted:
                at = np.nonzero(ok)[0][k]
                best = FunctionDesign(task.mechanism, tuple(float(v) for v in lengths[at]),
                                      (float(starts[at][0]), float(starts[at][1])),
                                      best.mode, float(score[k]))
        step = step / 5
    return best


def _minimax_fit(task, seed):
    """More than three points: the lengths (and, without a task's start, the start)
    fitted so that the largest structural error over the whole range is small: the
    minimax as a smooth problem (minimise t with -t <= error(x_k) <= t at every sample,
    the transmission angle within its bounds), by SLSQP from ``seed``."""
    four = task.mechanism == "four-bar"
    scale = 1.0 if four else abs(task.swing[1])
    free_start = task.start is None
    xs = task.precision_x()
    lo, hi = min(xs[0], xs[-1]), max(xs[0], xs[-1])
    grid = np.linspace(task.x[0], task.x[1], _FITTED)
    inside = np.zeros(grid.size, dtype=bool)
    inside[::4] = True                 # the transmission angle, more coarsely
    inside &= (grid >= lo) & (grid <= hi)
    mt = task.min_transmission

    def unpack(p):
        size = [float(np.exp(np.clip(v, -30.0, 30.0))) for v in p[:3]]
        lengths: tuple[float, ...] = ((size[0], size[1], size[2], FRAME) if four else
                                      (size[0] * scale, size[1] * scale, float(p[2]) * scale))
        start = ((p[3], p[4] * scale) if free_start else task.start)
        return lengths, start

    def constraints(q):
        lengths, start = unpack(q[:-1])
        err, mu = design_error(task, task.mechanism, lengths, start, seed.mode, grid)
        err, mu = err / scale, mu[inside]
        out = np.concatenate([q[-1] - err, q[-1] + err, (mu - mt) / 90, (180 - mt - mu) / 90])
        return np.where(np.isfinite(out), out, -1.0)
    if four:
        p0 = [math.log(seed.lengths[0]), math.log(seed.lengths[1]), math.log(seed.lengths[2])]
    else:
        p0 = [math.log(seed.lengths[0] / scale), math.log(seed.lengths[1] / scale),
              seed.lengths[2] / scale]
    if free_start:
        p0 += [seed.start[0], seed.start[1] / scale]
    q0 = np.asarray(p0 + [seed.predicted / scale])
    found = minimize(lambda q: q[-1], q0, method="SLSQP",
                     jac=lambda q: np.eye(q.size)[-1],
                     constraints=[{"type": "ineq", "fun": constraints}],
                     options={"maxiter": 200, "ftol": 1e-12})
    lengths, start = unpack(found.x[:-1])
    positive = lengths[:4] if four else lengths[:2]
    score, why = _scores(task, np.asarray([lengths]), np.asarray([start]),
                         np.asarray([seed.mode]), xs)
    if why[0] is not None or max(positive) / min(positive) > MAX_RATIO \
            or not score[0] < seed.predicted:
        return seed
    return FunctionDesign(task.mechanism, tuple(float(v) for v in lengths),
                          (float(start[0]), float(start[1])), seed.mode, float(score[0]))


def _candidates(task, rejected):
    """The designs to certify, best predicted first, and how many were tried."""
    starts = (np.asarray([task.start]) if task.start is not None else _grid_starts(task))
    designs = _designs_at(task, starts, rejected)
    tried = len(starts)
    designs.sort(key=lambda dsg: dsg.predicted)
    if task.start is None:
        apart = (3 * _GRID, 3 * _GRID if task.mechanism == "four-bar"
                 else 3 * (_OFFSETS[1] - _OFFSETS[0]) * abs(task.swing[1]))
        designs = [_refine_start(task, dsg) if task.points == 3 else dsg
                   for dsg in _distinct(designs, _REFINED, apart=apart)]
    if task.points > 3:
        designs = [_minimax_fit(task, dsg) for dsg in designs[:_FITTED_SEEDS]] + designs[_FITTED_SEEDS:]
    designs.sort(key=lambda dsg: dsg.predicted)
    return [_in_solver_range(task, dsg) for dsg in _distinct(designs, None)], tried


def _in_solver_range(task, design):
    """The design with its start turned by whole turns so that the input's angle at
    the first precision point is in (-180, 180], as the drawing gives it to the solver
    (and a four-bar's output likewise)."""
    x1 = task.precision_x()[0]
    first = design.start[0] + float(task.input_at(x1))
    out = design.start[1]
    if design.kind == "four-bar":
        out -= 360.0 * math.floor((out + float(task.output_at(x1)) + 180.0) / 360.0)
    turn = 360.0 * math.floor((first + 180.0) / 360.0)
    return replace(design, start=(design.start[0] - turn, out))


def _distinct(designs, limit, *, apart=None):
    """The designs, near-repeats dropped (the same mode and lengths within 1e-3, or,
    with ``apart``, starts closer than that in degrees or in the output's units); the
    first ``limit`` of them."""
    out: list[FunctionDesign] = []
    for dsg in designs:
        if apart is not None:
            same = [o for o in out if o.mode == dsg.mode and abs(_wrap(
                o.start[0] - dsg.start[0])) < apart[0] and abs(
                (_wrap(o.start[1] - dsg.start[1]) if dsg.kind == "four-bar"
                 else o.start[1] - dsg.start[1])) < apart[1]]
        else:
            same = [o for o in out if o.mode == dsg.mode
                    and np.allclose(dsg.lengths, o.lengths, rtol=1e-3, atol=1e-9)]
        if not same:
            out.append(dsg)
        if limit is not None and len(out) == limit:
            break
    return out


# -- the mechanism, its certification and the result -----------------------------------
def _chain(task, design, table):
    """The designed mechanism drawn at the first precision point, with its task."""
    x1 = float(task.precision_x()[0])
    theta = math.radians(design.start[0] + float(task.input_at(x1)))
    err, _ = design_error(task, design.kind, design.lengths, design.start, design.mode,
                          [x1])
    out = design.start[1] + float(task.output_at(x1)) + float(err[0])
    title = f"y = {task.function.text} for {task.x[0]:g} <= x <= {task.x[1]:g}"
    if design.kind == "four-bar":
        a, b, c, d = design.lengths
        psi = math.radians(out)
        joints = (Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
                  Joint("B", "R", ("crank", "coupler"), at=(a * math.cos(theta),
                                                             a * math.sin(theta))),
                  Joint("C", "R", ("coupler", "rocker"), at=(d + c * math.cos(psi),
                                                              c * math.sin(psi))),
                  Joint("D", "R", ("rocker", "frame"), at=(d, 0.0)))
        sizes = f"crank {a:.6g}, coupler {b:.6g}, rocker {c:.6g}, frame {d:.6g}"
        output, family = "rocker", "four-bar chain"
    else:
        r, l, e = design.lengths
        joints = (Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
                  Joint("B", "R", ("crank", "rod"), at=(r * math.cos(theta),
                                                         r * math.sin(theta))),
                  Joint("C", "R", ("rod", "slider"), at=(out, e)),
                  Joint("S", "P", ("frame", "slider"), at=(out, e), axis=0.0))
        sizes = f"crank {r:.6g}, rod {l:.6g}, offset {e:.6g}"
        output, family = "slider", "single slider crank chain"
    return Chain(f"Function generator: {title}", joints, family=family, units=task.units,
                 notes=f"Designed by chaingraph (function generation, {design.kind}): "
                       f"{sizes}; drawn at the first precision point.",
                 mechanism=Mechanism("frame", "crank", 1.0, output), task=table)


def _table(task, design):
    """The chain file's [task] table: the task, with the start the solution chose."""
    table = task.to_dict()
    table["start"] = list(design.start)
    table["precision_x"] = [float(v) for v in task.precision_x()]
    return {k: v for k, v in table.items() if v is not None}


def _targets(task, design, chain):
    xs = task.precision_x()
    err, _ = design_error(task, design.kind, design.lengths, design.start, design.mode, xs)
    outputs = design.start[1] + task.output_at(xs) + err
    inputs = design.start[0] + task.input_at(xs)
    a, b = task.x

    def wanted(theta):
        x = a + (np.asarray(theta) - design.start[0]) / task.swing[0] * (b - a)
        return design.start[1] + task.output_at(x)
    return FunctionTargets(tuple(float(v) for v in inputs), tuple(float(v) for v in outputs),
                           chain.mechanism.output,
                           (design.start[0], design.start[0] + task.swing[0]), wanted)


def _names(chain):
    found = identify(chain)
    return tuple(n for n in (found.chain, found.inversion) if n)


def _solution(task, design, certified: Certified):
    theta, err = certified.curve
    a, b = task.x
    x = a + (theta - design.start[0]) / task.swing[0] * (b - a)
    unit = "degrees" if design.kind == "four-bar" else task.units
    curve = Curve(x, err, "x", f"structural error ({unit})",
                  tuple(float(v) for v in task.precision_x()))
    names = (("crank", "coupler", "rocker", "frame") if design.kind == "four-bar"
             else ("crank", "rod", "offset"))
    dimensions = dict(zip(names, design.lengths))
    dimensions.update(input_start=design.start[0], output_start=design.start[1])
    return certified.solution(names=_names(certified.chain), curve=curve,
                              dimensions=dimensions)


def function(*, function: str, x: tuple[float, float], swing: tuple[float, float],
             start: tuple[float, float] | None = None, points: int = 3,
             spacing: str = "chebyshev", kind: str = "four-bar", solutions: int = 5,
             units: str = "mm", min_transmission: float = 30.0) -> Synthesis:
    """Synthesise a function generator: a four-bar (input crank, output rocker) or a
    slider crank (input crank, output slide) whose output follows y = f(x).

    Parameters
    ----------
    function : str
        y as an expression in x: ``+ - * / **``, ``sqrt exp log log10 sin cos tan``
        (radians) and ``pi``.
    x : (float, float)
        The range A, B of x.
    swing : (float, float)
        IN, OUT: the input turns through IN degrees while x runs from A to B; the output
        turns through OUT degrees (a slide: moves OUT file units) while y runs from y(A)
        to y(B), both linearly.
    start : (float, float), optional
        The input's angle and the output's angle (a slide: its position along the
        guide) at x = A; by default searched.
    points : int
        Precision points: three are matched exactly; more are fitted over the range.
    spacing : {"chebyshev", "even"}
    kind : {"four-bar", "slider-crank"}
    solutions : int
        At most this many certified solutions, best first.
    units : str
        The chain files' length unit.
    min_transmission : float
        The transmission angle must stay within [min, 180 - min] degrees between the
        first precision point and the last.

    Returns
    -------
    Synthesis
        Certified solutions, best first (smallest largest structural error, then largest
        least transmission angle), the candidates rejected by reason, what was searched.

    Raises
    ------
    DesignError
        For a bad task (``parameter`` names it).

    Examples
    --------
    The textbooks' task, from their starting angles (a least transmission angle of
    25.8 degrees: below the default bound):

    >>> s = function(function="log10(x)", x=(1, 2), swing=(60, 90), start=(45, 135),
    ...              min_transmission=25)
    >>> best = s.solutions[0]
    >>> best.mechanism.mechanism.output, best.input, len(best.reached_at)
    ('rocker', 'rocks', 3)
    >>> [round(best.dimensions[k] / 100, 4) for k in ("crank", "coupler", "rocker")]
    [1.8509, 2.868, 1.9205]
    """
    task = function_task(function=function, x=x, swing=swing, start=start, points=points,
                         spacing=spacing, kind=kind, units=units,
                         min_transmission=min_transmission)
    check_options(solutions=solutions, min_transmission=min_transmission, units=units,
                  kind="function")
    rejected: Counter = Counter()
    designs, tried = _candidates(task, rejected)
    found: list[Solution] = []
    for design in designs[:_CERTIFIED * solutions]:
        if len(found) >= solutions:
            break
        chain = _chain(task, design, _table(task, design))
        result = certify(chain, _targets(task, design, chain),
                         min_transmission=task.min_transmission)
        if isinstance(result, Certified):
            found.append(_solution(task, design, result))
        else:
            rejected[result.reason] += 1
    return Synthesis(task, ranked(found, solutions), dict(sorted(rejected.items())),
                     Searched(1, 1, tried))


def structural_error(chain: Chain, *, steps: int = 720) -> Curve:
    """A function generator's structural error over its task's range, from its file:
    the chain (as ``design function --out`` writes it, with its ``[task]``: ``function``,
    ``x``, ``swing``, the ``start`` chosen, ``precision_x``) solved by chaingraph's
    solver over the input's swing, its output set against the task's, in the output's
    units; the precision points marked.

    Raises
    ------
    DesignError
        A chain whose ``[task]`` is not a function generator's, or is not a good task.

    Examples
    --------
    >>> from chaingraph.naming.catalog import catalog_path
    >>> import chaingraph
    >>> c = structural_error(chaingraph.load(catalog_path("log10-function-generator")))
    >>> round(float(abs(c.y).max()), 4), [round(v, 3) for v in c.marks]
    (0.0901, [1.067, 1.5, 1.933])
    """
    table = chain.task or {}
    if table.get("kind") != "function" or "start" not in table or chain.mechanism is None \
            or chain.mechanism.output is None:
        raise DesignError(f"{chain.name!r} has no function generator's [task] (kind, "
                          "function, x, swing, start) and output", kind="function",
                          parameter="task")
    task = function_task(function=table.get("function", ""), x=table.get("x", ()),
                         swing=table.get("swing", ()), start=table["start"],
                         points=int(table.get("points", 3)),   # TOML writes 3.0
                         spacing=table.get("spacing", "chebyshev"),
                         kind=table.get("mechanism", "four-bar"))
    assert task.start is not None
    t0, o0 = task.start
    motion = solve(chain, start=t0, stop=t0 + task.swing[0], steps=steps, summary=False)
    a, b = task.x
    x = a + (motion["theta"] - t0) / task.swing[0] * (b - a)
    wanted = o0 + task.output_at(x)
    got = output_values(chain, motion, chain.mechanism.output, near=float(wanted[0]))
    unit = "degrees" if task.mechanism == "four-bar" else (chain.units or "file units")
    marks = table.get("precision_x") or [float(v) for v in task.precision_x()]
    return Curve(np.asarray(x, dtype=float), np.asarray(got - wanted, dtype=float), "x",
                 f"structural error ({unit})", tuple(float(v) for v in marks))
