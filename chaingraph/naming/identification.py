"""Identify a chain or mechanism in the catalog.

The chain is found by structure alone, whatever the dimensions and with or without a
mechanism: by its canonical form with P orientation respected, then forgotten, then
with every joint taken as a turning pair (a sliding pair is a turning pair at infinity).
The inversion, for a mechanism file, through :func:`chaingraph.naming.inversion_classes.catalog_matches`:
its fixed link always; a name of behaviour (a beam engine is a crank-rocker) also needs
the behaviour where both have dimensions; among the names that apply, the one whose
driver and output correspond, then of the nearest proportions (link lengths over the
largest), is taken. The mapping is the isomorphism behind the name given.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from chaingraph.kinematics.behaviour import behaviour
from chaingraph.model.chain import Chain, Joint
from chaingraph.naming.catalog import bundled_catalog, catalog_dir
from chaingraph.naming.inversion_classes import (
    Match,
    catalog_matches,
    naming_matches,
    require_connected,
)
from chaingraph.structure.isomorphism import canonical_form, isomorphism

__all__ = ["Identification", "identify"]


@dataclass(frozen=True)
class Identification:
    """What :func:`identify` found; ``chain`` and ``inversion`` are None when not found."""

    chain: str | None
    inversion: str | None
    mapping: dict[str, str] = field(default_factory=dict)
    chain_file: str | None = None
    inversion_file: str | None = None
    orientation: str = "respected"     # or "ignored": P orientation had to be forgotten
    joint_kinds: str = "respected"     # or "ignored": found with every joint as an R joint
    note: str | None = None            # e.g. why no inversion is named

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``chaingraph identify --json``."""
        return {"chain": self.chain, "inversion": self.inversion, "mapping": dict(self.mapping),
                "orientation": self.orientation, "joint_kinds": self.joint_kinds,
                "note": self.note}


def _lengths(chain: Chain) -> dict[str, list[float]]:
    """Each link's sorted joint-to-joint distances, over the chain's largest one."""
    out: dict[str, list[float]] = {}
    for link in chain.links:
        pts = [j.at for j in chain.joints_of(link) if j.at is not None]
        out[link] = sorted(math.dist(a, b) for i, a in enumerate(pts) for b in pts[i + 1:])
    top = max((v for d in out.values() for v in d), default=0.0) or 1.0
    return {k: [v / top for v in d] for k, d in out.items()}


def _proportion_distance(chain: Chain, entry: Chain, mapping: Mapping[str, str]) -> float:
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


def identify(chain: Chain, *, catalog: Sequence[Chain] | None = None) -> Identification:
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
    >>> from chaingraph.naming.catalog import catalog_path
    >>> found = identify(chaingraph.load(catalog_path("scotch-yoke")))
    >>> found.chain, found.inversion
    ('Double slider crank chain', 'Scotch yoke')
    """
    require_connected(chain)
    if catalog is None:
        catalog = bundled_catalog()
    chain_name = chain_file = None
    mapping: dict[str, str] | None = {}
    orientation, kinds = "respected", "respected"
    chains = [e for e in catalog if e.mechanism is None]
    for level in ("oriented", "unoriented", "kinds"):
        mine = _as_turning_pairs(chain) if level == "kinds" else chain
        oriented = level == "oriented"
        form = canonical_form(mine, oriented=oriented)
        for entry in chains:
            theirs = _as_turning_pairs(entry) if level == "kinds" else entry
            if len(entry.links) == len(chain.links) and \
                    canonical_form(theirs, oriented=oriented) == form:
                chain_name, chain_file = entry.name, _shown(entry.source)
                mapping = isomorphism(mine, theirs, oriented=oriented)
                orientation = "respected" if oriented else "ignored"
                kinds = "ignored" if level == "kinds" else "respected"
                break
        if chain_name is not None:
            break
    inversion = inversion_file = note = None
    m = chain.mechanism
    if m is not None:
        matches = catalog_matches(chain, m.fixed, catalog, driver=m.driver, output=m.output)
        naming = naming_matches(matches)
        if naming:
            # the behaviour's own name first, then the corresponding driver and output,
            # then the nearest proportions (the file itself, when it is a catalog entry)
            # a worked example's name only for the example itself: a general name first
            def rank(x: Match) -> tuple[bool, bool, float, float]:
                distance = _proportion_distance(chain, x.entry, x.mapping)
                return (x.alike is not True, x.entry.naming == "example" and distance > 1e-9,
                        -x.score, distance)
            best = min(naming, key=rank)
            inversion, inversion_file = best.entry.name, _shown(best.entry.source)
            mapping = best.mapping
            orientation = "respected" if best.oriented else "ignored"
        elif matches:
            nearest = [x for x in matches if x.oriented] or matches
            names = ", ".join(dict.fromkeys(x.entry.name for x in nearest))
            how = behaviour(chain, m.fixed) or "another way"
            note = (f"by structure this is the catalog's {names}, but as dimensioned it "
                    f"behaves otherwise ({how}), and those names need the catalog's behaviour")
        else:
            note = "the catalog names no inversion of this structure with this link fixed"
    if chain_name is None:
        note = "; ".join(x for x in ("the catalog has no chain of this structure", note) if x)
    return Identification(chain=chain_name, inversion=inversion, mapping=mapping or {},
                          chain_file=chain_file, inversion_file=inversion_file,
                          orientation=orientation, joint_kinds=kinds, note=note)


def _shown(source: str | None) -> str | None:
    """A catalog file as ``catalog/NAME.toml`` (where it is installed is no concern of
    the reader's); any other file as it was given."""
    if source is None:
        return None
    path = Path(source)
    try:
        if path.resolve().parent == catalog_dir().resolve():
            return f"catalog/{path.name}"
    except OSError:
        pass
    return str(source)


def _as_turning_pairs(chain: Chain) -> Chain:
    """The chain's structure with every joint an R joint (no pose): a sliding pair is a
    turning pair whose centre is at infinity."""
    return Chain(chain.name, tuple(Joint(j.id, "R", j.links) for j in chain.joints))
