"""The illustrated atlas's index: a thumbnail per chain, its base chain named, where its
sliding pairs and multiple joints are, its named inversions, and a filter that a real
browser runs."""

import html
import json
import re
import shutil

import pytest

import chaingraph
from chaingraph.naming.atlas import atlas_names
from chaingraph.naming.catalog import catalog_path
from chaingraph.report.atlas import write_illustrated
from chaingraph.report.atlas_index import index_page
from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.multiple import multiple_atlas
from chaingraph.structure.atlas.sliding import sliding_atlas
from chaingraph.structure.isomorphism import canonical_form

from .browser import Browser

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
ROW = re.compile(r'<tr class="chain" id="chain-(\d+)" ([^>]*)>(.*?)</tr>', re.S)


def _rows(page):
    """{chain id: (data attributes, the row's HTML)} of an index page."""
    out = {}
    for m in ROW.finditer(page):
        attrs = {k: html.unescape(v) for k, v in re.findall(r'data-(\w+)="([^"]*)"', m[2])}
        out[int(m[1])] = (attrs, m[3])
    return out


@pytest.fixture(scope="module")
def six(tmp_path_factory):
    """The 6-link atlas with every number of sliding pairs, drawn (not animated)."""
    result = sliding_atlas(atlas_graphs(6, 1), prismatic=range(8))
    out = tmp_path_factory.mktemp("atlas6")
    write_illustrated(result, out, animate=False)
    return result, out, (out / "index.html").read_text(encoding="utf-8")


def _ternary_adjacent(entry):
    """Whether the two ternary links of a 6-link chain are joined (Watt's) or not
    (Stephenson's): the textbook's way of telling the two apart."""
    degree = [sum(x in j for j in entry.edges) for x in range(entry.links)]
    a, b = [x for x, d in enumerate(degree) if d == 3]
    return any(set(j) == {a, b} for j in entry.edges)


def test_the_index_tells_watt_from_stephenson(six):
    result, _, page = six
    rows = _rows(page)
    assert sorted(rows) == [e.id for e in result]
    watt = canonical_form(chaingraph.load(catalog_path("watt-six-bar-chain")))
    stephenson = canonical_form(chaingraph.load(catalog_path("stephenson-six-bar-chain")))
    turning = [rows[e.id][0]["base"] for e in result if e.prismatic == 0]
    assert sorted(turning) == ["Stephenson six-bar chain", "Watt six-bar chain"]
    for e in result:
        base = rows[e.id][0]["base"]
        assert base == ("Watt six-bar chain" if _ternary_adjacent(e)
                        else "Stephenson six-bar chain"), e.id
        form = canonical_form(chaingraph.Chain("base", tuple(
            chaingraph.Joint(f"J{i}", "R", (f"L{a}", f"L{b}")) for i, (a, b) in
            enumerate(e.edges))))
        assert form == (watt if base.startswith("Watt") else stephenson)
        assert f'>{base}</a>' in rows[e.id][1]          # linked to the base chain's page
    counts = {b: sum(a["base"] == b for a, _ in rows.values())
              for b in ("Watt six-bar chain", "Stephenson six-bar chain")}
    assert sum(counts.values()) == len(result) and min(counts.values()) > 0
    assert f'<option value="Watt six-bar chain">Watt six-bar chain ' \
           f'({counts["Watt six-bar chain"]})</option>' in page


def test_every_chain_has_its_skeleton_as_a_thumbnail(six):
    result, out, page = six
    rows = _rows(page)
    for e in result:
        assert f'<img class="thumb" src="thumbs/chain-{e.id}.svg"' in rows[e.id][1]
        svg = (out / "thumbs" / f"chain-{e.id}.svg").read_text()
        assert svg.count('class="pin"') == e.kinds.count("R")
        assert svg.count('class="block"') == e.prismatic
        plates = sum(v for k, v in e.link_orders.items() if k != "binary")
        assert svg.count('class="plate"') == plates
        assert "<text" not in svg                        # no labels at thumbnail size
    assert len(list((out / "thumbs").glob("*.svg"))) == len(result)


def test_where_the_sliding_pairs_are_and_the_named_inversions(six):
    result, _, page = six
    rows = _rows(page)
    named = 0
    for e in result:
        attrs, row = rows[e.id]
        assert attrs["sliding"] == str(e.prismatic) and attrs["multiple"] == "0"
        assert row.count("sliding pair J") == e.prismatic
        for i, (a, b) in enumerate(e.edges):
            said = re.search(rf"sliding pair J{i + 1} between \w+ L(\d) and \w+ L(\d)", row)
            assert (said is not None) == (e.kinds[i] == "P")
            if said:
                assert {int(said[1]), int(said[2])} == {a + 1, b + 1}
        names = atlas_names(e.chain(1))
        inversions = [n for c in names["inversions"] for n in c["names"]]
        for n in names["chain"] + inversions:
            assert html.escape(n) in row
        assert attrs["named"] == ("1" if inversions else "0")
        named += bool(inversions)
    assert named == 4            # Watt's, Stephenson's, the quick return with its ram, the beam engine's
    for n in ("Watt I six-bar mechanism", "Watt II six-bar mechanism",
              "Stephenson I six-bar mechanism", "Stephenson II six-bar mechanism",
              "Stephenson III six-bar mechanism", "Beam engine with its piston"):
        assert n in page


def test_degrees_of_freedom_are_counted_in_words(six):
    _, _, page = six
    assert "<h1>Chains of 6 links, 1 degree of freedom</h1>" in page
    assert "degree(s)" not in page and "1 inversions" not in page
    seven = sliding_atlas(atlas_graphs(7, 2), prismatic=1)
    cards = [(e, atlas_names(e.chain(2)), None) for e in seven]
    other = index_page(seven, cards)
    assert "<h1>Chains of 7 links, 2 degrees of freedom</h1>" in other
    assert "degree(s)" not in other


def test_multiple_joints_are_said_and_filtered():
    result = sliding_atlas(multiple_atlas(atlas_graphs(6, 1)), prismatic=range(8))
    cards = [(e, atlas_names(e.chain(1)), None) for e in result]
    page = index_page(result, cards)
    rows = _rows(page)
    assert sorted(rows) == [e.id for e in result]
    seen = set()
    for e in result:
        attrs, row = rows[e.id]
        multiple = [j for j in e.edges if len(j) > 2]
        assert attrs["multiple"] == str(len(multiple))
        assert row.count("multiple joint J") == len(multiple)
        for j in multiple:
            links = ", ".join(f"L{x + 1}" for x in j[:-1]) + f" and L{j[-1] + 1}"
            assert f"joining {links}" in row
        seen.add(len(multiple))
    assert seen == {0, 1, 2}
    assert '<select id="f-multiple">' in page
    assert "chaingraph atlas --links 6 --multiple" in page
    assert "<h2>0 sliding pairs, 2 multiple joints (" in page
    two = [a["base"] for a, _ in rows.values() if a["multiple"] == "2" and a["sliding"] == "0"]
    assert two == ["Six links on two ternary joints"]           # the catalog's name


_VISIBLE = """(function () {
  var rows = Array.prototype.filter.call(document.querySelectorAll('tr.chain'),
    function (r) { return r.getClientRects().length > 0; });
  var groups = Array.prototype.filter.call(document.querySelectorAll('section.group'),
    function (g) { return g.getClientRects().length > 0; });
  var images = Array.prototype.filter.call(document.querySelectorAll('img.thumb'),
    function (i) { return i.complete && i.naturalWidth > 0; });
  return {rows: rows.map(function (r) { return +r.id.slice(6); }), groups: groups.length,
          counts: groups.map(function (g) { return +g.querySelector('.shown').textContent; }),
          shown: document.getElementById('f-shown').textContent, loaded: images.length,
          form: !document.getElementById('filter').hidden};
})()"""


_FIRST_IMAGES = """Promise.all(Array.prototype.slice.call(
  document.querySelectorAll('img.thumb'), 0, 3).map(function (i) {
    return Promise.race([i.decode().then(function () { return i.naturalWidth > 0; }),
                         new Promise(function (done) { setTimeout(done, 20000, false); })]);
  }))"""


def _set(browser, tab, field, value):
    prop = "checked" if field == "f-named" else "value"
    browser.evaluate(tab, f"(function () {{ var f = document.getElementById('{field}'); "
                          f"f.{prop} = {json.dumps(value)}; "
                          "f.dispatchEvent(new Event('input')); return true; })()")
    return browser.evaluate(tab, _VISIBLE)


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (.ci/run installs "
                                             "Debian's chromium; install it to run this test)")
def test_the_filter_hides_rows_in_a_real_browser(six):
    result, out, _ = six
    everything = [e.id for e in sorted(result, key=lambda e: (e.prismatic, e.id))]
    one = [e.id for e in result if e.prismatic == 1]
    watt_one = [e.id for e in result if e.prismatic == 1 and _ternary_adjacent(e)]
    with Browser() as browser:
        tab = browser.open((out / "index.html").as_uri())
        # the first thumbnails, in view, load (lazily: after the page's load event)
        assert browser.evaluate(tab, _FIRST_IMAGES) == [True, True, True]
        start = browser.evaluate(tab, _VISIBLE)
        assert start["form"] and sorted(start["rows"]) == sorted(everything)
        assert start["shown"] == f"{len(result)} of {len(result)} chains shown"
        assert start["loaded"] >= 3
        shown = _set(browser, tab, "f-sliding", "1")
        assert sorted(shown["rows"]) == sorted(one) and shown["groups"] == 1
        assert shown["counts"] == [len(one)]
        shown = _set(browser, tab, "f-base", "Watt six-bar chain")
        assert sorted(shown["rows"]) == sorted(watt_one)
        assert shown["shown"] == f"{len(watt_one)} of {len(result)} chains shown"
        assert shown["counts"] == [len(watt_one)] and 0 < len(watt_one) < len(one)
        shown = _set(browser, tab, "f-text", "BEAM engine")
        beam = [e.id for e in result if e.prismatic == 1 and any(
            "Beam engine" in n for c in atlas_names(e.chain(1))["inversions"]
            for n in c["names"])]
        assert shown["rows"] == beam and len(beam) == 1
        _set(browser, tab, "f-text", "")
        _set(browser, tab, "f-base", "")
        _set(browser, tab, "f-sliding", "")
        shown = _set(browser, tab, "f-named", True)
        named = [e.id for e in result if atlas_names(e.chain(1))["inversions"]]
        assert sorted(shown["rows"]) == sorted(named) and len(named) == 4
        shown = _set(browser, tab, "f-named", False)
        assert sorted(shown["rows"]) == sorted(everything)
        assert sum(shown["counts"]) == len(result) and shown["groups"] == len(
            {e.prismatic for e in result})


def test_oriented_sliding_pairs_say_which_link_carries_the_guide():
    result = sliding_atlas(atlas_graphs(4, 1), prismatic=2, oriented=True)
    page = index_page(result, [(e, atlas_names(e.chain(1), oriented=True), None)
                               for e in result])
    assert "(oriented)</h1>" in page
    rows = _rows(page)
    guides = set()
    for e in result:
        row = rows[e.id][1]
        for i, ((a, b), kind) in enumerate(zip(e.edges, e.kinds)):
            if kind == "P":
                assert f"sliding pair J{i + 1}: binary L{b + 1} on a guide on binary " \
                       f"L{a + 1}" in row
                guides.add((e.base, a, b))
    assert len(result) == 5 and len(guides) > len({(g[0], *sorted(g[1:])) for g in guides})
