"""Drawings of a mechanism in the textbook's style, as SVG (no matplotlib, no script).

One drawing for the report, ``solve --draw`` and the notebook: fixed pivots on hatched
ground; each sliding pair as a block on its guide, the guide drawn on the link that
carries it (a hatched way on the fixed link, a slot on a moving link that reaches past
the block over the whole motion); binary links as bars, links of three or more joints as
plates; tracer points marked with their paths; every joint labelled; a scale bar in the
file's units. :func:`mechanism_svg` draws one pose, or, with ``frames``, a cycle in which
every frame is drawn the same way (SMIL, with the first frame shown without it).

The drawing is plain SVG that tests (and users) can read: each frame is a
``<g class="frame">``; a block is ``<polygon class="block" data-joint=...>``, its guide
``<line class="guide" data-joint=...>`` (the guide's centre line), a link
``<polyline class="bar">`` or ``<polygon class="plate">`` with ``data-link``.
"""

from __future__ import annotations

import html
import math

import numpy as np

__all__ = ["mechanism_svg", "frame_steps", "skeleton_svg"]

_COLOURS = ["#1f77b4", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf",
            "#bcbd22", "#ff7f0e"]


def _hull(points):
    """Convex hull of 2-D points, counter-clockwise (monotone chain)."""
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts

    def half(seq):
        out = []
        for p in seq:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                                     - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(pts), half(reversed(pts))
    return lower[:-1] + upper[:-1]


class _Scene:
    """What the drawing needs from a solved motion, in the motion's own coordinates."""

    def __init__(self, motion):
        from .kinematics.columns import _link_direction
        self.motion = motion
        self.chain = chain = motion.plan.chain
        self.fixed = motion.fixed
        n = motion.theta.size
        self.n = n
        names = [j.id for j in chain.joints] + [p.id for p in chain.points]
        self.xy = {name: (np.asarray(motion[f"x:{name}"]), np.asarray(motion[f"y:{name}"]))
                   for name in names}
        self.turn = {link: np.radians(np.asarray(motion[f"angle:{link}"])
                                      - _link_direction(chain, link)) for link in chain.links}
        finite = [np.concatenate([v[0][np.isfinite(v[0])] for v in self.xy.values()]),
                  np.concatenate([v[1][np.isfinite(v[1])] for v in self.xy.values()])]
        self.guides = {}
        for j in chain.joints:
            if j.kind == "P":
                self.guides[j.id] = self._guide_range(j)
                for k in (0, n - 1):
                    # the guide's ends, over the motion, belong in the picture too
                    for end in self.ends(j, k):
                        if all(math.isfinite(v) for v in end):
                            finite[0] = np.append(finite[0], end[0])
                            finite[1] = np.append(finite[1], end[1])
        self.lo = (float(finite[0].min()), float(finite[1].min()))
        self.hi = (float(finite[0].max()), float(finite[1].max()))
        self.span = max(self.hi[0] - self.lo[0], self.hi[1] - self.lo[1], 1e-9)
        self.pad = 0.12 * self.span
        self.w = 0.035 * self.span           # a block's half length, a slot's width

    def _carrier(self, joint):
        """Which link the guide is drawn on, and the joint the block is drawn at. The
        guide link, with the block at the P joint's reference point; but when the guide
        link is itself no more than a block on a pin (the textbook's numbering of the
        crank and slotted lever, whose "block" carries the pair's guide) the slot goes
        on the other link and the block on that pin."""
        guide, block = joint.links
        tol = 0.035 * self._extent()

        def pins(link):
            return [x for x in self.chain.joints_of(link) if x.kind == "R"]

        near = [x for x in pins(guide) if math.dist(x.at, joint.at) <= tol]
        if (guide != self.fixed and near and len(near) == len(pins(guide))
                and self.fixed not in near[0].links
                and any(math.dist(x.at, joint.at) > tol for x in pins(block))):
            return block, near[0].id
        return guide, None

    def _extent(self):
        pts = [j.at for j in self.chain.joints] + [p.at for p in self.chain.points]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        return max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)

    def _guide_range(self, joint):
        """The slot or way, as slides along the line from the P joint's reference
        point: it covers the block's whole travel and, on a moving link, that link's own
        pivots (a slot reaches its pivot). Also: the link it is on, and the pin the block
        is drawn at (None: the reference point)."""
        carrier, pin = self._carrier(joint)
        s = np.asarray(self.motion[f"s:{joint.id}"])
        s = s[np.isfinite(s)]
        travel = (-s if pin else s)
        lo, hi = (float(travel.min()), float(travel.max())) if travel.size else (0.0, 0.0)
        if carrier != self.fixed:
            u = (math.cos(math.radians(joint.axis)), math.sin(math.radians(joint.axis)))
            for other in self.chain.joints_of(carrier):
                if other.kind == "R":
                    t = (other.at[0] - joint.at[0]) * u[0] + (other.at[1] - joint.at[1]) * u[1]
                    lo, hi = min(lo, t), max(hi, t)
        margin = 0.06 * max(hi - lo, 1e-9) + 0.04 * self._extent()
        return lo - margin, hi + margin, carrier, pin

    def axis(self, joint, k):
        turn = self.turn[joint.links[0]][k]
        return math.radians(joint.axis) + (turn if np.isfinite(turn) else 0.0)

    def ends(self, joint, k):
        """The guide's two ends at step ``k``."""
        lo, hi, carrier, pin = self.guides[joint.id]
        shift = 0.0 if pin else float(self.motion[f"s:{joint.id}"][k])
        if not math.isfinite(shift):
            shift = 0.0
        return self.line_point(joint, k, lo - shift), self.line_point(joint, k, hi - shift)

    def line_point(self, joint, k, along):
        x, y = self.xy[joint.id][0][k], self.xy[joint.id][1][k]
        a = self.axis(joint, k)
        return x + along * math.cos(a), y + along * math.sin(a)

    # model -> picture coordinates (y up -> y down)
    def X(self, x):
        return x - self.lo[0] + self.pad

    def Y(self, y):
        return self.hi[1] - y + self.pad

    def pt(self, x, y):
        return f"{self.X(x):.4g},{self.Y(y):.4g}"

    @property
    def size(self):
        return (self.hi[0] - self.lo[0] + 2 * self.pad, self.hi[1] - self.lo[1] + 2 * self.pad)


def _frame(scene, k):
    """The SVG elements of the pose at step ``k``."""
    chain, w = scene.chain, scene.w
    stroke = 0.012 * scene.span
    out = []
    at = {name: (v[0][k], v[1][k]) for name, v in scene.xy.items()}
    # links: plates and bars (between their R joints and points)
    for c, link in enumerate(chain.links):
        if link == scene.fixed:
            continue
        members = [j.id for j in chain.joints_of(link) if j.kind == "R"]
        members += [p.id for p in chain.points if p.link == link]
        pts = [at[m] for m in members if all(math.isfinite(v) for v in at[m])]
        colour = _COLOURS[c % len(_COLOURS)]
        name = html.escape(link, quote=True)
        if len(pts) >= 3:
            hull = _hull([(round(x, 12), round(y, 12)) for x, y in pts])
            out.append(f'<polygon class="plate" data-link="{name}" points="'
                       + " ".join(scene.pt(*p) for p in hull)
                       + f'" fill="{colour}" fill-opacity="0.25" stroke="{colour}" '
                       f'stroke-width="{stroke:.3g}" stroke-linejoin="round"/>')
        elif len(pts) == 2:
            out.append(f'<polyline class="bar" data-link="{name}" points="'
                       + " ".join(scene.pt(*p) for p in pts)
                       + f'" fill="none" stroke="{colour}" stroke-width="{2 * stroke:.3g}" '
                       'stroke-linecap="round"/>')
    # sliding pairs: the guide on its link, the block on it
    for j in chain.joints:
        if j.kind != "P" or not all(math.isfinite(v) for v in at[j.id]):
            continue
        _, _, carrier, pin = scene.guides[j.id]
        a = scene.axis(j, k)
        u, nrm = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
        p1, p2 = scene.ends(j, k)
        jid = html.escape(j.id, quote=True)
        guide_fixed = carrier == scene.fixed
        out.append(f'<line class="guide" data-joint="{jid}" data-link="'
                   f'{html.escape(carrier, quote=True)}" x1="{scene.X(p1[0]):.4g}" '
                   f'y1="{scene.Y(p1[1]):.4g}" x2="{scene.X(p2[0]):.4g}" '
                   f'y2="{scene.Y(p2[1]):.4g}" stroke="#444444" '
                   f'stroke-width="{stroke * (1.0 if guide_fixed else 0.5):.3g}"/>')
        if guide_fixed:
            # a way on the fixed link: hatched on one side
            n_hatch = 12
            for i in range(n_hatch + 1):
                t = i / n_hatch
                bx, by = p1[0] + t * (p2[0] - p1[0]), p1[1] + t * (p2[1] - p1[1])
                bx, by = bx - 0.9 * w * nrm[0], by - 0.9 * w * nrm[1]
                ex, ey = bx - 0.5 * w * (u[0] + nrm[0]), by - 0.5 * w * (u[1] + nrm[1])
                out.append(f'<line class="hatch" x1="{scene.X(bx):.4g}" y1="{scene.Y(by):.4g}" '
                           f'x2="{scene.X(ex):.4g}" y2="{scene.Y(ey):.4g}" stroke="#777777" '
                           f'stroke-width="{stroke * 0.5:.3g}"/>')
        else:
            # a slot (or cylinder) on a moving link: two sides
            for side in (-1, 1):
                q1 = (p1[0] + side * 0.8 * w * nrm[0], p1[1] + side * 0.8 * w * nrm[1])
                q2 = (p2[0] + side * 0.8 * w * nrm[0], p2[1] + side * 0.8 * w * nrm[1])
                out.append(f'<line class="slot" data-joint="{jid}" x1="{scene.X(q1[0]):.4g}" '
                           f'y1="{scene.Y(q1[1]):.4g}" x2="{scene.X(q2[0]):.4g}" '
                           f'y2="{scene.Y(q2[1]):.4g}" stroke="#444444" '
                           f'stroke-width="{stroke:.3g}"/>')
        c = at[pin] if pin else at[j.id]
        corners = [(c[0] + du * w * u[0] + dn * 0.7 * w * nrm[0],
                    c[1] + du * w * u[1] + dn * 0.7 * w * nrm[1])
                   for du, dn in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        out.append(f'<polygon class="block" data-joint="{jid}" points="'
                   + " ".join(scene.pt(*p) for p in corners)
                   + f'" fill="#f2f2f2" stroke="#222222" stroke-width="{stroke:.3g}"/>')
    # joints: fixed pivots on hatched ground, pins as circles
    for j in chain.joints:
        if j.kind != "R" or not all(math.isfinite(v) for v in at[j.id]):
            continue
        x, y = at[j.id]
        if scene.fixed in j.links:
            tri = [(x, y), (x - 1.1 * w, y - 1.6 * w), (x + 1.1 * w, y - 1.6 * w)]
            out.append('<polygon class="ground" points="' + " ".join(scene.pt(*p) for p in tri)
                       + f'" fill="#dddddd" stroke="#222222" stroke-width="{stroke * 0.7:.3g}"/>')
            for i in range(5):
                bx = x - 1.5 * w + i * 0.75 * w
                out.append(f'<line class="hatch" x1="{scene.X(bx):.4g}" '
                           f'y1="{scene.Y(y - 1.6 * w):.4g}" x2="{scene.X(bx - 0.5 * w):.4g}" '
                           f'y2="{scene.Y(y - 2.1 * w):.4g}" stroke="#777777" '
                           f'stroke-width="{stroke * 0.5:.3g}"/>')
        out.append(f'<circle class="pin" data-joint="{html.escape(j.id, quote=True)}" '
                   f'cx="{scene.X(x):.4g}" cy="{scene.Y(y):.4g}" r="{0.45 * w:.3g}" '
                   f'fill="{"#555555" if scene.fixed in j.links else "white"}" '
                   f'stroke="#111111" stroke-width="{stroke * 0.8:.3g}"/>')
    for p in chain.points:
        x, y = at[p.id]
        if math.isfinite(x) and math.isfinite(y):
            out.append(f'<circle class="point" data-point="{html.escape(p.id, quote=True)}" '
                       f'cx="{scene.X(x):.4g}" cy="{scene.Y(y):.4g}" r="{0.3 * w:.3g}" '
                       'fill="#c00000"/>')
    # labels, legible at any size: a share of the drawing, with a white halo
    font = 0.045 * scene.span
    for name, (x, y) in at.items():
        if math.isfinite(x) and math.isfinite(y):
            out.append(f'<text class="label" x="{scene.X(x) + 0.6 * w:.4g}" '
                       f'y="{scene.Y(y) - 0.6 * w:.4g}" font-size="{font:.3g}" '
                       'font-family="sans-serif" paint-order="stroke" stroke="white" '
                       f'stroke-width="{0.25 * font:.3g}">{html.escape(name)}</text>')
    return out


def frame_steps(motion, frames):
    """The steps of the motion that an animation of ``frames`` frames shows: evenly
    over the sweep, and back again for a rocker."""
    n = motion.theta.size
    picks = [int(k) for k in np.linspace(0, n - 1, min(frames, n)).round()]
    if motion.summary and not motion.summary.get("full_turn", True):
        picks = picks + picks[::-1][1:-1]
    return picks


def mechanism_svg(motion, *, frames=None, seconds=4.0, width=640):
    """The mechanism drawn in the textbook's style, as SVG text.

    Parameters
    ----------
    motion : Motion
        A solved motion (its drawn pose, or its cycle).
    frames : int, optional
        Without it, the first pose of the motion with every point's path; with it, one
        cycle in that many frames, animated with SMIL (a rocker goes there and back).
    seconds : float
        The cycle's duration.
    width : int
        The picture's width in pixels (it scales; the coordinates are the file's).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")), steps=36)
    >>> svg = mechanism_svg(m)
    >>> svg.count('class="block"'), svg.count('class="guide"'), svg.count('class="frame"')
    (1, 1, 1)
    """
    scene = _Scene(motion)
    picks = frame_steps(motion, frames) if frames else [0]
    width_m, height_m = scene.size
    height = int(round(width * height_m / width_m))
    units = motion.units or "units"
    parts = ['<?xml version="1.0"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
             f'viewBox="0 0 {width_m:.6g} {height_m:.6g}">',
             f'<title>{html.escape(motion.name)}</title>',
             '<rect class="background" width="100%" height="100%" fill="white"/>']
    # the paths of the points (and pins) that move, faint, under everything
    for name, (xs, ys) in scene.xy.items():
        ok = np.isfinite(xs) & np.isfinite(ys)
        if ok.sum() > 1 and np.ptp(xs[ok]) + np.ptp(ys[ok]) > 1e-9 * scene.span:
            is_point = any(p.id == name for p in scene.chain.points)
            parts.append('<polyline class="path" points="'
                         + " ".join(scene.pt(x, y) for x, y in zip(xs[ok], ys[ok]))
                         + f'" fill="none" stroke="{"#e07b00" if is_point else "#bbbbbb"}" '
                         f'stroke-width="{0.004 * scene.span:.3g}"/>')
    count = len(picks)
    for i, k in enumerate(picks):
        shown = "visible" if i == 0 else "hidden"
        anim = ""
        if count > 1:
            if i == 0:
                values, times = "visible;hidden", f"0;{1 / count:.6f}"
            else:
                values, times = "hidden;visible;hidden", f"0;{i / count:.6f};{(i + 1) / count:.6f}"
            anim = (f'<animate attributeName="visibility" values="{values}" keyTimes="{times}" '
                    f'calcMode="discrete" dur="{seconds:g}s" repeatCount="indefinite"/>')
        parts.append(f'<g class="frame" data-step="{k}" visibility="{shown}">{anim}')
        parts += _frame(scene, k)
        parts.append("</g>")
    # a scale bar in the file's units
    bar = 10 ** math.floor(math.log10(scene.span / 3))
    for step in (5, 2):
        if bar * step <= scene.span / 3:
            bar *= step
            break
    x0, y0 = 0.4 * scene.pad, height_m - 0.4 * scene.pad
    parts.append(f'<g class="scale"><line x1="{x0:.4g}" y1="{y0:.4g}" x2="{x0 + bar:.4g}" '
                 f'y2="{y0:.4g}" stroke="black" stroke-width="{0.006 * scene.span:.3g}"/>'
                 f'<text x="{x0:.4g}" y="{y0 - 0.02 * scene.span:.4g}" '
                 f'font-size="{0.035 * scene.span:.3g}" font-family="sans-serif">'
                 f'{bar:g} {html.escape(units)}</text></g>')
    parts.append("</svg>")
    return "\n".join(parts)


def skeleton_svg(chain, *, width=420):
    """The kinematic skeleton of any chain, mechanism or not: its links as bars (binary)
    and plates (three or more joints) between its joints, R joints as pins, P joints as
    blocks, higher pairs as dashed rings, the fixed link (if any) on hatched ground.
    From the drawn pose when every joint has one, else from a computed layout.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.catalog import catalog_path
    >>> svg = skeleton_svg(chaingraph.load(catalog_path("stephenson-six-bar-chain")))
    >>> svg.count('class="plate"'), svg.count('class="bar"'), svg.count('class="pin"')
    (2, 4, 7)
    """
    import networkx as nx

    drawn = all(j.at is not None for j in chain.joints)
    if drawn:
        pos = {j.id: j.at for j in chain.joints}
    else:
        g = nx.Graph()
        g.add_nodes_from(j.id for j in chain.joints)
        for link in chain.links:
            ids = [j.id for j in chain.joints_of(link)]
            g.add_edges_from((a, b) for i, a in enumerate(ids) for b in ids[i + 1:])
        layout = nx.spring_layout(g, seed=7, iterations=200)
        pos = {k: (float(v[0]) * 100, float(v[1]) * 100) for k, v in layout.items()}
    xs, ys = [p[0] for p in pos.values()], [p[1] for p in pos.values()]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    pad = 0.15 * span
    w_m, h_m = max(xs) - min(xs) + 2 * pad, max(ys) - min(ys) + 2 * pad

    def pt(p):
        return f"{p[0] - min(xs) + pad:.4g},{max(ys) - p[1] + pad:.4g}"

    fixed = chain.mechanism.fixed if chain.mechanism else None
    r, stroke = 0.025 * span, 0.01 * span
    parts = ['<?xml version="1.0"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" '
             f'height="{int(round(width * h_m / w_m))}" viewBox="0 0 {w_m:.6g} {h_m:.6g}">',
             f'<title>{html.escape(chain.name)}: kinematic skeleton'
             f'{"" if drawn else " (computed layout)"}</title>',
             '<rect width="100%" height="100%" fill="white"/>']
    for c, link in enumerate(chain.links):
        ends = [pos[j.id] for j in chain.joints_of(link)]
        colour = "#444444" if link == fixed else _COLOURS[c % len(_COLOURS)]
        name = html.escape(link, quote=True)
        if len(ends) >= 3:
            hull = _hull([(round(x, 12), round(y, 12)) for x, y in ends])
            parts.append(f'<polygon class="plate" data-link="{name}" points="'
                         + " ".join(pt(p) for p in hull) + f'" fill="{colour}" '
                         f'fill-opacity="0.2" stroke="{colour}" stroke-width="{stroke:.3g}"/>')
        elif len(ends) == 2:
            parts.append(f'<polyline class="bar" data-link="{name}" points="'
                         + " ".join(pt(p) for p in ends) + f'" stroke="{colour}" '
                         f'stroke-width="{2 * stroke:.3g}" stroke-linecap="round"/>')
    for j in chain.joints:
        x, y = (float(v) for v in pt(pos[j.id]).split(","))
        jid = html.escape(j.id, quote=True)
        if fixed in j.links:
            parts.append(f'<polygon class="ground" points="{x:.4g},{y:.4g} {x - 1.4 * r:.4g},'
                         f'{y + 2 * r:.4g} {x + 1.4 * r:.4g},{y + 2 * r:.4g}" fill="#dddddd" '
                         f'stroke="#222222" stroke-width="{0.6 * stroke:.3g}"/>')
        if j.kind == "R":
            parts.append(f'<circle class="pin" data-joint="{jid}" cx="{x:.4g}" cy="{y:.4g}" '
                         f'r="{r:.3g}" fill="white" stroke="#111111" '
                         f'stroke-width="{0.8 * stroke:.3g}"/>')
        elif j.kind == "P":
            parts.append(f'<rect class="block" data-joint="{jid}" x="{x - 1.5 * r:.4g}" '
                         f'y="{y - r:.4g}" width="{3 * r:.3g}" height="{2 * r:.3g}" '
                         f'fill="#f2f2f2" stroke="#222222" stroke-width="{0.8 * stroke:.3g}"/>')
        else:
            parts.append(f'<circle class="higher" data-joint="{jid}" cx="{x:.4g}" '
                         f'cy="{y:.4g}" r="{1.3 * r:.3g}" fill="none" stroke="#b05000" '
                         f'stroke-dasharray="{stroke:.3g}" stroke-width="{0.8 * stroke:.3g}"/>')
        parts.append(f'<text x="{x + 1.2 * r:.4g}" y="{y - 1.2 * r:.4g}" '
                     f'font-size="{0.06 * span:.3g}" font-family="sans-serif" '
                     f'paint-order="stroke" stroke="white" stroke-width="{0.015 * span:.3g}">'
                     f'{html.escape(j.id)}</text>')
    parts.append("</svg>")
    return "\n".join(parts)
