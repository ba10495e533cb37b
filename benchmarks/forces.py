"""Forces over a sweep against the motion alone: the catalog's reciprocating engine,
Whitworth drive with ram (their own masses and loads) and Stephenson III (a unit mass
on every moving link), 3,600 steps, repeated (the motion's cycle cached): the issue's
goal is at most 3 times the motion's cost. Side by side, the wall clock and the CPU
time of this process (the machine is shared: the CPU time is the steadier), each the
best of ``--repeat`` runs (9 by default); then the first call in a fresh process.

    python benchmarks/forces.py [--repeat N]
"""

import argparse
import subprocess
import sys
import time
from dataclasses import replace

import chaingraph
from chaingraph.naming.catalog import catalog_path

NAMES = ("reciprocating-engine", "whitworth-quick-return-with-ram", "stephenson-iii-mechanism")


def best(f, repeat=9):
    """The least wall clock and the least CPU time (s) of ``repeat`` calls of ``f``."""
    wall, cpu = [], []
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        f()
        cpu.append(time.process_time() - c)
        wall.append(time.perf_counter() - t)
    return min(wall), min(cpu)


def loaded(name):
    chain = chaingraph.load(catalog_path(name))
    if not (chain.masses or chain.loads or chain.gravity):
        fixed = chain.mechanism.fixed
        chain = replace(chain, masses=tuple(chaingraph.LinkMass(x, 1.0)
                                            for x in chain.links if x != fixed),
                        gravity=(0.0, -9.81), units=chain.units or "mm")
    return chain


def main(repeat=9):
    print(f"{'':34s} {'wall clock (ms)':>30s}   {'CPU time (ms)':>30s}")
    print(f"{'':34s} {'solve':>9s} {'forces':>9s} {'ratio':>6s}    {'solve':>9s} {'forces':>9s} "
          f"{'ratio':>6s}")
    for name in NAMES:
        chain = loaded(name)
        chaingraph.forces(chain, steps=3600)            # (the cycle's integrals, kept)
        motion = best(lambda: chaingraph.solve(chain, steps=3600), repeat)
        forces = best(lambda: chaingraph.forces(chain, steps=3600), repeat)
        print(f"{name:34s} " + "    ".join(
            f"{motion[i] * 1000:9.2f} {forces[i] * 1000:9.2f} {forces[i] / motion[i]:6.2f}"
            for i in (0, 1)) + "   (forces: solve included)")


def first_calls():
    """The first call in a fresh process (nothing cached), for the same three."""
    code = '''
import time, chaingraph, sys
from dataclasses import replace
from chaingraph.naming.catalog import catalog_path
c = chaingraph.load(catalog_path(sys.argv[1]))
if not (c.masses or c.loads or c.gravity):
    c = replace(c, masses=tuple(chaingraph.LinkMass(x, 1.0) for x in c.links
                                if x != c.mechanism.fixed), gravity=(0, -9.81),
                units=c.units or "mm")
t = time.perf_counter()
getattr(chaingraph, sys.argv[2])(c, steps=3600)
print(time.perf_counter() - t)
'''
    for name in NAMES:
        t = [float(subprocess.run([sys.executable, "-c", code, name, what], capture_output=True,
                                  text=True, check=True).stdout) for what in ("solve", "forces")]
        print(f"{name:34s} first call: solve {t[0] * 1000:7.1f} ms  forces {t[1] * 1000:7.1f} "
              f"ms  ratio {t[1] / t[0]:4.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=9, help="runs of each (the best kept)")
    main(parser.parse_args().repeat)
    first_calls()
