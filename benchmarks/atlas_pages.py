"""The illustrated atlas pages at 8 links with every K, animated: seconds per inversion
on a sample of the chains, and the whole run estimated from it.

Usage: python benchmarks/atlas_pages.py [--links 8] [--stride 31] [--no-animate]

The full run (``chaingraph atlas --links 8 --prismatic all --out DIR``: 3,107 chains,
23,093 inversions) takes hours; this times every ``--stride``-th chain's page alone (CPU
time of this process, so that a busy machine changes little), and prints the seconds
per inversion, the slowest chains, and the estimate of the whole run against the bound
the atlas sets for animating by default (``LOCAL_HOURS`` on the workers asked).
Target (issue 36): the 8-link pages animated by default within that bound on the 2-core
machine (``--workers 2``).
"""

import argparse
import dataclasses
import tempfile
import time

from chaingraph.report.atlas import SECONDS_PER_INVERSION, write_illustrated
from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.contracted import joints_for
from chaingraph.structure.atlas.estimate import LOCAL_HOURS
from chaingraph.structure.atlas.sliding import sliding_atlas


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=8)
    parser.add_argument("--stride", type=int, default=31)
    parser.add_argument("--offset", type=int, default=0)
    parser.add_argument("--no-animate", action="store_true")
    parser.add_argument("--workers", type=int, default=2,
                        help="the workers of the run estimated (default 2)")
    args = parser.parse_args()
    base = atlas_graphs(args.links, 1)
    result = sliding_atlas(base, prismatic=range(joints_for(args.links, 1) + 1))
    sample = result.entries[args.offset::args.stride]
    times = []
    with tempfile.TemporaryDirectory() as out:
        for e in sample:
            one = dataclasses.replace(result, entries=(e,))
            start = time.process_time()
            write_illustrated(one, out, animate=not args.no_animate, workers=1)
            times.append((time.process_time() - start, e.inversion_classes, e.id))
    total = sum(t for t, _, _ in times)
    inversions = sum(n for _, n, _ in times)
    per = total / inversions
    whole = per * result.distinct_inversions / args.workers
    print(f"{len(sample)} of {len(result)} chains ({inversions} of "
          f"{result.distinct_inversions} inversions): {total:.1f} s of CPU, "
          f"{per:.3f} s per inversion ({'drawn' if args.no_animate else 'animated'})")
    print(f"the whole run on {args.workers} workers: about {whole / 60:.0f} min "
          f"(the bound: {LOCAL_HOURS * 60:.0f} min; the estimate's figure "
          f"{SECONDS_PER_INVERSION.get(args.links)} s per inversion)")
    print("slowest chains (s, inversions, id):")
    for t, n, i in sorted(times, reverse=True)[:8]:
        print(f"  {t:6.2f} {n:3d}  chain {i}")


if __name__ == "__main__":
    main()
