"""The report's gear trains (issue 39): which entries are trains, their speeds against the
products of the teeth and the textbook's epicyclic table worked here, and their pages:
the train's drawing in place of the skeleton, the speeds table, the index's pictures."""

import re
import shutil
import subprocess
from fractions import Fraction

import pytest

import chaingraph
from chaingraph.naming.catalog import catalog_dir, catalog_files, catalog_path
from chaingraph.report.build import build_report
from chaingraph.kinematics.gears import is_gear_train
from chaingraph.report.gears import train_fixed, train_ways

from ..conftest import solver_takes

TRAINS = ["simple-gear-train", "compound-gear-train", "reverted-gear-train",
          "epicyclic-gear-train", "differential-gear-train"]


def load(name):
    return chaingraph.load(catalog_path(name))


def teeth(chain):
    """Each link's teeth in each pair: {(pair id, link): z}."""
    return {(g.id, x): z for g in chain.gears for x, z in zip(g.links, g.teeth)}


def test_the_catalog_s_gear_trains_are_the_five_trains():
    found = sorted(p.stem for p in catalog_files() if is_gear_train(chaingraph.load(p)))
    assert found == sorted(TRAINS)
    # a linkage with gears in it is no train (the solver moves it), nor is a cam
    for path in (catalog_dir() / "geared-five-bar.toml",
                 catalog_path("disc-cam-roller-follower")):
        assert not is_gear_train(chaingraph.load(path)), path
    # and the solver tests leave exactly the trains out for their gears
    assert all(not solver_takes(load(n)) for n in TRAINS)


def test_one_freedom_trains_run_by_their_first_moving_link():
    """Driven at 1 rpm, every link turns by the product of the teeth along the way
    (the driver's over the driven's per mesh, the sense reversed by each external
    mesh)."""
    for name, path in [("simple-gear-train", ["G1", "G2"]),
                       ("compound-gear-train", ["G1", "G2", "G3"]),
                       ("reverted-gear-train", ["G1", "G2"])]:
        chain = load(name)
        assert train_fixed(chain) == "frame"
        (way,) = train_ways(chain)
        assert way.held is None and way.driver == chain.links[1]
        z, speed = teeth(chain), Fraction(1)
        for g in (g for pid in path for g in chain.gears if g.id == pid):
            a, b = g.links
            speed *= Fraction(-z[g.id, a], z[g.id, b])
            assert way.result.speeds[b] == speed, (name, b)


def test_the_epicyclic_train_with_each_member_held():
    """The textbook's table, worked here from the teeth (sun 20, annulus 80): annulus
    held, arm / sun = zs / (zs + za); sun held, annulus / arm = 1 + zs / za; arm held,
    annulus / sun = -zs / za."""
    chain = load("epicyclic-gear-train")
    zs, za = 20, 80
    ways = {w.held: w.result for w in train_ways(chain)}
    assert sorted(ways) == ["annulus", "arm", "sun"]
    w = ways["annulus"].speeds
    assert w["arm"] / w["sun"] == Fraction(zs, zs + za) == Fraction(1, 5)
    w = ways["sun"].speeds
    assert w["annulus"] / w["arm"] == 1 + Fraction(zs, za) == Fraction(5, 4)
    w = ways["arm"].speeds
    assert w["annulus"] / w["sun"] == Fraction(-zs, za)
    assert all(r.speeds["frame"] == 0 and r.freedom == 2 for r in ways.values())
    # held by its arm, it is an ordinary train (the planet an idler); else epicyclic
    kinds = {w.held: w.kind for w in train_ways(chain)}
    assert kinds == {"sun": "epicyclic", "annulus": "epicyclic", "arm": "simple"}


def test_the_differential_s_wheels_share_the_case():
    """Held one wheel, the other turns at twice the case (left + right = 2 case), the
    case at -12/48 of the pinion."""
    ways = {w.held: w.result.speeds for w in train_ways(load("differential-gear-train"))}
    w = ways["left"]
    assert w["case"] == Fraction(-12, 48) * w["pinion"]
    assert w["left"] + w["right"] == 2 * w["case"]
    # the pinion held holds the case: the wheels turn equally and oppositely
    assert ways["pinion"]["case"] == 0 and ways["pinion"]["left"] == -ways["pinion"]["right"]


@pytest.fixture(scope="module")
def gear_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("gears")
    paths = [catalog_path(n) for n in TRAINS] + [catalog_path("four-bar-chain")]
    return build_report(paths, out, progress=None, workers=1), out


def test_a_train_s_page_has_its_drawing_speeds_and_no_skeleton(gear_report):
    result, out = gear_report
    assert result.complete
    for name in TRAINS:
        text = (out / f"{name}.html").read_text()
        assert f"img/{name}-train.svg" in text and "skeleton" not in text, name
        assert 'id="gear-speeds"' in text and 'class="gear-tabular"' in text, name
        assert "player" not in text and 'id="summary"' not in text    # no animation
        drawing = (out / "img" / f"{name}-train.svg").read_text()
        assert drawing.count("<circle") >= 2 * len(load(name).gears)
    page = (out / "epicyclic-gear-train.html").read_text()
    speeds = page.split('id="gear-speeds"')[1].split("</table>")[0]
    rows = re.findall(r"<tr><td>(\w+)</td><td>(\w+)</td><td>(\w+)</td>", speeds)
    assert [held for held, _, _ in rows] == ["sun", "annulus", "arm"]
    assert "1/5" in speeds and "-1/4" in speeds and "4/5" in speeds
    simple = (out / "simple-gear-train.html").read_text()
    assert "driver / driven</td><td class=\"num\">5/2" in simple
    four = (out / "four-bar-chain.html").read_text()
    assert "img/four-bar-chain-skeleton.svg" in four and "gear-speeds" not in four


def test_the_index_pictures_each_entry(gear_report):
    result, out = gear_report
    index = (out / "index.html").read_text()
    for row in result.entries:
        want = "train-front" if row.slug in TRAINS else "skeleton"
        assert f'src="img/{row.slug}-{want}.svg"' in index
        assert (out / "img" / f"{row.slug}-{want}.svg").stat().st_size > 500


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (.ci/run installs "
                                             "Debian's chromium; install it to run this test)")
def test_a_train_s_page_in_a_real_browser(gear_report):
    _, out = gear_report
    for name in ("index.html", "epicyclic-gear-train.html"):
        dom = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                              "--no-first-run", "--disable-background-networking",
                              "--disable-component-update", "--disable-sync",
                              "--virtual-time-budget=10000", "--dump-dom",
                              (out / name).as_uri()],
                             capture_output=True, text=True, timeout=120).stdout
        body = re.search(r"<body[^>]*>", dom).group(0)
        total = int(re.search(r'data-images="(\d+)"', body).group(1))
        assert int(re.search(r'data-images-loaded="(\d+)"', body).group(1)) == total > 1
