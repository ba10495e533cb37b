"""Load chaingraph's Pyslvs expressions in Pyslvs 22.7 and solve them (run inside
Pyslvs's own venv by benchmarks/interchange.py); also list Pyslvs's own examples.

Reads a JSON object on standard input: {"models": [{"path", "input": [base, drive],
"angles": [degrees...]}]}; prints one JSON object: "models": for each path the joints'
positions (a slider's pin) at each angle, by Pyslvs's triangle solver (t_config and
expr_solving) or, where that finds no formula (a group of class 3), its BFGS solver
(SolverSystem) stepped from the drawn pose; or {"error": "..."}; and "examples":
Pyslvs's example_list, {name: [expression, input pairs]}.
"""
import json
import sys

from pyslvs import SolverSystem, all_examples, example_list, expr_solving, parse_vpoints, \
    t_config


def pins(solved):
    return [list(c[1]) if isinstance(c[0], tuple) else list(c) for c in solved]


def solve(expression, pair, angles):
    vpoints = parse_vpoints(expression)
    try:
        exprs = t_config(vpoints, [pair])
        rows = [pins(expr_solving(exprs, parse_vpoints(expression), {pair: a}))
                for a in angles]
        return {"positions": rows, "solver": "triangles"}
    except Exception as e:                       # noqa: BLE001 - the other solver then
        why = f"{type(e).__name__}: {e}"
    system = SolverSystem(vpoints, {pair: angles[0]})
    rows = []
    for a in angles:
        system.set_inputs({pair: a})
        rows.append([list(c) if not isinstance(c[0], tuple) else list(c[1])
                     for c in system.solve()])
    return {"positions": rows, "solver": f"BFGS (triangles: {why})"}


job = json.load(sys.stdin)
out = {"models": {}, "examples": {n: list(example_list(n)) for n in all_examples()}}
for model in job["models"]:
    try:
        out["models"][model["path"]] = solve(open(model["path"]).read(),
                                             tuple(model["input"]), model["angles"])
    except Exception as e:                       # noqa: BLE001 - reported, not raised
        out["models"][model["path"]] = {"error": f"{type(e).__name__}: {e}"}
print(json.dumps(out))
