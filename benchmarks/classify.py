"""Classify 1,000 random 12-link chains and print the time it takes.

Usage: python benchmarks/classify.py [--chains N] [--links L] [--seed S]

Each chain has J = 3L/2 - 2 joint equivalents, two ternary joints and two sliding
pairs; the whole classification runs, rigid sub-chain search included. Target (issue 2):
1,000 chains of 12 links in under 5 s.
"""

import argparse
import time

from chaingraph import classify
from chaingraph.structure.generators import random_chain


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chains", type=int, default=1000)
    parser.add_argument("--links", type=int, default=12)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    chains = [random_chain(args.links, seed=args.seed + i, ternary=2, sliding=2)
              for i in range(args.chains)]
    start = time.perf_counter()
    degenerate = sum(classify(c).degenerate for c in chains)
    elapsed = time.perf_counter() - start
    print(f"classified {args.chains} random {args.links}-link chains in {elapsed:.2f} s "
          f"({1000 * elapsed / args.chains:.2f} ms each); {degenerate} degenerate")
    for links in (8, 14, 18):
        chain = random_chain(links, seed=args.seed)
        start = time.perf_counter()
        classify(chain)
        print(f"one {links}-link chain: {1000 * (time.perf_counter() - start):.1f} ms")


if __name__ == "__main__":
    main()
