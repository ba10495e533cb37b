"""Synthesis benchmarks (not timed tests): function generation by three precision points,
five-point path generation of the four-bar, a 20-point closed curve; each task's time
(best of a few runs, wall clock), its best error and its number of solutions.

    PYTHONPATH=$PWD python benchmarks/synthesis.py
    PYTHONPATH=$PWD python benchmarks/synthesis.py --peer    # against pylinkage 1.3.0

``--peer`` gives the same tasks to pylinkage 1.3.0 (installed on first use into
benchmarks/.venv-pylinkage as benchmarks/solve.py does, with scipy, which pylinkage's
synthesis imports; it runs there, in benchmarks/_pylinkage_synthesis.py) and writes each
of its solutions as a chaingraph chain, drawn where pylinkage draws it (the first
target), certified by :func:`chaingraph.synthesis.certify` against the task's targets
with no transmission bound (only the defects count): a function generator's three
precision points (the input and the output's angles there, the structural error over
the range), a path's points (passed in order). pylinkage has no search over the
starting angles of a function generator: "starts searched" hands it the 36 x 36 grid of
starts that chaingraph's own coarse search scans, one call each. Its error is its own
(a path's: the largest of ``verify_path_generation``'s distances; a function
generator's solutions are exact at their three points, and it reports no error over the
range); "certified" counts the solutions chaingraph certifies, with the best one's
error recomputed by chaingraph's solver (a function's largest structural error,
degrees; a path's largest distance from a target). Seconds are one run, wall clock.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

import chaingraph
from chaingraph.model.chain import Chain, Joint, Mechanism, Point
from chaingraph.synthesis import (
    Certified,
    FunctionTargets,
    PointTargets,
    certify,
    function,
    function_task,
    path,
)


def crank_rocker_points(picks):
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
    "path, 5 points (exact)": lambda: path(points=crank_rocker_points(
        [10, 60, 120, 200, 290]), seed=1),
    "path, 20 points closed (fit)": lambda: path(points=crank_rocker_points(
        range(0, 360, 18)), closed=True, seed=1),
}


# -- against pylinkage 1.3.0 ------------------------------------------------------------
HERE = Path(__file__).resolve().parent
LOG10 = dict(function="log10(x)", x=(1.0, 2.0), swing=(60.0, 90.0))
GRID = [(t, o) for t in range(0, 360, 10) for o in range(0, 360, 10)]   # design's coarse grid
DEFECTS = ("circuit defect", "branch defect", "order defect")


def _peer_python():
    """pylinkage's venv (made as benchmarks/solve.py makes it), with scipy, which its
    synthesis imports but its package does not require."""
    sys.path.insert(0, str(HERE))
    from solve import pylinkage_python
    exe = pylinkage_python(sys.executable)
    if subprocess.run([str(exe), "-c", "import scipy"], capture_output=True).returncode:
        subprocess.run([str(exe), "-m", "pip", "install", "--quiet", "scipy"], check=True)
    return exe


def _peer(exe, task):
    done = subprocess.run([str(exe), str(HERE / "_pylinkage_synthesis.py")],
                          input=json.dumps(task), capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


def _four_bar(pose, name, task, output):
    """A peer's solution as a chaingraph chain file would hold it (drawn where the peer
    draws it: at the first target)."""
    joints = (Joint("A", "R", ("frame", "crank"), at=tuple(pose["A"])),
              Joint("B", "R", ("crank", "coupler"), at=tuple(pose["B"])),
              Joint("C", "R", ("coupler", "rocker"), at=tuple(pose["C"])),
              Joint("D", "R", ("rocker", "frame"), at=tuple(pose["D"])))
    points = (Point("P", "coupler", tuple(pose["P"])),) if "P" in pose else ()
    return Chain(name, joints, points=points, task=task,
                 mechanism=Mechanism("frame", "crank", 1.0, output))


def _function_targets(start):
    """The log10 task's angle pairs at Chebyshev's points from ``start`` (degrees), and
    the targets chaingraph certifies against (the start turned by whole turns so that
    the first point's input and output are in (-180, 180], as the solver reads a drawn
    pose's angles and as chaingraph's own designs give them)."""
    first = function_task(**LOG10, start=start).precision_x()[0]
    lift = [360.0 * math.floor((v + d + 180.0) / 360.0) for v, d in
            zip(start, (60.0 * (first - 1.0), 90.0 * math.log10(first) / math.log10(2)))]
    start = (start[0] - lift[0], start[1] - lift[1])
    task = function_task(**LOG10, start=start)
    xs = task.precision_x()
    inputs = start[0] + task.input_at(xs)
    outputs = start[1] + task.output_at(xs)
    a, b = task.x

    def wanted(theta):
        return start[1] + task.output_at(a + (np.asarray(theta) - start[0]) / 60.0 * (b - a))
    targets = FunctionTargets(tuple(map(float, inputs)), tuple(map(float, outputs)), "rocker",
                              (start[0], start[0] + 60.0), wanted)
    return np.radians(np.stack([inputs, outputs], axis=1)).tolist(), targets


def _judged(found, targets_of, task, output):
    """Each peer solution certified by chaingraph (its transmission angle not bounded:
    only the defects are counted): (reasons counted, certified errors, the errors of
    those also within chaingraph's default bounds: a transmission angle in [30, 150]
    degrees, the longest link at most 20 times the shortest)."""
    reasons, errors, bounded = Counter(), [], []
    for k, pose in enumerate(found["solutions"]):
        chain = _four_bar(pose, f"pylinkage solution {k + 1}", task, output)
        result = certify(chain, targets_of(pose), min_transmission=0.0)
        if isinstance(result, Certified):
            reasons["certified"] += 1
            errors.append(result.error_max)
            sides = [math.dist(pose[p], pose[q]) for p, q in ("AB", "BC", "CD", "DA")]
            ta = result.transmission_angle
            if ta is not None and 30.0 <= ta[0] and ta[1] <= 150.0 \
                    and max(sides) <= 20.0 * min(sides):
                bounded.append(result.error_max)
        else:
            reasons[result.reason] += 1
    return reasons, errors, bounded


def peer_rows(exe):
    """One row per task: the task, pylinkage's solutions, its own best error, how many
    have a defect (circuit, branch, order) or do not assemble when chaingraph solves
    their files, its best certified error and seconds; chaingraph's solutions, best
    error and seconds."""
    rows = []
    t = time.perf_counter()
    ours = function(**LOG10)
    ours_s = time.perf_counter() - t
    best_start = tuple(ours.solutions[0].mechanism.task["start"])
    for name, starts, mine, seconds in (
            ("function log10, start given", [best_start], None, None),
            ("function log10, starts searched", GRID, ours, ours_s)):
        if mine is None:
            t = time.perf_counter()
            mine = function(**LOG10, start=best_start)
            seconds = time.perf_counter() - t
        sets = [_function_targets(s) for s in starts]
        found = _peer(exe, {"kind": "function", "pair_sets": [p for p, _ in sets]})
        judged = _judged(found, lambda pose: sets[pose["set"]][1], {"kind": "function"},
                         "rocker")
        rows.append((name, len(found["solutions"]), None, *judged, found["seconds"], mine,
                     seconds))
    for picks in ([10, 90, 200, 290], [10, 60, 120, 200, 290]):
        points = crank_rocker_points(picks)
        t = time.perf_counter()
        mine = path(points=points, seed=1)
        seconds = time.perf_counter() - t
        found = _peer(exe, {"kind": "path", "points": points})
        own = [s["error"] for s in found["solutions"] if s["error"] is not None]
        judged = _judged(found, lambda pose: PointTargets(tuple(points), "P"),
                         {"kind": "path", "targets": [list(p) for p in points]}, "P")
        rows.append((f"path, {len(points)} points", len(found["solutions"]),
                     min(own) if own else None, *judged, found["seconds"], mine, seconds))
    return rows


def _g(value):
    return "-" if value is None else f"{value:.3g}"


def peer_table(rows):
    """The comparison as a Markdown table."""
    out = ["| task | pylinkage solutions | its error | circuit / branch / order defects | "
           "does not assemble | certified (best error) | within bounds (best error) | "
           "pylinkage s | chaingraph solutions | chaingraph error | chaingraph s |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, count, own, reasons, errors, bounded, peer_s, mine, seconds in rows:
        defects = " / ".join(str(reasons.get(r, 0)) for r in DEFECTS)
        best = f"{reasons.get('certified', 0)} ({_g(min(errors) if errors else None)})"
        kept = f"{len(bounded)} ({_g(min(bounded) if bounded else None)})"
        error = mine.solutions[0].error.max if mine.solutions else None
        out.append(f"| {name} | {count} | {_g(own)} | {defects} | "
                   f"{reasons.get('does not assemble', 0)} | {best} | {kept} | {peer_s:.2f} | "
                   f"{len(mine.solutions)} | {_g(error)} | {seconds:.2f} |")
    return "\n".join(out)


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
    if "--peer" in sys.argv:
        print(peer_table(peer_rows(_peer_python())))
    else:
        main()
