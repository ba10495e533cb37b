"""chaingraph's own chain files (TOML) in and out: read (:mod:`chaingraph.model.chainfile` parses and checks), then
placed (a file given by lengths assembled into its drawn pose, a file of coordinates
with its drawing-level rounding mended: :func:`place`); written
back by :func:`dumps` and :func:`save`.
"""

from __future__ import annotations

import os
from dataclasses import replace
from typing import Any

from chaingraph.kinematics.assembly import Assembly, assemble
from chaingraph.model.chain import Chain, Joint, Point
from chaingraph.model.chainfile import (
    Document,
    dumps,
    parse_document,
    parse_file,
    parse_text,
    save,
)
from chaingraph.model.snap import check_link_sizes, snap_to_lines

__all__ = ["load", "loads", "from_document", "dumps", "save", "read_file", "read_text",
           "read_document", "place"]


def load(path: str | os.PathLike[str]) -> Chain:
    """Read a chain file.

    Parameters
    ----------
    path : str or os.PathLike
        A TOML chain file in the public format.

    Returns
    -------
    Chain
        The chain, with its pose, points and mechanism when the file has them.

    Raises
    ------
    ChainFileError
        When the file cannot be read or is not a valid chain; the message names the
        file, the joint or key, and what is wrong (a :class:`DimensionError` for lengths
        that give no pose).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> chain = chaingraph.load(catalog_path("four-bar-chain"))
    >>> chain.name, len(chain.links), len(chain.joints)
    ('Four-bar chain', 4, 4)
    """
    return read_file(path)[0]


def loads(text: str, *, source: str = "<string>") -> Chain:
    """Read a chain from TOML text; see :func:`load`.

    Examples
    --------
    >>> loads('name = "x"\\n[[joints]]\\nid = "A"\\nkind = "Q"\\nlinks = ["a", "b"]')
    Traceback (most recent call last):
    ...
    chaingraph.errors.ChainFileError: <string>: joint 'A': unknown kind 'Q' (expected one of R, P, screw, cylindrical, spherical, planar, rolling, cam, gear)
    """
    return read_text(text, source=source)[0]


def from_document(doc: dict[str, Any], *, source: str = "<document>") -> Chain:
    """A chain from an already parsed document (a dict of the file's keys)."""
    return read_document(doc, source=source)[0]


def read_file(path: str | os.PathLike[str]) -> tuple[Chain, Assembly | None]:
    """``(chain, assembly)`` of a chain file: ``assembly`` is the
    :class:`~chaingraph.kinematics.assembly.Assembly` found for a mechanism given by its lengths
    (its modes, its groups), else None."""
    return place(parse_file(path))


def read_text(text: str, *, source: str = "<string>") -> tuple[Chain, Assembly | None]:
    """``(chain, assembly)`` of TOML text; see :func:`read_file`."""
    return place(parse_text(text, source=source))


def read_document(doc: dict[str, Any], *,
                  source: str = "<document>") -> tuple[Chain, Assembly | None]:
    """``(chain, assembly)`` of a parsed document; see :func:`read_file`."""
    return place(parse_document(doc, source=source))


def place(document: Document) -> tuple[Chain, Assembly | None]:
    """A read chain file in its drawn pose: ``(chain, assembly)``. A file given by
    lengths is assembled (``assembly`` is its :class:`~chaingraph.kinematics.assembly.Assembly`: modes and groups); a
    file of coordinates has its drawing-level rounding mended (:func:`snap_to_lines`,
    ``assembly`` None)."""
    if document.dimensions is None:
        check_link_sizes(document.chain)
        return snap_to_lines(document.chain), None
    structure, dims = document.chain, document.dimensions
    point_links = [(p.id, p.link) for p in document.points]
    pose = assemble(structure, point_links, dims)
    placed = tuple(Joint(j.id, j.kind, j.links, at=pose.joints[j.id],
                         axis=pose.axes.get(j.id), closure=j.closure, friction=j.friction)
                   for j in document.joints)
    placed_points = tuple(Point(p.id, p.link, pose.points[p.id]) for p in document.points)
    mechanism = structure.mechanism
    if mechanism is not None and mechanism.inputs:
        # a P input's values are measured from its guide's origin, as its 'at' is
        kinds = {j.id: j.kind for j in document.joints}
        single = dims.values.get(None) if len(mechanism.inputs) == 1 else None
        mechanism = replace(mechanism, inputs=tuple(
            replace(item, at=dims.values.get(item.joint, single))
            if kinds.get(item.joint) == "P" else item for item in mechanism.inputs))
    return replace(structure, joints=placed, points=placed_points, mechanism=mechanism), pose
