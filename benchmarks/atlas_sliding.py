"""The atlas with sliding pairs: counts by K and the time, oriented and not.

Usage: python benchmarks/atlas_sliding.py [--max-links N]

Targets (issue 27): 8 links with every K under 10 s, 10 links under 5 minutes, on the
2-core machine. The time goes to the exact evaluation of the assignments the structure does not
decide; the table below is what docs/atlas.md quotes. No peer is compared: pylinkage and
Pyslvs enumerate turning pairs only.
"""

import argparse
import resource
import time

from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.contracted import joints_for
from chaingraph.structure.atlas.sliding import sliding_atlas


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-links", type=int, default=10)
    args = parser.parse_args()
    for links in range(4, args.max_links + 1, 2):
        base = atlas_graphs(links, 1)
        every = range(joints_for(links, 1) + 1)
        for oriented in (False, True):
            start = time.perf_counter()
            result = sliding_atlas(base, prismatic=every, oriented=oriented)
            took = time.perf_counter() - start
            counts = {k: v for k, v in result.count_by_prismatic.items() if v}
            peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
            print(f"{links} links{' oriented' if oriented else ''}: {len(result):,} chains "
                  f"{counts}, {result.distinct_inversions:,} inversions, rejected "
                  f"{result.rejected}; {took:.2f} s, peak {peak:.0f} MB", flush=True)


if __name__ == "__main__":
    main()
