"""The illustrated atlas: a page per chain, a chain file per inversion that solve runs."""

import contextlib
import html
import io
import itertools
import math
import os
import random
import re
import subprocess
import sys
import tomllib
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph.cli.main import main
from chaingraph.geometry import segment_distance
from chaingraph.naming.atlas import atlas_names
from chaingraph.report import atlas as pages
from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.illustrate import generic_pose, inversion_mechanism
from chaingraph.structure.atlas.sliding import sliding_atlas
from chaingraph.structure.isomorphism import automorphism_orbits

from ..conftest import catalog_path, run_cli


@pytest.fixture(scope="module")
def four_link_pages(tmp_path_factory):
    """The 4-link atlas with every number of sliding pairs, drawn: (folder, what the run
    printed)."""
    out = tmp_path_factory.mktemp("atlas4") / "atlas"
    code, said, err = run_cli("atlas", "--links", "4", "--prismatic", "all", "--out", out, "-q")
    assert code == 0, err
    return out, said


def test_the_four_link_atlas_is_drawn_named_and_animated(four_link_pages):
    out, said = four_link_pages
    # 7 inversions; the named ones animated once per catalog mechanism of theirs
    assert "4 chain pages, 15 inversion chain files, 15 animations" in said
    index = (out / "index.html").read_text()
    assert "Single slider crank chain" in index and "Double slider crank chain" in index
    page = (out / "chain-2.html").read_text()
    assert 'class="frame"' in page and "Reciprocating engine" in page
    for path in sorted((out / "chains").glob("chain-*-inversion-*.toml")):
        motion = chaingraph.solve(_read_back(path), steps=12, summary=False)
        assert motion["theta"].size == 13


# -- the animations, read back from the pages ---------------------------------------------
NS = {"s": "http://www.w3.org/2000/svg"}


def _figures(page):
    """(chain file name, animation's svg or None, the notes under it) of each inversion
    figure on a chain's page."""
    out = []
    for chunk in page.split('<a href="chains/')[1:]:
        name = chunk.split('"', 1)[0]
        found = re.search(r'<figure class="inversion">\s*(<svg.*?</svg>)\s*</figure>',
                          chunk.split('<a href="chains/')[0], re.S)
        notes = re.findall(r'<p class="note">([^<]*)</p>', chunk)
        out.append((name, found.group(1) if found else None, [html.unescape(n) for n in notes]))
    return out


def _points(element):
    return [tuple(map(float, xy.split(","))) for xy in element.get("points").split()]


def _inside(p, polygon):
    inside = False
    for (x1, y1), (x2, y2) in zip(polygon, polygon[1:] + polygon[:1]):
        if (y1 > p[1]) != (y2 > p[1]) and p[0] < x1 + (p[1] - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def _frame_faults(svg, chain):
    """What a reader would trip over in an animation, frame by frame: a block away from
    its own link (the one the guide is not on), the links' box under 12 % of the view,
    two joint labels overlapping (their boxes from the font size: 0.55 of it per
    character, 0.75 above the baseline and 0.2 below), a link whose lengths change by
    more than the drawing's rounding."""
    root = ET.fromstring(svg)
    _, _, vw, vh = (float(v) for v in root.get("viewBox").split())
    rounding = 4 * 10.0 ** -max(0, 5 - math.floor(math.log10(max(vw, vh))))
    faults, lengths = [], {}
    for frame in root.findall("s:g[@class='frame']", NS):
        bodies = {e.get("data-link"): _points(e) for e in
                  frame.findall("s:polyline[@class='bar']", NS)
                  + frame.findall("s:polygon[@class='plate']", NS)}
        for link, pts in bodies.items():
            lengths.setdefault(link, []).append(
                sorted(math.dist(a, b) for a, b in itertools.combinations(pts, 2)))
        for j in (j for j in chain.joints if j.kind == "P"):
            (block,) = frame.findall(f"s:polygon[@class='block'][@data-joint='{j.id}']", NS)
            (guide,) = frame.findall(f"s:line[@class='guide'][@data-joint='{j.id}']", NS)
            own = [x for x in j.links if x != guide.get("data-link")][0]
            corners = _points(block)
            centre = (sum(p[0] for p in corners) / 4, sum(p[1] for p in corners) / 4)
            body = bodies.get(own)
            if body is None or own == chain.mechanism.fixed:
                continue                           # the block is its link's body
            off = 0.0 if len(body) > 2 and _inside(centre, body) else min(
                segment_distance(centre, a, b) for a, b in zip(body, body[1:] + body[:1]))
            if off > math.dist(corners[0], corners[2]):
                faults.append(f"block {j.id} {off:.3g} off its link {own}")
        drawn = [p for pts in bodies.values() for p in pts] + [
            (float(c.get("cx")), float(c.get("cy"))) for c in frame.findall("s:circle[@class='pin']", NS)]
        xs, ys = [p[0] for p in drawn], [p[1] for p in drawn]
        share = max((max(xs) - min(xs)) / vw, (max(ys) - min(ys)) / vh)
        if share < 0.12:
            faults.append(f"the links span {share:.0%} of the view {vw:.4g} x {vh:.4g}")
        boxes = []
        for t in frame.findall("s:text[@class='label']", NS):
            x, y, size = float(t.get("x")), float(t.get("y")), float(t.get("font-size"))
            boxes.append((x, y - 0.75 * size, x + 0.55 * size * len(t.text), y + 0.2 * size,
                          t.text))
        for a, b in itertools.combinations(boxes, 2):
            if a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]:
                faults.append(f"labels {a[4]} and {b[4]} overlap")
    for link, seen in lengths.items():
        change = max(abs(u - v) for d in seen for u, v in zip(d, seen[0]))
        if change > rounding or any(len(d) != len(seen[0]) for d in seen):
            faults.append(f"link {link} changes its lengths by {change:.3g}")
    return sorted(set(faults))


def _read_back(path):
    """A chain file the atlas wrote, read with every warning an error (none is adjusted:
    a PoseAdjustedWarning fails), checked to hold exactly the positions written."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        chain = chaingraph.load(path)
    written = tomllib.loads(Path(path).read_text())["joints"]
    assert [tuple(j["at"]) for j in written] == [j.at for j in chain.joints], path
    return chain


#: the textbook's names that promise an input that turns fully
TURNING = {"Reciprocating engine", "Beam engine (crank and lever mechanism)",
           "Whitworth quick return mechanism", "Rotary (Gnome) engine"}


def test_named_four_link_inversions_move_as_named(four_link_pages):
    """Every named inversion is animated with its catalog mechanism's proportions: its
    input turns fully exactly when the catalog's does (the crank of the engines and the
    quick return turns, the triple rocker's rocks), the whole range is shown, and the
    chain file is the mechanism animated (its first pose is the first frame)."""
    out, _ = four_link_pages
    named = set()
    for page in sorted(out.glob("chain-*.html")):
        for name, svg, notes in _figures(page.read_text()):
            chain = _read_back(out / "chains" / name)
            assert not _frame_faults(svg, chain), (name, _frame_faults(svg, chain))
            said = [re.search(r"the catalog's (.*) \(catalog/(.*)\.toml", n) for n in notes]
            said = [m for m in said if m]
            if not said:
                continue
            title, stem = said[0].groups()
            own = chaingraph.solve(chaingraph.load(catalog_path(stem)), steps=36)
            motion = chaingraph.solve(chain, steps=36)
            assert motion.summary.full_turn == own.summary.full_turn, name
            assert motion.summary.full_turn or title not in TURNING, name
            assert not any("part of its range" in n for n in notes), name
            frames = ET.fromstring(svg).findall("s:g[@class='frame']", NS)
            assert len(frames) == 24
            first = next(f for f in frames if f.get("visibility") == "visible")
            pins = {c.get("data-joint"): (float(c.get("cx")), float(c.get("cy")))
                    for c in first.findall("s:circle[@class='pin']", NS)}
            a, *rest = sorted(pins)
            for b in rest:          # the picture's y points down
                want = (motion[f"x:{b}"][0] - motion[f"x:{a}"][0],
                        motion[f"y:{a}"][0] - motion[f"y:{b}"][0])
                got = (pins[b][0] - pins[a][0], pins[b][1] - pins[a][1])
                assert math.dist(want, got) < 1e-3 * max(map(abs, want + (1.0,))), name
            named.add(title)
    assert TURNING <= named and "Non-Grashof four-bar (triple rocker)" in named


@pytest.fixture(scope="module")
def six_link_pages(tmp_path_factory):
    """The 6-link atlas with every number of sliding pairs, drawn and animated."""
    out = tmp_path_factory.mktemp("atlas6") / "atlas"
    # one process: the suite's other worker has the other core
    code, said, err = run_cli("atlas", "--links", "6", "--prismatic", "all", "--out", out,
                              "--workers", "1", "-q")
    assert code == 0, err
    return out, said


@pytest.mark.slow
def test_every_six_link_animation_reads_at_every_frame(six_link_pages):
    """Over every animated inversion of the 6-link atlas with sliding pairs, at every
    frame: each block on its own link, the links filling the picture, no two labels
    overlapping, every link's lengths kept to the drawing's rounding; a part of a range
    shown is said and is the chain file's sweep; every chain file reads back exactly,
    without adjustment."""
    out, said = six_link_pages
    assert "did not solve" not in said
    animated = 0
    for page in sorted(out.glob("chain-*.html")):
        for name, svg, notes in _figures(page.read_text()):
            chain = _read_back(out / "chains" / name)
            assert svg is not None, name
            assert not _frame_faults(svg, chain), (name, _frame_faults(svg, chain))
            item = chain.mechanism.inputs[0]
            part = any("part of its range" in n or "without a limit" in n for n in notes)
            assert part == (item.start is not None), name
            animated += 1
    assert animated >= 234


def test_atlas_chain_files_read_back_exactly():
    """A generic pose keeps its turning pairs off the sliding lines of their links by
    far more than rounding, so that a file of it reads back as written (no joint put on
    a line with a PoseAdjustedWarning): every 6-link chain in its poses 0 to 3, every
    7th 8-link chain (72 of the 8-link chains had a joint within 1e-3 of the size)."""
    six = sliding_atlas(atlas_graphs(6, 1), prismatic=range(8))
    eight = list(sliding_atlas(atlas_graphs(8, 1), prismatic=range(11)))[::7]
    for entry, seed in [(e, s) for e in six for s in range(4)] + [(e, 0) for e in eight]:
        chain = generic_pose(entry.chain(1), seed=seed)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            back = chaingraph.loads(chaingraph.dumps(chain))
        assert back.joints == chain.joints, (len(chain.links), entry.id, seed)


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
    than the hour an atlas run takes without asking (every K at 8 links: about 40
    minutes on two workers, an hour and a half on one); then the pages are drawn all the
    same, and the run says what it left out, how long it would take and how to ask for
    it."""
    six = sliding_atlas(atlas_graphs(6, 1), prismatic=range(8))
    seven = sliding_atlas(atlas_graphs(7, 2), prismatic=5)
    eight = sliding_atlas(atlas_graphs(8, 1), prismatic=range(11))
    assert pages.animated_by_default(six) and pages.animated_by_default(seven)
    assert not pages.animated_by_default(eight, workers=1)
    assert pages.animated_by_default(eight, workers=2)        # under the hour on 2
    assert 0.5 < pages.animation_seconds(eight, workers=2) / 3600 < 1.0
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


def test_a_chains_generic_pose_is_the_same_in_every_run():
    """The pages of one atlas are the same from run to run: the links' layout does not
    follow Python's hash seed (networkx's planar embedding iterates over sets of the
    nodes, so the links are laid out as their numbers, not their names). Before, chain
    841 of the 8-link atlas was drawn differently with each seed."""
    code = ("import chaingraph\n"
            "from chaingraph.structure.atlas.illustrate import generic_pose\n"
            "chain = chaingraph.Chain('c', tuple(chaingraph.Joint(f'J{k}', kind, links) "
            "for k, (kind, links) in enumerate([('R', ('L1', 'L2')), ('P', ('L1', 'L7')), "
            "('R', ('L2', 'L5')), ('P', ('L3', 'L6')), ('R', ('L3', 'L8')), "
            "('R', ('L4', 'L5')), ('P', ('L4', 'L6')), ('R', ('L5', 'L8')), "
            "('R', ('L6', 'L7')), ('R', ('L7', 'L8'))], start=1)))\n"
            "print([j.at for j in generic_pose(chain).joints])\n")
    # this run's (its hash seed drawn at random) against a run with another seed
    here = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, "PYTHONHASHSEED": "1"}, check=True).stdout
    namespace: dict = {}
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(code, namespace)
    assert printed.getvalue() == here
