"""A check shared by the kinematics tests: a mechanism solved without closed forms (its
groups by Newton's method) has the poses and rates of its closed forms."""

import numpy as np

from chaingraph.kinematics.plan import build_plan
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.tracking import evaluate


def assert_newton_agrees_with_closed_forms(chain, kinds, span, points):
    """``chain`` solved both ways over ``span`` degrees of its input in ``points``
    points: the Newton plan's steps are of ``kinds``, every point assembles, and the
    links' positions (1e-7), velocities (1e-6) and accelerations (1e-5) agree."""
    closed, newton = build_plan(chain), build_plan(chain, closed_form=False)
    assert [s.kind for s in newton.steps] == list(kinds)
    theta = closed.theta0 + np.linspace(0.0, span, points)
    e1, e2 = evaluate(closed, theta), evaluate(newton, theta)
    assert e2.feasible.all()
    v1, a1, _ = rates(closed, e1.pose, 1.5, theta.size)
    v2, a2, _ = rates(newton, e2.pose, 1.5, theta.size)
    for link in chain.links:
        for j in (0, 1):
            np.testing.assert_allclose(np.broadcast_to(e1.pose[link][j], theta.shape),
                                       np.broadcast_to(e2.pose[link][j], theta.shape),
                                       atol=1e-7)
        for j in range(3):
            np.testing.assert_allclose(v1[link][j], v2[link][j], atol=1e-6, rtol=1e-6)
            np.testing.assert_allclose(a1[link][j], a2[link][j], atol=1e-5, rtol=1e-6)
