"""The catalog's names of the atlas's chains and of their inversion classes.

A chain of the atlas is named where the catalog has a chain of its structure (its link
graph and joint kinds; with ``oriented``, also which link carries each guide), and each
of its inversion classes (an orbit of its links) where the catalog has a mechanism of
that structure whose fixed link falls in the class: the four-link chains come out as
the four-bar chain, the single slider crank chain and the double slider crank chain,
with the textbook's inversions on their fixed links.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from chaingraph.model.chain import Chain, Input, Mechanism
from chaingraph.model.snap import size_of
from chaingraph.naming.catalog import bundled_catalog
from chaingraph.structure.isomorphism import (
    automorphism_orbits,
    canonical,
    canonical_form,
    isomorphism,
)

__all__ = ["atlas_names", "chain_names", "named_mechanisms", "NamedMechanism"]


def _key(chain):
    """What two chains of one structure share, cheaply: links, joints, P joints."""
    return (len(chain.links), len(chain.joints), sum(j.kind == "P" for j in chain.joints))


@lru_cache(maxsize=4)
def _catalog_forms(oriented, catalog=None):
    """The catalog's chains and mechanisms by (key, canonical form)."""
    out: dict[Any, Any] = {}
    for entry in catalog if catalog is not None else bundled_catalog():
        if entry.space != "planar":
            continue
        try:
            form = canonical_form(entry, oriented=oriented)
        except Exception:                 # a chain the labelling does not take
            continue
        out.setdefault((_key(entry), form), []).append(entry)
    return out


def atlas_names(chain: Chain, *, oriented: bool = False,
                catalog: Iterable[Chain] | None = None) -> dict[str, list[Any]]:
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
    out: dict[str, list[Any]] = {"chain": [], "inversions": []}
    key = _key(chain)
    if not any(k == key for k, _ in forms):
        return out
    entries = forms.get((key, canonical_form(chain, oriented=oriented)), [])
    if not entries:
        return out
    classes = automorphism_orbits(chain, oriented=oriented)
    where = {link: i for i, c in enumerate(classes) for link in c}
    named: dict[Any, Any] = {}
    for entry in entries:
        if entry.mechanism is None:
            if entry.name not in out["chain"]:
                out["chain"].append(entry.name)
            continue
        mapping = isomorphism(chain, entry, oriented=oriented)
        assert mapping is not None               # the entry has the chain's canonical form
        back = {theirs: mine for mine, theirs in mapping.items()}
        fixed = back.get(entry.mechanism.fixed)
        if fixed in where:
            names = named.setdefault(where[fixed], [])
            if entry.name not in names:
                names.append(entry.name)
    out["inversions"] = [{"links": list(classes[i]), "names": named[i]} for i in sorted(named)]
    return out


def chain_names(chain: Chain, *, oriented: bool = False,
                catalog: Iterable[Chain] | None = None) -> list[str]:
    """The catalog's names of a chain's structure (see :func:`atlas_names`)."""
    return atlas_names(chain, oriented=oriented, catalog=catalog)["chain"]


@dataclass(frozen=True)
class NamedMechanism:
    """A catalog mechanism of an atlas chain's structure, in the atlas chain's names.

    ``links`` is the inversion class (an orbit of links) its fixed link falls in,
    ``name`` and ``source`` the catalog entry's name and file name, ``mechanism`` the
    atlas chain with the entry's proportions (its drawn pose scaled by ``scale``, a
    power of two, to about 100 units, so that what lies on a line stays exactly on it),
    the entry's fixed link and its input."""

    links: tuple[str, ...]
    name: str
    source: str
    scale: float
    mechanism: Chain


def named_mechanisms(chain: Chain, *, oriented: bool = False,
                     catalog: Iterable[Chain] | None = None) -> list[NamedMechanism]:
    """Every catalog mechanism of ``chain``'s structure (see :func:`atlas_names`) as a
    :class:`NamedMechanism`: the atlas chain's links and joints, posed and driven as the
    catalog's mechanism is, so that it moves as its name says. In the order of the
    inversion classes, then of the catalog; entries without a drawn pose are left out.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas
    >>> slider = next(atlas(links=4, prismatic=1))
    >>> engine = next(m for m in named_mechanisms(slider) if m.source == "reciprocating-engine")
    >>> engine.scale, engine.mechanism.mechanism.fixed in engine.links
    (0.5, True)
    """
    forms = _catalog_forms(oriented, tuple(catalog) if catalog is not None else None)
    key = _key(chain)
    if not any(k == key for k, _ in forms):
        return []
    entries = forms.get((key, canonical_form(chain, oriented=oriented)), [])
    classes = automorphism_orbits(chain, oriented=oriented)
    where = {link: i for i, c in enumerate(classes) for link in c}
    out = []
    for entry in entries:
        if entry.mechanism is None or not entry.has_pose:
            continue
        mine, theirs = canonical(chain, oriented=oriented), canonical(entry, oriented=oriented)
        back = {y[1]: x[1] for x, y in zip(mine.order, theirs.order) if x[0] == y[0]}
        posed = _posed_as(chain, entry, back)
        if posed is not None and posed[1].mechanism.fixed in where:
            scale, mechanism = posed
            out.append(NamedMechanism(classes[where[mechanism.mechanism.fixed]], entry.name,
                                      Path(entry.source or entry.name).stem, scale,
                                      mechanism))
    order = {c: i for i, c in enumerate(classes)}
    return sorted(out, key=lambda m: order[m.links])


def _posed_as(chain, entry, back):
    """(scale, the atlas chain posed, fixed and driven as the catalog ``entry``), its
    links and joints named through ``back`` (the entry's names to the chain's), or None
    when the entry's input is none of the chain's joints."""
    theirs = {back[j.id]: j for j in entry.joints}
    size = size_of({j.id: j.at for j in entry.joints})
    scale = 2.0 ** round(math.log2(100.0 / size))
    joints = tuple(replace(j, at=(theirs[j.id].at[0] * scale, theirs[j.id].at[1] * scale),
                           axis=theirs[j.id].axis) for j in chain.joints)
    m = entry.mechanism
    fixed = back[m.fixed]
    if m.inputs:
        inputs = []
        for item in m.inputs:
            joint = back.get(item.joint)
            if joint is None:
                return None
            along = scale if theirs[joint].kind == "P" else 1.0
            inputs.append(Input(joint, *(None if v is None else v * along
                                         for v in (item.start, item.stop, item.at))))
    else:
        driver = back[m.driver]
        pivot = [j.id for j in joints if set(j.links) == {fixed, driver}]
        if not pivot:
            return None
        inputs = [Input(pivot[0])]
    output = back.get(m.output) if m.output else None
    name = f"{chain.name}: {entry.name}"
    return scale, Chain(name, joints, family=chain.family, units=entry.units or "mm",
                        notes=chain.notes, mechanism=Mechanism(fixed, inputs=tuple(inputs),
                                                               output=output))
