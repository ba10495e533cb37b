"""A model brought in from another tool: its chain file and what did not come over."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from chaingraph.errors import ChainFileError
from chaingraph.model.chain import Chain
from chaingraph.model.chainfile import Document, file_bytes, parse_document, toml_text
from chaingraph.files.native import place

__all__ = ["Imported", "imported", "model_text", "model_kind"]


@dataclass(frozen=True)
class Imported:
    """A model of another tool read as a chain file.

    Attributes
    ----------
    document : Document
        The chain file, parsed and checked as a TOML file is
        (:class:`~chaingraph.model.chainfile.Document`).
    notes : tuple of str
        What could not be carried over, one line each (a feature of the other tool
        without an equivalent here, a choice the model did not make).
    keys : dict
        The chain file's document (the dict :func:`~chaingraph.model.chainfile.toml_text`
        writes).
    """

    document: Document
    notes: tuple[str, ...]
    keys: dict[str, Any] = field(repr=False)

    @cached_property
    def chain(self) -> Chain:
        """The chain in its drawn pose, as :func:`chaingraph.load` gives a file."""
        return place(self.document)[0]

    def toml(self) -> str:
        """The chain file's text."""
        return toml_text(self.keys)


def imported(keys: dict[str, Any], notes: list[str], *, source: str) -> Imported:
    """An :class:`Imported` of a chain file's document, checked as a file is."""
    return Imported(parse_document(keys, source=source), tuple(notes), keys)


def model_text(path: str | os.PathLike[str]) -> str:
    """The text of another tool's model file (UTF-8), or ChainFileError naming it."""
    source = os.fspath(path)
    raw = file_bytes(source, what="model file")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ChainFileError(f"is not UTF-8 text (byte {e.start})", source=source) from None


def model_kind(text: str) -> str | None:
    """Which tool's model ``text`` is: ``"pylinkage"`` (a JSON object), ``"pyslvs"`` (a
    mechanism expression, ``M[...]``), or None (not another tool's: a chain file).

    >>> model_kind('{"name": "four-bar", "joints": []}'), model_kind("M[J[R, P[0, 0]]]")
    ('pylinkage', 'pyslvs')
    >>> model_kind('name = "four-bar"') is None
    True
    """
    head = text.lstrip()
    if head.startswith("{"):
        return "pylinkage"
    if head.startswith("M["):
        return "pyslvs"
    return None
