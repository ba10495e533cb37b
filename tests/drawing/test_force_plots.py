"""The turning-moment diagram over the cycle with its energy loops, and the polar
diagram of the shaking force."""

from __future__ import annotations

import math

import numpy as np
import pytest

import chaingraph
from chaingraph import Chain, Joint, LinkMass, Load, Mechanism
from chaingraph.drawing.forces import (
    closed_cycle,
    cycle_of,
    energy_lobes,
    plot_shaking,
    plot_turning_moment,
)
from chaingraph.dynamics.balance import balance
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli
from ..dynamics.test_balance import crank_rocker


def engine(torque):
    """A slider crank drawn at 60 degrees whose crank carries a steady ``torque``."""
    r, l = 50.0, 200.0
    ax, ay = r * math.cos(math.radians(60)), r * math.sin(math.radians(60))
    bx = ax + math.sqrt(l * l - ay * ay)
    return Chain("engine", (
        Joint("O", "R", ("frame", "crank"), at=(0.0, 0.0)),
        Joint("A", "R", ("crank", "rod"), at=(ax, ay)),
        Joint("B", "R", ("rod", "piston"), at=(bx, 0.0)),
        Joint("S", "P", ("frame", "piston"), at=(bx, 0.0), axis=0.0)),
        units="mm", mechanism=Mechanism("frame", driver="crank"),
        masses=(LinkMass("rod", 1.0), LinkMass("piston", 2.0)),
        loads=(Load("crank", None, None, torque),))


def test_the_sweep_is_laid_over_its_cycle_from_zero():
    f = chaingraph.forces(engine(5.0), steps=36, omega=50.0)
    theta = np.asarray(f["theta"])
    assert theta[0] == pytest.approx(60.0)
    x, order, cycle = cycle_of(f)
    assert cycle == 360.0 and x[0] == pytest.approx(0.0, abs=1e-6)
    assert x[-1] == pytest.approx(360.0) and np.all(np.diff(x) > 0)
    assert np.allclose(np.mod(theta[order], 360.0)[:-1], x[:-1])


def test_the_cycle_is_closed_at_zero_and_its_end():
    x = np.array([10.0, 130.0, 250.0, 370.0])            # a sweep from 10 degrees, wrapped
    v = np.array([1.0, 2.0, 3.0, 1.0])
    xs, vs = closed_cycle(x, v, 360.0)
    assert list(xs) == [0.0, 10.0, 130.0, 250.0, 360.0]
    # between 250 (3.0) and 370 (1.0): at 360, 3 - 2 x 110/120
    assert vs[0] == vs[-1] == pytest.approx(3.0 - 2.0 * 110.0 / 120.0)


def test_the_energy_loops_of_a_sine_about_its_mean():
    x = np.linspace(0.0, 360.0, 721)
    t = 10.0 * np.sin(np.radians(x)) + 3.0
    lobes = energy_lobes(x, t, 3.0)
    assert [round(a) for a, _, _ in lobes] == [0, 180]
    assert [e for _, _, e in lobes] == pytest.approx([20.0, -20.0], rel=1e-5)


def test_an_engine_s_diagram_is_the_turning_moment_it_delivers():
    f = chaingraph.forces(engine(5.0), steps=72, omega=50.0)
    assert f.summary.efforts["O"].mean == pytest.approx(-5.0, rel=1e-9)
    fig = plot_turning_moment(f)
    line = fig.axes[0].lines[0]
    _, order, _ = cycle_of(f)
    assert np.allclose(line.get_ydata()[1:-1], -np.asarray(f["effort:O"])[order][:-1])
    assert "delivered" in line.get_label()
    assert fig.axes[0].get_xlim() == (0.0, 360.0)
    # the loops marked add up to nothing over the cycle, the largest swing is the summary's
    x = line.get_xdata()
    lobes = energy_lobes(x, line.get_ydata(), 5.0)
    swing = f.summary.energy_fluctuation
    assert sum(e for _, _, e in lobes) == pytest.approx(0.0, abs=1e-9 * swing)
    # the loops end where the curve crosses the mean, found between the rows; the
    # summary's swing (today) takes its extremes on the rows: 72 steps, within 0.5 %
    work = np.cumsum([0.0] + [e for _, _, e in lobes])
    assert np.ptp(work) == pytest.approx(swing, rel=5e-3)
    texts = [t.get_text() for t in fig.axes[0].texts if t.get_text().endswith(" J")]
    assert len(texts) >= 2
    driven = plot_turning_moment(chaingraph.forces(engine(-5.0), steps=72, omega=50.0))
    assert "to drive it" in driven.axes[0].lines[0].get_label()


def test_the_polar_diagram_is_the_tip_of_the_shaking_force(tmp_path):
    f = chaingraph.forces(chaingraph.load(catalog_path("reciprocating-engine")), steps=72,
                          omega=100.0)
    fig = plot_shaking(f)
    line = fig.axes[0].lines[0]
    _, order, _ = cycle_of(f)
    assert np.allclose(line.get_xdata()[1:-1], f["shaking:Fx"][order][:-1])
    assert np.allclose(line.get_ydata()[1:-1], f["shaking:Fy"][order][:-1])
    status, out, err = run_cli("forces", catalog_path("reciprocating-engine"), "--steps", "36",
                               "--polar", tmp_path / "p.svg")
    assert status == 0, err
    assert "<svg" in (tmp_path / "p.svg").read_text()
    status, out, err = run_cli("forces", catalog_path("reciprocating-engine"), "--at", "30",
                               "--polar", tmp_path / "q.svg")
    assert status == 2 and "--polar is for a sweep" in err


def test_the_polar_diagram_of_a_balanced_four_bar_draws_both():
    f = chaingraph.forces(crank_rocker(), steps=72, omega=20.0)
    b = balance(f)
    fig = plot_shaking(f, balanced=b.result)
    lines = {line.get_label(): line for line in fig.axes[0].lines}
    assert np.abs(lines["balanced"].get_xdata()).max() <= 1e-9 * np.abs(f["shaking:Fx"]).max()
