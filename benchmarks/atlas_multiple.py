"""The atlas with multiple joints: counts by number and degree of multiple joints, then
with sliding pairs on their simple joints (--prismatic all), and the times.

Usage: python benchmarks/atlas_multiple.py [--max-links N] [--no-prismatic]

Targets (issue 35): ``chaingraph atlas --links 10 --multiple`` under 5 minutes on the
2-core machine, and ``--multiple --prismatic all`` at 10 links with it if it can. The
tables of docs/atlas.md quote what this prints. The time of the first part goes to
nauty's canonical forms of the link-joint graphs the search makes; of the second, to
the exact evaluation of each assignment of sliding pairs the structure does not decide.
"""

import argparse
import resource
import time

from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.contracted import joints_for
from chaingraph.structure.atlas.multiple import multiple_atlas
from chaingraph.structure.atlas.sliding import sliding_atlas


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-links", type=int, default=10)
    parser.add_argument("--no-prismatic", action="store_true",
                        help="leave out the chains with sliding pairs")
    args = parser.parse_args()
    for links in range(4, args.max_links + 1, 2):
        start = time.perf_counter()
        result = multiple_atlas(atlas_graphs(links, 1))
        took = time.perf_counter() - start
        degrees = ", ".join(f"{'+'.join(map(str, d)) or 'none'}: {n:,}"
                            for d, n in result.count_by_degrees.items())
        print(f"{links} links: {len(result):,} chains, {result.distinct_inversions:,} "
              f"inversions; by multiple joints {result.count_by_multiple}; by their degrees "
              f"{{{degrees}}}; {took:.2f} s", flush=True)
        if args.no_prismatic:
            continue
        start = time.perf_counter()
        every = sliding_atlas(result, prismatic=range(joints_for(links, 1) + 1))
        took = time.perf_counter() - start
        counts = {k: v for k, v in every.count_by_prismatic.items() if v}
        inversions = {}
        for e in every:
            inversions[e.prismatic] = inversions.get(e.prismatic, 0) + e.inversion_classes
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"{links} links, every K: {len(every):,} chains {counts}, inversions "
              f"{inversions} ({every.distinct_inversions:,}), rejected {every.rejected}; "
              f"{took:.2f} s, peak {peak:.0f} MB", flush=True)


if __name__ == "__main__":
    main()
