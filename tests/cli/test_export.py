"""``chaingraph export FILE --to dxf|svg`` (issue 40): the file written, and bad input as
one line with exit status 2 (an input value that cannot be assembled: 1)."""

import sys

import ezdxf
import pytest

import chaingraph
from chaingraph.cli import export
from chaingraph.naming.catalog import catalog_path
from chaingraph.structure.isomorphism import is_isomorphic

from ..conftest import run_cli

ENGINE = catalog_path("reciprocating-engine")
ROCKER = catalog_path("non-grashof-four-bar")


@pytest.mark.parametrize("to", ["dxf", "svg"])
def test_export_writes_the_outlines(tmp_path, to):
    out = tmp_path / "deep" / f"engine.{to}"
    code, stdout, err = run_cli("export", ENGINE, "--to", to, "--at", "45", "--hole", "3",
                                "--width", "8", "-o", out)
    assert code == 0, err
    if to == "dxf":
        doc = ezdxf.readfile(out)
        layers = {layer.dxf.name for layer in doc.layers} - {"0", "Defpoints"}
        assert layers == {"frame", "crank", "connecting rod", "crosshead"}
        assert {c.dxf.radius for c in doc.modelspace().query("CIRCLE")} == {1.5}
    else:
        assert out.read_text().count('class="hole"') == 6      # O, A twice, B twice
        assert 'data-link="connecting rod"' in out.read_text()


@pytest.mark.parametrize("args, words", [
    (["--to", "step"], "invalid choice: 'step'"),
    (["--to", "dxf", "--hole", "0"], "--hole: must be a number above 0"),
    (["--to", "dxf", "--width", "-2"], "--width: must be a number above 0"),
    (["--to", "dxf", "--width", "nan"], "--width: must be a number above 0"),
    (["--to", "dxf", "--width", "4", "--hole", "5"], "must be smaller than the bars' width"),
    (["--to", "dxf", "--at", "x"], "--at: invalid float value"),
])
def test_bad_options_one_line_exit_2(tmp_path, args, words):
    code, out, err = run_cli("export", ENGINE, *args, "-o", tmp_path / "x.dxf")
    assert code == 2 and words in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "x.dxf").exists()


def test_a_pose_that_cannot_be_assembled_is_exit_1(tmp_path):
    code, out, err = run_cli("export", ROCKER, "--to", "svg", "--at", "180",
                             "-o", tmp_path / "x.svg")
    assert code == 1 and "cannot be assembled" in err and len(err.strip().splitlines()) == 1


def test_an_output_folder_is_refused(tmp_path):
    code, out, err = run_cli("export", ENGINE, "--to", "svg", "-o", tmp_path)
    assert code == 2 and "is a folder" in err


def test_dxf_without_ezdxf_one_line_exit_2(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    code, out, err = run_cli("export", ENGINE, "--to", "dxf", "-o", tmp_path / "x.dxf")
    assert (code, err) == (2, "chaingraph: error: DXF needs the cad extra: pip install "
                              "chaingraph[cad]\n")


def test_a_writer_of_the_chain_alone_is_one_more_format(tmp_path, monkeypatch):
    monkeypatch.setitem(export.WRITERS, "names", export.chain_writers(
        {"names": lambda chain: "\n".join(chain.links)})["names"])
    code, out, err = run_cli("export", ENGINE, "--to", "names", "-o", tmp_path / "n.txt")
    assert code == 0, err
    assert (tmp_path / "n.txt").read_text() == "frame\ncrank\nconnecting rod\ncrosshead"


@pytest.mark.parametrize("to", ["pylinkage", "pyslvs"])
def test_export_to_a_peer_and_import_back_gives_the_same_mechanism(tmp_path, to):
    """`export --to pylinkage|pyslvs` then `import --from` the same: an isomorphic chain
    with every joint where it was drawn (to 1e-9 of the size), its driver the same."""
    source = catalog_path("watt-i-mechanism")
    out, back = tmp_path / f"watt.{to}", tmp_path / "back.toml"
    code, _, err = run_cli("export", source, "--to", to, "-o", out)
    assert code == 0, err
    code, _, err = run_cli("import", out, "--from", to, "-o", back)
    assert code == 0, err
    a, b = chaingraph.load(source), chaingraph.load(back)
    assert is_isomorphic(a, b, oriented=False)
    drawn = sorted(j.at for j in a.joints)
    assert all(abs(p - q) <= 1e-9 * 200 for u, v in zip(drawn, sorted(j.at for j in b.joints))
               for p, q in zip(u, v))
    code, _, err = run_cli("export", source, "--to", to, "--at", "30", "-o", out)
    assert code == 2 and err.count("\n") == 1 and "--at" in err
