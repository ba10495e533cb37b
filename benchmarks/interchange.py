"""pylinkage and Pyslvs load what chaingraph exports, and trace the same paths.

Usage:
    python benchmarks/interchange.py [--pylinkage PYTHON] [--pyslvs PYTHON]

Every catalog mechanism that each format holds is exported (``pylinkage_json``,
``pyslvs_expression``) and loaded by the real package in its own process and venv
(pylinkage 1.3 in benchmarks/.venv-pylinkage, as benchmarks/solve.py makes it; Pyslvs
22.7 in benchmarks/.venv-pyslvs, built from its sdist with Cython 3.0.0: ``python -m
venv benchmarks/.venv-pyslvs && benchmarks/.venv-pyslvs/bin/pip install cython==3.0.0
numpy lark-parser setuptools wheel && benchmarks/.venv-pyslvs/bin/pip install
--no-build-isolation pyslvs==22.7.0``), which steps it over a turn of its crank, a degree
a step from the drawn pose; chaingraph solves the same turn and the largest distance
between the two tools' positions of any joint or point is printed, with the
mechanism's size. A mechanism the tool cannot step is printed with the tool's error.

Then the peers' own example mechanisms are imported (Pyslvs's ``example_list`` with its
input pairs; pylinkage's six-bar factories ``watt_from_lengths`` and
``stephenson_from_lengths``, saved by tests/files/data/make_pylinkage_models.py) and what
chaingraph names them, with its structural verdict.
"""

import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

import chaingraph
from chaingraph.errors import ChainGraphError
from chaingraph.files import pylinkage_json, pyslvs_expression, read_pylinkage, read_pyslvs
from chaingraph.files.pyslvs import pins_in_slots
from chaingraph.naming.catalog import catalog_files

HERE = Path(__file__).resolve().parent
DATA = HERE.parent / "tests" / "files" / "data"


def size(chain):
    xy = [j.at for j in chain.joints] + [q.at for q in chain.points]
    return max(math.dist(a, b) for a in xy for b in xy)


def turn(chain):
    """chaingraph's run of the driver a degree a step from the drawn pose: a whole turn
    for a crank; for a driver that rocks, up to its upper limit (where pylinkage's
    arc_driver turns back); or None and the reason there is none to compare."""
    m = chain.mechanism
    if m.driver is None:
        return None, "driven through inputs, not a crank"
    motion = chaingraph.solve(chain, steps=360, summary=False)
    theta = motion.columns["theta"]
    if abs(theta[-1] - theta[0] - 360.0) <= 1e-9:
        return motion, None
    drawn = drawn_angle(chain)
    steps = math.floor(max(theta) - drawn - 1e-6)
    if steps < 1:
        return None, "its driver is drawn at its limit"
    return chaingraph.solve(chain, start=drawn, stop=drawn + steps, steps=steps,
                            summary=False), None


def span(motion):
    theta = motion.columns["theta"]
    if abs(theta[-1] - theta[0] - 360.0) <= 1e-9:
        return "a turn"
    return f"{theta[0]:.4g} to {theta[-1]:.4g} deg"


def drawn_angle(chain):
    """The driver's drawn direction (degrees): from its pivot to its first other joint
    by id, as chaingraph's theta and the exports measure it."""
    m = chain.mechanism
    pivot = next(j for j in chain.joints if j.kind == "R" and {m.fixed, m.driver}
                 <= set(j.links))
    return chain.reference_direction(m.driver, joint=pivot.id)


def xy(motion, chain, name):
    """A joint's or point's positions over the turn, (361, 2)."""
    part = motion.point(name) if name in {q.id for q in chain.points} else motion.joint(name)
    return np.column_stack([part.x, part.y])


def run(python, script, job):
    done = subprocess.run([str(python), str(HERE / script)], input=json.dumps(job),
                          capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{script} failed in {python}:\n{done.stderr[-2000:]}")
    return json.loads(done.stdout)


def exported(writer, folder, suffix):
    """``[(stem, chain, path or None, refusal or None)]`` for every catalog mechanism."""
    out = []
    for path in catalog_files():
        chain = chaingraph.load(path)
        if chain.mechanism is None:
            continue
        try:
            text = writer(chain)
        except ChainGraphError as e:
            out.append((path.stem, chain, None, e.problem))
            continue
        target = folder / f"{path.stem}{suffix}"
        target.write_text(text)
        out.append((path.stem, chain, target, None))
    return out


def line(tool, stem, text):
    print(f"{tool:<10} {stem:<36} {text}")


def compare_pylinkage(python, folder):
    rows = exported(pylinkage_json, folder, ".json")
    got = run(python, "_interchange_pylinkage.py", [str(p) for _, _, p, _ in rows if p])
    worst = 0.0
    for stem, chain, path, refusal in rows:
        if refusal:
            line("pylinkage", stem, f"not exported: {refusal}")
            continue
        theirs = got[str(path)]
        if "error" in theirs:
            line("pylinkage", stem, f"loads; cannot step it: {theirs['error']}")
            continue
        motion, why = turn(chain)
        if motion is None:
            line("pylinkage", stem, f"loads; not compared: {why}")
            continue
        rows = len(motion.columns["theta"])
        positions = np.array(theirs["positions"])[:rows]
        deviation = max(float(np.abs(xy(motion, chain, name) - positions[:, k, :]).max())
                        for k, name in enumerate(theirs["ids"]))
        worst = max(worst, deviation / size(chain))
        line("pylinkage", stem, f"max deviation {deviation:.3g} (size {size(chain):.4g}; "
                                f"{span(motion)}; its {theirs['solver']} solver)")
    return worst


def pyslvs_order(chain):
    """The joints as pyslvs_expression writes them (the crank's pivot first; a pin in a
    slot once, as its RP joint, compared at the pin), then the points; and the input
    pair (the pivot, the driver's reference joint) as indices, or None."""
    m = chain.mechanism
    pivot = next(j.id for j in chain.joints if j.kind == "R" and {m.fixed, m.driver}
                 <= set(j.links))
    pins = pins_in_slots(chain, {m.fixed, m.driver})
    names = [pins.get(i, i) for i in [pivot, *(j.id for j in chain.joints if j.id != pivot)]
             if i not in pins.values()] + [q.id for q in chain.points]
    spots = sorted((j.id, j.at) for j in chain.joints_of(m.driver))
    drive = next((i for i, at in spots if i != pivot and i in names
                  and math.dist(at, chain.joint(pivot).at) > 0), None)
    return names, None if drive is None else (0, names.index(drive))


def compare_pyslvs(python, folder):
    rows = exported(pyslvs_expression, folder, ".txt")
    jobs, motions = [], {}
    for stem, chain, path, refusal in rows:
        if path is None or chain.mechanism.driver is None:
            continue
        motion, why = turn(chain)
        names, pair = pyslvs_order(chain)
        if pair is None:
            motion, why = None, "the driver has no joint apart from its pivot (Pyslvs's " \
                                "input is a pair of joints of one link)"
        motions[stem] = (motion, why)
        if motion is not None:
            jobs.append({"path": str(path), "input": pair,
                         "angles": [float(t) for t in motion.columns["theta"]]})
    # one process a model: Pyslvs's C++ solvers may crash the process on a model
    got = run(python, "_interchange_pyslvs.py", {"models": []})
    for job in jobs:
        done = subprocess.run([str(python), str(HERE / "_interchange_pyslvs.py")],
                              input=json.dumps({"models": [job]}), capture_output=True,
                              text=True)
        got["models"][job["path"]] = json.loads(done.stdout)["models"][job["path"]] \
            if done.returncode == 0 else {"error": f"Pyslvs's process ended with status "
                                                    f"{done.returncode}"}
    worst = 0.0
    for stem, chain, path, refusal in rows:
        if refusal:
            line("pyslvs", stem, f"not exported: {refusal}")
            continue
        motion, why = motions.get(stem, (None, "driven through inputs, not a crank"))
        if motion is None:
            line("pyslvs", stem, f"not compared: {why}")
            continue
        theirs = got["models"][str(path)]
        if "error" in theirs:
            line("pyslvs", stem, f"cannot solve it: {theirs['error']}")
            continue
        names, _ = pyslvs_order(chain)
        positions = np.array(theirs["positions"])
        deviation = max(float(np.abs(xy(motion, chain, name) - positions[:, k, :]).max())
                        for k, name in enumerate(names))
        worst = max(worst, deviation / size(chain))
        line("pyslvs", stem, f"max deviation {deviation:.3g} (size {size(chain):.4g}; "
                             f"{span(motion)}; its {theirs['solver']} solver)")
    return worst, got["examples"]


def named(model):
    """What chaingraph calls an imported model, and its structure's verdict."""
    chain = model.chain
    c = chaingraph.classify(chain)
    name = chaingraph.identify(chain)
    what = name.inversion or name.chain or "not in the catalog"
    verdict = f"{len(chain.links)} links, mobility {c.mobility}"
    if c.degenerate:
        verdict += f", degenerate: rigid {', '.join(sorted(c.rigid_subchains[0]))}"
    return f"{what} ({verdict})"


def peers_examples(examples):
    for name, (expression, pairs) in sorted(examples.items()):
        try:
            model = read_pyslvs(expression, inputs=[tuple(p) for p in pairs], name=name)
            line("pyslvs", name, named(model))
        except ChainGraphError as e:
            line("pyslvs", name, f"not imported: {e}")
    for stem in ("pylinkage-watt-factory", "pylinkage-stephenson-factory"):
        model = read_pylinkage((DATA / f"{stem}.json").read_text(), source=stem)
        line("pylinkage", stem.removeprefix("pylinkage-"), named(model))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pylinkage", default=HERE / ".venv-pylinkage" / "bin" / "python",
                        help="pylinkage 1.3's Python")
    parser.add_argument("--pyslvs", default=HERE / ".venv-pyslvs" / "bin" / "python",
                        help="Pyslvs 22.7's Python")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        worst = compare_pylinkage(args.pylinkage, Path(folder))
        print(f"pylinkage: largest deviation {worst:.3g} of the mechanism's size")
        worst, examples = compare_pyslvs(args.pyslvs, Path(folder))
        print(f"pyslvs: largest deviation {worst:.3g} of the mechanism's size")
    print("\nthe peers' own examples, imported and named here:")
    peers_examples(examples)


if __name__ == "__main__":
    sys.exit(main())
