"""The atlas: published counts, and an independent brute-force cross-check."""

import itertools
import json

import networkx as nx
import pytest

import chaingraph
from chaingraph import AtlasSizeError
from chaingraph.atlas import assortments, atlas_graphs, joints_for

from .conftest import run_cli

# the brute force buckets graphs by networkx's WL hash within one run; the hash values'
# change in networkx 3.5 (its warning) does not matter here
pytestmark = pytest.mark.filterwarnings("ignore:The hashes produced:UserWarning")


@pytest.mark.parametrize("links, count, inversions", [(4, 1, 1), (6, 2, 5), (8, 16, 71),
                                                      (10, 230, 1834)])
def test_published_one_dof_counts(links, count, inversions):
    entries = atlas_graphs(links, 1)
    assert len(entries) == count
    assert sum(e.inversion_classes for e in entries) == inversions


@pytest.mark.slow
def test_twelve_links_6856():
    entries = atlas_graphs(12, 1, workers=2)
    assert len(entries) == 6856


# -- an independent brute force: every graph of the size, by networkx ---------------
def _rigid_part(g):
    """Some proper subset of two or more links whose own mobility is <= 0 (by itertools)."""
    nodes = list(g)
    for size in range(2, len(nodes)):
        for subset in itertools.combinations(nodes, size):
            if 3 * (size - 1) - 2 * g.subgraph(subset).number_of_edges() <= 0:
                return True
    return False


def _all_graphs(n, m):
    """Every graph on n nodes with m edges, up to isomorphism, edge by edge."""
    level = [nx.empty_graph(n)]
    for _ in range(m):
        buckets = {}
        for g in level:
            for u, v in itertools.combinations(range(n), 2):
                if g.has_edge(u, v):
                    continue
                h = g.copy()
                h.add_edge(u, v)
                key = (tuple(sorted(d for _, d in h.degree())),
                       nx.weisfeiler_lehman_graph_hash(h, iterations=3))
                reps = buckets.setdefault(key, [])
                if not any(nx.is_isomorphic(h, r) for r in reps):
                    reps.append(h)
        level = [g for reps in buckets.values() for g in reps]
    return level


def _brute_force(n, dof):
    twice = 3 * (n - 1) - dof
    if twice % 2 or twice // 2 < n:
        return None
    chains = [g for g in _all_graphs(n, twice // 2)
              if min(d for _, d in g.degree()) >= 2 and nx.is_connected(g)
              and not _rigid_part(g)]
    orbits = 0
    for g in chains:
        autos = list(nx.algorithms.isomorphism.GraphMatcher(g, g).isomorphisms_iter())
        orbits += len({frozenset(a[v] for a in autos) for v in g})
    return len(chains), orbits


SIZES = [(n, f) for f in (1, 2, 3) for n in range(3, 9) if not (3 * (n - 1) - f) % 2
         and (3 * (n - 1) - f) // 2 >= n]


@pytest.mark.parametrize("links, dof", SIZES, ids=[f"{n}-links-{f}-dof" for n, f in SIZES])
def test_atlas_against_brute_force(links, dof):
    expected = _brute_force(links, dof)
    entries = atlas_graphs(links, dof)
    assert (len(entries), sum(e.inversion_classes for e in entries)) == expected


def test_sizes_without_chains_and_bad_numbers():
    for links, dof, words in [(5, 1, "is odd"), (3, 2, "fewer than"), (0, 1, "positive"),
                              (4, 0, "positive"), (7, 1, "is odd")]:
        with pytest.raises(AtlasSizeError, match=words):
            joints_for(links, dof)
    code, out, err = run_cli("atlas", "--links", "5", "--dof", "1")
    assert code == 2 and "odd" in err and "Traceback" not in err
    code, out, err = run_cli("atlas", "--links", "-2")
    assert code == 2 and "positive" in err


def test_assortments():
    # eight links, ten joints: (binary, ternary, quaternary, ...) counts
    found = {tuple(x for x in a[:3]) for a in assortments(8, 10) if not any(a[3:])}
    assert {(4, 4, 0), (5, 2, 1), (6, 0, 2)} <= found
    # seven links, two dof: one quaternary link shared by two loops is possible
    assert any(a[2] == 1 and a[0] == 6 for a in assortments(7, 8))


def test_atlas_chains_are_chains():
    chains = list(chaingraph.atlas(links=8, dof=1))
    assert len(chains) == 16
    forms = set()
    for chain in chains:
        c = chaingraph.classify(chain)
        assert c.mobility == 1 and not c.degenerate and c.verdict == "kinematic chain"
        forms.add(chaingraph.canonical_form(chain))
    assert len(forms) == 16
    watt = chaingraph.load(chaingraph.catalog.catalog_path("watt-six-bar-chain"))
    steph = chaingraph.load(chaingraph.catalog.catalog_path("stephenson-six-bar-chain"))
    six = {chaingraph.canonical_form(c) for c in chaingraph.atlas(links=6, dof=1)}
    assert six == {chaingraph.canonical_form(watt), chaingraph.canonical_form(steph)}


def test_nonplanar_link_graphs_are_included():
    # ten links, one dof: some link graphs are not planar (they first appear at 10)
    entries = atlas_graphs(10, 1)
    nonplanar = [e for e in entries if not nx.check_planarity(nx.Graph(list(e.edges)))[0]]
    assert nonplanar


def test_cli_json_and_out(tmp_path):
    code, out, err = run_cli("atlas", "--links", "8", "--dof", "1", "--json", "--out", tmp_path,
                             "--workers", "2")
    assert code == 0, err
    d = json.loads(out)
    assert set(d) == {"links", "dof", "count", "count_non_fractionated",
                      "distinct_inversions", "chains"}
    assert (d["count"], d["count_non_fractionated"], d["distinct_inversions"]) == (16, 16, 71)
    assert set(d["chains"][0]) == {"id", "edges", "link_orders", "inversion_classes",
                                   "fractionated"}
    assert [c["id"] for c in d["chains"]] == list(range(1, 17))
    assert json.loads((tmp_path / "atlas.json").read_text()) == d
    lines = (tmp_path / "atlas-8-links-1-dof.g6").read_bytes().splitlines()
    assert len(lines) == 16
    for line, chain in zip(lines, d["chains"]):
        g = nx.from_graph6_bytes(line)
        assert nx.is_isomorphic(g, nx.Graph([tuple(e) for e in chain["edges"]]))
    files = sorted((tmp_path / "chains").glob("*.toml"))
    assert len(files) == 16
    loaded = [chaingraph.classify(chaingraph.load(f)) for f in files]
    assert all(c.mobility == 1 and not c.degenerate for c in loaded)
    page = (tmp_path / "index.html").read_text()
    assert page.count("<svg") == 16 and "71 distinct inversions" in page
