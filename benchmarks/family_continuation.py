"""The Newton families' continuation (synthesis.family.LoopFamily), checked and timed (a
benchmark, not a test).

    PYTHONPATH=$PWD python benchmarks/family_continuation.py sweep --seeds 1-40
    PYTHONPATH=$PWD python benchmarks/family_continuation.py time --repeat 3
    PYTHONPATH=$PWD python benchmarks/family_continuation.py time --against /tmp/old

``sweep``: tests/synthesis/test_type_synthesis.py's
``test_every_family_traces_what_the_solver_traces`` for every random stream asked, on the
Newton families only (the six-link cases, turning and with a sliding pair: the same
mechanisms as the test, the dyads' draws made to keep the stream, not solved): each
mechanism traced by its family and by the solver from its written file, the largest
distance between the two (NaN where one assembles and the other not) and the seeds that
fail (over 1e-9 of the size).

``time``: the eight triad families of ``atlas_space(6)`` searched on a fixed small
budget for a 20-point closed curve, CPU seconds each; with ``--against DIR`` the same
in a process whose chaingraph is DIR's (e.g. an export of main), alternately, so that
both are measured on the same machine load.

One run (2026-11-26, 2 cores shared with other jobs): ``sweep --seeds 1-40`` fails
seeds 15 and 34 on main (a node step corrected by Newton alone), 9, 30 and 34 on the
first predictor-corrector (the correction's bound alone let a step cross onto a branch
passing near), none now; ``time --rounds 2 --against`` an export of main: the eight
triads 132.4 CPU s against main's 127.6 (1.04 times; the first predictor-corrector
took 285.7).
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import chaingraph
from chaingraph.synthesis.family import AtlasFamily, LoopFamily
from chaingraph.synthesis.path_generation import Budget
from chaingraph.synthesis.type_synthesis import atlas_space

#: the test's cases with a Newton family: (links, prismatic, every)
CASES = [(6, None, 1), (6, 1, 5)]
#: the fixed budget of ``time``
BUDGET = Budget(samples=100, starts=5, fitted=1, generations=3)


def traced(seed: int) -> list[tuple[str, float]]:
    """The Newton families' mechanisms of one random stream: (family, the largest
    distance from the solver's point, of the size; inf where one assembles alone)."""
    out = []
    for links, prismatic, every in CASES:
        rng = np.random.default_rng(seed)
        space = atlas_space(links, prismatic)
        turning = [c for c in space.choices if not c.slides]
        sliding = [c for c in space.choices if c.sliding]
        for c in turning[::every] + sliding[::every]:
            kind = AtlasFamily if c.method == "dyads" else LoopFamily
            family = kind(c.chain, c.fixed, c.driver, c.carrier)
            p = family.sample(rng, 1)[0] * 50.0
            if c.method == "dyads":
                continue
            drawn = float(family.first_input(p[None, :])[0])
            span = None
            if c.sliding:
                ends = family.sweep(p[None, :], 2)[0] - drawn
                span = (0.95 * ends[0], 0.95 * ends[1])
            chain = family.chain(p, name="sampled", units="mm", notes="", span=span)
            m = chaingraph.solve(chain, steps=24, summary=False)
            if c.sliding:
                theta = drawn + m["theta"][None, :-1]
            elif abs(m["theta"][0] - math.degrees(drawn)) > 1e-6:
                continue
            else:
                theta = np.radians(m["theta"])[None, :-1]
            x, y = family.positions(p[None, :], theta)
            with np.errstate(invalid="ignore"):
                d = np.hypot(x[0] - m["x:P"][:-1], y[0] - m["y:P"][:-1])
            bad = np.isfinite(x[0]) != np.isfinite(m["x:P"][:-1])
            far = float(np.inf if bad.any() else np.nanmax(d, initial=0.0)) / 50.0
            out.append((f"{links}/{prismatic} {c.names[-1] if c.names else ''} "
                        f"{c.fixed}/{c.driver}/{c.carrier}", far))
    return out


def sweep(seeds: list[int]) -> None:
    """Every seed's worst mechanism, and the seeds that fail."""
    failed = []
    for seed in seeds:
        rows = traced(seed)
        worst = max(rows, key=lambda r: r[1])
        bad = [r for r in rows if not r[1] <= 1e-9]
        print(f"seed {seed:3d}: {len(rows)} mechanisms, worst {worst[1]:.2e} of the size "
              f"({worst[0]})" + (f"  FAILS {len(bad)}" if bad else ""), flush=True)
        for name, far in bad:
            print(f"    {far:.2e} {name}")
        if bad:
            failed.append(seed)
    print(f"failed seeds: {len(failed)} of {len(seeds)}: {failed}")


def time_triads(repeat: int) -> list[float]:
    """CPU seconds of the eight triad families' searches on :data:`BUDGET`."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from synthesis import crank_rocker_points
    from chaingraph.synthesis import path
    points = crank_rocker_points(range(0, 360, 18))
    space = atlas_space(6)
    triads = [c for c in space.choices if c.method == "newton"]
    out = []
    for c in triads:
        best = math.inf
        for _ in range(repeat):
            t = time.process_time()
            path(points=points, closed=True, seed=1, links=6, budget=BUDGET,
                 families=lambda x, c=c: x == c)
            best = min(best, time.process_time() - t)
        out.append(best)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=("sweep", "time", "_time"))
    parser.add_argument("--seeds", default="1-40")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--against", default=None)
    args = parser.parse_args()
    if args.what == "sweep":
        lo, _, hi = args.seeds.partition("-")
        sweep(list(range(int(lo), int(hi or lo) + 1)))
        return
    if args.what == "_time":
        print(" ".join(f"{v:.3f}" for v in time_triads(args.repeat)))
        return
    trees = {"this": os.environ.get("PYTHONPATH", ".")}
    if args.against:
        trees["against"] = args.against
    totals: dict[str, list[list[float]]] = {k: [] for k in trees}
    for _ in range(args.rounds):
        for name, tree in trees.items():
            env = dict(os.environ, PYTHONPATH=tree)
            run = subprocess.run([sys.executable, __file__, "_time", "--repeat",
                                  str(args.repeat)], env=env, capture_output=True,
                                 text=True, check=True)
            cpu = [float(v) for v in run.stdout.split()]
            totals[name].append(cpu)
            print(f"{name:8s} {sum(cpu):6.2f} CPU s: " + " ".join(f"{v:5.2f}" for v in cpu),
                  flush=True)
    if args.against:
        this = np.min(np.array(totals["this"]), axis=0)
        other = np.min(np.array(totals["against"]), axis=0)
        print(f"best of {args.rounds}: this {this.sum():.2f}, against {other.sum():.2f} "
              f"CPU s: {this.sum() / other.sum():.2f} times")


if __name__ == "__main__":
    main()
