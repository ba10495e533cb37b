"""The bundled catalog: the textbook's named chains and mechanisms as TOML files.

The catalog is data, loaded and validated by :func:`chaingraph.load` like any user's
file. An installed wheel carries it as ``chaingraph/bundled/``; a source checkout
(editable install) has it in the top-level ``catalog/`` folder.
"""

from __future__ import annotations

from pathlib import Path

from chaingraph.files import load

__all__ = ["catalog_dir", "catalog_files", "catalog_path", "load_catalog"]


def catalog_dir() -> Path:
    """The folder of the bundled catalog files."""
    here = Path(__file__).resolve().parent.parent      # the chaingraph package
    for candidate in (here / "bundled", here.parent / "catalog"):
        if candidate.is_dir() and any(candidate.glob("*.toml")):
            return candidate
    raise FileNotFoundError("the chaingraph catalog is not installed with this package")


def catalog_files() -> list[Path]:
    """Every catalog file, sorted by file name."""
    return sorted(catalog_dir().glob("*.toml"))


def catalog_path(stem: str) -> Path:
    """The catalog file called ``stem`` (file name without ``.toml``).

    Examples
    --------
    >>> catalog_path("four-bar-chain").name
    'four-bar-chain.toml'
    """
    path = catalog_dir() / f"{stem}.toml"
    if not path.is_file():
        raise KeyError(f"no catalog entry {stem!r}")
    return path


def load_catalog() -> list:
    """Every catalog entry as a :class:`~chaingraph.model.chain.Chain`, in file name order."""
    return [load(path) for path in catalog_files()]


_BUNDLED = None


def bundled_catalog() -> tuple:
    """The bundled catalog's names, loaded once per process (chains are immutable): every
    entry but a synthesised mechanism's (a file with a ``[task]``, such as
    ``log10-function-generator``), which is an example of a design, not a kind of
    mechanism, and names nothing (identify, inversions and the atlas would otherwise
    call every triple rocker driven by its crank after it)."""
    global _BUNDLED
    if _BUNDLED is None:
        _BUNDLED = tuple(c for c in load_catalog() if not c.task)
    return _BUNDLED
