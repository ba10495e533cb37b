"""Names for the atlas of epicyclic gear trains: the trains of chain files (the catalog's,
or any folder's) found among the atlas's entries by the key of their rotation graph."""

from __future__ import annotations

import os
from collections.abc import Hashable, Iterable
from pathlib import Path

from chaingraph.errors import ChainGraphError
from chaingraph.files import load
from chaingraph.naming.catalog import catalog_dir
from chaingraph.structure.atlas.gears import (
    GearAtlas,
    chain_graph,
    rotation_key,
    train_verdict,
)

__all__ = ["gear_train_names"]


def _named_trains(folders: Iterable[str | os.PathLike[str]], links: int,
                  ) -> dict[Hashable, list[str]]:
    """The rotation key of every admissible gear train of ``links`` links in the chain
    files of ``folders`` -> the names of the files' trains."""
    out: dict[Hashable, list[str]] = {}
    for folder in folders:
        for path in sorted(Path(folder).glob("*.toml")):
            if "[[gears]]" not in path.read_text(encoding="utf-8"):
                continue
            try:
                chain = load(path)
            except ChainGraphError:
                continue
            names, turning, gears = chain_graph(chain)
            if len(names) != links or train_verdict(links, turning, gears) is not None:
                continue
            out.setdefault(rotation_key(links, gears), []).append(chain.name)
    return out


def gear_train_names(atlas: GearAtlas, *,
                     folders: Iterable[str | os.PathLike[str]] | None = None,
                     ) -> list[list[str]]:
    """The names of each entry of ``atlas``: those of the gear trains of the chain files
    in ``folders`` (by default the catalog) that are that entry (one rotation graph).

    Examples
    --------
    >>> from chaingraph.structure.atlas.gears import gear_atlas
    >>> names = gear_train_names(gear_atlas(4, 1), folders=[])
    >>> names
    [[], []]
    """
    if folders is None:
        try:
            folders = [catalog_dir()]
        except FileNotFoundError:
            folders = []
    named = _named_trains(folders, atlas.links)
    return [named.get(rotation_key(atlas.links, e.gears), []) for e in atlas]
