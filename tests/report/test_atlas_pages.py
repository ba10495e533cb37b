"""The illustrated atlas: a page per chain, a chain file per inversion that solve runs."""

import itertools
import math
import random
import warnings

import numpy as np
import pytest

import chaingraph
from chaingraph.cli.main import main
from chaingraph.naming.atlas import atlas_names
from chaingraph.report import atlas as pages
from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.illustrate import generic_pose, inversion_mechanism
from chaingraph.structure.atlas.sliding import sliding_atlas
from chaingraph.structure.isomorphism import automorphism_orbits


def test_the_four_link_atlas_is_drawn_named_and_animated(tmp_path, capsys):
    out = tmp_path / "atlas"
    assert main(["atlas", "--links", "4", "--prismatic", "all", "--out", str(out), "-q"]) == 0
    said = capsys.readouterr().out
    assert "4 chain pages, 7 inversion chain files, 7 animations" in said
    index = (out / "index.html").read_text()
    assert "Single slider crank chain" in index and "Double slider crank chain" in index
    page = (out / "chain-2.html").read_text()
    assert 'class="frame"' in page and "Reciprocating engine" in page
    for path in sorted((out / "chains").glob("chain-*-inversion-*.toml")):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            motion = chaingraph.solve(chaingraph.load(path), steps=12, summary=False)
        assert motion["theta"].size == 13


def _rigid(motion, chain, size):
    """Closure checked apart from the solver's equations: on every link the distances
    between its turning pairs stay as drawn, and links joined by a sliding pair keep
    their relative angle; returns the worst deviation over the size."""
    worst = 0.0
    for link in chain.links:
        on = [j for j in chain.joints if link in j.links and j.kind == "R"]
        for a, b in itertools.combinations(on, 2):
            d = np.hypot(motion[f"x:{a.id}"] - motion[f"x:{b.id}"],
                         motion[f"y:{a.id}"] - motion[f"y:{b.id}"])
            worst = max(worst, float(np.abs(d - math.dist(a.at, b.at)).max()) / size)
    for j in chain.joints:
        if j.kind == "P":
            a, b = j.links
            turn = np.radians(motion[f"angle:{a}"] - motion[f"angle:{b}"])
            worst = max(worst, float(np.abs(np.sin(turn - turn[0])).max()))
    return worst


def _solve_closed(entry, chain, *, steps, at_most=None):
    """Solve the inversions of ``chain`` that have a natural input and a bounded range
    (at most ``at_most`` of them), each checked rigid to 1e-9 of the size; how many."""
    size = max(max(j.at[0] for j in chain.joints) - min(j.at[0] for j in chain.joints),
               max(j.at[1] for j in chain.joints) - min(j.at[1] for j in chain.joints))
    solved = 0
    for links in automorphism_orbits(chain, oriented=False):
        mechanism = inversion_mechanism(chain, links[0])
        if mechanism is None:
            continue
        try:
            motion = chaingraph.solve(mechanism, steps=steps, summary=False)
        except chaingraph.UnboundedRangeError:
            continue
        assert _rigid(motion, chain, size) <= 1e-9, (entry.id, links)
        solved += 1
        if solved == at_most:
            break
    return solved


@pytest.mark.slow
def test_six_link_chain_files_classify_to_the_atlas_and_their_inversions_solve_closed():
    result = sliding_atlas(atlas_graphs(6, 1), prismatic=range(8))
    solved = 0
    for entry in result:
        chain = generic_pose(entry.chain(1))
        back = chaingraph.loads(chaingraph.dumps(chain))
        c = chaingraph.classify(back)
        assert (c.links, c.mobility, c.pair_kinds.get("P", 0)) == (6, 1, entry.prismatic)
        assert len(automorphism_orbits(back, oriented=False)) == entry.inversion_classes
        if entry.id % 8:                      # a sample of the inversions: every 8th chain
            continue
        solved += _solve_closed(entry, back, steps=24)
    assert solved >= 20


@pytest.mark.slow
def test_a_sample_of_eight_link_chain_files_classifies_and_solves_closed():
    """Every 50th chain of the 8-link atlas with every number of sliding pairs: its
    chain file reads back to the atlas's figures, and the first inversion with a
    natural input of every 400th solves with rigid links."""
    result = sliding_atlas(atlas_graphs(8, 1), prismatic=range(11))
    solved = 0
    for entry in list(result)[::50]:
        back = chaingraph.loads(chaingraph.dumps(generic_pose(entry.chain(1))))
        c = chaingraph.classify(back)
        assert (c.links, c.mobility, c.pair_kinds.get("P", 0)) == (8, 1, entry.prismatic)
        assert len(automorphism_orbits(back, oriented=False)) == entry.inversion_classes
        if entry.id % 400 != 1:
            continue
        solved += _solve_closed(entry, back, steps=12, at_most=1)
    assert solved >= 7


def test_names_survive_relabelling_the_links_and_joints():
    rng = random.Random(7)
    named = 0
    for entry in sliding_atlas(atlas_graphs(6, 1), prismatic=range(3)):
        chain = entry.chain(1)
        names = atlas_names(chain)
        if not names["chain"]:
            continue
        named += 1
        order = list(chain.links)
        shuffled = order[:]
        rng.shuffle(shuffled)
        rename = dict(zip(order, (f"X{k}" for k in range(len(order)))))
        rename = {a: rename[b] for a, b in zip(order, shuffled)}
        joints = [chaingraph.Joint(f"K{n}", j.kind, tuple(rename[x] for x in j.links),
                                   at=j.at, axis=j.axis)
                  for n, j in enumerate(reversed(chain.joints))]
        other = atlas_names(chaingraph.Chain("relabelled", tuple(joints)))
        assert other["chain"] == names["chain"]
        assert sorted(sorted(c["names"]) for c in other["inversions"]) == \
            sorted(sorted(c["names"]) for c in names["inversions"])
        assert {rename[x] for c in names["inversions"] for x in c["links"]} == \
            {x for c in other["inversions"] for x in c["links"]}
    assert named == 4            # Watt's, Stephenson's, the quick return with its ram, the beam engine's


def test_larger_runs_are_animated_when_asked(tmp_path, capsys, monkeypatch):
    """Every inversion up to 8 links is animated unless that is estimated to take more
    than the hour an atlas run takes without asking (every K at 8 links: about two
    hours on two workers); then the pages are drawn all the same, and the run says what
    it left out, how long it would take and how to ask for it."""
    six = sliding_atlas(atlas_graphs(6, 1), prismatic=range(8))
    seven = sliding_atlas(atlas_graphs(7, 2), prismatic=5)
    eight = sliding_atlas(atlas_graphs(8, 1), prismatic=range(11))
    assert pages.animated_by_default(six) and pages.animated_by_default(seven)
    assert not pages.animated_by_default(eight, workers=2)
    assert pages.animated_by_default(eight, workers=8)        # under the hour on 8
    assert 1.5 < pages.animation_seconds(eight, workers=2) / 3600 < 2.5
    monkeypatch.setitem(pages.SECONDS_PER_INVERSION, 7, 3600.0)
    assert pages.animated_by_default(six) and not pages.animated_by_default(seven)
    out = tmp_path / "seven"
    argv = ["atlas", "--links", "7", "--dof", "2", "--prismatic", "5", "--out", str(out),
            "--workers", "1", "-q"]
    assert main(argv) == 0
    said = capsys.readouterr().out
    assert "18 chain pages, 116 inversion chain files, 0 animations" in said
    assert "not animated: 116 inversions of 7 links, about 116.0 hours on 1 worker" in said
    assert "--illustrate" in said
    assert "<svg" in (out / "chain-1.html").read_text()          # drawn all the same
