"""Another tool's model read from its file, whichever tool wrote it."""

from __future__ import annotations

import os
from collections.abc import Sequence

from chaingraph.errors import InterchangeError
from chaingraph.files.imported import Imported, model_kind, model_text
from chaingraph.files.pylinkage import read_pylinkage
from chaingraph.files.pyslvs import read_pyslvs

__all__ = ["read_model"]


def read_model(path: str | os.PathLike[str], peer: str | None = None, *,
               driver: str | None = None, inputs: Sequence[tuple[int, int]] | None = None,
               name: str | None = None) -> Imported:
    """The model in the file at ``path``, written by ``peer`` (``"pylinkage"``: its
    JSON; ``"pyslvs"``: a mechanism expression), or by whichever of them its text says
    (:func:`~chaingraph.files.imported.model_kind`) when ``peer`` is None. ``driver``,
    ``inputs`` and ``name`` are :func:`~chaingraph.files.pyslvs.read_pyslvs`'s (a
    pylinkage model names its drivers and itself).

    Raises
    ------
    ChainFileError
        The file cannot be read; InterchangeError, the text is neither tool's model, or
        malformed (its reader's message).
    """
    source = os.fspath(path)
    text = model_text(source)
    peer = peer or model_kind(text)
    if peer == "pylinkage":
        return read_pylinkage(text, source=source)
    if peer == "pyslvs":
        return read_pyslvs(text, source=source, driver=driver, inputs=inputs, name=name)
    raise InterchangeError("neither a pylinkage model (a JSON object) nor a Pyslvs "
                           "expression (M[...])", source=source)
