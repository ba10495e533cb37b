"""The ``chaingraph`` command line.

Exit status: 0 on success, 2 on bad input (the message names the file, joint or key),
1 when the analysis fails (for example a mechanism that cannot be assembled). Errors
are printed as one line on stderr, without a traceback.
"""

from __future__ import annotations

import sys
import warnings

from chaingraph.cli.parser import build_parser
from chaingraph.cli.text import error_text, exit_status
from chaingraph.errors import ChainGraphError, ChainGraphWarning

__all__ = ["main"]


def main(argv=None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    shown = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, ChainGraphWarning):
            print(f"chaingraph: warning: {message}", file=sys.stderr)
        else:
            shown(message, category, filename, lineno, file, line)

    warnings.showwarning = show
    try:
        return args.run(args)
    except ChainGraphError as e:
        print(f"chaingraph: error: {error_text(e)}", file=sys.stderr)
        return exit_status(e)
    except BrokenPipeError:
        return 0
    except MemoryError:
        print("chaingraph: error: out of memory: the analysis needs more memory than this "
              "machine (or its limit) gives; try a smaller size or fewer steps",
              file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("chaingraph: interrupted", file=sys.stderr)
        return 130
    except OSError as e:             # a write that failed midway: a full disk, a lost mount
        where = f"{e.filename}: " if e.filename else ""
        print(f"chaingraph: error: {where}{e.strerror or e}", file=sys.stderr)
        return 2
    finally:
        warnings.showwarning = shown
