"""The model: chains, joints, pairs, inputs and mechanisms; the chain file (parse,
check, write: it solves nothing); the dimensions of a file given by lengths; the numbers
a file accepts.

* :mod:`.chain` :class:`Chain` (links and joints, a link-joint graph), :class:`Joint`,
  :class:`Point`, :class:`Mechanism` with its :class:`Input` values, masses and loads;
* :mod:`.chainfile` the chain file's :class:`Document`: parsed and checked, written back
  (:func:`toml_text`, :func:`dumps`, :func:`save`);
* :mod:`.dimensions` a file given by lengths (:class:`Dimensions`);
* :mod:`.gears` gear pairs (``[[gears]]``: two links in mesh, their teeth, the carrier);
* :mod:`.pairs` the kinds of pair (R, P) and what each allows;
* :mod:`.snap` a drawing's rounding mended onto its lines, the size of a chain;
* :mod:`.values` the numbers a file accepts.
"""

from chaingraph.model.chain import (
    Chain,
    Input,
    Joint,
    LinkMass,
    Load,
    Mechanism,
    Point,
    chosen_inputs,
    joint_node,
    line_direction,
    link_node,
    mass_centre,
)
from chaingraph.model.chainfile import (
    Document,
    chain_document,
    dumps,
    parse_document,
    parse_file,
    parse_text,
    save,
    toml_text,
)
from chaingraph.model.dimensions import (
    MODE_WORDS,
    Dimensions,
    LineSpec,
    link_features,
    link_shape,
    parse_dimensions,
)
from chaingraph.model.gears import GearPair
from chaingraph.model.pairs import PAIR_KINDS, PairKind, pair_kind
from chaingraph.model.snap import check_link_sizes, feature_label, size_of, snap_to_lines
from chaingraph.model.values import LARGEST, number

__all__ = ["Chain", "Joint", "Point", "Input", "Mechanism", "LinkMass", "Load",
           "chosen_inputs", "line_direction", "mass_centre", "link_node", "joint_node",
           "GearPair", "Document", "parse_file", "parse_text", "parse_document", "chain_document",
           "toml_text", "dumps", "save", "Dimensions", "LineSpec", "parse_dimensions",
           "link_features", "link_shape", "MODE_WORDS", "PairKind", "PAIR_KINDS",
           "pair_kind", "snap_to_lines", "check_link_sizes", "size_of", "feature_label",
           "LARGEST", "number"]
