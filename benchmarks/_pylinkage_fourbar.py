"""Time pylinkage on the crank-rocker four-bar (run inside pylinkage's own venv).

Prints one JSON line: milliseconds for 3,600 steps with velocity and acceleration by the
numba path (step_fast_with_kinematics), and by the pure-Python path
(step_with_derivatives), and the rocker's extreme positions as a sanity check.
"""
import json
import math
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


def best_of(fn, repeats):
    best = math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best * 1000.0


linkage, crank = build()
linkage.step_fast_with_kinematics(iterations=STEPS)   # compile (numba)
fast = best_of(lambda: linkage.step_fast_with_kinematics(iterations=STEPS), 30)
slow = best_of(lambda: list(linkage.step_with_derivatives(iterations=STEPS)), 3)
positions, _, _ = linkage.step_fast_with_kinematics(iterations=STEPS)
xs = [row[-1][0] for row in positions]
print(json.dumps({"numba_ms": fast, "python_ms": slow, "steps": STEPS,
                  "c_x_min": min(xs), "c_x_max": max(xs)}))
