"""The ``chaingraph`` command line.

Exit status: 0 on success, 2 on bad input (the message names the file, joint or key),
1 when the analysis fails (for example a mechanism that cannot be assembled), 130 on
Ctrl-C and 143 on SIGTERM (what a CI timeout or a service manager sends), after the
same clean-up. Errors are printed as one line on stderr, without a traceback.
"""

from __future__ import annotations

import signal
import sys
import threading
import warnings
from collections.abc import Callable, Sequence
from types import FrameType
from typing import TextIO

from chaingraph.cli.parser import build_parser
from chaingraph.cli.text import error_text, exit_status
from chaingraph.errors import ChainGraphError, ChainGraphWarning

__all__ = ["main"]


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread as Ctrl-C is, so that every clean-up that
    Ctrl-C runs (workers stopped, temporary files removed) runs for it too."""


def _terminate(signum: int, frame: FrameType | None) -> None:
    raise Terminated()


def _on_sigterm() -> Callable[[], object]:
    """Turn SIGTERM into :class:`Terminated` while a command runs; returns a function
    that puts the previous handler back (a no-op where signals cannot be set: not the
    main thread)."""
    if threading.current_thread() is not threading.main_thread():
        return lambda: None
    previous = signal.signal(signal.SIGTERM, _terminate)
    return lambda: signal.signal(signal.SIGTERM,
                                 signal.SIG_DFL if previous is None else previous)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    shown = warnings.showwarning

    def show(message: Warning | str, category: type[Warning], filename: str, lineno: int,
             file: TextIO | None = None, line: str | None = None) -> None:
        if issubclass(category, ChainGraphWarning):
            print(f"chaingraph: warning: {message}", file=sys.stderr)
        else:
            shown(message, category, filename, lineno, file, line)

    warnings.showwarning = show
    restore = _on_sigterm()
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
    except Terminated:
        print("chaingraph: terminated (SIGTERM)", file=sys.stderr)
        return 143
    except KeyboardInterrupt:
        print("chaingraph: interrupted", file=sys.stderr)
        return 130
    except OSError as e:             # a write that failed midway: a full disk, a lost mount
        where = f"{e.filename}: " if e.filename else ""
        print(f"chaingraph: error: {where}{e.strerror or e}", file=sys.stderr)
        return 2
    finally:
        warnings.showwarning = shown
        restore()
