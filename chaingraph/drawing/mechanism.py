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

import networkx as nx
import numpy as np

from chaingraph.kinematics.columns import link_direction

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


def _area(polygon):
    """The area of a simple polygon (shoelace)."""
    return 0.5 * abs(sum(p[0] * q[1] - q[0] * p[1]
                         for p, q in zip(polygon, polygon[1:] + polygon[:1])))


class _Pair:
    """How one sliding pair is drawn: the link that carries the guide and the guide's
    style (a hatched ``way`` on the fixed link, a ``slot`` in a moving link, the barrel
    of a ``cylinder``), the guide's extent in line coordinates on that link (slides from
    the joint's reference point in the drawn pose), and where the block sits on the
    other link: on a pin (``pin``), else at line coordinate ``at``."""

    def __init__(self, carrier, block_link, style, extent, *, pin=None, at=0.0, cap=None):
        self.carrier, self.block_link, self.style = carrier, block_link, style
        self.lo, self.hi = extent
        self.pin, self.at = pin, at
        self.cap = cap                     # a barrel's closed end: "lo" or "hi"


class _Scene:
    """What the drawing needs from a solved motion, in the motion's own coordinates."""

    def __init__(self, motion):
        self.motion = motion
        self.chain = chain = motion.plan.chain
        self.fixed = motion.fixed
        self.n = motion.theta.size
        names = [j.id for j in chain.joints] + [p.id for p in chain.points]
        self.xy = {name: (np.asarray(motion[f"x:{name}"]), np.asarray(motion[f"y:{name}"]))
                   for name in names}
        turn = {link: np.radians(np.asarray(motion[f"angle:{link}"])
                                 - link_direction(chain, link)) for link in chain.links}
        self.slides = [j for j in chain.joints if j.kind == "P"]
        self.angle, self.slide, self.pairs, self.ends, self.blocks = {}, {}, {}, {}, {}
        for j in self.slides:
            t = turn[j.links[0]]
            self.angle[j.id] = math.radians(j.axis) + np.where(np.isfinite(t), t, 0.0)
            s = np.asarray(motion[f"s:{j.id}"], dtype=float)
            self.slide[j.id] = np.where(np.isfinite(s), s, 0.0)
            pair = self.pairs[j.id] = self._pair(j, s[np.isfinite(s)])
            side = j.links.index(pair.carrier)
            self.ends[j.id] = (self.on_line(j, side, pair.lo), self.on_line(j, side, pair.hi))
            self.blocks[j.id] = (self.xy[pair.pin] if pair.pin else
                                 self.on_line(j, j.links.index(pair.block_link), pair.at))
        xs = [v[0] for v in self.xy.values()] + [e[0] for p in self.ends.values() for e in p]
        ys = [v[1] for v in self.xy.values()] + [e[1] for p in self.ends.values() for e in p]
        xs, ys = np.concatenate(xs), np.concatenate(ys)
        xs, ys = xs[np.isfinite(xs)], ys[np.isfinite(ys)]
        self.lo = (float(xs.min()), float(ys.min()))
        self.hi = (float(xs.max()), float(ys.max()))
        self.span = max(self.hi[0] - self.lo[0], self.hi[1] - self.lo[1], 1e-9)
        self.pad = 0.12 * self.span
        self.w = 0.035 * self.span           # a block's half length, a slot's width

    def on_line(self, joint, side, along):
        """Over the motion, the point at line coordinate ``along`` on the pair's link
        ``joint.links[side]`` (the joint's reference point moves with the second link;
        the first sees it slide by ``s``)."""
        x, y = self.xy[joint.id]
        a = self.angle[joint.id]
        c = along - self.slide[joint.id] if side == 0 else along
        return x + c * np.cos(a), y + c * np.sin(a)

    def _pair(self, joint, s):
        """Which link carries the guide, in what style, over what extent.

        A way on the fixed link. Between moving links: a slot in the link that reaches
        past a block on a pin (the textbook numbers the crank and slotted lever so that
        the small block carries the pair's guide; the slot still goes on the lever); but
        a block on a pin to the frame is a trunnion, drawn as an oscillating cylinder
        with the other link's rod and piston in it; a pair whose two links both reach
        away from it, the second from one side only, is a cylinder and its rod."""
        chain, fixed = self.chain, self.fixed
        s = s if s.size else np.zeros(1)
        pts = [x.at for x in chain.joints] + [p.at for p in chain.points]
        extent = max(max(p[0] for p in pts) - min(p[0] for p in pts),
                     max(p[1] for p in pts) - min(p[1] for p in pts), 1e-9)
        tol = 0.035 * extent
        u = (math.cos(math.radians(joint.axis)), math.sin(math.radians(joint.axis)))

        def coord(p):
            return (p[0] - joint.at[0]) * u[0] + (p[1] - joint.at[1]) * u[1]

        def pins(link):
            return [x for x in chain.joints_of(link) if x.kind == "R"]

        def on_pin(link):
            p = pins(link)
            if link != fixed and p and all(math.dist(x.at, joint.at) <= tol for x in p):
                return p[0]
            return None

        def across(c, side):
            """Line coordinate ``c`` on link ``side``, seen from the other link."""
            return c + s if side == 1 else c - s

        def padded(values, extra):
            values = np.concatenate([np.atleast_1d(np.asarray(v, dtype=float)) for v in values])
            lo, hi = float(values.min()), float(values.max())
            margin = 0.06 * (hi - lo) + extra
            return lo - margin, hi + margin

        links = joint.links
        if fixed in links:
            side = 1 - links.index(fixed)
            pin = on_pin(links[side])
            at = coord(pin.at) if pin else 0.0
            return _Pair(fixed, links[side], "way", padded([across(at, side)], 0.04 * extent),
                         pin=pin.id if pin else None, at=at)
        held = [side for side in (0, 1) if on_pin(links[side])]
        if len(held) == 1:
            side = held[0]
            pin, other = on_pin(links[side]), 1 - side
            at = coord(pin.at)
            if fixed in pin.links and pins(links[other]):
                # a trunnion: the block's link is the cylinder, the other link its rod,
                # with the piston at the rod's end beyond the trunnion's whole travel
                travel = across(at, side)
                rod = [coord(x.at) for x in pins(links[other])]
                gap = 0.1 * float(np.ptp(travel)) + 2 * tol
                ahead = np.mean(rod) <= 0.5 * (travel.min() + travel.max())
                end = float(travel.max() + gap if ahead else travel.min() - gap)
                piston = across(end, other)
                entry = np.mean([across(c, other).mean() for c in rod])
                return _Pair(links[side], links[other], "cylinder",
                             padded([piston, at], 1.2 * tol), at=end,
                             cap="hi" if entry < piston.mean() else "lo")
            return _Pair(links[other], links[side], "slot",
                         padded([across(at, side)] + [coord(x.at) for x in pins(links[other])],
                                0.04 * extent), pin=pin.id, at=at)
        travel = across(0.0, 1)                      # the second link's reference point
        rod = [coord(x.at) for x in pins(links[1])]
        reach = [coord(x.at) for x in pins(links[0])]
        if rod and (all(c > tol for c in rod) or all(c < -tol for c in rod)):
            return _Pair(links[0], links[1], "cylinder", padded([travel] + reach, 1.2 * tol),
                         cap="lo" if rod[0] > 0 else "hi")
        return _Pair(links[0], links[1], "slot", padded([travel] + reach, 0.04 * extent))

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


def _finite(*points):
    return all(math.isfinite(v) for p in points for v in p)


def _line(scene, cls, p, q, colour, width, extra=""):
    return (f'<line class="{cls}"{extra} x1="{scene.X(p[0]):.4g}" y1="{scene.Y(p[1]):.4g}" '
            f'x2="{scene.X(q[0]):.4g}" y2="{scene.Y(q[1]):.4g}" stroke="{colour}" '
            f'stroke-width="{width:.3g}"/>')


def _frame(scene, k):
    """The SVG elements of the pose at step ``k``."""
    chain, w = scene.chain, scene.w
    stroke = 0.012 * scene.span
    out = []
    at = {name: (v[0][k], v[1][k]) for name, v in scene.xy.items()}
    ends = {j: ((e1[0][k], e1[1][k]), (e2[0][k], e2[1][k])) for j, (e1, e2) in scene.ends.items()}
    blocks = {j: (b[0][k], b[1][k]) for j, b in scene.blocks.items()}
    # what a link's body joins besides its pins and points: a rod reaches its piston;
    # a link with fewer than two pins and points (a yoke, Oldham's disc) joins its
    # blocks and the middles of its slots
    rods, spare = {}, {}
    for jid, pair in scene.pairs.items():
        if pair.style == "cylinder":
            rods.setdefault(pair.block_link, []).append(blocks[jid])
        elif pair.pin is None:
            spare.setdefault(pair.block_link, []).append(blocks[jid])
        if pair.style == "slot":
            (x1, y1), (x2, y2) = ends[jid]
            spare.setdefault(pair.carrier, []).append((0.5 * (x1 + x2), 0.5 * (y1 + y2)))
    # links: plates and bars (between their R joints and points)
    for c, link in enumerate(chain.links):
        if link == scene.fixed:
            continue
        members = [at[j.id] for j in chain.joints_of(link) if j.kind == "R"]
        members += [at[p.id] for p in chain.points if p.link == link]
        members += rods.get(link, [])
        if len(members) < 2:
            members += spare.get(link, [])
        pts = [p for p in members if _finite(p)]
        colour = _COLOURS[c % len(_COLOURS)]
        name = html.escape(link, quote=True)
        hull = _hull([(round(x, 12), round(y, 12)) for x, y in pts])
        if len(hull) >= 3 and _area(hull) <= 1e-6 * scene.span ** 2:
            # points in one line (a rod through its pin and point to its piston): a bar
            hull = max(((p, q) for p in hull for q in hull), key=lambda e: math.dist(*e))
        if len(hull) >= 3:
            out.append(f'<polygon class="plate" data-link="{name}" points="'
                       + " ".join(scene.pt(*p) for p in hull)
                       + f'" fill="{colour}" fill-opacity="0.25" stroke="{colour}" '
                       f'stroke-width="{stroke:.3g}" stroke-linejoin="round"/>')
        elif len(hull) == 2:
            out.append(f'<polyline class="bar" data-link="{name}" points="'
                       + " ".join(scene.pt(*p) for p in hull)
                       + f'" fill="none" stroke="{colour}" stroke-width="{2 * stroke:.3g}" '
                       'stroke-linecap="round"/>')
    # sliding pairs: the guide on its link, the block on it
    for j in scene.slides:
        pair = scene.pairs[j.id]
        p1, p2 = ends[j.id]
        centre = blocks[j.id]
        if not _finite(p1, p2, centre):
            continue
        a = float(scene.angle[j.id][k])
        u, nrm = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
        jid = html.escape(j.id, quote=True)
        tag = f' data-joint="{jid}" data-link="{html.escape(pair.carrier, quote=True)}"'

        def off(p, d):
            return (p[0] + d * nrm[0], p[1] + d * nrm[1])

        if pair.style == "way":
            # a way on the fixed link: hatched on one side
            out.append(_line(scene, "guide", p1, p2, "#444444", stroke, tag))
            for i in range(13):
                t = i / 12
                b = off((p1[0] + t * (p2[0] - p1[0]), p1[1] + t * (p2[1] - p1[1])), -0.9 * w)
                e = (b[0] - 0.5 * w * (u[0] + nrm[0]), b[1] - 0.5 * w * (u[1] + nrm[1]))
                out.append(_line(scene, "hatch", b, e, "#777777", 0.5 * stroke))
        elif pair.style == "slot":
            # a slot in a moving link: two sides about its centre line
            out.append(_line(scene, "guide", p1, p2, "#444444", 0.5 * stroke, tag))
            for side in (-1, 1):
                out.append(_line(scene, "slot", off(p1, side * 0.8 * w), off(p2, side * 0.8 * w),
                                 "#444444", stroke, f' data-joint="{jid}"'))
        else:
            # a cylinder: the barrel, closed at one end, about a dash-dot centre line
            out.append(_line(scene, "guide", p1, p2, "#888888", 0.4 * stroke,
                             tag + f' stroke-dasharray="{2 * stroke:.3g} {stroke:.3g} '
                             f'{0.5 * stroke:.3g} {stroke:.3g}"'))
            shut, open_ = (p1, p2) if pair.cap == "lo" else (p2, p1)
            wall = [off(open_, -0.9 * w), off(shut, -0.9 * w), off(shut, 0.9 * w),
                    off(open_, 0.9 * w)]
            out.append(f'<polyline class="barrel"{tag} points="'
                       + " ".join(scene.pt(*p) for p in wall)
                       + f'" fill="none" stroke="#333333" '
                       f'stroke-width="{stroke:.3g}" stroke-linejoin="round"/>')
        half = (0.6 * w, 0.85 * w) if pair.style == "cylinder" else (w, 0.7 * w)
        corners = [(centre[0] + du * half[0] * u[0] + dn * half[1] * nrm[0],
                    centre[1] + du * half[0] * u[1] + dn * half[1] * nrm[1])
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
    # (names at one place, such as a pen on a pin, are stacked, not overprinted)
    font = 0.045 * scene.span
    placed = []
    for name, (x, y) in at.items():
        if math.isfinite(x) and math.isfinite(y):
            lift = 1.1 * font * sum(math.dist((x, y), p) < 0.5 * w for p in placed)
            placed.append((x, y))
            out.append(f'<text class="label" x="{scene.X(x) + 0.6 * w:.4g}" '
                       f'y="{scene.Y(y) - 0.6 * w - lift:.4g}" font-size="{font:.3g}" '
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


def mechanism_svg(motion, *, frames=None, seconds=4.0, width=640, paths=True):
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
    paths : bool
        Draw the paths of the moving joints and points (not for a motion whose rows
        are not one path, such as a grid over two inputs).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
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
    for name, (xs, ys) in scene.xy.items() if paths else ():
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
    blocks on their guides, higher pairs as dashed rings; the fixed link (if any) is the
    ground: hatched pivots and ways, not a body. Pins are drawn over blocks.
    From the drawn pose when every joint has one, else from a computed layout.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> svg = skeleton_svg(chaingraph.load(catalog_path("stephenson-six-bar-chain")))
    >>> svg.count('class="plate"'), svg.count('class="bar"'), svg.count('class="pin"')
    (2, 4, 7)
    """

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
    colours = {link: _COLOURS[c % len(_COLOURS)] for c, link in enumerate(chain.links)}
    # the moving links as plates and bars; the fixed link is the ground, drawn at its
    # joints (hatched pivots, ways for its slots), never as a moving body
    for link in chain.links:
        if link == fixed:
            continue
        ends = [pos[j.id] for j in chain.joints_of(link)]
        colour, name = colours[link], html.escape(link, quote=True)
        if len(ends) >= 3:
            hull = _hull([(round(x, 12), round(y, 12)) for x, y in ends])
            parts.append(f'<polygon class="plate" data-link="{name}" points="'
                         + " ".join(pt(p) for p in hull) + f'" fill="{colour}" '
                         f'fill-opacity="0.2" stroke="{colour}" stroke-width="{stroke:.3g}"/>')
        elif len(ends) == 2:
            parts.append(f'<polyline class="bar" data-link="{name}" points="'
                         + " ".join(pt(p) for p in ends) + f'" stroke="{colour}" '
                         f'stroke-width="{2 * stroke:.3g}" stroke-linecap="round"/>')
    where = {j.id: tuple(float(v) for v in pt(pos[j.id]).split(",")) for j in chain.joints}
    # sliding pairs: the guide along the axis on the link that carries it (a hatched
    # way on the ground), the block across it; under the pins, which stay in sight
    for j in chain.joints:
        if j.kind != "P":
            continue
        x, y = where[j.id]
        turn = -(j.axis if drawn and j.axis is not None else 0.0)   # SVG's y points down
        jid = html.escape(j.id, quote=True)
        on_ground = j.guide == fixed
        colour = "#222222" if on_ground else colours[j.guide]
        parts.append(f'<g class="guide" data-joint="{jid}" '
                     f'transform="translate({x:.4g},{y:.4g}) rotate({turn:.4g})">'
                     f'<line x1="{-4 * r:.4g}" y1="{r:.4g}" x2="{4 * r:.4g}" y2="{r:.4g}" '
                     f'stroke="{colour}" stroke-width="{0.8 * stroke:.3g}"/>'
                     + ("".join(f'<line x1="{t * r:.4g}" y1="{r:.4g}" x2="{(t - 0.6) * r:.4g}" '
                                f'y2="{1.7 * r:.4g}" stroke="#222222" '
                                f'stroke-width="{0.5 * stroke:.3g}"/>'
                                for t in range(-4, 5, 2)) if on_ground else
                        f'<line x1="{-4 * r:.4g}" y1="{-r:.4g}" x2="{4 * r:.4g}" '
                        f'y2="{-r:.4g}" stroke="{colour}" stroke-width="{0.8 * stroke:.3g}"/>')
                     + f'<rect class="block" x="{-1.5 * r:.4g}" y="{-r:.4g}" '
                     f'width="{3 * r:.3g}" height="{2 * r:.3g}" fill="#f2f2f2" '
                     f'stroke="#222222" stroke-width="{0.8 * stroke:.3g}"/></g>')
    for j in chain.joints:
        x, y = where[j.id]
        jid = html.escape(j.id, quote=True)
        if j.kind == "R" and fixed in j.links:
            parts.append(f'<polygon class="ground" points="{x:.4g},{y:.4g} {x - 1.4 * r:.4g},'
                         f'{y + 2 * r:.4g} {x + 1.4 * r:.4g},{y + 2 * r:.4g}" fill="#dddddd" '
                         f'stroke="#222222" stroke-width="{0.6 * stroke:.3g}"/>')
        if j.kind == "R":
            parts.append(f'<circle class="pin" data-joint="{jid}" cx="{x:.4g}" cy="{y:.4g}" '
                         f'r="{r:.3g}" fill="white" stroke="#111111" '
                         f'stroke-width="{0.8 * stroke:.3g}"/>')
        elif j.kind != "P":
            parts.append(f'<circle class="higher" data-joint="{jid}" cx="{x:.4g}" '
                         f'cy="{y:.4g}" r="{1.3 * r:.3g}" fill="none" stroke="#b05000" '
                         f'stroke-dasharray="{stroke:.3g}" stroke-width="{0.8 * stroke:.3g}"/>')
        parts.append(f'<text x="{x + 1.2 * r:.4g}" y="{y - 1.2 * r:.4g}" '
                     f'font-size="{0.06 * span:.3g}" font-family="sans-serif" '
                     f'paint-order="stroke" stroke="white" stroke-width="{0.015 * span:.3g}">'
                     f'{html.escape(j.id)}</text>')
    parts.append("</svg>")
    return "\n".join(parts)
