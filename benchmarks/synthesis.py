"""Synthesis benchmarks (not timed tests): function generation by three precision points,
five-point path generation of the four-bar, a 20-point closed curve; each task's time
(best of a few runs, wall clock), its best error and its number of solutions.

    PYTHONPATH=$PWD python benchmarks/synthesis.py

The peer comparison (pylinkage 1.3.0, installed into benchmarks/.venv-pylinkage as
benchmarks/solve.py does) is not run here yet.
"""

from __future__ import annotations

import math
import time

import chaingraph
from chaingraph.model.chain import Chain, Joint, Mechanism, Point
from chaingraph.synthesis import function, path


def _crank_rocker_points(picks):
    joints = (Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
              Joint("B", "R", ("crank", "coupler"), at=(20.0, 0.0)),
              Joint("C", "R", ("coupler", "rocker"), at=(70.0 - 50.0 * math.cos(1.2),
                                                         50.0 * math.sin(1.2))),
              Joint("D", "R", ("rocker", "frame"), at=(70.0, 0.0)))
    c = joints[2].at
    chain = Chain("crank-rocker", joints, points=(Point("P", "coupler", (c[0] - 5, c[1] + 25)),),
                  mechanism=Mechanism("frame", "crank", 1.0, "P"))
    m = chaingraph.solve(chain, steps=360, summary=False)
    return [(float(m["x:P"][k]), float(m["y:P"][k])) for k in picks]


TASKS = {
    "function log10, 3 points": lambda: function(function="log10(x)", x=(1, 2),
                                                 swing=(60, 90)),
    "path, 5 points (exact)": lambda: path(points=_crank_rocker_points(
        [10, 60, 120, 200, 290]), seed=1),
    "path, 20 points closed (fit)": lambda: path(points=_crank_rocker_points(
        range(0, 360, 18)), closed=True, seed=1),
}


def main(repeats: int = 2) -> None:
    print(f"{'task':32}  {'seconds':>8}  {'solutions':>9}  best error")
    for name, run in TASKS.items():
        best, found = math.inf, None
        for _ in range(repeats):
            t = time.perf_counter()
            found = run()
            best = min(best, time.perf_counter() - t)
        error = found.solutions[0].error.max if found.solutions else float("nan")
        print(f"{name:32}  {best:8.2f}  {len(found.solutions):9d}  {error:.3g}")


if __name__ == "__main__":
    main()
