"""Time pylinkage on the crank-rocker four-bar (run inside pylinkage's own venv).

Without arguments past the step count, prints one JSON line: milliseconds for 3,600
steps with velocity and acceleration by the numba path (step_fast_with_kinematics) and
by the pure-Python path (step_with_derivatives), each the median of several runs, and
the rocker's extreme positions as a sanity check.

With ``--serve``, it compiles the numba path, prints ``ready`` and then, for each line
``N`` read from its standard input, times N runs of the numba path and prints their
milliseconds as one JSON list: the caller interleaves these rounds with its own, so
that both sides are measured under the same load.
"""
import json
import math
import statistics
import sys
import time

import pylinkage as pl

STEPS = int(sys.argv[1]) if len(sys.argv) > 1 else 3600


def build():
    a = pl.Ground(0.0, 0.0, name="A")
    d = pl.Ground(100.0, 0.0, name="D")
    crank = pl.Crank(anchor=a, radius=40.0, angular_velocity=2 * math.pi / STEPS,
                     initial_angle=math.radians(60.0), name="B")
    c = pl.RRRDyad(anchor1=crank.output, anchor2=d, distance1=120.0, distance2=80.0,
                   name="C")
    linkage = pl.Linkage([a, d, crank, c], name="four-bar")
    linkage.set_input_velocity(crank, omega=1.0)
    return linkage, crank


def times_ms(fn, repeats):
    out = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        out.append(1000.0 * (time.perf_counter() - start))
    return out


linkage, crank = build()


def fast():
    return linkage.step_fast_with_kinematics(iterations=STEPS)


fast()                                                 # compile (numba)
if "--serve" in sys.argv:
    print("ready", flush=True)
    for line in sys.stdin:
        print(json.dumps(times_ms(fast, int(line))), flush=True)
    sys.exit(0)
fast_ms = statistics.median(times_ms(fast, 30))
slow_ms = statistics.median(times_ms(lambda: list(linkage.step_with_derivatives(iterations=STEPS)), 3))
positions, _, _ = fast()
xs = [row[-1][0] for row in positions]
print(json.dumps({"numba_ms": fast_ms, "python_ms": slow_ms, "steps": STEPS,
                  "c_x_min": min(xs), "c_x_max": max(xs)}))
