"""An inversion's animation that a reader can follow: the picture framed on the links at
one scale over every frame, over the part of the input's range around the drawn pose
where the links fill the picture.

A slide that runs far (a guide nearly parallel to a link's path, a slide without a
limit) would make the links specks in a picture fitted to its whole travel; the range
shown is then the longest run of steps about the drawn pose over which the box round
all the links over the run is at most four times the links' own size at any step, and
the page says which part is shown. The mechanism returned carries that sweep, so that its chain
file runs what is shown.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from chaingraph.drawing.mechanism import mechanism_svg
from chaingraph.drawing.scene import Scene
from chaingraph.errors import ChainGraphError, UnboundedRangeError
from chaingraph.kinematics import cycle, solve
from chaingraph.model.chain import Chain, Input
from chaingraph.model.snap import size_of

__all__ = ["Animation", "animate_inversion", "SPREAD", "STEPS_PER_FRAME"]

#: the box round the links over all the frames shown is at most this many times the
#: links' own size at any frame (the diagonal of their box): a lever turning about its
#: end sweeps twice its length, a slotted lever turning with its slot more; a slide that runs far, many times
SPREAD = 4.0
#: steps solved per frame, to choose the range shown from
STEPS_PER_FRAME = 4


@dataclass(frozen=True)
class Animation:
    """An inversion animated: ``svg`` (SMIL), the ``mechanism`` shown (with its input's
    sweep when only a part of the range is shown), ``shown`` the share of the input's
    range shown (1: all of it), ``turns`` whether the input turns fully in it, and the
    ``notes`` a page prints under it."""

    svg: str
    mechanism: Chain
    shown: float
    turns: bool
    notes: tuple[str, ...]


def animate_inversion(mechanism: Chain, *, frames: int = 24, width: int = 300) -> Animation:
    """``mechanism`` (a posed chain with one input) animated in ``frames`` frames at
    ``width`` pixels, over the part of its range where the links fill the picture (see
    the module's notes).

    Raises
    ------
    ChainGraphError
        When the mechanism cannot be solved.
    """
    steps = STEPS_PER_FRAME * frames
    units = mechanism.units or "units"
    notes = []
    try:
        motion = solve(mechanism, steps=steps, summary=False)
        full = cycle(motion.plan).full_turn
    except UnboundedRangeError:
        m = mechanism.mechanism
        item = m.inputs[0] if m is not None and m.inputs else None
        if item is None or mechanism.joint(item.joint).kind != "P":
            raise
        # a slide without a limit: a bounded part of it, the chain's size each way
        drawn = {j.id: j.at for j in mechanism.joints if j.at is not None}   # (all: solved)
        half = float(f"{size_of(drawn):.2g}")
        try:
            motion = solve(_swept(mechanism, -half, half), steps=steps, summary=False)
            mechanism = _swept(mechanism, -half, half)
            said = f"{half:g} {units} each way of the drawn pose"
        except ChainGraphError:
            # a limit the other way (the walk that found no limit went forward)
            mechanism = _swept(mechanism, 0.0, 2 * half)
            motion = solve(mechanism, steps=steps, summary=False)
            said = f"{2 * half:g} {units} on from the drawn pose"
        full = False
        notes.append(f"Its input slides without a limit: a bounded part of the slide is "
                     f"shown, {said}.")
    n = motion.theta.size - (1 if full else 0)      # a turn's last step is its first
    rows = _window(motion, mechanism, n, full)
    shown = len(rows) / n
    if shown == 1.0:
        rows = list(range(n))                  # from the drawn pose, as the file runs
    theta = np.asarray(motion.theta, dtype=float)
    period = 360.0 if full else 0.0

    def value(k):
        return float(theta[k % n] + period * (k // n))

    if shown < 1.0:
        lo, hi = value(rows[0]), value(rows[-1])
        m = mechanism.mechanism
        assert m is not None, "a mechanism solved above"
        unit = "degrees" if mechanism.joint(m.inputs[0].joint).kind == "R" else units
        whole = "a full turn" if full else \
            f"{float(theta.min()):.4g} to {float(theta.max()):.4g} {unit}"
        notes.append(f"Shown over the part of its range where the links fill the picture: "
                     f"{lo:.4g} to {hi:.4g} {unit} of {whole} (beyond it a slide runs far "
                     "out).")
        mechanism = _swept(mechanism, lo, hi)
    svg = mechanism_svg(motion, frames=frames, width=width, rows=[k % n for k in rows],
                        there_and_back=not (full and shown == 1.0), compact=True)
    return Animation(svg.split("?>", 1)[-1], mechanism, shown, full and shown == 1.0,
                     tuple(notes))


def _swept(mechanism, start, stop):
    """The mechanism with its (one) input swept from ``start`` to ``stop``."""
    m = mechanism.mechanism
    item = m.inputs[0]
    return replace(mechanism, mechanism=replace(
        m, inputs=(Input(item.joint, float(start), float(stop), item.at),)))


def _window(motion, mechanism, n, full):
    """The steps shown, in order (below 0 or from ``n`` on: round the turn again): the
    longest run about the drawn pose over which the box round the links and the guides
    they carry (each as long as its slide's travel over the run) is at most
    :data:`SPREAD` times the links' own size (their box's diagonal) at any step."""
    scene = Scene.of_motion(motion)
    names = [j.id for j in mechanism.joints] + [p.id for p in mechanism.points]
    xs = np.array([scene.xy[x][0][:n] for x in names])
    ys = np.array([scene.xy[x][1][:n] for x in names])
    box = np.stack([xs.min(axis=0), ys.min(axis=0), xs.max(axis=0), ys.max(axis=0)], axis=1)
    spans = np.hypot(box[:, 2] - box[:, 0], box[:, 3] - box[:, 1])
    # the guides on moving links: (the pair's point, its line's direction, its slide,
    # the side of the link that carries it) over the steps
    guides = [(scene.xy[j.id][0][:n], scene.xy[j.id][1][:n], np.cos(scene.angle[j.id][:n]),
               np.sin(scene.angle[j.id][:n]), scene.slide[j.id][:n],
               j.links.index(scene.pairs[j.id].carrier))
              for j in scene.slides if scene.pairs[j.id].carrier != scene.fixed]
    home = 0 if full else int(np.argmin(_distance_to_drawn(xs, ys, mechanism, names)))
    first = last = home

    def fits(a, b):
        idx = np.arange(a, b + 1) % n
        lo, hi = box[idx, :2].min(axis=0), box[idx, 2:].max(axis=0)
        for x, y, ux, uy, s, side in guides:
            sw = s[idx]
            for c in ((sw.min(), sw.max()) if side == 0 else (-sw.max(), -sw.min())):
                along = c - sw if side == 0 else np.full(sw.shape, c)
                ex, ey = x[idx] + along * ux[idx], y[idx] + along * uy[idx]
                lo = np.minimum(lo, (ex.min(), ey.min()))
                hi = np.maximum(hi, (ex.max(), ey.max()))
        return SPREAD * spans[idx].min() >= (hi - lo).max()

    while last - first + 1 < n:
        for a, b in (((first, last + 1), (first - 1, last)) if last - home <= home - first
                     else ((first - 1, last), (first, last + 1))):
            if (full or (0 <= a and b < n)) and fits(a, b):
                first, last = a, b
                break
        else:
            break
    return list(range(first, last + 1))


def _distance_to_drawn(xs, ys, mechanism, names):
    """Over the steps, how far the joints and points are from their drawn places."""
    where = mechanism.positions()
    at = np.array([where[x] for x in names])
    return ((xs - at[:, :1]) ** 2 + (ys - at[:, 1:]) ** 2).sum(axis=0)
