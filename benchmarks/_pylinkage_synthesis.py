"""Run pylinkage 1.3.0's synthesis on one task (run inside pylinkage's own venv).

Reads one JSON task from standard input and prints one JSON object: the seconds the
calls took (wall clock, the whole loop for a list of angle-pair sets) and every solution
pylinkage returned, as its FourBarSolution's drawn pose (A, B, C, D and, for a path,
the coupler point P) with pylinkage's own error where it reports one (for a path, the
largest of ``verify_path_generation``'s distances from each target to the coupler
point's trajectory; a function generator's solutions are exact at their angle pairs by
construction and pylinkage reports no error over a range).

Tasks: ``{"kind": "function", "pair_sets": [[[theta2, theta4] x 3], ...]}`` (radians;
pylinkage's ``function_generation``, called once per set, ``require_grashof`` off so as
not to drop the non-Grashof rockers a function generator often is), or
``{"kind": "path", "points": [[x, y], ...]}`` (``path_generation`` with its defaults).
"""
import json
import sys
import time
import warnings

from pylinkage.synthesis import function_generation, path_generation
from pylinkage.synthesis.conversion import solution_to_linkage
from pylinkage.synthesis.path_generation import verify_path_generation


def _pose(raw):
    out = {"A": list(raw.ground_pivot_a), "B": list(raw.crank_pivot_b),
           "C": list(raw.coupler_pivot_c), "D": list(raw.ground_pivot_d)}
    if raw.coupler_point is not None:
        out["P"] = list(raw.coupler_point)
    return out


def function_task(task):
    found = []
    t = time.perf_counter()
    for k, pairs in enumerate(task["pair_sets"]):
        result = function_generation([tuple(p) for p in pairs], ground_length=100.0,
                                     require_grashof=False)
        found += [{"set": k, **_pose(raw)} for raw in result.raw_solutions]
    seconds = time.perf_counter() - t
    return {"seconds": seconds, "solutions": found}


def path_task(task):
    points = [tuple(p) for p in task["points"]]
    t = time.perf_counter()
    result = path_generation(points)
    seconds = time.perf_counter() - t
    found = []
    for raw in result.raw_solutions:
        try:                        # its own check, on its own simulation
            _, distances = verify_path_generation(solution_to_linkage(raw), points)
            error = max(distances) if distances else None
        except Exception:           # what solutions_to_linkages itself skips
            error = None
        found.append({**_pose(raw), "error": error})
    return {"seconds": seconds, "solutions": found, "warnings": list(result.warnings)}


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    given = json.loads(sys.stdin.read())
    run = function_task if given["kind"] == "function" else path_task
    print(json.dumps(run(given)))
