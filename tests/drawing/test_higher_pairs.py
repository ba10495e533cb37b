"""Higher pairs in the mechanism's picture: a cam's profile turns with the cam and the
roller on its follower touches it in every frame; a gear's pitch circle stays on its
axis and its spoke turns with the gear."""

from __future__ import annotations

import math

import numpy as np

import chaingraph
from chaingraph.drawing.scene import Scene, frame_shapes
from chaingraph.kinematics.cams import analyse_cam, turn_angles


def _distance_to_polygon(p, polygon):
    """The distance from point ``p`` to the closed polygon's edges."""
    pts = np.asarray(polygon)
    a, b = pts, np.roll(pts, -1, axis=0)
    ab = b - a
    t = np.clip(np.sum((p - a) * ab, axis=1) / np.sum(ab * ab, axis=1), 0.0, 1.0)
    foot = a + t[:, None] * ab
    return float(np.min(np.hypot(*(p - foot).T)))


def test_the_roller_touches_the_turning_profile_in_every_frame():
    chain = chaingraph.load("catalog/cam-rocker.toml")
    m = chaingraph.solve(chain, steps=24)
    scene = Scene.of_motion(m)
    cam = chain.cams[0]
    profile = analyse_cam(cam, turn_angles(cam, 180)).profile   # the cam's own frame
    for k in range(m.theta.size):
        shapes = frame_shapes(scene, k)
        (outline,) = [s for s in shapes if s.cls == "cam"]
        (roller,) = [s for s in shapes if s.cls == "roller"]
        # the profile turned by the cam's turn (its centre O at the origin, drawn with
        # the follower along +y, so the cam's frame is the drawing's)
        turn = math.radians(m.theta[k] - m.theta[0])
        c, s = math.cos(turn), math.sin(turn)
        want = np.stack([c * profile[:, 0] - s * profile[:, 1],
                         s * profile[:, 0] + c * profile[:, 1]], axis=1)
        np.testing.assert_allclose(np.asarray(outline.points), want, atol=1e-9)
        # the roller: on the follower (its centre 40 + s up the line x = 0), touching
        centre = np.asarray(roller.points[0])
        np.testing.assert_allclose(centre, (0.0, 40.0 + m.slide("S").s[k]), atol=1e-9)
        assert roller.radius == cam.roller
        gap = _distance_to_polygon(centre, outline.points) - cam.roller
        assert abs(gap) < 0.02 * cam.roller        # to the profile's 180-gon
        # the follower's body reaches its roller
        bars = [sh for sh in shapes if sh.data == (("link", "follower"),) and sh.cls == "bar"]
        assert any(min(math.dist(p, centre) for p in b.points) < 1e-9 for b in bars)


def test_gears_turn_on_their_axes():
    chain = chaingraph.load("catalog/geared-five-bar.toml")
    m = chaingraph.solve(chain, start=0.0, stop=90.0, steps=6)
    scene = Scene.of_motion(m)
    for k in range(m.theta.size):
        shapes = frame_shapes(scene, k)
        circles = {s.data[0][1]: s for s in shapes if s.cls == "pitch"}
        spokes = {s.data[0][1]: s for s in shapes if s.cls == "spoke"}
        assert circles["left crank"].points[0] == (0.0, 0.0)
        assert circles["right crank"].points[0] == (100.0, 0.0)
        assert circles["left crank"].radius == circles["right crank"].radius == 50.0
        # each spoke points at the pitch point in the drawing (crank at 60 degrees),
        # turned with its gear: the left by theta - 60, the right the other way
        turn = math.radians(m.theta[k] - 60.0)
        left = np.subtract(spokes["left crank"].points[1], (0.0, 0.0))
        right = np.subtract(spokes["right crank"].points[1], (100.0, 0.0))
        np.testing.assert_allclose(left, (50 * math.cos(turn), 50 * math.sin(turn)), atol=1e-9)
        np.testing.assert_allclose(right, (-50 * math.cos(turn), 50 * math.sin(turn)),
                                   atol=1e-9)
