"""``chaingraph gears FILE``: the speeds of a gear train's links, its kind and graph."""

from __future__ import annotations

import argparse
import html
import json
import math
import time
from collections.abc import Callable
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

from chaingraph._util import freedom
from chaingraph._util.parallel import process_runner
from chaingraph._util.atomic import withdraw, write_atomic
from chaingraph.cli.outputs import Writing, output_folder, svg_file
from chaingraph.cli.text import print_json, table
from chaingraph.drawing.gears import schematic_svg, train_graph_svg, train_svg
from chaingraph.errors import ChainGraphError, MechanismError
from chaingraph.model.chain import Chain
from chaingraph.files import dumps, load
from chaingraph.kinematics.gears import TrainSpeeds, train_speeds
from chaingraph.naming.gear_trains import gear_train_names
from chaingraph.structure.atlas import DaskRunner
from chaingraph.structure.atlas.gear_chains import gear_chain
from chaingraph.structure.atlas.entry import chain_file_name
from chaingraph.structure.atlas.output import FIGURES_UP_TO
from chaingraph.structure.atlas.gears import (
    GearAtlas,
    GearEntry,
    check_gear_size,
    gear_atlas,
    gear_atlas_dict,
)

__all__ = ["gears_command", "cmd_gears", "speed_argument", "cmd_gear_atlas"]

#: the flags of ``atlas`` that mean nothing for gear trains
_NOT_FOR_GEARS = (("prismatic", "--prismatic"), ("oriented", "--oriented"),
                  ("multiple", "--multiple"), ("resume", "--resume"), ("illustrate", "--illustrate"))


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
    p.add_argument("--draw", type=path_argument, metavar="PATH.svg",
                   help="draw the train (pitch circles about the axes, carriers as arms, "
                        "the fixed link hatched) and its graph, as SVG")
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
    if args.draw:
        svg_file(args.draw, what="gear train")
    chain = load(args.file)
    speeds: dict[str, float] = {}
    for link, rpm in args.speeds or ():
        if link in speeds:
            raise MechanismError(f"'speeds' gives {link!r} twice", mechanism=chain.name,
                                 parameter="speeds")
        speeds[link] = rpm
    result = train_speeds(chain, fixed=args.fixed, speeds=speeds)
    if args.draw:
        with Writing(args.draw):
            write_atomic(args.draw, train_svg(chain, fixed=result.fixed))
    if args.json:
        print_json({"name": chain.name, "fixed": result.fixed,
                    "speeds": {x: float(w) for x, w in result.speeds.items()},
                    "kind": result.kind, "graph": result.train.graph()})
        return 0
    print(gears_text(result))
    return 0


#: pixels per millimetre of the schematics, and per unit of the graphs, on the index
_SCHEMATIC_SCALE, _GRAPH_SCALE = 1.5, 58.0


def _inline(svg: str) -> str:
    return svg.split("\n", 1)[1]                        # inline: no XML declaration


def _gear_index(atlas: GearAtlas, shown: list[GearEntry], chains: list[Chain],
                named: dict[int, list[str]], files: bool) -> str:
    """The HTML page of ``atlas --gears --out``: each train's functional schematic
    (drawn from its chain file) and its graph, all at one scale, with its gear pairs,
    its names in the catalog and a link to its chain file."""
    cells = []
    for i, (e, chain) in enumerate(zip(shown[:FIGURES_UP_TO], chains), start=1):
        schematic = schematic_svg(chain, unit=1.0, scale=_SCHEMATIC_SCALE)
        graph = train_graph_svg([str(x + 1) for x in range(atlas.links)], e.turning,
                                e.gears, title=f"train {i}: graph", scale=_GRAPH_SCALE)
        link = (f' <a href="chains/{chain_file_name(i, len(shown))}">chain file</a>'
                if files else "")
        names = "".join(f"<br><b>{html.escape(x)}</b>" for x in named[e.id])
        m = chain.mechanism
        held = f"; {m.fixed} fixed, {m.driver} driving" if m is not None else ""
        cells.append(f'<figure id="train-{i}"><div class="pics">{_inline(schematic)}'
                     f'{_inline(graph)}</div><figcaption><b>{i}</b>: gears '
                     f'{html.escape(e.key)}; {e.inversions} inversions, {e.arrangements} '
                     f'arrangements{"; fractionated" if e.fractionated else ""}'
                     f"{html.escape(held)}{link}{names}</figcaption></figure>")
    title = (f"{len(shown)} epicyclic gear trains of {atlas.links} links and "
             f"{freedom(atlas.dof)}")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
            f"{html.escape(title)}</title><style>"
            "body{font-family:Georgia,serif;margin:2em;color:#1b1b1b}"
            "h1{font-family:Arial,sans-serif;color:#1f4e79}"
            ".grid{display:flex;flex-wrap:wrap;gap:10px;align-items:flex-start}"
            "figure{margin:0;border:1px solid #ddd;padding:4px}"
            ".pics{display:flex;align-items:center;gap:6px}"
            "figcaption{font-size:12px;max-width:420px}</style></head><body>"
            f"<h1>{html.escape(title)}</h1><p>Each train twice, at one scale for all. Left, "
            "its functional schematic, drawn from its chain file: the axes are the "
            "dash-dotted lines, each link a shaft along the axes it turns about (coaxial "
            "links drawn a little apart), each gear a bar of its pitch diameter (its "
            "teeth above it) in its pair's column, so gears in mesh touch; a carrier "
            "is an arm joining its axes, the fixed link's bearings are hatched, circles "
            "are pins. Right, its graph: vertices are links (L1, L2, ... in the chain "
            "file), thin edges turning pairs, each with the letter of its axis (the "
            "chain file's joint of that letter), thick arcs gear pairs, each with the "
            "number of its carrier (the transfer vertex). Gears a-b/c: a and b mesh, "
            "c carries them.</p>"
            + ("" if len(cells) == len(shown) else
               f"<p>The first {len(cells):,} trains are drawn below; every train is in "
               "atlas.json and has its chain file.</p>")
            + "<div class=\"grid\">" + "".join(cells)
            + "</div></body></html>\n")


def _write_chains(out: Path, chains: list[Chain]) -> list[Path]:
    """One chain file per train shown, numbered as listed, under ``out/chains``."""
    folder = out / "chains"
    folder.mkdir(exist_ok=True)
    paths = []
    for i, chain in enumerate(chains, start=1):
        path = folder / chain_file_name(i, len(chains))
        write_atomic(path, dumps(chain))
        paths.append(path)
    return paths


def cmd_gear_atlas(args: argparse.Namespace, *, workers: int = 1) -> int:
    """``chaingraph atlas --gears``: the epicyclic gear trains of N links, searched one
    tree of turning pairs per task on ``workers`` local processes or on the Dask
    cluster of ``args.scheduler``."""
    for name, flag in _NOT_FOR_GEARS:
        if getattr(args, name, None):
            raise ChainGraphError(f"--gears enumerates gear trains (turning and gear "
                                  f"pairs): leave out {flag}")
    if args.out:
        output_folder(args.out, what="atlas")
    start = time.perf_counter()
    check_gear_size(args.links, args.dof)
    if args.scheduler is not None:
        with DaskRunner(args.scheduler, workers=workers) as runner:
            atlas = gear_atlas(args.links, args.dof, runner=runner)
    else:
        atlas = gear_atlas(args.links, args.dof, runner=process_runner(workers))
    elapsed = time.perf_counter() - start
    record = gear_atlas_dict(atlas, no_fractionated=args.no_fractionated)
    named = dict(zip((e.id for e in atlas), gear_train_names(atlas)))
    shown = [e for e in atlas if not (args.no_fractionated and e.fractionated)]
    for train, e in zip(record["trains"], shown):
        train["names"] = named[e.id]
    if args.out:
        out = Path(args.out)
        with Writing(out):
            withdraw(out)
            write_atomic(out / "atlas.json",
                         json.dumps(record, indent=2, ensure_ascii=False) + "\n")
            chains = [gear_chain(replace(e, id=i), args.dof)
                      for i, e in enumerate(shown, start=1)]
            files = _write_chains(out, chains) if args.chain_files is not False else []
            write_atomic(out / "index.html", _gear_index(atlas, shown, chains, named,
                                                         bool(files)))
    if args.json or args.summary:
        if args.summary:
            record.pop("trains")
        print_json(record)
        return 0
    which = "non-fractionated " if args.no_fractionated else ""
    print(f"{len(shown)} {which}epicyclic gear trains of {args.links} links and "
          f"{freedom(args.dof)} ({atlas.count_non_fractionated} non-fractionated), "
          f"{record['arrangements']} arrangements of turning pairs, "
          f"{record['distinct_inversions']} distinct inversions ({elapsed:.2f} s)")
    if len(shown) <= 60:
        rows = [[i, e.key, " ".join(f"{a + 1}-{b + 1}" for a, b in e.turning),
                 e.arrangements, e.inversions, "yes" if e.fractionated else "no"]
                for i, e in enumerate(shown, start=1)]
        print(table(rows, ["id", "gear pairs (a-b/carrier)", "turning pairs (simplest)",
                           "arrangements", "inversions", "fractionated"]))
    if args.out:
        also = f", {len(files)} chain files in {out / 'chains'}" if files else ""
        print(f"written: {out / 'atlas.json'}, {out / 'index.html'}{also}")
    return 0

