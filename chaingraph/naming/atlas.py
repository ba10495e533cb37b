"""The catalog's names of the atlas's chains and of their inversion classes.

A chain of the atlas is named where the catalog has a chain of its structure (its link
graph and joint kinds; with ``oriented``, also which link carries each guide), and each
of its inversion classes (an orbit of its links) where the catalog has a mechanism of
that structure whose fixed link falls in the class: the four-link chains come out as
the four-bar chain, the single slider crank chain and the double slider crank chain,
with the textbook's inversions on their fixed links.
"""

from __future__ import annotations

from functools import lru_cache

from chaingraph.naming.catalog import bundled_catalog
from chaingraph.structure.isomorphism import (
    automorphism_orbits,
    canonical_form,
    isomorphism,
)

__all__ = ["atlas_names", "chain_names"]


def _key(chain):
    """What two chains of one structure share, cheaply: links, joints, P joints."""
    return (len(chain.links), len(chain.joints), sum(j.kind == "P" for j in chain.joints))


@lru_cache(maxsize=4)
def _catalog_forms(oriented, catalog=None):
    """The catalog's chains and mechanisms by (key, canonical form)."""
    out = {}
    for entry in catalog if catalog is not None else bundled_catalog():
        if entry.space != "planar":
            continue
        try:
            form = canonical_form(entry, oriented=oriented)
        except Exception:                 # a chain the labelling does not take
            continue
        out.setdefault((_key(entry), form), []).append(entry)
    return out


def atlas_names(chain, *, oriented=False, catalog=None) -> dict:
    """The catalog's names of ``chain`` (an atlas chain) and of its inversion classes:
    ``{"chain": [names], "inversions": [{"links": [...], "names": [...]}]}``, an item for
    each inversion class (an orbit of links, as
    :func:`~chaingraph.structure.isomorphism.automorphism_orbits` gives them) where the
    catalog has a mechanism of the chain's structure fixed on a link of the class.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas
    >>> slider = next(atlas(links=4, prismatic=1))
    >>> names = atlas_names(slider)
    >>> names["chain"]
    ['Single slider crank chain']
    >>> sorted(n for c in names["inversions"] for n in c["names"])[:3]
    ['Crank and slotted lever quick return mechanism', 'Duplex pump', 'Oscillating cylinder engine']
    >>> atlas_names(next(atlas(links=8, prismatic=0)))
    {'chain': [], 'inversions': []}
    """
    forms = _catalog_forms(oriented, tuple(catalog) if catalog is not None else None)
    out = {"chain": [], "inversions": []}
    key = _key(chain)
    if not any(k == key for k, _ in forms):
        return out
    entries = forms.get((key, canonical_form(chain, oriented=oriented)), [])
    if not entries:
        return out
    classes = automorphism_orbits(chain, oriented=oriented)
    where = {link: i for i, c in enumerate(classes) for link in c}
    named = {}
    for entry in entries:
        if entry.mechanism is None:
            if entry.name not in out["chain"]:
                out["chain"].append(entry.name)
            continue
        mapping = isomorphism(chain, entry, oriented=oriented)
        back = {theirs: mine for mine, theirs in mapping.items()}
        fixed = back.get(entry.mechanism.fixed)
        if fixed in where:
            names = named.setdefault(where[fixed], [])
            if entry.name not in names:
                names.append(entry.name)
    out["inversions"] = [{"links": list(classes[i]), "names": named[i]} for i in sorted(named)]
    return out


def chain_names(chain, *, oriented=False, catalog=None) -> list:
    """The catalog's names of a chain's structure (see :func:`atlas_names`)."""
    return atlas_names(chain, oriented=oriented, catalog=catalog)["chain"]
