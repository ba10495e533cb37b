"""The atlas: counts, time per stage and memory, up to 14 links; and an estimate of
the 16-link run from measured piece times.

Usage: python benchmarks/atlas.py [--max-links N] [--workers K] [--sample-16 PIECES]

For one degree of freedom, each size is run as the command line runs it (plan, pieces,
then the output folder written: atlas.json, graph6, index.html), and its counts are
checked against the published ones (OEIS A233288). Targets (issue 15): 12 links under
5 s and 14 links under 5 minutes with two workers, memory under 1 GB.

``--sample-16 PIECES`` plans the 16-link atlas (every contracted graph), times PIECES
pieces drawn with probability proportional to their work, and estimates the whole run's
CPU time from them (Hansen-Hurwitz: the total work times the mean time per unit of work
of the drawn pieces), then the wall time on clusters of several sizes. No peer is
compared: pylinkage's and Pyslvs' atlases stop at 8 links.
"""

import argparse
import random
import resource
import tempfile
import time

from chaingraph.structure.atlas import process_runner, run_atlas, write_atlas
from chaingraph.structure.atlas.pieces import piece, piece_work
from chaingraph.structure.atlas.run import plan

PUBLISHED = {4: 1, 6: 2, 8: 16, 10: 230, 12: 6856, 14: 318162, 16: 19819281}


def peak_mb():
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return max(own, children) / 1024.0


def cpu_seconds():
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def sizes(args):
    print(f"{'links':>5} {'chains':>8} {'published':>9} {'inversions':>10} {'plan s':>7} "
          f"{'pieces s':>8} {'write s':>7} {'total s':>7} {'CPU s':>6} {'workers':>7} "
          f"{'peak MB':>7}")
    for links in range(4, args.max_links + 1, 2):
        workers = args.workers if links >= 12 else 1
        stages = {}

        def progress(fraction, text):
            if text.startswith("shard") and "pieces" not in stages:
                stages["pieces"] = time.perf_counter()
        cpu = cpu_seconds()
        start = time.perf_counter()
        with tempfile.TemporaryDirectory() as out:
            atlas = run_atlas(links, 1, runner=process_runner(workers), out=out,
                              progress=progress, keep=False)
            computed = time.perf_counter()
            write_atlas(atlas, out, shard_dir=f"{out}/shards", chain_files=False)
            written = time.perf_counter()
        # the plan ends when the first shard is handed out; its time is the plan stage
        first = stages.get("pieces", computed)
        plan_s = first - start
        print(f"{links:>5} {atlas.count:>8} {PUBLISHED.get(links, '?'):>9} "
              f"{atlas.distinct_inversions:>10} {plan_s:>7.2f} {computed - first:>8.2f} "
              f"{written - computed:>7.2f} {written - start:>7.2f} "
              f"{cpu_seconds() - cpu:>6.1f} {workers:>7} {peak_mb():>7.0f}")


def sample_16(args):
    start = time.perf_counter()
    jobs = plan(16, 1, runner=process_runner(args.workers))
    planned = time.perf_counter() - start
    work = [piece_work(j) for j in jobs]
    total_work = sum(work)
    print(f"16 links: {len(jobs):,} pieces planned in {planned:.1f} s with {args.workers} "
          f"workers; total work {total_work:,} distributions")
    rng = random.Random(16)
    drawn = rng.choices(range(len(jobs)), weights=work, k=args.sample_16)
    per_work, chains = [], 0
    for i in drawn:
        t = time.process_time()
        found = piece(jobs[i])
        per_work.append((time.process_time() - t) / work[i])
        chains += len(found)
    mean = sum(per_work) / len(per_work)
    spread = (sum((x - mean) ** 2 for x in per_work) / (len(per_work) - 1)) ** 0.5
    cpu = total_work * mean
    error = total_work * spread / len(per_work) ** 0.5
    print(f"sampled {len(drawn)} pieces ({chains:,} chains): estimated CPU for the pieces "
          f"{cpu:,.0f} s +- {2 * error:,.0f} s (two standard errors), "
          f"{cpu / PUBLISHED[16] * 1e6:.0f} us per chain")
    for cores in (2, 16, 64, 256):
        wall = cpu / cores + planned * args.workers / min(cores, 64)
        print(f"  on {cores:>3} cores: about {wall / 60:,.1f} minutes (plan included)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-links", type=int, default=14)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--sample-16", type=int, default=0, metavar="PIECES")
    args = parser.parse_args()
    sizes(args)
    if args.sample_16:
        sample_16(args)


if __name__ == "__main__":
    main()
