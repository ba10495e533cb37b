"""The illustrated atlas: a page per chain, a chain file per inversion that solve runs."""

import warnings

import chaingraph
from chaingraph.cli.main import main


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
