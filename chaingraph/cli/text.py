"""What the command line prints: JSON, tables, figures, and an error's message with the
flag of the parameter at fault and the exit status it gives."""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from typing import Any

from chaingraph.errors import AssemblyError
from chaingraph.kinematics import Assembly, PoseMotion
from chaingraph.structure import Classification

__all__ = ['print_json', 'table', 'classification_text', 'figure', 'instant_heading', 'mode_lines', 'FLAGS', 'exit_status', 'error_text']


def print_json(obj: Any) -> None:
    """Print a JSON value (any that :func:`json.dumps` writes), indented."""
    print(json.dumps(obj, indent=2, ensure_ascii=False))

def table(rows: Sequence[Sequence[object]], header: Sequence[object]) -> str:
    """Rows as a plain-text table under ``header``, columns padded to their widest."""
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    fmt = lambda r: "  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip()  # noqa: E731
    return "\n".join([fmt(header), fmt(["-" * w for w in widths]), *map(fmt, rows)])

def classification_text(result: Classification, source: str) -> str:
    """What ``chaingraph classify`` prints."""
    rows = [list(row) for row in result.rows()]
    head = f"{result.name}  ({source})"
    body = table(rows, ["", "", ""]).split("\n", 2)[2]
    lines = [head, body]
    lines += [f"note: {o}" for o in result.oddities if not o.startswith("degenerate")]
    return "\n".join(lines)

def figure(value: object, unit: str = "") -> str:
    """A value as a table shows it: a float to 6 figures, None as "-"."""
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.6g}{unit}"
    return f"{value}{unit}"

def instant_heading(what: str, state: PoseMotion) -> list[str]:
    """The heading of a result at one input value (centres, polygons)."""
    lines = [f"{what} of {state.name}",
             f"{state.fixed} fixed, {state.input_text()} ({state.speed_text})"]
    if len(state.plan.inputs) > 1:
        lines.append("the inputs move together at their sweeps' rates (a polygon per "
                     "input, by superposition, is not drawn yet)")
    return lines

def mode_lines(assembly: Assembly) -> list[str]:
    """Each assembly mode chosen, one line each."""
    return [f"{m.part}: {m.word} {m.reference} ({m.source})" for m in assembly.modes]

# the library's parameters as the command line's options, for its messages
FLAGS = {"fixed": "--fixed LINK", "driver": "--driver LINK", "inputs": "--input JOINT",
          "steps": "--steps N", "start": "--from", "stop": "--to", "at": "--at",
          "omega": "--omega", "time_ratio": "--time-ratio", "crank": "--crank",
          "stroke": "--stroke", "links": "--links N", "dof": "--dof F",
          "scheduler": "--scheduler ADDRESS", "workers": "--workers K", "out": "--out DIR",
          "resume": "--resume", "prismatic": "--prismatic K", "oriented": "--oriented",
          "speed_fluctuation": "--speed-fluctuation CS", "static": "--static",
          "output": "--output NAME", "length": "--length LINK=FROM:TO:STEP",
          "hours": "--max-hours H", "speeds": "--speed LINK=RPM"}

def exit_status(error: BaseException) -> int:
    """The exit status of an error: 1 for an analysis that failed (a pose that cannot
    be assembled), 2 for bad input."""
    return 1 if isinstance(error, AssemblyError) else 2

# a synthesis's parameters (``design function | path | motion``)
SYNTHESIS_FLAGS = {"function": "--function EXPR", "x": "--x A:B", "swing": "--swing IN:OUT",
                   "start": "--start IN0:OUT0", "points": "--points N",
                   "spacing": "--spacing chebyshev|even",
                   "kind": "--kind four-bar|slider-crank", "solutions": "--solutions K",
                   "min_transmission": "--min-transmission DEG", "units": "--units U",
                   "poses": "--poses \"X,Y,DEG; ...\"", "links": "--links 4|6|8",
                   "prismatic": "--prismatic K|all"}
SYNTHESES = ("function", "path", "motion")
# where a path task's parameter has its own flag
PATH_FLAGS = {"points": '--points "X,Y; ..."', "points_file": "--points-file CSV",
              "timing": '--timing "DEG; ..."', "seed": "--seed S",
              "kind": None}


def error_text(error: BaseException) -> str:
    """The error's message, with the flag of the parameter at fault."""
    kind = getattr(error, "kind", None)
    flags: Mapping[str, str | None] = SYNTHESIS_FLAGS if kind in SYNTHESES else FLAGS
    if kind == "path":
        flags = {**flags, **PATH_FLAGS}
    parameter = getattr(error, "parameter", None)
    flag = flags.get(parameter) if parameter is not None else None
    return f"{error}" if flag is None else f"{error}; on the command line: {flag}"
