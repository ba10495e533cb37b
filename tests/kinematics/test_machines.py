"""The textbook's machines whole, against hand geometry: the rotary engine's seven
pistons, the duplex pump's two, the beam engine's piston."""

import math

import numpy as np
import pytest

import chaingraph
from chaingraph.naming.catalog import catalog_path


def test_every_piston_of_the_rotary_engine_follows_the_slider_crank_law():
    """Crank r = 30 fixed along OA, rods l = 100, cylinders 360/7 apart turning about O:
    piston i is at r cos(a) + sqrt(l^2 - r^2 sin^2(a)) from O along its cylinder, a the
    cylinder's angle from OA."""
    engine = chaingraph.load(catalog_path("rotary-engine-seven-cylinders"))
    m = chaingraph.solve(engine, steps=144)
    r, l = 30.0, 100.0
    theta = np.radians(m["theta"])                      # the block: cylinder 1's direction
    for i in range(1, 8):
        a = theta + 2 * math.pi * (i - 1) / 7
        x = r * np.cos(a) + np.sqrt(l * l - (r * np.sin(a)) ** 2)
        drawn = math.hypot(*engine.joint(f"S{i}").at)
        assert np.allclose(m[f"s:S{i}"] + drawn, x, atol=1e-9 * l), i
        # the piston pin B_i is on cylinder i's axis at that distance
        assert np.allclose(m[f"x:B{i}"], x * np.cos(a), atol=1e-9 * l)
        assert np.allclose(m[f"y:B{i}"], x * np.sin(a), atol=1e-9 * l)
        s = chaingraph.solve(engine, steps=72, output=f"S{i}").summary
        assert s.stroke == pytest.approx(2 * r, rel=1e-9) and s.time_ratio == pytest.approx(1.0)
    # the block turns fully about O; the crankshaft stays
    assert m.summary.full_turn and np.allclose(m["omega:crankshaft"], 0.0)
    assert np.allclose(m["omega:cylinders"], m.omega)
    c = chaingraph.classify(engine)
    assert (c.links, c.mobility) == (16, 1) and c.joint_orders["octonary"] == 1


def test_the_duplex_pump_s_two_pistons_share_the_rod_s_stroke():
    pump = chaingraph.load(catalog_path("duplex-pump"))
    single = chaingraph.solve(chaingraph.load(catalog_path("pendulum-pump"))).summary
    upper = chaingraph.solve(pump, output="upper piston").summary
    lower = chaingraph.solve(pump, output="lower piston").summary
    rod = chaingraph.solve(pump, output="piston rod").summary
    assert upper.stroke == pytest.approx(lower.stroke, rel=1e-12)
    assert upper.stroke == pytest.approx(rod.stroke, rel=1e-9)
    assert upper.stroke == pytest.approx(single.stroke, rel=1e-9)
    # the stroke by hand: the rod slides on the line x = 0 through the pendulum's pivot
    # B; its pin O is a crank's length from the pendulum's pin A, A on a circle about B:
    # O is highest with the pendulum upright (swing + crank) and lowest at the limits,
    # where the crank lies level (sqrt(swing^2 - crank^2))
    a0, o0 = pump.joint("A").at, pump.joint("O").at
    crank, swing = math.dist(a0, o0), math.hypot(*a0)
    assert upper.stroke == pytest.approx(swing + crank - math.sqrt(swing ** 2 - crank ** 2),
                                         rel=1e-9)
    assert all(p.link == "piston rod" for p in pump.points)


def test_the_beam_engine_s_piston_stroke_from_the_lever_s_rocking():
    beam = chaingraph.load(catalog_path("beam-engine-with-piston"))
    j = {x.id: x.at for x in beam.joints}
    crank = math.dist(j["A"], j["B"])
    rod = math.dist(j["B"], j["C"])
    lever = math.dist(j["D"], j["C"])
    piston_rod = math.dist(j["E"], j["F"])
    ends = []
    for reach in (rod + crank, rod - crank):             # crank and rod in line
        # C on the circles about A (radius reach) and D (radius lever), above AD
        d = math.dist(j["A"], j["D"])
        x = (reach * reach - lever * lever + d * d) / (2 * d)
        c = (x, math.sqrt(reach * reach - x * x))
        turn = math.atan2(c[1] - j["D"][1], c[0] - j["D"][0]) - math.atan2(
            j["C"][1] - j["D"][1], j["C"][0] - j["D"][0])
        ex = j["D"][0] + math.cos(turn) * (j["E"][0] - j["D"][0]) - math.sin(turn) * (j["E"][1] - j["D"][1])
        ey = j["D"][1] + math.sin(turn) * (j["E"][0] - j["D"][0]) + math.cos(turn) * (j["E"][1] - j["D"][1])
        ends.append(ex + math.sqrt(piston_rod ** 2 - (ey - j["F"][1]) ** 2))
    s = chaingraph.solve(beam).summary
    assert s.output == "piston" and s.stroke_unit == "mm"
    assert s.stroke == pytest.approx(abs(ends[0] - ends[1]), rel=1e-9)
    # the same time ratio as the lever's (the piston follows the lever monotonically)
    lever_summary = chaingraph.solve(beam, output="lever").summary
    assert s.time_ratio == pytest.approx(lever_summary.time_ratio, rel=1e-9)


def test_the_four_bar_notes_correct_the_notes_type_2_error():
    """The notes say every inversion of a chain with s + l > p + q is a double crank;
    every one is a triple rocker, and the catalog's notes say so."""
    notes = chaingraph.load(catalog_path("four-bar-chain")).notes
    assert "s + l > p + q" in notes and "triple rockers" in notes and "double crank" in notes
    found = chaingraph.inversions(chaingraph.load(catalog_path("non-grashof-four-bar")))
    assert {row[2] for row in found.rows()[1:]} == {"triple rocker"}
