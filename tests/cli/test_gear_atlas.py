"""``chaingraph atlas --gears`` and ``chaingraph gears --draw`` (issue 39): the counts, the
JSON, the written folder and the picture, and bad input as one line with exit status 2."""

import json

import pytest

from chaingraph.naming.catalog import catalog_path
from chaingraph.structure.atlas import DaskRunner
from chaingraph.structure.atlas import run as atlas_run
from chaingraph.structure.atlas.gears import gear_atlas, train_verdict

from ..conftest import run_cli


def _fixed(e):
    """The link the atlas's chain file fixes: the one in most turning pairs."""
    return max(range(e.links), key=lambda v: (sum(v in p for p in e.turning), -v))



def test_text_lists_the_trains():
    code, out, err = run_cli("atlas", "--gears", "--links", "5")
    assert code == 0, err
    first, *rest = out.splitlines()
    assert first.startswith("6 epicyclic gear trains of 5 links and 1 degree of freedom "
                            "(6 non-fractionated), 20 arrangements of turning pairs")
    rows = [line.split() for line in rest[2:]]
    assert [r[0] for r in rows] == [str(i) for i in range(1, 7)]
    assert [" ".join(r[1:4]) for r in rows] == [e.key for e in gear_atlas(5, 1)]


def test_json_and_summary():
    code, out, err = run_cli("atlas", "--gears", "--links", "6", "--dof", "2", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert (data["links"], data["dof"], data["gear_pairs"]) == (6, 2, 3)
    assert data["count"] == len(data["trains"]) == 12
    assert data["count_non_fractionated"] == sum(not t["fractionated"] for t in data["trains"]) == 2
    for t in data["trains"]:
        assert set(t) == {"id", "turning", "gears", "levels", "inversions", "fractionated",
                          "arrangements", "key", "names"}
        assert train_verdict(6, [tuple(p) for p in t["turning"]],
                             [tuple(g) for g in t["gears"]], dof=2) is None
    assert data["arrangements"] == sum(t["arrangements"] for t in data["trains"])
    code, out, _ = run_cli("atlas", "--gears", "--links", "6", "--dof", "2", "--summary")
    summary = json.loads(out)
    assert "trains" not in summary and summary["count"] == 12
    code, out, _ = run_cli("atlas", "--gears", "--links", "6", "--dof", "2", "--summary",
                           "--no-fractionated")
    assert json.loads(out)["count"] == 2


def test_out_writes_the_json_and_an_index(tmp_path):
    code, out, err = run_cli("atlas", "--gears", "--links", "5", "--out", tmp_path / "g")
    assert code == 0, err
    data = json.loads((tmp_path / "g" / "atlas.json").read_text())
    assert data["count"] == 6 and len(data["trains"]) == 6
    page = (tmp_path / "g" / "index.html").read_text()
    # each train's schematic (a bar per gear of a pair) and graph (an arc per pair)
    assert page.count("<svg") == 2 * 6 and page.count('class="gear"') == 6 * 3 * (2 + 1)
    assert page.count('class="arm"') == sum(               # a moving carrier: one arm
        len({c for *_, c in e.gears} - {_fixed(e)}) for e in gear_atlas(5, 1))
    for i in range(1, 7):
        assert f'href="chains/chain-{i}.toml"' in page
    assert "Compound gear train" in page
    assert "written:" in out


@pytest.mark.parametrize("flag", [["--prismatic", "1"], ["--multiple"], ["--oriented"],
                                  ["--resume"]])
def test_other_atlas_flags_are_refused(flag):
    code, out, err = run_cli("atlas", "--gears", "--links", "5", *flag)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "leave out " + flag[0] in err


@pytest.mark.parametrize("size, words", [(["--links", "2"], "--links N"),
                                         (["--links", "4", "--dof", "0"], "--dof F"),
                                         (["--links", "12"], "--links N")])
def test_sizes_without_trains_are_one_line(size, words):
    code, out, err = run_cli("atlas", "--gears", *size)
    assert code == 2 and out == "" and err.count("\n") == 1 and words in err


def test_gears_draw_writes_the_schematic(tmp_path):
    path = tmp_path / "train.svg"
    code, out, err = run_cli("gears", catalog_path("epicyclic-gear-train"), "--fixed",
                             "frame", "--speed", "annulus=0", "--speed", "sun=1000",
                             "--draw", path)
    assert code == 0, err
    assert "arm" in out                        # the speeds are printed as without --draw
    svg = path.read_text()
    assert svg.startswith("<?xml") and svg.count('class="gear"') == 3 + 2  # + graph arcs
    assert svg.count('class="annulus"') == 1 and 'class="arm"' in svg


def test_gears_draw_needs_an_svg(tmp_path):
    code, out, err = run_cli("gears", catalog_path("simple-gear-train"), "--fixed",
                             "frame", "--speed", "driver=100", "--draw", tmp_path / "x.png")
    assert code == 2 and out == "" and err.count("\n") == 1 and not (tmp_path / "x.png").exists()


def test_gears_draw_refuses_a_train_whose_axes_are_not_placed(tmp_path):
    text = (catalog_path("simple-gear-train")).read_text()
    text = "\n".join(line for line in text.splitlines() if not line.startswith("at = "))
    (tmp_path / "t.toml").write_text(text)
    code, out, err = run_cli("gears", tmp_path / "t.toml", "--fixed", "frame", "--speed",
                             "driver=100", "--draw", tmp_path / "t.svg")
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "axes are not placed" in err and not (tmp_path / "t.svg").exists()


def test_workers_give_the_atlas_of_one_process():
    """Split by tree over two processes, six links give the trains of one process, in
    the same order, with the same arrangements (the pieces are merged in tree order)."""
    runs = []
    for workers in ("1", "2"):
        code, out, err = run_cli("atlas", "--gears", "--links", "6", "--workers", workers,
                                 "--json")
        assert code == 0, err
        runs.append(json.loads(out))
    assert [t["key"] for t in runs[0]["trains"]] == [t["key"] for t in runs[1]["trains"]]
    assert len(runs[0]["trains"]) == 27 and runs[0] == runs[1]


def test_out_writes_a_chain_file_per_train_that_gears_solves(tmp_path):
    code, out, err = run_cli("atlas", "--gears", "--links", "4", "--out", tmp_path / "g")
    assert code == 0, err
    files = sorted((tmp_path / "g" / "chains").glob("*.toml"))
    assert [f.name for f in files] == ["chain-1.toml", "chain-2.toml"]
    assert "2 chain files in" in out
    for f in files:
        code, out, err = run_cli("gears", f)
        assert code == 0, err
        assert "1 degree of freedom" in out
    code, out, err = run_cli("atlas", "--gears", "--links", "4", "--out", tmp_path / "h",
                             "--no-chain-files")
    assert code == 0 and not (tmp_path / "h" / "chains").exists()
    # asked for explicitly, they are written as by default (not refused)
    code, out, err = run_cli("atlas", "--gears", "--links", "4", "--out", tmp_path / "i",
                             "--chain-files")
    assert code == 0, err
    assert len(list((tmp_path / "i" / "chains").glob("*.toml"))) == 2


def test_a_local_dask_cluster_gives_the_atlas_of_one_process():
    """The gear search split by tree of turning pairs on a Dask cluster (a local one of
    two workers) gives the trains one process gives, in the same order."""
    alone = gear_atlas(6, 1)
    with DaskRunner("local", workers=2) as runner:
        cluster = gear_atlas(6, 1, runner=runner)
    assert [e.to_dict() for e in cluster] == [e.to_dict() for e in alone]
    assert len(cluster) == 27


def test_an_unreachable_scheduler_is_one_line(monkeypatch):
    monkeypatch.setattr(atlas_run, "CONNECT_TIMEOUT", 1.0)  # nothing listens there anyway
    code, out, err = run_cli("atlas", "--gears", "--links", "5", "--scheduler",
                             "tcp://127.0.0.1:9", "-q")
    assert code == 2 and "Traceback" not in err
    assert err.strip().count("\n") == 0 and "cannot reach the Dask scheduler" in err
