"""The command line: the only place that speaks of flags and exit statuses.

* :mod:`.main` :func:`main`, the console script ``chaingraph`` (exit statuses, Ctrl-C);
* :mod:`.parser` the commands' arguments; :mod:`.commands` each command's work;
* :mod:`.text` and :mod:`.outputs` what the commands print and write.
"""

from chaingraph.cli.main import main
from chaingraph.cli.parser import build_parser

__all__ = ["main", "build_parser"]
