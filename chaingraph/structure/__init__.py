"""Structure: classification, rigid sub-chains, isomorphism, chain generators and the
atlas of every chain of N links.

* :mod:`.classification` :func:`classify`: counts, mobility and the textbook's checks;
* :mod:`.rigidity` the rigid sub-chains and a sub-chain's mobility;
* :mod:`.isomorphism` canonical forms, isomorphisms and automorphism orbits (the
  function ``isomorphism`` itself is :func:`chaingraph.isomorphism`, so that its name
  here stays the module's);
* :mod:`.generators` random chains for the tests;
* :mod:`.atlas` every chain of N links and F degrees of freedom (loaded when first
  used: it loads pynauty).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from chaingraph._util.lazy import lazy_attribute
from chaingraph.structure.classification import (
    Check,
    Classification,
    classify,
    order_name,
    verdict_for,
)
from chaingraph.structure.generators import random_chain
from chaingraph.structure.isomorphism import (
    Canon,
    automorphism_generators,
    automorphism_orbits,
    canonical,
    canonical_form,
    is_isomorphic,
    pair_orbits,
)
from chaingraph.structure.rigidity import (
    RigidParts,
    one_rigid_subchain,
    rigid_parts,
    rigid_regions,
    rigid_subchains,
    subchain_mobility,
)

if TYPE_CHECKING:
    from chaingraph.structure import atlas

#: loaded when first used (the atlas loads pynauty): name -> (module, attribute)
_LAZY: dict[str, tuple[str, str | None]] = {"atlas": ("chaingraph.structure.atlas", None)}


def __getattr__(name: str) -> Any:
    return lazy_attribute(__name__, _LAZY, name)


__all__ = ["classify", "Classification", "Check", "order_name", "verdict_for",
           "rigid_subchains", "rigid_parts", "RigidParts", "one_rigid_subchain",
           "rigid_regions", "subchain_mobility", "canonical_form", "canonical", "Canon",
           "is_isomorphic", "automorphism_orbits", "automorphism_generators",
           "pair_orbits", "random_chain", "atlas"]
