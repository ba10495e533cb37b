"""The CSV's columns from solved poses and rates: links' angles and rates, joints' and
points' positions, velocities and accelerations, P joints' slides.
"""

from __future__ import annotations

import math

import numpy as np

from chaingraph.geometry import turn_by


# -- columns -------------------------------------------------------------------------
def _point_motion(pose, vel, acc, link, p):
    x, y = pose[link][:2]
    vx, vy, w = vel[link]
    ax, ay, al = acc[link]
    rx, ry = turn_by(pose[link], p)
    return (rx + x, ry + y, vx - w * ry, vy + w * rx,
            ax - al * ry - w * w * rx, ay + al * rx - w * w * ry)


def reference_link(joint, fixed):
    """The link whose motion a joint's CSV columns follow: a P joint's block, an R
    joint's fixed link when it has it, else its first link."""
    if joint.kind == "P":
        return joint.block
    return fixed if fixed in joint.links else joint.links[0]


def slide_rates(pose, vel, acc, joint, at):
    """A P joint's slide, its rate and acceleration; ``at`` its point in the plan's frame."""
    g, b = joint.links
    pg = _point_motion(pose, vel, acc, g, at)
    pb = _point_motion(pose, vel, acc, b, at)
    d = (pb[0] - pg[0], pb[1] - pg[1])
    dd = (pb[2] - pg[2], pb[3] - pg[3])
    ddd = (pb[4] - pg[4], pb[5] - pg[5])
    w, al = vel[g][2], acc[g][2]
    u = turn_by(pose[g], (math.cos(math.radians(joint.axis)), math.sin(math.radians(joint.axis))))
    pu = (-u[1], u[0])
    du = (w * pu[0], w * pu[1])
    ddu = (al * pu[0] - w * w * u[0], al * pu[1] - w * w * u[1])
    s = d[0] * u[0] + d[1] * u[1]
    v = dd[0] * u[0] + dd[1] * u[1] + d[0] * du[0] + d[1] * du[1]
    a = (ddd[0] * u[0] + ddd[1] * u[1] + 2 * (dd[0] * du[0] + dd[1] * du[1])
         + d[0] * ddu[0] + d[1] * ddu[1])
    return s, v, a


def _continuous_degrees(phi, n):
    """Radians (possibly a constant) to degrees along the sweep, without jumps of a
    turn, the first value in (-180, 180]."""
    if np.ndim(phi) == 0:
        return np.full(n, math.degrees(math.remainder(float(phi), 2 * math.pi)))
    step = np.diff(phi)
    step -= 2 * math.pi * np.round(step / (2 * math.pi))
    out = np.empty(n)
    out[0] = math.remainder(float(phi[0]), 2 * math.pi)
    np.cumsum(step, out=out[1:])
    out[1:] += out[0]
    return np.degrees(out)


def _array(v, n):
    return np.full(n, float(v)) if np.ndim(v) == 0 else v


def csv_columns(plan, theta, pose, vel, acc):
    chain = plan.chain
    n = theta.size
    cols = {}
    if not plan.from_driver:      # with inputs: each input's value first
        for item, value in zip(plan.inputs, plan.values(theta)):
            cols["input:" + item.joint] = np.array(np.broadcast_to(value, theta.shape), dtype=float)
    cols["theta"] = theta if plan.from_driver else np.asarray(plan.value(theta), dtype=float)
    for link in chain.links:
        direction = math.radians(chain.reference_direction(link)) + pose[link][2]
        cols[f"angle:{link}"] = _continuous_degrees(direction, n)
        cols[f"omega:{link}"] = _array(vel[link][2], n)
        cols[f"alpha:{link}"] = _array(acc[link][2], n)
    items = [(j.id, reference_link(j, plan.fixed), j.at) for j in chain.joints]
    items += [(p.id, p.link, p.at) for p in chain.points]
    ox, oy = plan.origin
    for name, link, at in items:
        if link == plan.fixed:
            values = (at[0], at[1], 0.0, 0.0, 0.0, 0.0)
        else:
            x, y, *rest = _point_motion(pose, vel, acc, link, plan.local(at))
            values = (x + ox, y + oy, *rest)
        for key, v in zip(("x", "y", "vx", "vy", "ax", "ay"), values):
            cols[f"{key}:{name}"] = _array(v, n)
    for j in chain.joints:
        if j.kind == "P":
            for key, v in zip(("s", "v", "a"), slide_rates(pose, vel, acc, j, plan.local(j.at))):
                cols[f"{key}:{j.id}"] = _array(v, n)
    return cols

