"""Write tests/data/long-chain-100.toml: a ladder of four-bar loops (96 links) with a
K(2,3) of five links (F = 0, no triangle) sharing one of its links, 100 links in all,
F = 1, degenerate with that K(2,3) as its one minimal rigid sub-chain (see
tests/structure/long_chains.py for why).

    PYTHONPATH=$PWD python tests/data/make_long_chains.py tests/data/long-chain-100.toml
"""

import sys

from chaingraph.files import dumps
from tests.structure.long_chains import buried_k23

if __name__ == "__main__":
    chain, _ = buried_k23(100)
    with open(sys.argv[1], "w", encoding="utf-8") as out:
        out.write(dumps(chain))
