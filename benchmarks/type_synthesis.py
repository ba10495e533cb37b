"""Type synthesis through the atlas (a benchmark, not a test): a 20-point closed curve
(benchmarks/synthesis.py's crank-rocker curve) searched over every family of a space of
the atlas; where the time goes and how it grows with the number of families searched.

    PYTHONPATH=$PWD python benchmarks/type_synthesis.py                 # --links 6
    PYTHONPATH=$PWD python benchmarks/type_synthesis.py --links 6 --prismatic 1 --every 4
    PYTHONPATH=$PWD python benchmarks/type_synthesis.py --links 8 --every 25
    PYTHONPATH=$PWD python benchmarks/type_synthesis.py --workers 2     # and the whole run
    PYTHONPATH=$PWD python benchmarks/type_synthesis.py --links 6 --prismatic 1 --open --only sliding
    PYTHONPATH=$PWD python benchmarks/type_synthesis.py --links 6 --prismatic 1 --open --only cylinder
    PYTHONPATH=$PWD python benchmarks/type_synthesis.py --count     # the spaces' families

``--open`` searches an open path instead (20 points of the same curve over half its
turn), which the families driven by a sliding input also search (a closed curve leaves
them out); ``--only sliding``, ``--only cylinder`` or ``--only turning`` searches only
the families driven by a slide on the fixed link, by a cylinder (a sliding pair between
two moving links), or by a turn; ``--method dyads|newton`` only the families solved so.
``--count`` prints each space's families by input and by method (how the cylinders grew
the space), and searches nothing.

Each family is searched alone, one after another in this process, exactly as the whole
search searches it (its number in the space, its random stream, its budget):
CPU seconds per family, by how its motion is found ("dyads" in closed form, "newton"
for the triads), and split into the optimiser's stages (the coarse search, differential
evolution, least squares, the certification by the solver) by profiling (shares of the
profiled time; the profiler inflates the solver's many small calls somewhat). ``--every K``
searches every K-th family only (a capped run) and projects the whole space from the
mean CPU per family of each method. ``--workers K`` then runs the whole search as
``design path --links L --workers K`` does (process_runner) and gives its wall clock.
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import resource
import statistics
import sys
import time
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from synthesis import crank_rocker_points  # noqa: E402

from chaingraph._util.parallel import process_runner  # noqa: E402
from chaingraph.synthesis import path  # noqa: E402
from chaingraph.synthesis.type_synthesis import atlas_space  # noqa: E402

#: the optimiser's stages, by the function that does each
STAGES = {"coarse search": "coarse_search", "differential evolution": "global_search",
          "least squares": "least_squares_fit", "certification": "_certified"}


def _stages(stats: pstats.Stats) -> dict[str, float]:
    """The cumulative seconds of each stage in a profile, and of the whole family's
    search (``"total"``)."""
    out = dict.fromkeys([*STAGES, "total"], 0.0)
    for (_, _, name), row in stats.stats.items():        # type: ignore[attr-defined]
        for stage, fn in [*STAGES.items(), ("total", "search_family")]:
            if name == fn:
                out[stage] += row[3]
    return out


def task_points(open_task: bool):
    """The task: 20 points of the crank-rocker's curve, over its whole turn (closed) or
    half of it (open)."""
    return crank_rocker_points(range(0, 180, 9) if open_task else range(0, 360, 18))


def _input(c) -> str:
    """How a family is driven: "turn", "slide" (on the fixed link) or "cylinder"."""
    return "cylinder" if c.cylinder else "slide" if c.sliding else "turn"


def _only(c, only: str | None) -> bool:
    """Whether a family is of those ``only`` names (None: all)."""
    return only is None or _input(c) == {"turning": "turn", "sliding": "slide",
                                         "cylinder": "cylinder"}[only]


SPACES = ((4, 1), (4, 2), (6, 1), (6, 2), (8, 1))


def count_spaces() -> None:
    """Each space's families by input (and by how they are solved), with the
    inversions that have a cylinder."""
    for links, prismatic in SPACES:
        space = atlas_space(links, prismatic)
        by: dict[str, dict[str, int]] = defaultdict(lambda: defaultdict(int))
        for c in space.choices:
            by[_input(c)][c.method] += 1
        cyl = len({(c.chain_id, c.inversion) for c in space.choices if c.cylinder})
        parts = "; ".join(f"{k} {sum(v.values())} {dict(v)}" for k, v in by.items())
        print(f"--links {links} --prismatic {prismatic}: {space.chains} chains, "
              f"{space.inversions} inversions ({cyl} with a cylinder), "
              f"{len(space.choices)} families: {parts}", flush=True)


def per_family(links: int, prismatic, every: int, seed: int = 1, open_task: bool = False,
               only: str | None = None, method: str | None = None):
    """Every ``every``-th family (of those ``only`` names: driven by a slide or by a
    turn; of that ``method`` only) searched alone: rows (number, method, names, CPU s,
    certified, stages)."""
    points = task_points(open_task)
    space = atlas_space(links, prismatic)
    rows = []
    chosen = [(k, c) for k, c in enumerate(space.choices)
              if _only(c, only) and (method is None or c.method == method)]
    sliding = sum(c.sliding for c in space.choices)
    cylinders = sum(bool(c.cylinder) for c in space.choices)
    print(f"families: {len(space.choices)}, of which {sliding} driven by a slide "
          f"({sum(c.sliding and c.solvable for c in space.choices)} solvable), "
          f"{cylinders} by a cylinder, {len(space.choices) - sliding - cylinders} by a turn",
          flush=True)
    for k, c in chosen[::every]:
        profile = cProfile.Profile()
        t = time.process_time()
        profile.enable()
        found = path(points=points, closed=not open_task, seed=seed, links=links,
                     prismatic=prismatic, families=lambda x, c=c: x == c)
        profile.disable()
        cpu = time.process_time() - t
        size = found.task.size
        best = min((s.error.max for s in found.solutions), default=float("nan"))
        rows.append((k, c.method, c.names[-1] if c.names else "", cpu, len(found.solutions),
                     best / size, _stages(pstats.Stats(profile))))
        print(f"{k:5d} {c.method or '-':7s} {_input(c):8s} "
              f"{rows[-1][2][:34]:34s} {cpu:7.1f} s  "
              f"{len(found.solutions)} certified  best {best / size:.4f} of the size",
              flush=True)
    return space, rows


def summary(space, rows, every: int, only: str | None = None) -> None:
    """CPU by method, the stages' shares, and the whole space (of those ``only``
    names) projected."""
    by: dict[str, list[float]] = defaultdict(list)
    stages: dict[str, dict[str, float]] = defaultdict(
        lambda: dict.fromkeys([*STAGES, "total"], 0.0))
    for _, method, _, cpu, _, _, st in rows:
        by[method].append(cpu)
        for name, v in st.items():
            stages[method][name] += v
    counts = defaultdict(int)
    for c in space.choices:
        if _only(c, only):
            counts[c.method] += 1
    print(f"\nspace: {space.chains} chains, {space.inversions} inversions, "
          f"{len(space.choices)} families {dict(counts)}; searched every {every}")
    whole = 0.0
    for method, cpus in by.items():
        mean = statistics.mean(cpus)
        whole += mean * counts[method]
        st = stages[method]
        share = ", ".join(f"{name} {st[name] / max(st['total'], 1e-9):.0%}" for name in STAGES)
        print(f"{method}: {len(cpus)} families, {sum(cpus):.1f} CPU s, mean {mean:.2f} s "
              f"(median {statistics.median(cpus):.2f}, max {max(cpus):.1f}); {share}")
    print(f"projected for the whole space: {whole:.0f} CPU s, about {whole / 2:.0f} s of "
          "wall clock on 2 cores")


def whole_run(links: int, prismatic, workers: int, open_task: bool = False) -> None:
    """The whole search as the command line runs it, timed."""
    points = task_points(open_task)
    t = time.perf_counter()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    found = path(points=points, closed=not open_task, seed=1, links=links, prismatic=prismatic,
                 runner=process_runner(workers))
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    best = found.solutions[0] if found.solutions else None
    print(f"\nwhole search on {workers} workers: {wall:.1f} s wall clock "
          f"(the workers {cpu:.0f} CPU s); "
          f"{len(found.solutions)} solutions, best "
          + (f"{best.error.max / found.task.size:.4f} of the size ({best.names[-1:]})"
             if best else "none")
          + f"; rejected {found.rejected}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=6)
    parser.add_argument("--prismatic", default=None)
    parser.add_argument("--every", type=int, default=1)
    parser.add_argument("--workers", type=int, default=0)
    parser.add_argument("--open", action="store_true")
    parser.add_argument("--only", choices=("sliding", "cylinder", "turning"), default=None)
    parser.add_argument("--count", action="store_true")
    parser.add_argument("--method", choices=("dyads", "newton"), default=None)
    args = parser.parse_args()
    if args.count:
        count_spaces()
        return
    prismatic = (None if args.prismatic is None else
                 args.prismatic if args.prismatic == "all" else int(args.prismatic))
    space, rows = per_family(args.links, prismatic, args.every, open_task=args.open,
                             only=args.only, method=args.method)
    summary(space, rows, args.every, args.only)
    if args.workers:
        whole_run(args.links, prismatic, args.workers, args.open)


if __name__ == "__main__":
    main()
