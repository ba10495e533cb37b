"""Balance: a four-bar's counterweights leave no shaking force (solved again); a slider
crank's primary balance leaves the secondary force of the closed form."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import chaingraph
from chaingraph import Chain, Joint, LinkMass, Load, Mechanism
from chaingraph.dynamics.balance import balance
from chaingraph.dynamics.equilibrium import UNIT_METRES
from chaingraph.errors import MechanismError
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli
from .conftest import L, R, slider_crank
from .test_shaking import centre_columns, shaking_from_columns


def crank_rocker(*, gravity=None, loads=()):
    """A Grashof crank-rocker with its masses' centres off the links' lines."""
    return Chain("crank-rocker", (
        Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
        Joint("B", "R", ("crank", "coupler"), at=(20.0, 34.641016)),
        Joint("C", "R", ("coupler", "rocker"), at=(133.880966, 72.471237)),
        Joint("D", "R", ("rocker", "frame"), at=(100.0, 0.0))),
        units="mm", mechanism=Mechanism("frame", driver="crank"), gravity=gravity,
        loads=loads,
        masses=(LinkMass("crank", 0.4, (12.0, 15.0), 2e-4),
                LinkMass("coupler", 1.1, (70.0, 70.0), 3e-3),
                LinkMass("rocker", 0.7, (110.0, 40.0), 1e-3)))


def test_the_balanced_four_bar_has_no_shaking_force_over_a_turn():
    chain = crank_rocker()
    f = chaingraph.forces(chain, steps=36, omega=20.0)
    b = balance(f)
    assert b.kind == "four-bar" and [c.link for c in b.counterweights] == ["crank", "rocker"]
    before = np.hypot(f["shaking:Fx"], f["shaking:Fy"]).max()
    assert before > 10.0                                    # it did shake
    # solved again here, the counterweights as masses on the links, and the sum of m a_G
    # taken from that motion's own columns
    again = chaingraph.forces(b.chain, steps=36, omega=20.0)
    fx, fy, _ = shaking_from_columns(b.chain, again.motion)
    assert np.abs(fx).max() <= 1e-9 * before and np.abs(fy).max() <= 1e-9 * before
    # the moving links' centre of mass stands still (positions alone, no rates)
    total = sum(m.mass for m in b.chain.masses)
    centre = sum(m.mass * np.array(centre_columns(b.chain, again.motion, m.link,
                                                  m.centre)[0]) for m in b.chain.masses)
    centre = centre / total
    assert np.ptp(centre, axis=1).max() <= 1e-12
    assert b.remaining[0] <= 1e-9 * before
    # each counterweight is its mass times radius at its radius from the frame's pivot
    for c, pivot in zip(b.counterweights, [(0.0, 0.0), (100.0, 0.0)]):
        assert math.dist(c.at, pivot) == pytest.approx(c.radius, rel=1e-12)
        assert c.mass * c.radius == pytest.approx(c.mass_radius, rel=1e-12)


def test_the_balance_leaves_the_weights_and_the_loads_alone():
    chain = crank_rocker(gravity=(0.0, -9.81), loads=(Load("coupler", "C", (50.0, 0.0)),))
    b = balance(chaingraph.forces(chain, steps=24, omega=20.0))
    again = b.result
    weight = sum(m.mass for m in b.chain.masses) * -9.81
    assert again["shaking:Fx"] == pytest.approx(np.full(25, 50.0), abs=1e-9)
    assert again["shaking:Fy"] == pytest.approx(np.full(25, weight), abs=1e-9)
    assert b.remaining[0] < 1e-9


def engine(rod_centre=0.3):
    """The shared test engine with masses, its rod's centre on the rod at
    ``rod_centre`` of the way from the crank pin."""
    bx = math.sqrt(L * L - R * R)
    g3 = (rod_centre * bx, R * (1 - rod_centre))
    return slider_crank(masses=(LinkMass("crank", 2.0, (0.0, 10.0), 1e-3),
                                LinkMass("rod", 1.5, g3, 4e-3), LinkMass("piston", 2.5)))


@pytest.mark.parametrize("fraction", [1.0, 2.0 / 3.0, 0.0])
def test_a_slider_crank_s_residual_after_primary_balance_is_the_secondary_force(fraction):
    w = 150.0
    f = chaingraph.forces(engine(), steps=48, omega=w)
    b = balance(f, fraction=fraction)
    assert b.kind == "slider crank"
    # the closed form: x = r cos t + sqrt(l^2 - r^2 sin^2 t) of the crank angle t, the
    # reciprocating mass m4 + 0.3 m3 and the balanced fraction c of it at the crank pin:
    # left are -m_r (x'' w^2 + c r w^2 cos t) along the stroke, -c m_r r w^2 sin t across
    u = UNIT_METRES["mm"]
    r, l = R * u, L * u
    m = b.result.motion
    t = np.arctan2(m["y:A"], m["x:A"])
    s, c = np.sin(t), np.cos(t)
    y = np.sqrt(l * l - r * r * s * s)
    x2 = -r * c - r * r * np.cos(2 * t) / y - r ** 4 * s * s * c * c / y ** 3
    mr = 2.5 + 0.3 * 1.5
    along = -mr * w * w * (x2 + fraction * r * c)
    across = -fraction * mr * r * w * w * s
    scale = mr * r * w * w
    assert np.abs(b.after.fx - along).max() <= 1e-9 * scale
    assert np.abs(b.after.fy - across).max() <= 1e-9 * scale
    if fraction == 1.0:                 # the secondary force: m_r w^2 r^2/l cos 2t, nearly
        secondary = mr * w * w * r * r / l * np.cos(2 * t)
        assert np.abs(b.after.fx - secondary).max() < 0.1 * np.abs(secondary).max()
    assert b.secondary == pytest.approx(np.abs(along).max(), rel=1e-9)
    assert b.transverse == pytest.approx(np.abs(across).max(), rel=1e-9, abs=1e-9 * scale)


def test_balance_refuses_what_it_does_not_balance():
    six = chaingraph.forces(chaingraph.load(catalog_path("shaper-crank-and-slotted-lever")),
                            steps=6)
    with pytest.raises(MechanismError, match="four-bar or a slider crank"):
        balance(six)
    f = chaingraph.forces(engine(), steps=6)
    with pytest.raises(MechanismError, match="between 0 and 1"):
        balance(f, fraction=1.5)
    piston = chaingraph.forces(engine(), inputs=["S"], steps=6, static=True)
    with pytest.raises(MechanismError, match="crank turning on the frame"):
        balance(piston)


def test_balance_on_the_command_line(tmp_path):
    path = catalog_path("reciprocating-engine")
    status, out, err = run_cli("forces", path, "--steps", "24", "--omega", "100", "--balance",
                               "--json")
    assert status == 0, err
    got = json.loads(out)["balance"]
    assert [c["link"] for c in got["counterweights"]] == ["crank"]
    assert set(got["remaining"]) >= {"force", "moment"}
    assert got["remaining"]["force"] < got["unbalanced"]["force"]
    status, out, err = run_cli("forces", path, "--steps", "24", "--balance")
    assert status == 0 and "counterweight on crank" in out
    status, out, err = run_cli("forces", path, "--at", "30", "--balance")
    assert status == 2 and "--balance is for a sweep" in err
    status, out, err = run_cli("forces", catalog_path("shaper-crank-and-slotted-lever"),
                               "--balance")
    assert status == 2 and len(err.strip().splitlines()) == 1
