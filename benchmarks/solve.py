"""Solver speed: microseconds per step for every catalog mechanism, and pylinkage side by side.

Usage:
    python benchmarks/solve.py            # chaingraph only
    python benchmarks/solve.py --compare  # also pylinkage 1.3.0 (installed on first use
                                          # into benchmarks/.venv-pylinkage, with numba)

Each figure is the median of several runs of a 3,600-step sweep with velocities and
accelerations of every link, joint and point (``solve(..., summary=False)``), after a
warm-up (the plan and the feasible range are built once per inversion and cached).
With ``--compare``, pylinkage runs in its own process beside this one, and the two take
turns in rounds (chaingraph's bare sweep, its sweep with the summary, pylinkage's numba
sweep, ``--per-round`` runs each), so that both are timed under the same load; each
side's figure is the median of all its runs.
Targets (issue 36): the whole call with its summary at most pylinkage's numba sweep, the
bare sweep at most 0.7 times it. Earlier targets (issue 4): the crank-rocker four-bar at least as fast as pylinkage's numba path
and 20 times faster than its pure-Python path; the six-link shaper at most three times
the four-bar; Stephenson's third inversion (Newton's method) under 100 ms. Issue 11:
the whole call *with* its summary (stroke, extremes, time ratio, dead centres, all
refined) no slower than pylinkage's numba path for the bare sweep; and the same four-bar
driven through an input joint, and an engine driven by its piston, timed too.
"""

import argparse
import json
import math
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import chaingraph
from chaingraph import Chain, Joint, Mechanism
from chaingraph.naming.catalog import catalog_files, catalog_path

HERE = Path(__file__).resolve().parent
STEPS = 3600


def times_ms(fn, repeats):
    """Milliseconds of each of ``repeats`` runs of ``fn``."""
    out = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        out.append(1000.0 * (time.perf_counter() - start))
    return out


def median_ms(fn, repeats):
    """The median milliseconds of ``repeats`` runs of ``fn``, after one to warm up."""
    fn()
    return statistics.median(times_ms(fn, repeats))


def crank_rocker():
    """Ground 100, crank 40, coupler 120, rocker 80; crank at 60 degrees (as pylinkage's)."""
    a = (0.0, 0.0)
    d = (100.0, 0.0)
    b = (40 * math.cos(math.radians(60)), 40 * math.sin(math.radians(60)))
    dx, dy = d[0] - b[0], d[1] - b[1]
    dist = math.hypot(dx, dy)
    along = (120 ** 2 - 80 ** 2 + dist ** 2) / (2 * dist)
    h = math.sqrt(120 ** 2 - along ** 2)
    c = (b[0] + along * dx / dist - h * dy / dist, b[1] + along * dy / dist + h * dx / dist)
    return Chain("crank-rocker four-bar", (
        Joint("A", "R", ("frame", "crank"), at=a), Joint("B", "R", ("crank", "coupler"), at=b),
        Joint("C", "R", ("coupler", "rocker"), at=c), Joint("D", "R", ("rocker", "frame"), at=d)),
        mechanism=Mechanism("frame", "crank", 1.0, "rocker"))


def stephenson_three():
    chain = chaingraph.load(catalog_path("stephenson-six-bar-chain"))
    return chain.with_mechanism("b4", "t2")


def sweep(chain, start=None, stop=None, summary=False, inputs=None):
    """The call timed: a 3,600-step sweep with velocities and accelerations."""
    return lambda: chaingraph.solve(chain, start=start, stop=stop, steps=STEPS,
                                    summary=summary, inputs=inputs)


def sweep_ms(chain, start=None, stop=None, repeats=20, summary=False, inputs=None):
    return median_ms(sweep(chain, start, stop, summary, inputs), repeats)


def pylinkage_python(python):
    """pylinkage's venv's Python, the venv made (pylinkage 1.3.0 and numba installed)
    on first use."""
    venv = HERE / ".venv-pylinkage"
    exe = venv / "bin" / "python"
    if not exe.exists():
        print(f"installing pylinkage 1.3.0 and numba into {venv} ...", file=sys.stderr)
        subprocess.run([python, "-m", "venv", str(venv)], check=True)
        subprocess.run([str(exe), "-m", "pip", "install", "--quiet", "pylinkage==1.3.0", "numba"],
                       check=True)
    return exe


def pylinkage(python):
    """pylinkage's figures run alone: medians of its numba and pure-Python paths, and
    the rocker's extremes as a check."""
    out = subprocess.run([str(pylinkage_python(python)), str(HERE / "_pylinkage_fourbar.py"),
                          str(STEPS)], check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def side_by_side(python, rounds, per_round):
    """Medians (ms) of chaingraph's bare sweep, its sweep with the summary and
    pylinkage's numba sweep of the crank-rocker, timed in turns in the same rounds."""
    chain = crank_rocker()
    bare, full = sweep(chain), sweep(chain, summary=True)
    bare(), full()
    server = subprocess.Popen([str(pylinkage_python(python)), str(HERE / "_pylinkage_fourbar.py"),
                               str(STEPS), "--serve"], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True)
    samples = {"bare": [], "summary": [], "pylinkage": []}
    faults = 0
    try:
        if server.stdout.readline().strip() != "ready":
            raise RuntimeError("pylinkage's timing process did not start")
        for _ in range(rounds):
            before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
            samples["bare"] += times_ms(bare, per_round)
            samples["summary"] += times_ms(full, per_round)
            faults += resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before
            server.stdin.write(f"{per_round}\n")
            server.stdin.flush()
            samples["pylinkage"] += json.loads(server.stdout.readline())
    finally:
        server.stdin.close()
        server.wait()
    medians = {k: statistics.median(v) for k, v in samples.items()}
    medians["faults"] = faults / (2 * rounds * per_round)
    return medians


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--compare", action="store_true", help="time pylinkage 1.3.0 too")
    parser.add_argument("--python", default=sys.executable,
                        help="the Python that makes pylinkage's venv")
    parser.add_argument("--rounds", type=int, default=30,
                        help="rounds of the side-by-side comparison (default 30)")
    parser.add_argument("--per-round", type=int, default=10,
                        help="runs of each side in a round (default 10)")
    parser.add_argument("--only-compare", action="store_true",
                        help="only the side-by-side comparison with pylinkage")
    args = parser.parse_args()
    if args.only_compare:
        compare(args)
        return

    print(f"{STEPS}-step sweeps with velocity and acceleration (median of 20):")
    print(f"{'mechanism':48s} {'ms':>8s} {'us/step':>8s}")
    for path in catalog_files():
        chain = chaingraph.load(path)
        if chain.mechanism is None or chain.mechanism.driver is None:
            continue
        ms = sweep_ms(chain)
        print(f"{chain.name[:48]:48s} {ms:8.2f} {1000 * ms / STEPS:8.3f}")
    four = sweep_ms(crank_rocker(), repeats=50)
    four_full = sweep_ms(crank_rocker(), repeats=50, summary=True)
    four_input = sweep_ms(crank_rocker(), repeats=50, summary=True, inputs=["A"])
    engine = chaingraph.load(catalog_path("reciprocating-engine"))
    piston = sweep_ms(engine, repeats=20, summary=True, inputs=["S"])
    shaper = sweep_ms(chaingraph.load(catalog_path("shaper-crank-and-slotted-lever")), repeats=50)
    s3 = stephenson_three()
    t0 = chaingraph.build_plan(s3).theta0
    newton_chain = sweep_ms(s3, start=t0, stop=t0 + 150.0, repeats=10)
    newton = sweep_ms(chaingraph.load(catalog_path("stephenson-iii-mechanism")), repeats=10)
    print()
    print(f"crank-rocker four-bar:            {four:7.2f} ms")
    print(f"  the whole call with its summary: {four_full:7.2f} ms "
          f"(driven through its input joint A: {four_input:.2f} ms)")
    print(f"reciprocating engine driven by its piston, with summary: {piston:7.2f} ms")
    print(f"six-link shaper:                  {shaper:7.2f} ms  ({shaper / four:.2f} x the four-bar)")
    print(f"Stephenson III mechanism (Newton, full turn): {newton:7.2f} ms")
    print(f"Stephenson chain, b4 fixed, t2 driving (Newton, 150 deg): {newton_chain:7.2f} ms")
    if args.compare:
        result = pylinkage(args.python)
        slow = result["python_ms"]
        print()
        print("pylinkage 1.3.0, the same four-bar, 3,600 steps with velocity and acceleration:")
        print(f"  step_with_derivatives (Python, alone): {slow:7.2f} ms")
        print(f"pylinkage Python / chaingraph: {slow / four:.1f}  (target >= 20)")
        m = chaingraph.solve(crank_rocker(), steps=STEPS, summary=False)
        lo, hi = float(np.nanmin(m["x:C"])), float(np.nanmax(m["x:C"]))
        print(f"check: C's x range chaingraph {lo:.6f}..{hi:.6f}, "
              f"pylinkage {result['c_x_min']:.6f}..{result['c_x_max']:.6f}")
        compare(args)


def compare(args):
    """Print the side-by-side medians and the two ratios against pylinkage's numba path."""
    m = side_by_side(args.python, args.rounds, args.per_round)
    fast = m["pylinkage"]
    print()
    print(f"side by side, {args.rounds} rounds of {args.per_round} runs each, medians:")
    print(f"  pylinkage 1.3.0 step_fast_with_kinematics (numba): {fast:7.3f} ms")
    print(f"  chaingraph solve(summary=False):                   {m['bare']:7.3f} ms")
    print(f"  chaingraph solve() with its summary:               {m['summary']:7.3f} ms")
    print(f"chaingraph bare sweep / pylinkage numba:    {m['bare'] / fast:.2f}  (target <= 0.7)")
    print(f"chaingraph with summary / pylinkage numba:  {m['summary'] / fast:.2f}  (target <= 1)")
    # the memory a call takes that the C library gave back to the system after the last
    # call (glibc trims its heap's top past 128 kB until a larger block has been freed)
    print(f"chaingraph's minor page faults per call: {m['faults']:.0f}")


if __name__ == "__main__":
    main()
