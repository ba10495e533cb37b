"""A chain file checked for what its author may not know: :func:`lint`.

Each :class:`Finding` says where (the chain, a link, a joint), what kind and what:

* ``locked``: the chain cannot move (Kutzbach's count 0 or less, or no freedom at the
  drawn pose for the mechanism's inputs), though the file does not say it is a
  structure;
* ``degenerate``: a rigid sub-chain inside a chain that moves (the links of a triangle
  that move as one), the chain in pieces, a link drawn with no size;
* ``mobility``: inputs that are not one per degree of freedom;
* ``name``: a name that does not fit the structure (a "Watt" that is a Stephenson, a
  "four-bar" of six links), by :func:`~chaingraph.naming.identify` and the links' count;
* ``pose``: a drawn pose that does not close: positions typed beyond drawing-level
  rounding from where the lengths put them;
* ``branch``: a drawn pose the inputs cannot take the mechanism out of, or at which they
  do not determine its motion (a dead centre: which branch follows is not theirs), or a
  drawn circuit on which the input only rocks while on another circuit of the same
  lengths (a dyad's other mode) it turns fully: a branch it cannot reach.

It takes the parsed file (:class:`~chaingraph.model.chainfile.Document`), so that a model
read from another program's format is checked as a chain file is.
"""

from __future__ import annotations

import itertools
import re
import warnings
from dataclasses import dataclass
from typing import Any

from chaingraph.errors import AssemblyError, ChainGraphError, DimensionError, MechanismError
from chaingraph.files import place, read_document
from chaingraph.kinematics import feasible_range, measured_document, pose_motion
from chaingraph.model.chain import Chain
from chaingraph.model.chainfile import Document
from chaingraph.naming.identification import identify
from chaingraph.structure import classify

__all__ = ["Finding", "lint", "finding_lines", "KINDS", "NAME_WORDS"]

#: the kinds of finding, in the order they are looked for
KINDS = ("pose", "degenerate", "locked", "mobility", "branch", "name")

#: words of a name (lower case, hyphens as spaces) and what the structure must then be:
#: a number of links, or words that the name identify finds must hold
NAME_WORDS: dict[str, int | str] = {
    "four bar": 4, "4 bar": 4, "fourbar": 4, "five bar": 5, "5 bar": 5, "six bar": 6,
    "6 bar": 6, "sixbar": 6, "eight bar": 8, "watt": "watt", "stephenson": "stephenson",
    "slider crank": "slider crank", "double slider": "double slider",
}

#: words by which a file says that it is a structure (a chain locked on purpose)
_STRUCTURE = re.compile(r"\b(locked|structure|truss|rigid|redundant)\b", re.IGNORECASE)

#: an input range narrower than this (degrees, or over the size for a slide) is none
_NO_RANGE = 1e-6


@dataclass(frozen=True)
class Finding:
    """One thing a file's author may not know: ``where`` (``"chain"``, ``"link 'x'"``,
    ``"joint 'B'"``), its ``kind`` (one of :data:`KINDS`) and the ``message``."""

    where: str
    kind: str
    message: str

    def to_dict(self) -> dict[str, Any]:
        """The finding as JSON's object."""
        return {"where": self.where, "kind": self.kind, "message": self.message}


def lint(document: Document | Chain) -> tuple[Finding, ...]:
    """What is wrong with a chain file that reads well: see the module's kinds.

    Parameters
    ----------
    document : Document or Chain
        A parsed chain file (:func:`chaingraph.model.chainfile.parse_file`), placed here;
        or a chain (as :func:`chaingraph.load` gives it, or built in Python).

    Returns
    -------
    tuple of Finding
        In the order of :data:`KINDS`; empty for a clean file.

    Examples
    --------
    >>> from chaingraph.model.chainfile import parse_file
    >>> from chaingraph.naming.catalog import catalog_path
    >>> lint(parse_file(catalog_path("watt-i-mechanism")))
    ()
    """
    chain, found = _placed(document if isinstance(document, Document) else Document(document))
    if chain is None:
        return tuple(found)
    c = classify(chain)
    if len(c.pieces) > 1:
        found.append(Finding("chain", "degenerate",
                             f"the chain is in {len(c.pieces)} pieces that share no joint: "
                             + "; ".join(", ".join(p) for p in c.pieces)))
    if c.degenerate and c.mobility > 0:
        for links in c.rigid_subchains:
            found.append(Finding("links " + ", ".join(repr(x) for x in links), "degenerate",
                                 "a rigid sub-chain: these links move as one body "
                                 f"although the chain has mobility {c.mobility}; the chain "
                                 "is in effect a smaller one"))
    said = " ".join(x for x in (chain.name, chain.family or "", chain.notes or ""))
    if c.mobility <= 0 and chain.mechanism is None and not _STRUCTURE.search(said):
        found.append(Finding("chain", "locked", f"Kutzbach's mobility is {c.mobility}: no "
                             "relative motion is possible (a structure), and the file does "
                             "not say so"))
    if chain.mechanism is not None and chain.has_pose and len(c.pieces) == 1:
        found += _motion(chain)
    found += _name(chain)
    return tuple(found)


def _placed(document: Document) -> tuple[Chain | None, list[Finding]]:
    """The file placed in its drawn pose, or None with the finding of why not (a pose
    that does not close, a link of no size)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")          # rounding mended: no finding
            chain, _ = place(document)
        return chain, []
    except DimensionError as e:
        joints = {j.id for j in document.chain.joints}
        where = e.where or (("joint" if e.part in joints else "link") + f" {e.part!r}"
                            if e.part else "chain")
        kind = "degenerate" if getattr(e, "link", None) else "pose"
        problem = (e.problem if kind == "degenerate" else
                   f"the drawn pose does not close: {e.problem}")
        return None, [Finding(where, kind, problem)]


def _motion(chain: Chain) -> list[Finding]:
    """The mechanism's inputs against its freedom at the drawn pose, and whether they
    can move it from there."""
    m = chain.mechanism
    assert m is not None
    where = (f"link {m.driver!r}" if m.driver and not m.inputs else
             "joint" + ("s " if len(m.inputs) > 1 else " ")
             + ", ".join(repr(i.joint) for i in m.inputs))
    try:
        state = pose_motion(chain)
    except MechanismError as e:
        if e.mobility is None:
            return []                      # not solvable for motion (a cam, gears): unchecked
        if e.mobility == 0:
            return [Finding(where, "locked", f"with {m.fixed!r} fixed the mechanism has no "
                            "freedom at the drawn pose: it cannot move")]
        return [Finding(where, "mobility", e.problem)]
    except AssemblyError as e:
        return [Finding(where, "branch", f"the inputs cannot be followed from the drawn "
                        f"pose: {e.problem}")]
    if not state.finite_rates:
        return [Finding(where, "branch", "at the drawn pose the inputs do not determine the "
                        "motion (a dead centre): which branch the mechanism takes from there "
                        "is not theirs to choose")]
    try:
        span = feasible_range(state.plan)
    except AssemblyError as e:
        return [Finding(where, "branch", f"the inputs cannot move the mechanism from the "
                        f"drawn pose: {e.problem}")]
    if span is not None and span[1] - span[0] < _NO_RANGE:
        return [Finding(where, "branch", f"the inputs cannot move the mechanism from the "
                        f"drawn pose: it assembles only at {span[0]:.6g}")]
    if span is not None and len(state.plan.inputs) == 1:
        other = _turning_circuit(chain)
        if other is not None:
            unit = state.plan.lead_unit
            return [Finding(where, "branch", f"on the drawn circuit the input only rocks, "
                            f"from {span[0]:.6g} to {span[1]:.6g} {unit}; assembled with "
                            f"{other} (the same lengths, another circuit) it turns fully: a "
                            "branch it cannot reach from the drawn pose")]
    return []


#: an assembly mode's word and its other
_OTHER_MODE = {"left": "right", "right": "left", "ahead": "behind", "behind": "ahead"}


def _turning_circuit(chain: Chain, *, most: int = 4) -> str | None:
    """Of the mechanism's other circuits (its dyads' modes flipped, up to ``most`` of
    them, at the drawn input value), the first on which the input turns fully, as the
    modes that give it ("C left"); None when there is none."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            doc = measured_document(chain)
    except ChainGraphError:
        return None
    modes = doc.get("assembly", {})
    dyads = sorted(k for k, v in modes.items() if isinstance(v, str) and v in _OTHER_MODE)
    if not dyads or len(dyads) > most:
        return None
    for flips in itertools.product((False, True), repeat=len(dyads)):
        if not any(flips):
            continue
        changed = {k: _OTHER_MODE[modes[k]] for k, flip in zip(dyads, flips) if flip}
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                other, _ = read_document({**doc, "assembly": {**modes, **changed}},
                                         source=chain.source or chain.name)
                if feasible_range(pose_motion(other).plan) is None:
                    return ", ".join(f"{k} {w}" for k, w in changed.items())
        except ChainGraphError:
            continue
    return None


def _words(text: str) -> str:
    return " ".join(re.sub(r"[-_']", " ", text.lower()).split())


def _name(chain: Chain) -> list[Finding]:
    """The words of the name against the structure: a count of links, or what identify
    names it."""
    name = _words(chain.name)
    claims = [(w, need) for w, need in NAME_WORDS.items() if re.search(rf"\b{w}", name)]
    if not claims:
        return []
    links = len(chain.links)
    try:
        found = identify(chain)
        known = _words(" ".join(x for x in (found.chain, found.inversion) if x))
    except ChainGraphError:
        found, known = None, ""
    out = []
    for word, need in claims:
        if isinstance(need, int) and links != need:
            out.append(Finding("chain", "name", f"the name says {word.replace(' ', '-')} "
                               f"({need} links), the chain has {links} links"))
        elif isinstance(need, str) and need not in known:
            said = (f"identify finds {found.chain!r}" if found is not None and found.chain
                    else f"identify finds its {links} links in no catalog chain")
            out.append(Finding("chain", "name", f"the name says {word.title()}, but "
                               f"{said}"))
    return out


def finding_lines(source: str, findings: tuple[Finding, ...]) -> list[str]:
    """One line per finding: ``SOURCE: WHERE: KIND: message``."""
    return [f"{source}: {f.where}: {f.kind}: {f.message}" for f in findings]

