"""``chaingraph import PATH --from pylinkage|pyslvs``: another tool's model as a chain file;
and the writers ``chaingraph export --to pylinkage|pyslvs`` uses (:func:`peer_writers`)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable

from chaingraph.cli.outputs import output_file, write_text
from chaingraph.files import pylinkage_json, pyslvs_expression, read_model
from chaingraph.model.chain import Chain

__all__ = ["import_command", "cmd_import", "peer_writers", "input_pair", "PEERS"]

#: the tools whose models come in and go out
PEERS = ("pylinkage", "pyslvs")


def peer_writers() -> dict[str, Callable[[Chain], str]]:
    """``{format: writer}`` for ``export --to``: each writer takes a drawn mechanism and
    gives the file's text (pylinkage's JSON, a Pyslvs expression), or raises
    :class:`~chaingraph.errors.InterchangeError` with the reason it cannot."""
    return {"pylinkage": pylinkage_json, "pyslvs": pyslvs_expression}


def import_command(sub: argparse._SubParsersAction,
                   path_argument: Callable[[str], str]) -> None:
    """The arguments of ``chaingraph import`` (``path_argument``: how a PATH is read)."""
    p = sub.add_parser("import", help="a pylinkage or Pyslvs model as a chain file",
                       description="Read a mechanism that pylinkage (its JSON "
                                   "serialisation, mechanism_to_json) or Pyslvs (its "
                                   "mechanism expression, M[J[...], ...]) wrote, and write "
                                   "it as a chain file: positions, links, drivers and "
                                   "tracer points. What cannot be carried over is named on "
                                   "standard error, one line each.")
    p.add_argument("file", type=path_argument, metavar="PATH", help="the model's file")
    p.add_argument("--from", dest="peer", required=True, choices=PEERS,
                   help="the tool that wrote it")
    p.add_argument("-o", "--out", type=path_argument, metavar="FILE",
                   help="write the chain file here (default: print it)")
    p.add_argument("--driver", metavar="LINK",
                   help="pyslvs: the input link (an expression holds none; default the "
                        "link on the first ground pivot)")
    p.add_argument("--input", dest="inputs", action="append", type=input_pair,
                   metavar="BASE:DRIVE", help="pyslvs: an input pair as Pyslvs gives it "
                   "(joint numbers: the link of BASE and DRIVE turns about BASE); repeat "
                   "it for each input")
    p.add_argument("--name", help="pyslvs: the chain's name (an expression has none)")
    p.set_defaults(run=cmd_import)


def input_pair(text: str) -> tuple[int, int]:
    """``BASE:DRIVE``, two joint numbers of a Pyslvs expression."""
    base, colon, drive = text.partition(":")
    if not (colon and base.strip().isdigit() and drive.strip().isdigit()):
        raise argparse.ArgumentTypeError(f"expected BASE:DRIVE, two joint numbers, got "
                                         f"{text!r}")
    return int(base), int(drive)


def cmd_import(args: argparse.Namespace) -> int:
    if args.peer == "pylinkage" and (args.driver or args.inputs or args.name):
        print("chaingraph import: error: --driver, --input and --name are for --from "
              "pyslvs (a pylinkage model names its drivers and itself)", file=sys.stderr)
        return 2
    if args.out:
        output_file(args.out, what="chain file")
    model = read_model(args.file, args.peer, driver=args.driver, inputs=args.inputs,
                       name=args.name)
    model.chain                          # placed: a pose that cannot be is an error here
    for note in model.notes:
        print(f"chaingraph import: note: {note}", file=sys.stderr)
    if args.out:
        write_text(args.out, model.toml())
    else:
        sys.stdout.write(model.toml())
    return 0
