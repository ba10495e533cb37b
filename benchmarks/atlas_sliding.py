"""The atlas with sliding pairs: counts by K and the time, oriented and not; with
``--fit``, the CPU times the size check's estimate is fitted to.

Usage: python benchmarks/atlas_sliding.py [--max-links N] [--fit [--sizes N ...]
       [--multiple-up-to N]]

Targets (issue 27): 8 links with every K under 10 s, 10 links under 5 minutes, on the
2-core machine. The time goes to the exact evaluation of the assignments the structure does not
decide; the table below is what docs/atlas.md quotes. No peer is compared: pylinkage and
Pyslvs enumerate turning pairs only.

``--fit`` times (CPU of this process, so that a busy machine changes little) at 6, 8
and 10 links: K = 0 alone (the cost of a chain), every K (plus the cost of each
assignment), every K oriented (plus each further orientation) and, up to
``--multiple-up-to`` links, the merging of multiple joints; then fits ``log10 seconds =
a + b N`` to each and prints ``SLIDING_FIT`` of ``chaingraph/structure/atlas/estimate.py``.
"""

import argparse
import resource
import time

import numpy as np

from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.contracted import joints_for
from chaingraph.structure.atlas.multiple import multiple_atlas
from chaingraph.structure.atlas.sliding import sliding_atlas


def table(max_links):
    for links in range(4, max_links + 1, 2):
        base = atlas_graphs(links, 1)
        every = range(joints_for(links, 1) + 1)
        for oriented in (False, True):
            start = time.perf_counter()
            result = sliding_atlas(base, prismatic=every, oriented=oriented, keep=False)
            took = time.perf_counter() - start
            counts = {k: v for k, v in result.count_by_prismatic.items() if v}
            peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
            print(f"{links} links{' oriented' if oriented else ''}: {len(result):,} chains "
                  f"{counts}, {result.distinct_inversions:,} inversions, rejected "
                  f"{result.rejected}; {took:.2f} s, peak {peak:.0f} MB", flush=True)


def cpu(fn):
    start = time.process_time()
    out = fn()
    return time.process_time() - start, out


def fit(sizes, multiple_up_to):
    points = {name: [] for name in ("chain", "assignment", "orientation", "merge",
                                    "multiple_chains")}
    for links in sizes:
        base = atlas_graphs(links, 1)
        joints, chains = joints_for(links, 1), len(base)
        every = range(joints + 1)
        alone, _ = cpu(lambda: sliding_atlas(base, prismatic=0, keep=False))
        plain, _ = cpu(lambda: sliding_atlas(base, prismatic=every, keep=False))
        oriented, _ = cpu(lambda: sliding_atlas(base, prismatic=every, oriented=True,
                                                keep=False))
        points["chain"].append((links, alone / chains))
        points["assignment"].append((links, (plain - alone) / chains / 2 ** joints))
        points["orientation"].append((links, (oriented - plain) / chains
                                      / (3 ** joints - 2 ** joints)))
        print(f"{links} links, {chains} chains: K = 0 {alone:.2f} s, every K {plain:.2f} s, "
              f"oriented {oriented:.2f} s (CPU)", flush=True)
        if links <= multiple_up_to:
            merged, found = cpu(lambda: multiple_atlas(base))
            points["merge"].append((links, merged / chains))
            points["multiple_chains"].append((links, len(found) / chains))
            print(f"{links} links: {len(found)} chains with multiple joints, merged in "
                  f"{merged:.2f} s (CPU)", flush=True)
    print("SLIDING_FIT = {")
    for name, xy in points.items():
        n = np.array([x for x, _ in xy], float)
        y = np.log10([max(v, 1e-12) for _, v in xy])
        b, a = np.polyfit(n, y, 1)
        print(f'    "{name}": ({a:.3f}, {b:.3f}),   # at {", ".join(f"{x}: {v:.3g}" for x, v in xy)}')
    print("}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-links", type=int, default=10)
    parser.add_argument("--fit", action="store_true")
    parser.add_argument("--multiple-up-to", type=int, default=8)
    parser.add_argument("--sizes", type=int, nargs="+", default=[6, 8, 10])
    args = parser.parse_args()
    if args.fit:
        fit(args.sizes, args.multiple_up_to)
    else:
        table(args.max_links)


if __name__ == "__main__":
    main()
