"""Chain files in and out: read (:mod:`chaingraph.model.chainfile` parses and checks), then
placed (a file given by lengths assembled into its drawn pose, a file of coordinates
with its drawing-level rounding mended: :func:`chaingraph.kinematics.assembly.place`); written
back by :func:`dumps` and :func:`save`.
"""

from __future__ import annotations

from chaingraph.kinematics.assembly import place
from chaingraph.model.chain import Chain
from chaingraph.model.chainfile import dumps, parse_document, parse_file, parse_text, save

__all__ = ["load", "loads", "from_document", "dumps", "save", "read_file", "read_text",
           "read_document"]


def load(path) -> Chain:
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


def from_document(doc, *, source: str = "<document>") -> Chain:
    """A chain from an already parsed document (a dict of the file's keys)."""
    return read_document(doc, source=source)[0]


def read_file(path):
    """``(chain, assembly)`` of a chain file: ``assembly`` is the
    :class:`~chaingraph.kinematics.assembly.Assembly` found for a mechanism given by its lengths
    (its modes, its groups), else None."""
    return place(parse_file(path))


def read_text(text: str, *, source: str = "<string>"):
    """``(chain, assembly)`` of TOML text; see :func:`read_file`."""
    return place(parse_text(text, source=source))


def read_document(doc, *, source: str = "<document>"):
    """``(chain, assembly)`` of a parsed document; see :func:`read_file`."""
    return place(parse_document(doc, source=source))
