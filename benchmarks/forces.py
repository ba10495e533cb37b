"""Forces over a sweep against the motion alone: the catalog's reciprocating engine
with masses, 3,600 steps (issue: at most 3 times the motion's cost).

    python benchmarks/forces.py
"""

import time
from dataclasses import replace

import chaingraph
from chaingraph.naming.catalog import catalog_path


def best(f, repeat=5):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def main():
    for name in ("reciprocating-engine", "whitworth-quick-return-with-ram",
                 "stephenson-iii-mechanism"):
        chain = chaingraph.load(catalog_path(name))
        if not (chain.masses or chain.loads or chain.gravity):
            fixed = chain.mechanism.fixed
            chain = replace(chain, masses=tuple(chaingraph.LinkMass(x, 1.0)
                                                for x in chain.links if x != fixed),
                            gravity=(0.0, -9.81), units=chain.units or "mm")
        motion = best(lambda: chaingraph.solve(chain, steps=3600))
        forces = best(lambda: chaingraph.forces(chain, steps=3600))
        print(f"{name:34s} solve {motion * 1000:7.1f} ms  forces {forces * 1000:7.1f} ms "
              f"(solve included)  ratio {forces / motion:4.2f}")


def first_calls():
    """The first call in a fresh process (nothing cached), for the same three."""
    import subprocess
    import sys
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
    for name in ("reciprocating-engine", "whitworth-quick-return-with-ram",
                 "stephenson-iii-mechanism"):
        t = [float(subprocess.run([sys.executable, "-c", code, name, what], capture_output=True,
                                  text=True, check=True).stdout) for what in ("solve", "forces")]
        print(f"{name:34s} first call: solve {t[0] * 1000:7.1f} ms  forces {t[1] * 1000:7.1f} "
              f"ms  ratio {t[1] / t[0]:4.2f}")


if __name__ == "__main__":
    main()
    first_calls()
