"""Write the chains whose rigid parts are known by construction (see
tests/structure/long_chains.py for why) into a folder:

- long-chain-100.toml: a ladder of four-bar loops (96 links) with a K(2,3) of five links
  (F = 0, no triangle) sharing one of its links, 100 links in all, F = 1, degenerate
  with that K(2,3) as its one minimal rigid sub-chain and its one rigid region;
- hub-on-grid-24.toml: a hub link pinned to every node of a 2-by-5 grid of links whose
  edges are binary links, 24 links: 10 minimal rigid sub-chains (the hub with each cycle
  of the grid), more than classify's search lists within its budget.

    PYTHONPATH=$PWD python tests/data/make_long_chains.py tests/data
"""

import sys
from pathlib import Path

from chaingraph.files import dumps
from tests.structure.long_chains import buried_k23, hub_on_grid

if __name__ == "__main__":
    folder = Path(sys.argv[1])
    chain, _ = buried_k23(100)
    (folder / "long-chain-100.toml").write_text(dumps(chain), encoding="utf-8")
    (folder / "hub-on-grid-24.toml").write_text(dumps(hub_on_grid(5)), encoding="utf-8")
