"""``chaingraph gears FILE``: the speeds of a gear train's links, its kind and graph."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from fractions import Fraction

from chaingraph.cli.text import print_json, table
from chaingraph.errors import MechanismError
from chaingraph.files import load
from chaingraph.kinematics.gears import TrainSpeeds, train_speeds

__all__ = ["gears_command", "cmd_gears", "speed_argument"]


def speed_argument(text: str) -> tuple[str, float]:
    """``LINK=RPM`` read as (link, rpm)."""
    link, eq, value = text.rpartition("=")
    try:
        rpm = float(value)
    except ValueError:
        rpm = float("nan")
    if not eq or not link or not math.isfinite(rpm):
        raise argparse.ArgumentTypeError(f"expected LINK=RPM (a link and a finite speed), "
                                         f"got {text!r}")
    return link, rpm


def gears_command(sub: argparse._SubParsersAction,
                  path_argument: Callable[[str], str]) -> None:
    """The arguments of ``chaingraph gears`` (``path_argument``: how a FILE is read)."""
    p = sub.add_parser("gears", help="a gear train's speeds, ratios, kind and graph",
                       description="The speed of every link of a gear train ([[gears]]) "
                                   "with the fixed link at rest and the given speeds, by "
                                   "the tabular method (checked against the Willis "
                                   "equations), the ratio between any two links, the "
                                   "train's kind and its graph.")
    p.add_argument("file", type=path_argument, metavar="FILE", help="a chain file (TOML) "
                   "with [[gears]]")
    p.add_argument("--fixed", metavar="LINK", help="the link at rest (default: the file's)")
    p.add_argument("--speed", dest="speeds", action="append", type=speed_argument,
                   metavar="LINK=RPM", help="a link's speed (rpm); repeat it, one per "
                                            "degree of freedom (default: the file's "
                                            "driver at 1 rpm)")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(run=cmd_gears)


def _shown(value: Fraction) -> str:
    """A speed as the table shows it: exact when it is short, else to 6 figures."""
    exact = str(value)
    return exact if len(exact) <= 12 else f"{float(value):.6g}"


def gears_text(result: TrainSpeeds) -> str:
    """What ``chaingraph gears`` prints."""
    train = result.train
    given = ", ".join(f"{x} at {_shown(w)} rpm" for x, w in result.given)
    plural = "" if result.freedom == 1 else "s"
    lines = [f"{train.name}: {result.fixed} fixed, {given}",
             f"kind: {result.kind}, {result.freedom} degree{plural} of freedom", ""]
    links = list(train.links)
    lines.append(table([[x, _shown(result.speeds[x]), f"{float(result.speeds[x]):.6g}"]
                        for x in links], ["link", "rpm", "rpm (decimal)"]))
    lines += ["", "ratios (row speed / column speed, over the links that turn)"]
    moving = [x for x in links if result.speeds[x] != 0]
    rows = [[a, *(_shown(result.speeds[a] / result.speeds[b]) for b in moving)]
            for a in links]
    lines.append(table(rows, ["", *moving]))
    lines += ["", "tabular method (carrier held, first gear +1 turn; times x; all turned "
                  "y with the carrier)"]
    for row in result.table:
        cells = [[x, _shown(r), _shown(row.y + row.x * r)] for x, r in row.ratios]
        lines.append(f"carrier {row.carrier}: x = {_shown(row.x)}, y = {_shown(row.y)}")
        lines.append(table(cells, ["gear", "+1 turn", "y + x r"]))
    turning = ", ".join(f"{a}-{b}" for a, b in train.turning)
    gears = ", ".join(f"{g.links[0]}-{g.links[1]} ({g.teeth[0]}:{g.teeth[1]}"
                      f"{', internal' if g.internal else ''}, carrier {g.carrier})"
                      for g in train.gears)
    lines += ["", f"turning pairs: {turning}", f"gear pairs: {gears}"]
    return "\n".join(lines)


def cmd_gears(args: argparse.Namespace) -> int:
    chain = load(args.file)
    speeds: dict[str, float] = {}
    for link, rpm in args.speeds or ():
        if link in speeds:
            raise MechanismError(f"'speeds' gives {link!r} twice", mechanism=chain.name,
                                 parameter="speeds")
        speeds[link] = rpm
    result = train_speeds(chain, fixed=args.fixed, speeds=speeds)
    if args.json:
        print_json({"name": chain.name, "fixed": result.fixed,
                    "speeds": {x: float(w) for x, w in result.speeds.items()},
                    "kind": result.kind, "graph": result.train.graph()})
        return 0
    print(gears_text(result))
    return 0
