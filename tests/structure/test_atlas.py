"""The atlas: published counts, and an independent brute-force cross-check."""

import itertools
import json

import networkx as nx
import pytest

import chaingraph
from chaingraph import AtlasSizeError
from chaingraph.structure.atlas import assortments, atlas_graphs, joints_for

from ..conftest import children, interruptible, run_cli, wait_for

# the brute force buckets graphs by networkx's WL hash within one run; the hash values'
# change in networkx 3.5 (its warning) does not matter here
pytestmark = pytest.mark.filterwarnings("ignore:The hashes produced:UserWarning")


@pytest.mark.parametrize("links, count, inversions", [(4, 1, 1), (6, 2, 5), (8, 16, 71),
                                                      (10, 230, 1834)])
def test_published_one_dof_counts(links, count, inversions):
    entries = atlas_graphs(links, 1)
    assert len(entries) == count
    assert sum(e.inversion_classes for e in entries) == inversions


def test_twelve_links_6856():
    entries = atlas_graphs(12, 1, workers=2)
    assert (entries.count, entries.distinct_inversions) == (6856, 75397)


@pytest.mark.slow
def test_fourteen_links_from_the_command_line():
    code, out, err = run_cli("atlas", "--links", "14", "--dof", "1", "--workers", "2",
                             "--summary", "-q")
    assert code == 0, err
    assert json.loads(out) == {"links": 14, "dof": 1, "count": 318162,
                               "count_non_fractionated": 318162,
                               "distinct_inversions": 4274510}


# Tuttle's tables and the literature count non-fractionated chains; both are checked
@pytest.mark.parametrize("links, dof, count, whole", [
    (7, 2, 4, 3), (9, 2, 40, 35), (11, 2, 839, 753),
    (8, 3, 7, 5), (10, 3, 98, 74), (12, 3, 2422, 1962)])
def test_published_multi_dof_counts(links, dof, count, whole):
    entries = atlas_graphs(links, dof)
    assert (entries.count, entries.count_non_fractionated) == (count, whole)
    assert entries.without_fractionated().count == whole


@pytest.mark.parametrize("links, dof", [(8, 1), (10, 1), (9, 2), (10, 3)])
def test_nauty_and_the_own_labelling_give_the_same_chains(links, dof):
    """The project's canonical labelling is the reference: the graphs nauty labels are,
    by the project's own canonical form, the graphs the own labelling gives."""
    from chaingraph.structure.isomorphism import canonical_form
    by = {}
    for labelling in ("nauty", "own"):
        entries = atlas_graphs(links, dof, labelling=labelling)
        by[labelling] = sorted((canonical_form(e.chain()), e.inversion_classes, e.fractionated)
                               for e in entries)
    assert by["nauty"] == by["own"]

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
    """(chains, distinct inversions, non-fractionated chains), by networkx alone."""
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
    # fractionated: a link (cut vertex) or a joint (bridge) whose removal splits it
    whole = sum(1 for g in chains if nx.is_biconnected(g))
    return len(chains), orbits, whole


SIZES = [(n, f) for f in (1, 2, 3) for n in range(3, 9) if not (3 * (n - 1) - f) % 2
         and (3 * (n - 1) - f) // 2 >= n]


@pytest.mark.parametrize("links, dof", SIZES, ids=[f"{n}-links-{f}-dof" for n, f in SIZES])
def test_atlas_against_brute_force(links, dof):
    expected = _brute_force(links, dof)
    entries = atlas_graphs(links, dof)
    assert (len(entries), sum(e.inversion_classes for e in entries),
            entries.count_non_fractionated) == expected
    for e in entries:                    # the flag of each chain, not only the count
        assert e.fractionated == (not nx.is_biconnected(nx.Graph(list(e.edges))))


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
    watt = chaingraph.load(chaingraph.naming.catalog.catalog_path("watt-six-bar-chain"))
    steph = chaingraph.load(chaingraph.naming.catalog.catalog_path("stephenson-six-bar-chain"))
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


# -- the run: shards, resume, cluster, interrupts, sizes ------------------------------
def _atlas_json(folder):
    return json.loads((folder / "atlas.json").read_text())


def test_summary_and_no_fractionated(tmp_path):
    code, out, err = run_cli("atlas", "--links", "9", "--dof", "2", "--summary", "-q")
    assert code == 0, err
    assert json.loads(out) == {"links": 9, "dof": 2, "count": 40, "count_non_fractionated": 35,
                               "distinct_inversions": 254}
    code, out, err = run_cli("atlas", "--links", "9", "--dof", "2", "--json",
                             "--no-fractionated", "--out", tmp_path, "-q")
    assert code == 0, err
    d = json.loads(out)
    assert (d["count"], d["count_non_fractionated"]) == (35, 35)
    assert [c["id"] for c in d["chains"]] == list(range(1, 36))
    assert not any(c["fractionated"] for c in d["chains"])
    assert d["distinct_inversions"] == sum(c["inversion_classes"] for c in d["chains"])
    assert _atlas_json(tmp_path) == d
    assert len((tmp_path / "atlas-9-links-2-dof.g6").read_bytes().splitlines()) == 35
    code, out, err = run_cli("atlas", "--links", "9", "--dof", "2")
    assert code == 0 and "40 chains" in out and "(35 non-fractionated)" in out
    assert "fractionated" in out.splitlines()[1]          # the table's column


def test_graph6_lines_match_networkx():
    import random

    import numpy as np

    from chaingraph.structure.atlas.entry import graph6_lines
    rng = random.Random(3)
    for n in (2, 5, 13, 20):
        graphs = [nx.gnm_random_graph(n, n, seed=rng.randrange(10**6)) for _ in range(20)]
        edges = np.array([list(g.edges()) for g in graphs])
        expected = b"".join(nx.to_graph6_bytes(g, header=False) for g in graphs)
        assert graph6_lines(n, edges) == expected


def test_chain_files_are_the_files_dumps_writes(tmp_path):
    from chaingraph.structure.atlas.output import chain_text
    for entry in atlas_graphs(10, 1)[:20]:
        assert chain_text(entry, 1) == chaingraph.dumps(entry.chain(1))
    code, out, err = run_cli("atlas", "--links", "10", "--no-chain-files", "--out", tmp_path,
                             "-q")
    assert code == 0 and not (tmp_path / "chains").exists()


def test_resume_redoes_only_the_missing_shards(tmp_path):
    code, _, err = run_cli("atlas", "--links", "11", "--dof", "2", "--out", tmp_path, "-q")
    assert code == 0, err
    whole = _atlas_json(tmp_path)
    shards = sorted((tmp_path / "shards").glob("shard-*.jsonl"))
    assert len(shards) > 10
    # a run that died: some shards never finished (one with its graph6 written and its
    # JSON lines not yet), no final files
    for path in shards[3:9]:
        path.unlink()
    (tmp_path / "shards" / "shard-00001.g6").unlink()
    (tmp_path / "atlas.json").unlink()
    kept = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "shards").glob("*.jsonl")}
    code, out, err = run_cli("atlas", "--links", "11", "--dof", "2", "--out", tmp_path,
                             "--resume", "-q")
    assert code == 0, err
    assert _atlas_json(tmp_path) == whole
    for name, mtime in kept.items():            # finished shards were not done again
        if name != "shard-00001.jsonl":
            assert (tmp_path / "shards" / name).stat().st_mtime_ns == mtime


def test_resume_refuses_what_it_cannot_continue(tmp_path):
    code, out, err = run_cli("atlas", "--links", "10", "--resume", "--out", tmp_path)
    assert code == 2 and "no run to resume" in err and "Traceback" not in err
    run_cli("atlas", "--links", "8", "--out", tmp_path, "-q")
    code, out, err = run_cli("atlas", "--links", "10", "--resume", "--out", tmp_path)
    assert code == 2 and "holds a run of 8 links" in err
    code, out, err = run_cli("atlas", "--links", "10", "--resume")
    assert code == 2 and "--out" in err


def test_a_local_dask_cluster_gives_the_local_run():
    import numpy as np

    from chaingraph.structure.atlas import DaskRunner, run_atlas
    local = run_atlas(11, 2, workers=2)
    with DaskRunner("local", workers=2) as runner:
        cluster = run_atlas(11, 2, runner=runner)
    assert np.array_equal(local.edges, cluster.edges)
    assert np.array_equal(local.inversion_classes, cluster.inversion_classes)
    assert np.array_equal(local.fractionated, cluster.fractionated)
    code, out, err = run_cli("atlas", "--links", "10", "--scheduler", "local", "--workers",
                             "2", "--summary", "-q")
    assert code == 0, err
    assert json.loads(out)["count"] == 230


def test_an_unreachable_scheduler_is_one_line(monkeypatch):
    from chaingraph.structure.atlas import run
    monkeypatch.setattr(run, "CONNECT_TIMEOUT", 1.0)     # nothing listens there anyway
    code, out, err = run_cli("atlas", "--links", "8", "--scheduler", "tcp://127.0.0.1:9",
                             "-q")
    assert code == 2 and "Traceback" not in err
    assert err.strip().count("\n") == 0 and "cannot reach the Dask scheduler" in err


@pytest.mark.parametrize("args, words", [
    (["--links", "18"], "refused on this machine"),
    (["--links", "1000000000"], "at most 40 links"),
    (["--links", "22", "--scheduler", "tcp://127.0.0.1:9"], "core-hours"),
    (["--links", "8", "--workers", "0"], "--workers must be 1 or more"),
])
def test_sizes_that_cannot_finish_are_refused_up_front(args, words):
    """Refused by the estimate (or the arguments) before any work: the message says so,
    and nothing is written."""
    code, out, err = run_cli("atlas", *args)
    assert code == 2 and words in err and "Traceback" not in err and out == ""
    if "18" in args:
        assert "--scheduler" in err and "days" in err      # the estimate and the way


def test_the_estimate_is_near_every_count():
    from chaingraph.structure.atlas.estimate import KNOWN, FIT, estimate
    for (links, dof), count in KNOWN.items():
        assert estimate(links, dof).chains == pytest.approx(count)
        loops = (links - 1 - dof) / 2
        a, b, c, d = FIT
        fitted = 10 ** (a + b * links + c * loops + d * links * loops)
        if count >= 40:
            assert count / 2 <= fitted <= 2 * count, (links, dof)


def test_workers_are_capped_at_the_cpus():
    code, out, err = run_cli("atlas", "--links", "8", "--workers", "500", "-q")
    assert code == 0 and "capped" in err and "16 chains" in out


def test_progress_without_a_terminal_is_a_few_plain_lines():
    code, out, err = run_cli("atlas", "--links", "11", "--dof", "2")
    lines = err.splitlines()
    assert code == 0 and "\r" not in err and 2 <= len(lines) <= 12
    assert lines[0].endswith("plan: contracted graphs") and lines[-1].startswith("[100%]")


@pytest.mark.slow
def test_ctrl_c_leaves_no_worker_and_a_resumable_folder(tmp_path):
    import os
    import signal
    import subprocess
    import sys
    import time

    out = tmp_path / "run"
    # 13 links with 2 degrees of freedom: hundreds of shards in seconds (14 links with 1
    # took half a minute to resume)
    size = ["--links", "13", "--dof", "2"]
    proc = subprocess.Popen([sys.executable, "-m", "chaingraph", "atlas", *size,
                             "--workers", "2", "--out", str(out), "-q"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, preexec_fn=interruptible)
    # interrupted while its workers are at work, with a shard written (a race else)
    assert wait_for(lambda: len(children(proc.pid)) >= 2 and
                    bool(list(out.glob("shards/*.jsonl"))), 120), "no shard written"
    assert proc.poll() is None, "the atlas finished before it could be interrupted"
    os.killpg(proc.pid, signal.SIGINT)              # as a terminal's Ctrl-C does
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130 and err.strip() == "chaingraph: interrupted"
    time.sleep(0.5)
    left = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            if str(out) in open(f"/proc/{pid}/cmdline").read():
                left.append(pid)
        except OSError:
            pass
    assert not left                                  # no worker process behind
    assert not list(out.glob("shards/*.tmp"))
    done = {f.name: f.stat().st_mtime_ns for f in out.glob("shards/*.jsonl")}
    code, resumed, err = run_cli("atlas", *size, "--workers", "2", "--out", out,
                                 "--resume", "--summary", "-q")
    assert code == 0, err
    code, whole, err = run_cli("atlas", *size, "--out", tmp_path / "whole", "--summary", "-q")
    assert code == 0, err
    # the resumed run is the uninterrupted one, and it kept the shards already written
    assert json.loads(resumed) == json.loads(whole)
    assert json.loads(resumed)["count"] > 0 and done
    assert {f: (out / "shards" / f).stat().st_mtime_ns for f in done} == done


def test_the_atlas_page_draws_no_joint_at_a_crossing_and_numbers_links_as_the_files():
    """A joint square at the crossing of two bars read as a multiple joint; the links are
    numbered 1..N on the page, as L1..LN in the chain files."""
    import re

    from chaingraph.structure.atlas import atlas_graphs
    from chaingraph.geometry import segment_distance
    from chaingraph.structure.atlas.output import atlas_svg, chain_text
    for entry in atlas_graphs(10, 1):
        svg = atlas_svg(entry)
        bars = [tuple(map(float, m)) for m in re.findall(
            r'<line x1="([-\d.]+)" y1="([-\d.]+)" x2="([-\d.]+)" y2="([-\d.]+)"', svg)]
        squares = [(float(x) + 3, float(y) + 3) for x, y in
                   re.findall(r'<rect class="joint" x="([-\d.]+)" y="([-\d.]+)"', svg)]
        assert len(bars) == len(squares) == len(entry.edges)
        for k, p in enumerate(squares):
            assert segment_distance(p, bars[k][:2], bars[k][2:]) < 0.2      # on its bar
            assert min(segment_distance(p, b[:2], b[2:])
                       for i, b in enumerate(bars) if i != k) >= 4.0
        labels = sorted(int(t) for t in re.findall(r">(\d+)</text>", svg))
        assert labels == list(range(1, entry.links + 1))
        assert f'"L{entry.links}"' in chain_text(entry)


# -- the size check and the memory of atlases with sliding pairs ------------------------
@pytest.mark.parametrize("args", [
    ["--links", "12", "--prismatic", "all", "--summary"],          # issue 35: ran for hours
    ["--links", "12", "--prismatic", "8", "--oriented", "--summary"],
    ["--links", "16", "--prismatic", "1"],
])
def test_atlases_with_sliding_pairs_that_cannot_finish_are_refused_up_front(args):
    """The estimate covers --prismatic, --oriented and --multiple: refused before any
    work, with the estimate and the option that allows it, and nothing printed."""
    code, out, err = run_cli("atlas", *args)
    assert code == 2 and out == "" and "Traceback" not in err and err.count("\n") == 1, err
    assert "refused on this machine" in err and "more than 1 hour" in err
    assert "of CPU in one process" in err and "--max-hours H" in err


@pytest.mark.parametrize("extra", [[], ["--prismatic", "all"], ["--max-hours", "1000"]])
def test_multiple_joints_past_what_was_measured_are_refused(extra):
    """12 links with multiple joints ran 15 minutes into 20 GB without finishing: it is
    refused in one line naming the links, whatever hours are allowed."""
    code, out, err = run_cli("atlas", "--links", "12", "--multiple", "--summary", *extra)
    assert code == 2 and out == "" and err.count("\n") == 1, err
    assert "measured to 10 links" in err and "--links" in err


def test_max_hours_is_what_a_run_may_take():
    """The same run refused under a tighter limit runs under the default one."""
    args = ["atlas", "--links", "6", "--prismatic", "all", "--summary", "-q"]
    code, out, err = run_cli(*args, "--max-hours", "1e-9")
    assert code == 2 and "more than 1e-09 hours" in err and out == ""
    code, out, err = run_cli(*args)
    assert code == 0 and json.loads(out)["count"] == 52
    code, out, err = run_cli("atlas", "--links", "22", "--max-hours", "1e9", "--workers",
                             "1", "--scheduler", "tcp://127.0.0.1:9")
    assert code == 2 and "core-hours" in err          # a cluster's own limit still holds


def test_the_sliding_estimate_grows_with_what_is_asked():
    from math import comb

    from chaingraph.structure.atlas.estimate import sliding_estimate
    every = tuple(range(17))
    one = sliding_estimate(12, 1, prismatic=(1,))
    plain = sliding_estimate(12, 1, prismatic=every)
    oriented = sliding_estimate(12, 1, prismatic=every, oriented=True)
    multiple = sliding_estimate(12, 1, prismatic=every, multiple=True)
    assert (one.assignments, plain.assignments) == (16, 2 ** 16)
    assert sliding_estimate(12, 1, prismatic=(2, 3)).assignments == comb(16, 2) + comb(16, 3)
    assert one.log10_seconds < plain.log10_seconds < oriented.log10_seconds
    assert plain.log10_seconds < multiple.log10_seconds
    for links in (6, 8, 10, 12, 14):           # more links, more time, whatever is asked
        now = sliding_estimate(links, 1, prismatic=every)
        after = sliding_estimate(links + 2, 1, prismatic=every)
        assert now.log10_seconds < after.log10_seconds
    assert plain.wall_seconds(2) > 3600 > one.wall_seconds(2)


def test_a_summary_counts_the_chains_as_it_finds_them(monkeypatch):
    """--summary (and the text of a long run) hold no list of chains: the chains are
    counted as they are found (memory flat: 10 links oriented, 18.8 million chains, once
    took 10 GB), and the counts are those of the listed atlas."""
    from chaingraph.cli import commands
    code, out, err = run_cli("atlas", "--links", "6", "--prismatic", "all", "--multiple",
                             "--json", "-q")
    assert code == 0, err
    listed = json.loads(out)
    del listed["chains"]

    def kept(*args, **kwargs):
        raise AssertionError("the chains were kept")
    monkeypatch.setattr(commands, "sliding_atlas", kept)
    code, out, err = run_cli("atlas", "--links", "6", "--prismatic", "all", "--multiple",
                             "--summary", "-q")
    assert code == 0, err
    assert json.loads(out) == listed and listed["count"] == 71          # docs/atlas.md
    assert listed["count_by_multiple"]["0"] == 52     # those of simple joints alone
    code, out, err = run_cli("atlas", "--links", "8", "--prismatic", "all", "--oriented",
                             "--summary", "-q")
    assert code == 0 and json.loads(out)["count"] == 50477             # docs/atlas.md
    code, out, err = run_cli("atlas", "--links", "8", "--prismatic", "1", "-q")
    assert code == 0 and out.startswith("84 chains") and "id  link assortment" not in out
    code, out, err = run_cli("atlas", "--links", "6", "--prismatic", "1", "-q")
    assert code == 0 and out.startswith("6 chains") and "id  link assortment" in out
    assert [line.split()[0] for line in out.splitlines()[-6:]] == list("123456")


def test_an_interrupted_rewrite_of_an_atlas_folder_presents_no_index(tmp_path, monkeypatch):
    """Rewriting an atlas folder (the turning-pair atlas's, the illustrated pages of one
    with sliding pairs) and interrupted halfway: no index.html beside the mixture."""
    from chaingraph.report import atlas as pages
    from chaingraph.structure.atlas import output

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt
    for args, module, name in ((["--links", "6"], output, "chain_text"),
                               (["--links", "4", "--prismatic", "all"], pages, "_page_job")):
        out = tmp_path / name
        code, _, err = run_cli("atlas", *args, "--out", out, "-q")
        assert code == 0 and (out / "index.html").exists(), err
        with monkeypatch.context() as m:
            m.setattr(module, name, interrupted)
            code, _, err = run_cli("atlas", *args, "--out", out, "-q")
        assert code == 130 and err.strip() == "chaingraph: interrupted"
        assert not (out / "index.html").exists() and (out / "chains").exists()
        code, _, err = run_cli("atlas", *args, "--out", out, "-q")       # and again, whole
        assert code == 0 and (out / "index.html").exists(), err
