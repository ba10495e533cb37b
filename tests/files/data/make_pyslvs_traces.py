"""Solve the Pyslvs models of tests/files/data with Pyslvs itself (run inside its venv:
benchmarks/.venv-pyslvs/bin/python tests/files/data/make_pyslvs_traces.py).

For each pyslvs-NAME.txt (hand-written as Pyslvs writes an expression), NAME.trace.json
holds every joint's position (a slider's pin) with the input pair (0, 1) at the drawn
angle and every 30 degrees from it over a turn, as Pyslvs's triangle solver
(t_config, expr_solving) gives them: what tests/files/test_pyslvs.py compares
chaingraph's solve with.
"""
import json
import math
from pathlib import Path

from pyslvs import expr_solving, parse_vpoints, t_config

HERE = Path(__file__).resolve().parent
INPUTS = ((0, 1),)


def main():
    for path in sorted(HERE.glob("pyslvs-*.txt")):
        vpoints = parse_vpoints(path.read_text())
        exprs = t_config(vpoints, INPUTS)
        base, drive = vpoints[0], vpoints[1]
        start = math.degrees(math.atan2(drive.cy - base.cy, drive.cx - base.cx))
        rows = []
        for k in range(13):
            angle = start + 30.0 * k
            solved = expr_solving(exprs, vpoints, {INPUTS[0]: angle})
            rows.append([list(c[1]) if isinstance(c[0], tuple) else list(c) for c in solved])
            vpoints = parse_vpoints(path.read_text())      # each from the drawn pose
        stem = path.stem
        (HERE / f"{stem}.trace.json").write_text(json.dumps(
            {"start_deg": start, "step_deg": 30.0, "positions": rows}) + "\n")
        print(stem, len(rows[0]), "joints")


if __name__ == "__main__":
    main()
