"""Identify a chain or mechanism in the catalog.

The chain is found by its canonical form (P orientation respected, then forgotten);
the inversion, for a mechanism file, through :func:`chaingraph.inversions.catalog_matches`:
its fixed link, its behaviour where both have dimensions, and its driver and output
where both name them; among catalog inversions equal in all of that, the one of the
nearest proportions (link lengths over the largest) is taken.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .inversions import catalog_matches, require_connected
from .isomorphism import canonical_form, isomorphism

__all__ = ["Identification", "identify"]


@dataclass(frozen=True)
class Identification:
    """What :func:`identify` found; ``chain`` and ``inversion`` are None when not found."""

    chain: str | None
    inversion: str | None
    mapping: dict = field(default_factory=dict)
    chain_file: str | None = None
    inversion_file: str | None = None

    def to_dict(self):
        return {"chain": self.chain, "inversion": self.inversion, "mapping": dict(self.mapping)}


def _lengths(chain):
    """Each link's sorted joint-to-joint distances, over the chain's largest one."""
    out = {}
    for link in chain.links:
        pts = [j.at for j in chain.joints_of(link) if j.at is not None]
        out[link] = sorted(math.dist(a, b) for i, a in enumerate(pts) for b in pts[i + 1:])
    top = max((v for d in out.values() for v in d), default=0.0) or 1.0
    return {k: [v / top for v in d] for k, d in out.items()}


def _proportion_distance(chain, entry, mapping):
    """How far the chain's proportions are from the entry's, links matched by mapping."""
    if not (chain.has_pose and entry.has_pose):
        return math.inf
    mine, theirs = _lengths(chain), _lengths(entry)
    total = 0.0
    for link, other in mapping.items():
        a, b = mine[link], theirs[other]
        if len(a) != len(b):
            return math.inf
        total += sum(abs(x - y) for x, y in zip(a, b))
    return total


def identify(chain, *, catalog=None) -> Identification:
    """Which catalog chain ``chain`` is and, for a mechanism, which catalog inversion.

    Parameters
    ----------
    chain : Chain
    catalog : sequence of Chain, optional
        The bundled catalog by default.

    Returns
    -------
    Identification
        ``mapping`` maps the file's links onto the catalog chain's links. A chain the
        catalog does not have gives ``chain=None`` (not an error).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.catalog import catalog_path
    >>> found = identify(chaingraph.load(catalog_path("scotch-yoke")))
    >>> found.chain, found.inversion
    ('Double slider crank chain', 'Scotch yoke')
    """
    require_connected(chain)
    if catalog is None:
        from .catalog import bundled_catalog
        catalog = bundled_catalog()
    chain_name = chain_file = None
    mapping = {}
    for oriented in (True, False):
        form = canonical_form(chain, oriented=oriented)
        entry = next((e for e in catalog if e.mechanism is None
                      and len(e.links) == len(chain.links)
                      and canonical_form(e, oriented=oriented) == form), None)
        if entry is not None:
            chain_name, chain_file = entry.name, entry.source
            mapping = isomorphism(chain, entry, oriented=oriented)
            break
    inversion = inversion_file = None
    m = chain.mechanism
    if m is not None:
        matches = catalog_matches(chain, m.fixed, catalog, driver=m.driver, output=m.output)
        if matches:
            top = max(score for score, _, _ in matches)
            tied = [(s_, e, mp) for s_, e, mp in matches if s_ == top]
            # among equals, the entry of the nearest proportions (the file itself, when
            # the file is a catalog entry)
            _, entry, entry_mapping = min(
                tied, key=lambda t: _proportion_distance(chain, t[1], t[2]))
            inversion, inversion_file = entry.name, entry.source
            if chain_name is None:
                chain_name, mapping = entry.family, entry_mapping
    return Identification(chain=chain_name, inversion=inversion, mapping=mapping,
                          chain_file=chain_file, inversion_file=inversion_file)
