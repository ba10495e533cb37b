"""``chaingraph export FILE --to FORMAT -o PATH``: the mechanism written for another
program (the command, kept apart from the others; its arguments are registered in
:mod:`chaingraph.cli.parser` by :func:`export_command`).

Each format is a writer in :data:`WRITERS`: a function of the parsed arguments and the
chain that returns the file's text; a new format is one more entry (a writer of the
chain alone through :func:`chain_writers`). ``--to``'s choices are the entries when the
parser is built.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable

from chaingraph.cli.interchange import peer_writers
from chaingraph.cli.outputs import output_file, write_text
from chaingraph.drawing import link_outlines, outlines_dxf, outlines_svg
from chaingraph.files import load
from chaingraph.model.chain import Chain

__all__ = ["cmd_export", "export_command", "WRITERS", "chain_writers"]


def _outlines(args: argparse.Namespace, chain: Chain):
    at = args.at
    return link_outlines(chain, at=None if not at else at[0] if len(at) == 1 else at,
                         width=args.width, hole=args.hole)


def _dxf(args: argparse.Namespace, chain: Chain) -> str:
    return outlines_dxf(_outlines(args, chain))


def _svg(args: argparse.Namespace, chain: Chain) -> str:
    return outlines_svg(_outlines(args, chain))


#: the formats of ``--to``: each a writer of the file's text from the arguments and chain
WRITERS: dict[str, Callable[[argparse.Namespace, Chain], str]] = {
    "dxf": _dxf,
    "svg": _svg,
}


def chain_writers(writers: dict[str, Callable[[Chain], str]]
                  ) -> dict[str, Callable[[argparse.Namespace, Chain], str]]:
    """Writers of the chain alone (a format with no pose or sizes to choose) as
    :data:`WRITERS` takes them: ``WRITERS.update(chain_writers({...}))``."""
    def taking_arguments(write: Callable[[Chain], str]
                         ) -> Callable[[argparse.Namespace, Chain], str]:
        return lambda args, chain: write(chain)
    return {name: taking_arguments(write) for name, write in writers.items()}


#: the models of other programs (pylinkage's JSON, a Pyslvs expression): the mechanism as
#: drawn, which those programs sweep from
MODELS = peer_writers()
WRITERS.update(chain_writers(MODELS))


def export_command(sub: argparse._SubParsersAction,
                   path_argument: Callable[[str], str],
                   positive_number: Callable[[str], float]) -> None:
    """Register ``chaingraph export`` with the subparsers ``sub`` (``path_argument`` and
    ``positive_number`` the parser's types of a path and a number above 0)."""
    p = sub.add_parser("export", help="the mechanism for another program: outlines to cut "
                                      "(DXF, SVG), a pylinkage or Pyslvs model",
                       description="Write the mechanism for another program: with --to dxf "
                                   "or svg, each link's outline at one pose, true size in "
                                   "the file's units, to cut it (a bar with rounded ends for "
                                   "a binary link, a plate round its joints for a ternary or "
                                   "quaternary link, a block and a slotted guide for a "
                                   "sliding pair, holes at the pins; in DXF a layer per "
                                   "link named after it); with --to pylinkage or pyslvs, "
                                   "the mechanism as drawn as pylinkage's JSON "
                                   "serialisation or a Pyslvs mechanism expression.")
    p.add_argument("file", type=path_argument, metavar="FILE", help="a chain file (TOML)")
    p.add_argument("--to", dest="to", required=True, choices=sorted(WRITERS),
                   help="the format")
    p.add_argument("-o", "--output", dest="out", required=True, type=path_argument,
                   metavar="PATH", help="the file to write")
    p.add_argument("--at", action="append", type=float, metavar="X",
                   help="the input value of the pose (degrees, or slide for a P input; "
                        "default: the drawn pose); with several inputs the first's value, "
                        "or repeat it, one per input")
    p.add_argument("--hole", type=positive_number, metavar="D",
                   help="the pins' holes' diameter (default half the width)")
    p.add_argument("--width", type=positive_number, metavar="W",
                   help="the bars' width (default a twentieth of the mechanism's size)")
    p.set_defaults(run=cmd_export)


def cmd_export(args: argparse.Namespace) -> int:
    chain = load(args.file)
    if args.to in MODELS and args.at:
        print(f"chaingraph: error: --at: a {args.to} model is the mechanism as drawn (its "
              "program sweeps from there); a pose is for dxf and svg", file=sys.stderr)
        return 2
    output_file(args.out, what=args.to.upper())
    write = WRITERS[args.to]
    try:
        text = write(args, chain)
    except ImportError as e:              # an optional extra not installed (ezdxf)
        print(f"chaingraph: error: {e}", file=sys.stderr)
        return 2
    write_text(args.out, text)
    return 0
