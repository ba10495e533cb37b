"""``chaingraph lint PATH...``: chain files checked for what their authors may not know
(the command, kept apart from the others; registered in :mod:`chaingraph.cli.parser` by
:func:`lint_command`).

One line per finding, ``PATH: WHERE: KIND: message``; exit status 1 when there is a
finding, 0 for clean files, 2 when a file cannot be read (its error on one line, the
other files still checked).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable

from chaingraph.cli.text import error_text, print_json
from chaingraph.errors import ChainGraphError
from chaingraph.files import model_kind, model_text, read_model
from chaingraph.model.chainfile import Document, parse_file
from chaingraph.naming import finding_lines, lint

__all__ = ["cmd_lint", "lint_command"]


def lint_command(sub: argparse._SubParsersAction,
                 path_argument: Callable[[str], str]) -> None:
    """Register ``chaingraph lint`` with the subparsers ``sub``."""
    p = sub.add_parser("lint", help="check chain files for what their authors may not know",
                       description="Check each chain file for a locked chain or a rigid "
                                   "sub-chain, a degenerate structure, inputs that are not "
                                   "one per degree of freedom, a name that does not fit the "
                                   "structure, a drawn pose that does not close and a drawn "
                                   "pose the inputs cannot move or do not determine; a "
                                   "pylinkage or Pyslvs model is read as its import "
                                   "reads it. One line per finding; exit status 1 when "
                                   "there is one.")
    p.add_argument("files", nargs="+", type=path_argument, metavar="PATH",
                   help="chain files (TOML), or pylinkage (JSON) or Pyslvs (an "
                        "expression) models, told apart by their text")
    p.add_argument("--json", action="store_true",
                   help="print JSON: each file's findings (where, kind, message)")
    p.set_defaults(run=cmd_lint)


def _document(path: str) -> Document:
    """The chain file at ``path``, or the model of another tool there, read as one."""
    if not path.endswith(".toml") and model_kind(model_text(path)) is not None:
        return read_model(path).document
    return parse_file(path)


def cmd_lint(args: argparse.Namespace) -> int:
    status, report = 0, {}
    for path in args.files:
        try:
            findings = lint(_document(path))
        except ChainGraphError as e:
            print(f"chaingraph: error: {error_text(e)}", file=sys.stderr)
            status = 2
            continue
        if findings and status == 0:
            status = 1
        report[path] = [f.to_dict() for f in findings]
        if not args.json:
            for line in finding_lines(path, findings):
                print(line)
    if args.json:
        print_json(report)
    return status
