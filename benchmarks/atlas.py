"""The atlas: chain counts up to 12 links with the time each takes.

Usage: python benchmarks/atlas.py [--max-links N] [--workers K]

Prints, for one degree of freedom, the number of chains and distinct inversions of each
size with the wall time and the peak memory (this process and its workers). Targets
(issue 6): 10 links with distinct inversions under 2 s; 12 links under 120 s with
--workers 2; memory under 1 GB.
"""

import argparse
import resource
import time

from chaingraph.atlas import atlas_graphs

PUBLISHED = {4: 1, 6: 2, 8: 16, 10: 230, 12: 6856}


def peak_mb():
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return max(own, children) / 1024.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-links", type=int, default=12)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    print(f"{'links':>5} {'chains':>7} {'published':>9} {'inversions':>10} {'seconds':>8} "
          f"{'workers':>7} {'peak MB':>8}")
    for links in range(4, args.max_links + 1, 2):
        workers = args.workers if links >= 12 else 1
        start = time.perf_counter()
        entries = atlas_graphs(links, 1, workers=workers)
        elapsed = time.perf_counter() - start
        inversions = sum(e.inversion_classes for e in entries)
        print(f"{links:>5} {len(entries):>7} {PUBLISHED.get(links, '?'):>9} {inversions:>10} "
              f"{elapsed:>8.2f} {workers:>7} {peak_mb():>8.0f}")


if __name__ == "__main__":
    main()
