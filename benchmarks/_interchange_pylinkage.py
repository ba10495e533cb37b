"""Load chaingraph's pylinkage exports in pylinkage 1.3 and step them (run inside
pylinkage's own venv by benchmarks/interchange.py).

Reads a JSON list of file paths on standard input; prints one JSON object: for each
file, {"ids": joint ids, "positions": [step][joint][x, y]} with the drawn pose as step 0
and 360 steps of the crank after it (its angular_velocity, a degree a step), or
{"error": "..."} when pylinkage cannot load or step it; and "solver": whether pylinkage
used its Assur group solver or fell back to its joint-by-joint one.
"""
import json
import sys

from pylinkage.mechanism.serialization import mechanism_from_json

out = {}
for path in json.load(sys.stdin):
    try:
        mechanism = mechanism_from_json(path)
        rows = [[list(j.position) for j in mechanism.joints]]
        rows += [[list(c) for c in coords] for coords in mechanism.step(iterations=360)]
        out[path] = {"ids": [j.id for j in mechanism.joints], "positions": rows,
                     "solver": "groups" if mechanism._use_group_solver else "joint by joint"}
    except Exception as e:                       # noqa: BLE001 - reported, not raised
        out[path] = {"error": f"{type(e).__name__}: {e}"}
print(json.dumps(out))
