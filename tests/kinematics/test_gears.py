"""Gear trains (issue 39): the speeds by the Willis equations and by the tabular method,
against the products of the teeth, a tabular method worked here by hand, the
relative-velocity equation, and a differential's two outputs."""

from fractions import Fraction
from itertools import product

import pytest

import chaingraph
from chaingraph.errors import ChainFileError, MechanismError
from chaingraph.kinematics.gears import (
    gear_train,
    tabular_speeds,
    train_kind,
    train_speeds,
    willis_speeds,
)
from chaingraph.model import Chain, GearPair, Joint, dumps, parse_text
from chaingraph.naming.catalog import catalog_path
from chaingraph.structure import classify


def catalog(name):
    """The textbook's train ``name`` from the catalog."""
    return chaingraph.load(catalog_path(name))


def planetary(zs, zp, za):
    """Sun, planet, annulus and arm: the four links, no housing (one freedom)."""
    return Chain("planetary", (Joint("O", "R", ("arm", "sun", "annulus")),
                               Joint("P", "R", ("arm", "planet"))),
                 gears=(GearPair("G1", ("sun", "planet"), (zs, zp), False, "arm"),
                        GearPair("G2", ("planet", "annulus"), (zp, za), True, "arm")))


def relative_velocity_holds(result):
    """Each pair's relative-velocity equation, (w_a - w_c) / (w_b - w_c) = -+ z_b / z_a,
    written as z_a (w_a - w_c) = -+ z_b (w_b - w_c)."""
    w = result.speeds
    for g in result.train.gears:
        (a, b), (za, zb), c = g.links, g.teeth, g.carrier
        sign = 1 if g.internal else -1
        if za * (w[a] - w[c]) != sign * zb * (w[b] - w[c]):
            return False
    return True


# -- ordinary trains: the product of the teeth -------------------------------------------
def test_simple_train_ratio_is_the_first_over_the_last_teeth():
    chain = catalog("simple-gear-train")
    result = train_speeds(chain, fixed="frame", speeds={"driver": 100})
    teeth = {x: z for g in chain.gears for x, z in zip(g.links, g.teeth)}
    # the idler's teeth cancel: driver / driven = z_driven / z_driver, same sense (two meshes)
    assert result.ratio("driver", "driven") == Fraction(teeth["driven"], teeth["driver"])
    assert result.speeds["idler"] == Fraction(-100 * teeth["driver"], teeth["idler"])
    assert result.kind == "simple" and result.freedom == 1
    assert relative_velocity_holds(result)


@pytest.mark.parametrize("name, first, last, kind", [
    ("compound-gear-train", "input", "output", "compound"),
    ("reverted-gear-train", "input", "output", "reverted")])
def test_compound_and_reverted_ratios_are_the_products_of_the_teeth(name, first, last, kind):
    chain = catalog(name)
    result = train_speeds(chain, fixed="frame", speeds={first: 700})
    # driven teeth over driving teeth, along the meshes in file order, a sign per mesh
    expected = Fraction(1)
    for g in chain.gears:
        expected *= Fraction(-g.teeth[1], g.teeth[0])
    assert result.ratio(first, last) == expected
    assert result.speeds[last] == 700 / expected
    assert result.kind == kind
    assert relative_velocity_holds(result)


def test_the_catalogs_figures():
    """The figures the catalog's notes give."""
    assert train_speeds(catalog("compound-gear-train"), fixed="frame",
                        speeds={"input": 1440}).speeds["output"] == -40       # 1440 / 36
    assert train_speeds(catalog("reverted-gear-train"), fixed="frame",
                        speeds={"input": 700}).speeds["output"] == 250        # 700 / 2.8


# -- the epicyclic train: a tabular method worked here -----------------------------------
def hand_table(zs, zp, za, fixed, given):
    """The textbook's table for sun, planet, annulus and arm, worked out here.
    Row 1, the arm held and the sun turned +1: sun 1, planet -zs/zp, annulus
    -zs/zp * zp/za = -zs/za (the planet an idler), arm 0. Times x, then everything
    turned y with the arm: arm y, sun y + x, planet y - x zs/zp, annulus y - x zs/za.
    ``fixed`` at 0 and ``given`` (one link, speed) give x and y."""
    row = {"arm": Fraction(0), "sun": Fraction(1), "planet": Fraction(-zs, zp),
           "annulus": Fraction(-zs, za)}
    (link, w), = given.items()
    # y + x row[fixed] = 0 and y + x row[link] = w
    x = Fraction(w) / (row[link] - row[fixed])
    y = -x * row[fixed]
    return {k: y + x * r for k, r in row.items()}


@pytest.mark.parametrize("fixed, given", [("annulus", {"sun": 1000}), ("sun", {"arm": 100}),
                                          ("arm", {"sun": 1000}), ("annulus", {"arm": 60}),
                                          ("sun", {"annulus": 125})])
@pytest.mark.parametrize("zs, zp, za", [(20, 30, 80), (18, 27, 72), (31, 17, 65)])
def test_epicyclic_train_against_the_hand_table(zs, zp, za, fixed, given):
    result = train_speeds(planetary(zs, zp, za), fixed=fixed, speeds=given)
    assert result.speeds == hand_table(zs, zp, za, fixed, given)
    assert relative_velocity_holds(result)
    assert result.kind == ("simple" if fixed == "arm" else "epicyclic")


def test_epicyclic_train_textbook_figures():
    """Sun 20, planet 30, annulus 80: annulus held, arm/sun = 20/100; sun held,
    annulus/arm = 1 + 20/80; arm held, annulus/sun = -20/80."""
    chain = planetary(20, 30, 80)
    assert train_speeds(chain, fixed="annulus", speeds={"sun": 1}).speeds["arm"] == \
        Fraction(1, 5)
    assert train_speeds(chain, fixed="sun", speeds={"arm": 1}).speeds["annulus"] == \
        Fraction(5, 4)
    assert train_speeds(chain, fixed="arm", speeds={"sun": 1}).speeds["annulus"] == \
        Fraction(-1, 4)


@pytest.mark.parametrize("held, given", [("annulus", ("sun", 1000)), ("sun", ("arm", 100)),
                                         ("arm", ("sun", 1000))])
def test_the_catalogs_train_in_its_housing_holds_each_member_in_turn(held, given):
    """The catalog's train has a housing (two freedoms): a member held to it by a
    brake (speed 0) gives the speeds of the four-link train with that member fixed."""
    result = train_speeds(catalog("epicyclic-gear-train"), fixed="frame",
                          speeds={held: 0, given[0]: given[1]})
    alone = hand_table(20, 30, 80, held, {given[0]: given[1]})
    assert {k: v for k, v in result.speeds.items() if k != "frame"} == alone
    assert result.freedom == 2 and result.kind == "epicyclic"


def test_willis_and_tabular_agree_on_a_two_stage_planetary():
    """Two planetary stages in series (the first arm drives the second sun), each
    annulus held by the frame: the two computations agree, the ratio is the product of
    the stages' (1 + za/zs)."""
    joints = (Joint("O", "R", ("frame", "sun1", "arm1", "arm2", "ring")),
              Joint("P1", "R", ("arm1", "p1")), Joint("P2", "R", ("arm2", "p2")),
              Joint("S", "R", ("arm1", "sun2")), Joint("Q", "R", ("arm2", "sun2")))
    gears = (GearPair("A", ("sun1", "p1"), (18, 27), False, "arm1"),
             GearPair("B", ("p1", "ring"), (27, 72), True, "arm1"),
             GearPair("C", ("sun2", "p2"), (24, 24), False, "arm2"),
             GearPair("D", ("p2", "ring"), (24, 72), True, "arm2"),
             GearPair("E", ("arm1", "sun2"), (40, 40), False, "frame"))
    # (sun2 is an idler gear cut on arm1's hub: meshes E with arm1's teeth, on the frame)
    chain = Chain("two stages", joints + (Joint("T", "R", ("frame", "sun2")),), gears=gears)
    train = gear_train(chain)
    given = {"sun1": Fraction(1000), "ring": Fraction(0)}
    willis, agree = willis_speeds(train, "frame", given)
    tabular, agree2, table = tabular_speeds(train, "frame", given)
    assert agree and agree2 and willis == tabular and None not in willis
    w = dict(zip(train.links, willis))
    assert w["arm1"] == Fraction(1000) / (1 + Fraction(72, 18))
    assert w["sun2"] == -w["arm1"]
    assert w["arm2"] == w["sun2"] / (1 + Fraction(72, 24))


# -- the differential ----------------------------------------------------------------------
@pytest.mark.parametrize("pinion, left", [(1000, -240), (1000, -250), (600, 0), (-800, 350)])
def test_differential_two_outputs(pinion, left):
    chain = catalog("differential-gear-train")
    result = train_speeds(chain, fixed="frame", speeds={"pinion": pinion, "left": left})
    w = result.speeds
    zp, zc = next(g.teeth for g in chain.gears if g.links == ("pinion", "case"))
    assert w["case"] == Fraction(-pinion * zp, zc)          # the crown wheel on the case
    assert w["left"] + w["right"] == 2 * w["case"]          # the wheels share the case's speed
    assert result.freedom == 2 and result.kind == "epicyclic"
    assert relative_velocity_holds(result)


def test_differential_needs_two_speeds():
    chain = catalog("differential-gear-train")
    with pytest.raises(MechanismError, match="2 degree"):
        train_speeds(chain, fixed="frame", speeds={"pinion": 1000})


# -- the graph, kinds and the structure ----------------------------------------------------
def test_graph_and_kinds_of_the_catalogs_trains():
    for name, kind, links, higher in [("simple-gear-train", "simple", 4, 2),
                                      ("compound-gear-train", "compound", 5, 3),
                                      ("reverted-gear-train", "reverted", 4, 2),
                                      ("epicyclic-gear-train", "epicyclic", 5, 2),
                                      ("differential-gear-train", "epicyclic", 7, 4)]:
        chain = catalog(name)
        train = gear_train(chain)
        assert train_kind(train, "frame") == kind, name
        graph = train.graph()
        assert len(graph["links"]) == links and len(graph["gears"]) == higher
        # a tree of turning pairs: one fewer than the links
        assert len(graph["turning"]) == links - 1
        c = classify(chain)
        assert c.higher_pairs == higher
        # Kutzbach with H = 1 a gear pair: F = 3 (L - 1) - 2 J - H
        assert c.mobility == 3 * (links - 1) - 2 * (links - 1) - higher


def test_a_train_with_the_arm_fixed_is_ordinary():
    assert train_kind(gear_train(planetary(20, 30, 80)), "arm") == "simple"


def test_gears_round_trip_and_relabel():
    chain = catalog("epicyclic-gear-train")
    again = parse_text(dumps(chain)).chain
    assert again == chain and again.gears == chain.gears
    renamed = chain.relabelled(links={"sun": "S"}, joints={"G1": "mesh"})
    assert renamed.gears[0] == GearPair("mesh", ("S", "planet"), (20, 30), False, "arm")
    assert train_speeds(renamed, fixed="frame", speeds={"annulus": 0, "S": 10}).speeds["arm"] == 2


# -- bad input -------------------------------------------------------------------------------
BASE = """name = "t"
[[joints]]
id = "A"
kind = "R"
links = ["frame", "a"]
[[joints]]
id = "B"
kind = "R"
links = ["frame", "b"]
[[joints]]
id = "C"
kind = "R"
links = ["b", "c"]
[mechanism]
fixed = "frame"
driver = "a"
[[gears]]
"""


@pytest.mark.parametrize("table, words", [
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [0, 30]', "'teeth' must be two positive whole"),
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [-20, 30]', "'teeth' must be two positive whole"),
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [20.5, 30]', "'teeth' must be two positive whole"),
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [20]', "'teeth' must be two positive whole"),
    ('id = "G"\nlinks = ["a", "b"]', "missing required key 'teeth'"),
    ('id = "G"\nlinks = ["a", "a"]\nteeth = [20, 30]', "names one link twice"),
    ('id = "G"\nlinks = ["a", "z"]\nteeth = [20, 30]', "names no link of the chain: 'z'"),
    ('id = "G"\nlinks = ["a", "c"]\nteeth = [20, 30]', "does not hold the axis of 'c'"),
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [20, 30]\ncarrier = "b"', "is one of the gears"),
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [20, 30]\ncarrier = "q"', "'carrier' names no link"),
    ('id = "A"\nlinks = ["a", "b"]\nteeth = [20, 30]', "gear pairs and joints share"),
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [20, 30]\nmodule = 2', "unknown key 'module'"),
    ('id = "G"\nlinks = ["a", "b"]\nteeth = [20, 30]\ninternal = 1', "'internal' must be true"),
])
def test_bad_gear_pairs_are_refused_naming_the_pair_and_key(table, words):
    with pytest.raises(ChainFileError, match="gear pair") as e:
        parse_text(BASE + table)
    assert words in str(e.value)


def test_a_pair_without_carrier_and_without_a_fixed_link():
    text = BASE.replace('[mechanism]\nfixed = "frame"\ndriver = "a"\n', "")
    with pytest.raises(ChainFileError, match="'carrier' is missing"):
        parse_text(text + 'id = "G"\nlinks = ["a", "b"]\nteeth = [20, 30]')


def test_the_library_refuses_bad_speeds():
    two = BASE.replace('[[joints]]\nid = "C"\nkind = "R"\nlinks = ["b", "c"]\n', "")
    chain = parse_text(two + 'id = "G"\nlinks = ["a", "b"]\nteeth = [20, 30]').chain
    assert train_speeds(chain).speeds["b"] == Fraction(-2, 3)     # the driver at 1 rpm
    for kwargs, words in [({"fixed": "nope"}, "'fixed' names no link"),
                          ({"speeds": {"nope": 1}}, "'speeds' names no link"),
                          ({"speeds": {"frame": 1}}, "to the fixed link"),
                          ({"speeds": {"a": 1, "b": 1}}, "disagree"),
                          ({"fixed": "a"}, "no input speed")]:
        with pytest.raises(MechanismError, match=words):
            train_speeds(chain, **kwargs)
    with pytest.raises(MechanismError, match="no gear pairs"):
        train_speeds(chaingraph.load(catalog_path("four-bar-chain")))


def test_locked_gears_turn_with_their_carrier():
    """Three gears in mesh in a ring lock (-1 cubed is not 1): they turn with the frame
    (at rest), and the two computations agree on it."""
    joints = tuple(Joint(k, "R", ("frame", k.lower())) for k in "ABC")
    gears = tuple(GearPair(f"G{i}", pair, (20, 20), False, "frame")
                  for i, pair in enumerate([("a", "b"), ("b", "c"), ("c", "a")]))
    chain = Chain("ring", joints, gears=gears)
    with pytest.raises(MechanismError, match="disagree"):
        train_speeds(chain, fixed="frame", speeds={"a": 1})
    for method in (willis_speeds, tabular_speeds):
        values = method(gear_train(chain), "frame", {})
        assert values[0] == [0, 0, 0, 0]


def test_exact_for_every_small_train():
    """Every simple three-gear train with teeth 12..15: the driven speed is the
    driver's times z_driver / z_driven (the idler cancels)."""
    for z1, z2, z3 in product(range(12, 16), repeat=3):
        chain = Chain("t", tuple(Joint(k, "R", ("frame", k.lower())) for k in "ABC"),
                      gears=(GearPair("G1", ("a", "b"), (z1, z2), False, "frame"),
                             GearPair("G2", ("b", "c"), (z2, z3), False, "frame")))
        assert train_speeds(chain, fixed="frame", speeds={"a": 7}).speeds["c"] == \
            Fraction(7 * z1, z3)
