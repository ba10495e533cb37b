"""Classification: the textbook's cases, every key of the contract, odd chains."""

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import chaingraph
from chaingraph import Chain, Joint, classify
from chaingraph.structure.generators import random_chain
from chaingraph.structure.rigidity import rigid_subchains, subchain_mobility

from ..conftest import catalog_path, run_cli

KEYS = ["name", "links", "pairs", "joint_equivalents", "higher_pairs", "joint_orders",
        "link_orders", "pair_kinds", "loops", "mobility", "checks", "verdict",
        "degenerate", "rigid_subchains", "rigid_subchains_complete", "rigid_regions"]
TWO_P, J_RULE = "L = 2P - 4", "J + H/2 = 3L/2 - 2"


def R(joint_id, *links):
    return Joint(joint_id, "R", links)


def facts(stem):
    return classify(chaingraph.load(catalog_path(stem))).to_dict()


def check(d, rule):
    return next(c for c in d["checks"] if c["rule"] == rule)


# (stem, L, P, J, H, loops, F, joint_orders, link_orders, pair_kinds, 2P verdict, J verdict)
TEXTBOOK = [
    ("three-link-locked-chain", 3, 3, 3, 0, 1, 0, {"binary": 3, "ternary": 0, "quaternary": 0},
     {"binary": 3, "ternary": 0, "quaternary": 0}, {"R": 3}, "locked chain", "locked chain"),
    ("four-bar-chain", 4, 4, 4, 0, 1, 1, {"binary": 4, "ternary": 0, "quaternary": 0},
     {"binary": 4, "ternary": 0, "quaternary": 0}, {"R": 4}, "kinematic chain", "kinematic chain"),
    ("five-link-chain", 5, 5, 5, 0, 1, 2, {"binary": 5, "ternary": 0, "quaternary": 0},
     {"binary": 5, "ternary": 0, "quaternary": 0}, {"R": 5}, "unconstrained chain",
     "unconstrained chain"),
    ("six-link-two-ternary-joints", 6, 5, 7, 0, 2, 1, {"binary": 3, "ternary": 2, "quaternary": 0},
     {"binary": 6, "ternary": 0, "quaternary": 0}, {"R": 5}, "kinematic chain", "kinematic chain"),
    ("watt-six-bar-chain", 6, 7, 7, 0, 2, 1, {"binary": 7, "ternary": 0, "quaternary": 0},
     {"binary": 4, "ternary": 2, "quaternary": 0}, {"R": 7}, None, "kinematic chain"),
    ("stephenson-six-bar-chain", 6, 7, 7, 0, 2, 1, {"binary": 7, "ternary": 0, "quaternary": 0},
     {"binary": 4, "ternary": 2, "quaternary": 0}, {"R": 7}, None, "kinematic chain"),
    ("single-slider-crank-chain", 4, 4, 4, 0, 1, 1, {"binary": 4, "ternary": 0, "quaternary": 0},
     {"binary": 4, "ternary": 0, "quaternary": 0}, {"R": 3, "P": 1}, "kinematic chain",
     "kinematic chain"),
    ("double-slider-crank-chain", 4, 4, 4, 0, 1, 1, {"binary": 4, "ternary": 0, "quaternary": 0},
     {"binary": 4, "ternary": 0, "quaternary": 0}, {"R": 2, "P": 2}, "kinematic chain",
     "kinematic chain"),
    ("quaternary-joint-chain", 8, 8, 10, 0, 3, 1, {"binary": 7, "ternary": 0, "quaternary": 1},
     {"binary": 6, "ternary": 2, "quaternary": 0}, {"R": 8}, None, "kinematic chain"),
    ("cam-and-follower", 3, 3, 2, 1, 1, 1, {"binary": 3, "ternary": 0, "quaternary": 0},
     {"binary": 3, "ternary": 0, "quaternary": 0}, {"R": 1, "P": 1, "cam": 1}, None,
     "kinematic chain"),
]


@pytest.mark.parametrize("row", TEXTBOOK, ids=[r[0] for r in TEXTBOOK])
def test_textbook_chains_every_key(row):
    stem, L, P, J, H, loops, F, jo, lo, kinds, two_p, j_verdict = row
    d = facts(stem)
    assert list(d)[:len(KEYS)] == KEYS
    assert (d["links"], d["pairs"], d["joint_equivalents"], d["higher_pairs"]) == (L, P, J, H)
    assert (d["loops"], d["mobility"]) == (loops, F)
    assert d["joint_orders"] == jo and d["link_orders"] == lo and d["pair_kinds"] == kinds
    verdict = {0: "locked chain", 1: "kinematic chain", 2: "unconstrained chain"}[F]
    assert d["verdict"] == verdict
    assert d["degenerate"] is False and d["rigid_subchains"] == []
    assert d["rigid_subchains_complete"] is True
    assert d["rigid_regions"] == ([list(chaingraph.load(catalog_path(stem)).links)] if F <= 0
                                  else [])   # a locked chain is one rigid region
    c2p, cj = check(d, TWO_P), check(d, J_RULE)
    assert set(c2p) == {"rule", "lhs", "rhs", "applicable", "verdict", "note"}
    assert (c2p["lhs"], c2p["rhs"]) == (L, 2 * P - 4)
    assert c2p["applicable"] is (two_p is not None) and c2p["verdict"] == two_p
    assert cj["applicable"] is True and cj["verdict"] == j_verdict
    assert cj["lhs"] == J + H / 2 and cj["rhs"] == 3 * L / 2 - 2
    assert c2p["note"] and cj["note"]


def test_watt_two_p_not_applicable_says_why():
    c = check(facts("watt-six-bar-chain"), TWO_P)
    assert c["applicable"] is False and c["verdict"] is None
    assert "every link is binary" in c["note"] and "2 ternary" in c["note"]


def test_cam_and_follower_j_check_holds_with_half_h():
    d = facts("cam-and-follower")
    c = check(d, J_RULE)
    assert (c["lhs"], c["rhs"]) == (2.5, 2.5) and c["verdict"] == "kinematic chain"
    assert "higher pair" in check(d, TWO_P)["note"]


def _all_binary_links(seed):
    """A chain whose links all have two joints, its joints binary or ternary at random:
    each link has two ends, and the ends are grouped into joints."""
    rng = random.Random(seed)
    n = rng.randint(4, 10)
    while True:
        ends = [f"L{i}" for i in range(n)] * 2
        rng.shuffle(ends)
        groups, ok = [], True
        while ends:
            size = 3 if len(ends) >= 5 and rng.random() < 0.3 else 2
            group, ends = ends[:size], ends[size:]
            if len(ends) == 1:
                group, ends = group + ends, []
            if len(set(group)) != len(group):
                ok = False
                break
            groups.append(group)
        if ok:
            return Chain("binary links", tuple(R(f"J{i}", *g) for i, g in enumerate(groups)))


def test_two_checks_agree_when_both_apply():
    # L - (2P - 4) = 2 (J - (3L/2 - 2)) for chains whose links are all binary
    for seed in range(60):
        c = classify(_all_binary_links(seed))
        a, b = c.check(TWO_P), c.check(J_RULE)
        assert a.applicable
        assert a.lhs - a.rhs == 2 * (b.lhs - b.rhs)
        assert a.verdict == b.verdict


def test_k23_rigid_subchain_without_a_triangle():
    # five links, six joints in a K(2,3) pattern (rigid, no triangle), hung on a
    # four-bar loop: the count says F = 1 but the K(2,3) part is locked
    joints = [R("a", "x1", "y1"), R("b", "x1", "y2"), R("c", "x1", "y3"),
              R("d", "x2", "y1"), R("e", "x2", "y2"), R("f", "x2", "y3"),
              R("g", "y3", "m"), R("h", "m", "n"), R("i", "n", "p"), R("k", "p", "y1")]
    chain = Chain("K23 on a loop", tuple(joints))
    result = classify(chain)
    assert (result.links, result.joint_equivalents, result.mobility) == (8, 10, 1)
    assert result.degenerate is True
    assert result.rigid_subchains == (("x1", "y1", "y2", "y3", "x2"),)
    assert subchain_mobility(chain, ["x1", "x2", "y1", "y2", "y3"]) == 0


def test_triangle_inside_a_chain_is_degenerate():
    chain = Chain("x", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "4"), R("D", "4", "1"),
                        R("E", "2", "5"), R("F", "5", "6"), R("G", "6", "2")))
    assert rigid_subchains(chain) == [("2", "5", "6")]


def test_ternary_joint_counts_in_subchains():
    # links a, b on a ternary joint with c, and a binary joint a-b: {a, b} is rigid
    chain = Chain("x", (R("T", "a", "b", "c"), R("X", "a", "b"), R("Y", "c", "d"),
                        R("Z", "d", "a")))
    assert ("a", "b") in rigid_subchains(chain)


def test_open_fractionated_and_disconnected_chains_are_reported():
    # two four-bar loops sharing one link: fractionated at that link
    two_loops = Chain("two loops", (
        R("A", "s", "a1"), R("B", "a1", "a2"), R("C", "a2", "a3"), R("D", "a3", "s"),
        R("E", "s", "b1"), R("F", "b1", "b2"), R("G", "b2", "b3"), R("H", "b3", "s")))
    c = classify(two_loops)
    assert c.fractionated and c.separating_links == ("s",) and c.mobility == 2
    # two loops on one quaternary joint: fractionated at the joint
    on_pin = Chain("pin", (R("Q", "a1", "a3", "b1", "b3"), R("B", "a1", "a2"), R("C", "a2", "a3"),
                           R("F", "b1", "b2"), R("G", "b2", "b3")))
    c = classify(on_pin)
    assert c.fractionated and c.separating_joints == ("Q",)
    # a link hanging on a four-bar by one joint: open, not fractionated
    hanging = Chain("open", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "4"),
                             R("D", "4", "1"), R("E", "3", "tail")))
    c = classify(hanging)
    assert c.singular_links == ("tail",) and not c.fractionated
    assert c.link_orders["singular"] == 1 and list(c.link_orders)[0] == "singular"
    assert c.check(TWO_P).applicable is False
    assert any("single joint" in o for o in c.oddities)
    # two pieces that share no joint: classified, pieces reported
    apart = Chain("apart", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "1"),
                            R("D", "4", "5")))
    c = classify(apart)
    assert c.pieces == (("1", "2", "3"), ("4", "5")) and any("2 pieces" in o for o in c.oddities)


def test_spatial_chain_uses_spatial_kutzbach():
    # RSSR: 6(4 - 1) - (5 + 3 + 3 + 5) = 2 (one of them the coupler's idle spin)
    rssr = Chain("RSSR", (R("A", "frame", "crank"), Joint("B", "spherical", ("crank", "rod")),
                          Joint("C", "spherical", ("rod", "rocker")), R("D", "rocker", "frame")),
                 space="spatial")
    c = classify(rssr)
    assert c.mobility == 2 and c.space == "spatial"
    assert not c.check(TWO_P).applicable and not c.check(J_RULE).applicable
    assert c.pair_kinds == {"R": 2, "spherical": 2}


def test_rolling_pair_counts_as_one_freedom():
    # a wheel rolling on a rail, the wheel's axle sliding along the frame: 3 links
    rolling = Chain("wheel", (R("A", "axle", "wheel"), Joint("B", "rolling", ("wheel", "frame")),
                              Joint("C", "P", ("frame", "axle"))))
    c = classify(rolling)
    assert c.mobility == 0  # the wheel cannot move: rolling fixes its spin to its travel
    jc = c.check(J_RULE)
    assert jc.lhs == 3 and "rolling" in jc.note


def test_link_orders_above_quaternary():
    star = Chain("star", tuple(R(f"J{i}", "hub", f"arm{i}") for i in range(5)))
    assert classify(star).link_orders == {"singular": 5, "binary": 0, "ternary": 0,
                                          "quaternary": 0, "quinary": 1}


def _relabel(chain, rng):
    links = {x: f"link-{i}" for i, x in enumerate(rng.sample(chain.links, len(chain.links)))}
    joints = {j.id: f"joint-{i}" for i, j in enumerate(rng.sample(chain.joints, len(chain.joints)))}
    shuffled = chain.relabelled(links=links, joints=joints)
    order = list(shuffled.joints)
    rng.shuffle(order)
    return Chain(shuffled.name, tuple(order)), links, joints


@settings(max_examples=60, deadline=None)
@given(st.integers(3, 11), st.integers(0, 2), st.integers(0, 2), st.integers(0, 10**6))
def test_relabelling_changes_no_classification(n, ternary, sliding, seed):
    rng = random.Random(seed)
    chain = random_chain(n, seed=seed, ternary=ternary, sliding=sliding)
    other, links, joints = _relabel(chain, rng)
    a, b = classify(chain).to_dict(), classify(other).to_dict()
    for key in ("links", "pairs", "joint_equivalents", "higher_pairs", "joint_orders",
                "link_orders", "pair_kinds", "loops", "mobility", "checks", "verdict",
                "degenerate", "fractionated"):
        assert a[key] == b[key], key
    rename = lambda sets: sorted(sorted(links[x] for x in s) for s in sets)  # noqa: E731
    assert rename(a["rigid_subchains"]) == sorted(sorted(s) for s in b["rigid_subchains"])
    assert sorted(links[x] for x in a["separating_links"]) == sorted(b["separating_links"])
    assert sorted(links[x] for x in a["singular_links"]) == sorted(b["singular_links"])


def test_rigid_search_takes_chains_past_the_scans_limit():
    # 27 links: more than the exhaustive scan takes; the search has no link limit
    chain = random_chain(27, seed=0)
    found = rigid_subchains(chain)
    assert all(subchain_mobility(chain, s) <= 0 for s in found)
    assert classify(chain).degenerate is bool(found)


def test_cli_text_and_json():
    path = catalog_path("watt-six-bar-chain")
    code, out, err = run_cli("classify", path)
    assert code == 0 and err == ""
    assert "Watt six-bar chain" in out and "not applicable" in out and "kinematic chain" in out
    code, out, _ = run_cli("classify", "--json", path)
    import json
    d = json.loads(out)
    assert code == 0 and d["name"] == "Watt six-bar chain" and d["joint_equivalents"] == 7
    code, out, _ = run_cli("classify", "--json", path, catalog_path("four-bar-chain"))
    assert code == 0 and [x["name"] for x in json.loads(out)] == ["Watt six-bar chain",
                                                                  "Four-bar chain"]
    code, out, _ = run_cli("classify", path, catalog_path("four-bar-chain"))
    assert code == 0 and out.count("kinematic chain") >= 2 and "L = 2P - 4" in out


def test_cli_several_files_one_bad(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "x"\n')
    code, out, err = run_cli("classify", "--json", catalog_path("four-bar-chain"), bad)
    import json
    assert code == 2 and len(json.loads(out)) == 1 and "bad.toml" in err


def test_cli_usage_errors_exit_2():
    code, out, err = run_cli("classify")
    assert code == 2 and "usage" in err
    code, out, err = run_cli("frobnicate")
    assert code == 2
