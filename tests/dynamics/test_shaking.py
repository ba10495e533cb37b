"""The shaking force and moment: against the sum of m a_G (plus gravity and loads) from
the motion's own columns, and against the frame's share of the reactions."""

from __future__ import annotations

import math
import random
from dataclasses import replace

import numpy as np
import pytest

import chaingraph
from chaingraph import LinkMass, Load
from chaingraph.dynamics.equilibrium import UNIT_METRES
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli


def with_masses(chain, seed):
    """The chain with masses whose centres sit anywhere near their links (off their
    lines), inertias, gravity and loads at R joints."""
    rng = random.Random(seed)
    fixed = chain.mechanism.fixed
    masses, loads = [], []
    for link in chain.links:
        pins = [j for j in chain.joints if j.kind == "R" and link in j.links]
        if link == fixed or not pins:
            continue
        j = rng.choice(pins)
        centre = (j.at[0] + rng.uniform(-30, 30), j.at[1] + rng.uniform(-30, 30))
        masses.append(LinkMass(link, rng.uniform(0.5, 3.0), centre, rng.uniform(1e-3, 5e-2)))
        if rng.random() < 0.6:
            loads.append(Load(link, j.id, (rng.uniform(-100, 100), rng.uniform(-100, 100)),
                              rng.uniform(-5, 5)))
    return replace(chain, masses=tuple(masses), loads=tuple(loads), gravity=(0.0, -9.81))


def centre_columns(chain, motion, link, centre):
    """The position (m) and acceleration (m/s^2) of a point of ``link`` drawn at
    ``centre``, from the motion's columns alone: an R joint's position and acceleration,
    the link's turn from step 0 (the drawn pose), its omega and alpha."""
    u = UNIT_METRES[chain.units]
    j = next(j for j in chain.joints if j.kind == "R" and link in j.links)
    turn = np.radians(motion[f"angle:{link}"] - motion[f"angle:{link}"][0])
    dx, dy = centre[0] - j.at[0], centre[1] - j.at[1]
    rx = (dx * np.cos(turn) - dy * np.sin(turn)) * u
    ry = (dx * np.sin(turn) + dy * np.cos(turn)) * u
    w, al = motion[f"omega:{link}"], motion[f"alpha:{link}"]
    x, y = motion[f"x:{j.id}"] * u + rx, motion[f"y:{j.id}"] * u + ry
    ax = motion[f"ax:{j.id}"] * u - al * ry - w * w * rx
    ay = motion[f"ay:{j.id}"] * u + al * rx - w * w * ry
    return (x, y), (ax, ay)


def shaking_from_columns(chain, motion, *, inertia=True, gravity=True, loads=True):
    """sum (m g + loads) - sum m a_G, and its moment about the origin (with the loads'
    torques and -I alpha), from the motion's columns alone."""
    u = UNIT_METRES[chain.units]
    g = chain.gravity or (0.0, 0.0)
    n = motion.steps + 1
    fx, fy, m = np.zeros(n), np.zeros(n), np.zeros(n)

    def add(p, f):
        nonlocal fx, fy, m
        fx, fy = fx + f[0], fy + f[1]
        m = m + p[0] * f[1] - p[1] * f[0]
    for mass in chain.masses:
        centre = mass.centre if mass.centre is not None else chaingraph.model.chain.mass_centre(
            chain, mass)
        p, a = centre_columns(chain, motion, mass.link, centre)
        if gravity:
            add(p, (mass.mass * g[0] * np.ones(n), mass.mass * g[1] * np.ones(n)))
        if inertia:
            add(p, (-mass.mass * a[0], -mass.mass * a[1]))
            m = m - mass.inertia * motion[f"alpha:{mass.link}"]
    for load in chain.loads if loads else ():
        p = (motion[f"x:{load.at}"] * u, motion[f"y:{load.at}"] * u)
        if load.force is not None:
            add(p, (load.force[0] * np.ones(n), load.force[1] * np.ones(n)))
        m = m + load.torque
    return fx, fy, m


def frame_share(f):
    """The force and moment (about the origin) the frame takes from its joints'
    reactions and the inputs' efforts: the other way to the shaking force."""
    chain, sol, plan = f.chain, f.solution, f.motion.plan
    u = UNIT_METRES[chain.units]
    ox, oy = plan.origin[0] * u, plan.origin[1] * u
    n = f.steps + 1
    fx, fy, m = np.zeros(n), np.zeros(n), np.zeros(n)

    def add(q, force, sign=1.0):
        nonlocal fx, fy, m
        gx, gy = sign * force[0], sign * force[1]
        fx, fy = fx + gx, fy + gy
        m = m + (q[0] + ox) * gy - (q[1] + oy) * gx
    for j in chain.joints:
        if plan.fixed not in j.links:
            continue
        q = sol.points[j.id]
        if (j.id, plan.fixed) in sol.forces:
            add(q, sol.forces[(j.id, plan.fixed)])
        else:                                   # the reaction on the frame's partner
            add(q, sol.forces[(j.id, j.links[0])], -1.0)
        if j.kind == "P":
            m = m + (1.0 if j.links[0] == plan.fixed else -1.0) * sol.couple[j.id]
    for item in plan.inputs:
        e = sol.efforts[item.joint]
        if item.a != plan.fixed:
            continue
        if item.kind == "R":
            m = m - e
        else:                                   # along its guide, the frame's
            axis = math.radians(chain.joint(item.joint).axis)
            add(sol.points[item.joint], (e * math.cos(axis), e * math.sin(axis)), -1.0)
    return fx, fy, m


SHAKEN = ["reciprocating-engine", "crank-rocker-with-slider", "stephenson-iii-mechanism",
          "whitworth-quick-return-with-ram", "beam-engine"]


@pytest.mark.parametrize("name", SHAKEN)
def test_the_shaking_force_is_the_weights_and_loads_minus_the_sum_of_m_a_g(name):
    chain = with_masses(chaingraph.load(catalog_path(name)), seed=len(name))
    f = chaingraph.forces(chain, steps=24, omega=7.0)
    fx, fy, m = shaking_from_columns(chain, f.motion)
    ok = np.isfinite(fx)
    assert ok.sum() >= 20
    scale = np.abs(np.concatenate([fx[ok], fy[ok]])).max() + 1.0
    size = scale * 0.5                       # a moment's scale: the force times 0.5 m
    assert np.abs(f["shaking:Fx"][ok] - fx[ok]).max() <= 1e-9 * scale
    assert np.abs(f["shaking:Fy"][ok] - fy[ok]).max() <= 1e-9 * scale
    assert np.abs(f["shaking:M"][ok] - m[ok]).max() <= 1e-9 * (size + np.abs(m[ok]).max())
    # and it is what the frame takes through its joints and the inputs' efforts
    gx, gy, gm = frame_share(f)
    good = ok & np.isfinite(gx)
    assert good.sum() >= 18
    assert np.abs(gx[good] - fx[good]).max() <= 1e-9 * scale
    assert np.abs(gy[good] - fy[good]).max() <= 1e-9 * scale
    assert np.abs(gm[good] - m[good]).max() <= 1e-9 * (size + np.abs(m[good]).max())


def test_static_shaking_is_the_weights_and_loads_and_the_summary_their_largest():
    chain = with_masses(chaingraph.load(catalog_path("reciprocating-engine")), seed=3)
    f = chaingraph.forces(chain, steps=12, static=True)
    fx, fy, m = shaking_from_columns(chain, f.motion, inertia=False)
    assert np.allclose(f["shaking:Fx"], fx, rtol=0, atol=1e-9 * np.abs(fx).max())
    assert np.allclose(f["shaking:Fy"], fy, rtol=0, atol=1e-9 * np.abs(fy).max())
    weight = sum(x.mass for x in chain.masses) * -9.81
    loads = sum(x.force[1] for x in chain.loads)
    assert f["shaking:Fy"] == pytest.approx(np.full(13, weight + loads), rel=1e-12)
    kinetic = chaingraph.forces(chain, steps=12, omega=30.0)
    s = kinetic.summary.to_dict()["shaking"]
    assert s["force"]["max"] == pytest.approx(
        np.hypot(kinetic["shaking:Fx"], kinetic["shaking:Fy"]).max(), rel=1e-12)
    assert s["moment"]["max"] == pytest.approx(np.abs(kinetic["shaking:M"]).max(), rel=1e-12)


def test_the_shaking_columns_and_summary_on_the_command_line(tmp_path):
    import json
    path = catalog_path("reciprocating-engine")
    status, out, err = run_cli("forces", path, "--steps", "12", "--csv", tmp_path / "f.csv",
                               "--json")
    assert status == 0, err
    head = (tmp_path / "f.csv").read_text().splitlines()[0].split(",")
    assert head[-3:] == ["shaking:Fx", "shaking:Fy", "shaking:M"]
    rows = np.loadtxt(tmp_path / "f.csv", delimiter=",", skiprows=1)
    summary = json.loads(out)["summary"]["shaking"]
    assert summary["force"]["max"] == pytest.approx(np.hypot(rows[:, -3], rows[:, -2]).max(),
                                                    rel=1e-9)
    status, out, err = run_cli("forces", path, "--steps", "12")
    assert status == 0 and "largest shaking force" in out and "largest shaking moment" in out
