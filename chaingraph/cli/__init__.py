"""The command line: the only place that speaks of flags and exit statuses."""

from chaingraph.cli.main import main

__all__ = ["main"]
