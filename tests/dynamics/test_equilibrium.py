"""The equilibrium's friction signs where they are hard: a guide whose friction locks
the mechanism (the signs never settle), and two guides with friction at once."""

from __future__ import annotations

import math

import pytest

import chaingraph
from chaingraph import Chain, Input, Joint, LinkMass, Load, Mechanism

from .conftest import L, R, slider_crank

LOCKS = "the friction locks the mechanism"


def engine(mu):
    """The shared test engine, a 1 kN load on its piston towards the crank, friction
    ``mu`` at the piston's guide."""
    return slider_crank(Load("piston", "B", (-1000.0, 0.0)), friction=mu)


def piston_by_hand(theta, mu):
    """The rod's thrust C and the guide's normal force Ny from the piston's equilibrium
    (C along the rod, the load, Ny, friction mu |Ny| against the sliding), for each
    sign of Ny that is consistent with the Ny it gives: [(C, Ny)], empty when neither
    is (the friction locks)."""
    t = math.radians(theta)
    r, l = R / 1000, L / 1000
    ax, ay = r * math.cos(t), r * math.sin(t)
    ux, uy = math.sqrt(l * l - ay * ay) / l, -ay / l
    v = -r * math.sin(t) - r * r * math.sin(t) * math.cos(t) / math.sqrt(l * l - ay * ay)
    s = math.copysign(1.0, v)
    found = []
    for sign in (1.0, -1.0):                # |Ny| = sign Ny, Ny = -C uy
        c = 1000.0 / (ux + mu * s * sign * uy)
        ny = -c * uy
        if ny * sign >= 0:
            found.append((c, ny, (ax, ay), (ux, uy)))
    return found


@pytest.mark.parametrize("theta", [30.0, 60.0, 90.0, 120.0, 240.0, 270.0, 300.0])
def test_a_guide_whose_friction_locks_is_said_to_lock_where_no_sign_holds(theta):
    """mu = 5 > 1 / tan(phi) near the crank's quarter turns: on one stroke both signs
    of the normal force hold (the first is taken), on the other neither does."""
    mu = 5.0
    f = chaingraph.forces(engine(mu), at=theta, static=True)
    by_hand = piston_by_hand(theta, mu)
    if not by_hand:
        assert any(LOCKS in n for n in f.notes)
        assert f.effort() is None and f.power_balance is None
        return
    assert not f.notes
    # the crank holds the rod's push; where both signs hold, the solve gives one of them
    answers = [(-(ax * (-c * uy) - ay * (-c * ux)), abs(ny))
               for c, ny, (ax, ay), (ux, uy) in by_hand]
    assert any(f.effort() == pytest.approx(effort, rel=1e-9)
               and abs(f.reaction("S").normal) == pytest.approx(normal, rel=1e-9)
               for effort, normal in answers)
    assert f.power_balance == pytest.approx(0.0, abs=1e-9)


def test_the_engine_locks_on_one_stroke_only():
    """The hand's verdict itself: locking happens, and only where the rod leans so far
    that mu tan(phi) > 1."""
    mu = 5.0
    locked = [theta for theta in range(0, 360, 15) if not piston_by_hand(theta, mu)]
    assert locked
    for theta in locked:
        phi = math.asin(R * math.sin(math.radians(theta)) / L)
        assert mu * abs(math.tan(phi)) > 1.0


def trammel(mu):
    """Two blocks on perpendicular guides joined by a rod of 100 mm, friction ``mu`` on
    both guides, a load and the rod's weight; the lower block slides as the input."""
    return Chain("trammel", (
        Joint("A", "R", ("s1", "rod"), at=(60.0, 0.0)),
        Joint("B", "R", ("rod", "s2"), at=(0.0, 80.0)),
        Joint("P", "P", ("frame", "s1"), at=(60.0, 0.0), axis=0.0, friction=mu),
        Joint("Q", "P", ("frame", "s2"), at=(0.0, 80.0), axis=90.0, friction=mu)),
        units="mm", mechanism=Mechanism("frame", inputs=(Input("P", -150.0, 30.0),)),
        loads=(Load("s2", "B", (30.0, -1000.0)),),
        masses=(LinkMass("rod", 2.0, None, 0.01),), gravity=(0.0, -9.81))


@pytest.mark.parametrize("mu", [0.2, 2.0])
def test_two_guides_with_friction_balance_power_wherever_they_do_not_lock(mu):
    """Friction on both guides: wherever the solve gives an answer, each guide's force
    along it is mu |N| and the power balances (so each friction opposes its slide);
    with mu = 2 some poses lock, and they are said to."""
    locked = 0
    for at in (-140.0, -110.0, -80.0, -50.0, -20.0, 10.0):
        f = chaingraph.forces(trammel(mu), at=at, static=True)
        if any(LOCKS in n for n in f.notes):
            locked += 1
            assert f.effort() is None
            continue
        assert f.power_balance == pytest.approx(0.0, abs=1e-6 * abs(f.effort()))
        for joint, along in (("P", 0), ("Q", 1)):
            r = f.reaction(joint)
            assert abs(r.force[along]) == pytest.approx(mu * abs(r.normal), rel=1e-9)
    assert (locked > 0) == (mu > 1.0)
