"""Mechanism families for path synthesis: a parametrised chain and the link that carries
the tracing point.

A family's parameters are the *drawn pose* of its chain: the position of every joint
of its template, in the template's order, then the tracing point's (x, y pairs, one row
of ``2 * (joints + 1)`` numbers per mechanism). So a similarity of the plane (the task's
own frame, :class:`~chaingraph.synthesis.optimiser.TaskFrame`) moves a mechanism by
moving its parameters as points, lengths follow from positions, the assembly mode is
the drawn one, and the input's value at the drawn pose (the first target) is read off
the drawing, as the solver reads it. A family supplies, vectorised over many mechanisms:

* :meth:`Family.positions`: where the tracing point is at given input values (NaN where
  the chain cannot be assembled), tracking the drawn assembly;
* :meth:`Family.transmission`: the transmission angle there (degrees);
* :meth:`Family.first_input`: the input's value (radians) at the drawn pose, and
  :meth:`Family.posed` the mechanisms drawn at other input values;
* :meth:`Family.sample`: random mechanisms of the family that can turn their input fully,
  about the origin at about unit size;
* :meth:`Family.chain`: one mechanism as a :class:`~chaingraph.model.chain.Chain` with
  its ``[mechanism]`` (output: the tracing point), to be certified from its file.

:class:`FourBar` is the four-bar's (closed form); a six-bar family plugs into the same
optimiser (:mod:`chaingraph.synthesis.optimiser`) by giving these six.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod

import numpy as np
import numpy.typing as npt

from chaingraph.geometry import circle_circle
from chaingraph.model.chain import Chain, Joint, Mechanism, Point

__all__ = ["Family", "FourBar", "FOUR_BAR"]


class Family(ABC):
    """A parametrised chain (see the module): ``template`` (its joints' ids and the
    links they join; positions are the parameters), ``carrier`` (the link that carries
    the tracing point ``point``), ``fixed`` and ``driver`` (the input turns about its
    joint with the fixed link)."""

    name: str
    family_name: str
    template: tuple[Joint, ...]
    carrier: str
    fixed: str
    driver: str
    point: str = "P"

    @property
    def size(self) -> int:
        """The number of parameters."""
        return 2 * (len(self.template) + 1)

    @abstractmethod
    def positions(self, params: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray,
                                                                         np.ndarray]:
        """The tracing point (x, y) of each mechanism (rows of ``params``, (M, size)) at
        input values ``theta`` (radians, (M, K)), in the drawn assembly; NaN where it
        cannot be assembled."""

    @abstractmethod
    def transmission(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The transmission angle (degrees, (M, K)) at ``theta``; NaN where unassembled."""

    @abstractmethod
    def first_input(self, params: np.ndarray) -> np.ndarray:
        """The input's value (radians, (M,)) at the drawn pose."""

    @abstractmethod
    def posed(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The same mechanisms drawn at input values ``theta`` (radians, (M,)) instead,
        in the drawn assembly (NaN where they cannot be)."""

    @abstractmethod
    def sample(self, rng: np.random.Generator, count: int) -> np.ndarray:
        """``count`` random mechanisms whose input turns fully, about the origin, their
        tracing point's path about unit size."""

    def link_ratio(self, params: np.ndarray) -> np.ndarray:
        """The longest link (the distance between two joints of one link) over the
        shortest, per mechanism ((M,))."""
        joints = np.asarray(params)[..., :-2].reshape(len(params), -1, 2)
        index = {j.id: k for k, j in enumerate(self.template)}
        spans = []
        for link in sorted({x for j in self.template for x in j.links}):
            on = [index[j.id] for j in self.template if link in j.links]
            for a in range(len(on)):
                for b in range(a + 1, len(on)):
                    spans.append(np.hypot(*(joints[:, on[a]] - joints[:, on[b]]).T))
        s = np.stack(spans, axis=1)
        with np.errstate(all="ignore"):
            return s.max(axis=1) / s.min(axis=1)

    def chain(self, params: npt.ArrayLike, *, name: str, units: str, notes: str,
              task: dict | None = None) -> Chain:
        """The mechanism of one row of parameters, drawn at its pose, its output the
        tracing point."""
        p = [float(v) for v in np.asarray(params, dtype=float)]
        joints = tuple(Joint(j.id, j.kind, j.links, at=(p[2 * k], p[2 * k + 1]))
                       for k, j in enumerate(self.template))
        return Chain(name, joints, family=self.family_name, units=units, notes=notes,
                     points=(Point(self.point, self.carrier, (p[-2], p[-1])),),
                     mechanism=Mechanism(self.fixed, self.driver, 1.0, self.point),
                     task=task)

    @abstractmethod
    def dimensions(self, params: np.ndarray) -> dict[str, float]:
        """One mechanism's lengths (and the tracing point's place on its link) by name."""


class FourBar(Family):
    """The four-bar: crank A-B about A, coupler B-C carrying the point P, rocker C-D
    about D. Parameters: A, B, C, D, P at the drawn pose (10 numbers)."""

    name = "four-bar"
    family_name = "four-bar chain"
    template = (Joint("A", "R", ("frame", "crank")), Joint("B", "R", ("crank", "coupler")),
                Joint("C", "R", ("coupler", "rocker")), Joint("D", "R", ("rocker", "frame")))
    carrier, fixed, driver = "coupler", "frame", "crank"

    @staticmethod
    def _unpack(params):
        p = np.asarray(params, dtype=float)
        a, b, c, d, pt = (p[:, 2 * k:2 * k + 2].T[..., None] for k in range(5))
        crank = np.hypot(b[0] - a[0], b[1] - a[1])
        coupler = np.hypot(c[0] - b[0], c[1] - b[1])
        rocker = np.hypot(c[0] - d[0], c[1] - d[1])
        # the drawn assembly: C left (+1) or right (-1) of the line from B to D
        mode = np.where((d[0] - b[0]) * (c[1] - b[1]) - (d[1] - b[1]) * (c[0] - b[0]) >= 0,
                        1.0, -1.0)
        with np.errstate(all="ignore"):
            ex, ey = (c[0] - b[0]) / coupler, (c[1] - b[1]) / coupler
        along = (pt[0] - b[0]) * ex + (pt[1] - b[1]) * ey
        across = -(pt[0] - b[0]) * ey + (pt[1] - b[1]) * ex
        return a, d, crank, coupler, rocker, mode, along, across

    def _joints(self, params, theta):
        a, d, crank, coupler, rocker, mode, along, across = self._unpack(params)
        theta = np.asarray(theta, dtype=float)
        bx, by = a[0] + crank * np.cos(theta), a[1] + crank * np.sin(theta)
        with np.errstate(all="ignore"):
            (mx, my), (nx, ny), raw = circle_circle((bx, by), coupler, (d[0], d[1]), rocker)
            root = mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
        cx, cy = mx + root * nx, my + root * ny
        return (bx, by), (cx, cy), d, coupler, along, across

    def positions(self, params: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray,
                                                                         np.ndarray]:
        (bx, by), (cx, cy), _, coupler, along, across = self._joints(params, theta)
        with np.errstate(all="ignore"):
            ex, ey = (cx - bx) / coupler, (cy - by) / coupler
        return bx + along * ex - across * ey, by + along * ey + across * ex

    def transmission(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        (bx, by), (cx, cy), d, _, _, _ = self._joints(params, theta)
        ux, uy, vx, vy = bx - cx, by - cy, d[0] - cx, d[1] - cy
        return np.degrees(np.arctan2(np.abs(ux * vy - uy * vx), ux * vx + uy * vy))

    def posed(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        p = np.asarray(params, dtype=float)
        th = np.asarray(theta, dtype=float)[:, None]
        (bx, by), (cx, cy), _, _, _, _ = self._joints(p, th)
        x, y = self.positions(p, th)
        return np.concatenate([p[:, 0:2], bx, by, cx, cy, p[:, 6:8], x, y], axis=1)

    def first_input(self, params: np.ndarray) -> np.ndarray:
        p = np.asarray(params, dtype=float)
        return np.arctan2(p[:, 3] - p[:, 1], p[:, 2] - p[:, 0])

    def sample(self, rng: np.random.Generator, count: int) -> np.ndarray:
        """Grashof crank-rockers (the crank the shortest link, so that it turns fully),
        in either assembly, at a random crank angle, the coupler point anywhere within
        about the coupler's length of it, turned and scaled so that the point's path is
        about unit size about the origin."""
        drawn = 4 * count + 16
        frame = np.ones(drawn)
        coupler = rng.uniform(0.3, 2.5, drawn)
        rocker = rng.uniform(0.3, 2.5, drawn)
        crank = rng.uniform(0.08, 0.8, drawn) * np.minimum(np.minimum(coupler, rocker), 1.0)
        longest = np.maximum(np.maximum(frame, coupler), rocker)
        # Grashof, the crank shortest (s + l < p + q): its input turns fully
        ok = (crank + 2 * longest < frame + coupler + rocker - 1e-3) & (longest <= 15 * crank)
        keep = np.nonzero(ok)[0][:count]
        while keep.size < count:        # (about a third pass; never in practice)
            keep = np.concatenate([keep, keep[:count - keep.size]])
        crank, coupler, rocker, frame = (v[keep] for v in (crank, coupler, rocker, frame))
        theta = rng.uniform(0.0, 2 * math.pi, count)
        mode = rng.choice([-1.0, 1.0], count)
        a = np.zeros((2, count))
        d = np.stack([frame, np.zeros(count)])
        b = a + crank * np.stack([np.cos(theta), np.sin(theta)])
        (mx, my), (nx, ny), raw = circle_circle(b, coupler, d, rocker)
        root = mode * np.sqrt(np.maximum(raw, 0.0))
        c = np.stack([mx + root * nx, my + root * ny])
        e = (c - b) / coupler
        along = rng.uniform(-0.5, 1.5, count) * coupler
        across = rng.uniform(-1.0, 1.0, count) * coupler
        pt = b + along * e + across * np.stack([-e[1], e[0]])
        params = np.concatenate([a, b, c, d, pt]).T
        return _centred_unit(self, params)

    def dimensions(self, params: np.ndarray) -> dict[str, float]:
        a, d, crank, coupler, rocker, _, along, across = self._unpack(np.atleast_2d(params))
        frame = np.hypot(d[0] - a[0], d[1] - a[1])
        return {"crank": float(crank[0, 0]), "coupler": float(coupler[0, 0]),
                "rocker": float(rocker[0, 0]), "frame": float(frame[0, 0]),
                "point along": float(along[0, 0]), "point across": float(across[0, 0])}


#: the four-bar family
FOUR_BAR = FourBar()

_CURVE = 64       # samples of the tracing point's path when sampling a family


def _centred_unit(family: Family, params: np.ndarray) -> np.ndarray:
    """Mechanisms moved and scaled so that their tracing point's path (over a turn of
    the input) is centred on the origin, its largest extent 1."""
    theta = family.first_input(params)[:, None] + np.linspace(0, 2 * math.pi, _CURVE,
                                                              endpoint=False)
    x, y = family.positions(params, theta)
    with np.errstate(all="ignore"):
        cx, cy = np.nanmean(x, axis=1), np.nanmean(y, axis=1)
        extent = np.maximum(np.nanmax(x, axis=1) - np.nanmin(x, axis=1),
                            np.nanmax(y, axis=1) - np.nanmin(y, axis=1))
    extent = np.where(np.isfinite(extent) & (extent > 0), extent, 1.0)
    pts = params.reshape(len(params), -1, 2)
    pts = (pts - np.stack([cx, cy], axis=1)[:, None, :]) / extent[:, None, None]
    return pts.reshape(len(params), -1)
