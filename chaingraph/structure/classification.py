"""Structural classification of a chain: counts, mobility and the textbook checks.

The textbook's two checks for whether an assemblage of links and pairs is a kinematic
chain are Grübler's criterion in two forms:

* ``J + H/2 = 3L/2 - 2``, which holds for every planar chain with constrained motion;
* ``L = 2P - 4``, the same criterion rewritten for chains whose links are all binary
  (then the links' joint ends add up to 2L, so J = 2L - P). With a ternary or
  quaternary link present the identity fails, and the check is reported as not
  applicable, with the reason, rather than with a wrong verdict.

On each, LHS > RHS is a locked chain, LHS = RHS a kinematic chain, LHS < RHS an
unconstrained chain. The overall verdict comes from the Kutzbach mobility.

Kutzbach's count is taken pair by pair as ``3 (L - 1) - sum of (3 - f) (k - 1)`` over
the joints (f the pair's freedom, k its links; ``6`` for ``3`` in space). For lower
pairs and cam or gear pairs this is the textbook's ``3 (L - 1) - 2J - H``; a rolling
pair (pure rolling, f = 1) removes two freedoms, as a lower pair does, and is counted
so in the J check.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import networkx as nx

from chaingraph.model.chain import Chain
from chaingraph.structure.rigidity import rigid_parts

__all__ = ["Check", "Classification", "classify", "order_name", "verdict_for"]

_ORDER_NAMES = {1: "singular", 2: "binary", 3: "ternary", 4: "quaternary", 5: "quinary",
                6: "senary", 7: "septenary", 8: "octonary", 9: "nonary", 10: "denary"}


def order_name(k: int) -> str:
    """The textbook word for a link or joint of order k (``3`` gives ``"ternary"``)."""
    return _ORDER_NAMES.get(k, f"{k}-ary")


def verdict_for(lhs: Fraction | float, rhs: Fraction | float) -> str:
    """The textbook's verdict on a check: locked, kinematic or unconstrained chain."""
    if lhs > rhs:
        return "locked chain"
    if lhs == rhs:
        return "kinematic chain"
    return "unconstrained chain"


def _num(x: Fraction) -> int | float:
    return int(x) if x.denominator == 1 else float(x)


@dataclass(frozen=True)
class Check:
    """One textbook check: ``rule`` with its two sides and verdict."""

    rule: str
    lhs: int | float | None
    rhs: int | float | None
    applicable: bool
    verdict: str | None
    note: str

    def to_dict(self) -> dict[str, Any]:
        """The check as the contract's JSON object."""
        return {"rule": self.rule, "lhs": self.lhs, "rhs": self.rhs,
                "applicable": self.applicable, "verdict": self.verdict, "note": self.note}


@dataclass(frozen=True)
class Classification:
    """The structural facts of a chain; :meth:`to_dict` gives the contract's JSON."""

    name: str
    links: int
    pairs: int
    joint_equivalents: int
    higher_pairs: int
    joint_orders: dict[str, int]
    link_orders: dict[str, int]
    pair_kinds: dict[str, int]
    loops: int
    mobility: int
    checks: tuple[Check, ...]
    verdict: str
    degenerate: bool
    rigid_subchains: tuple[tuple[str, ...], ...]
    space: str = "planar"
    fractionated: bool = False
    separating_links: tuple[str, ...] = ()
    separating_joints: tuple[str, ...] = ()
    singular_links: tuple[str, ...] = ()
    pieces: tuple[tuple[str, ...], ...] = field(default=())
    rigid_subchains_complete: bool = True
    rigid_regions: tuple[tuple[str, ...], ...] = ()

    def __repr__(self) -> str:
        return (f"Classification({self.name!r}, links={self.links}, pairs={self.pairs}, "
                f"mobility={self.mobility}, verdict={self.verdict!r}, "
                f"degenerate={self.degenerate})")

    def rows(self) -> list[tuple[str, int | str, str | None]]:
        """The facts as (what, value, detail) rows in the textbook's words, as the
        command line, the report and a notebook show them.

        Examples
        --------
        >>> import chaingraph
        >>> from chaingraph.naming.catalog import catalog_path
        >>> rows = chaingraph.classify(chaingraph.load(catalog_path("four-bar-chain"))).rows()
        >>> rows[0], rows[-2]
        (('links L', 4, 'binary 4'), ('verdict', 'kinematic chain', ''))
        """
        def counts(d: dict[str, int]) -> str:
            return ", ".join(f"{k} {v}" for k, v in d.items() if v) or "none"

        def sides(check: Check) -> str:
            if not check.applicable or check.lhs is None or check.rhs is None:
                return "n/a"
            sign = "=" if check.lhs == check.rhs else (">" if check.lhs > check.rhs else "<")
            return f"{check.lhs} {sign} {check.rhs}"
        rows: list[tuple[str, int | str, str | None]] = [
            ("links L", self.links, counts(self.link_orders)),
            ("pairs P", self.pairs, counts(self.pair_kinds)),
            ("joint equivalents J", self.joint_equivalents,
             "joints: " + counts(self.joint_orders)),
            ("higher pairs H", self.higher_pairs, ""),
            ("loops", self.loops, "independent closed loops"),
            ("mobility F", self.mobility,
             "Kutzbach, " + ("3(L - 1) - 2J - H" if self.space == "planar"
                             else "6(L - 1) - sum(6 - f)")),
        ]
        rows += [(c.rule, sides(c),
                  c.verdict if c.applicable else f"not applicable: {c.note}")
                 for c in self.checks]
        rows.append(("verdict", self.verdict, ""))
        rows.append(("degenerate", "yes" if self.degenerate else "no",
                     "; ".join("{" + ", ".join(s) + "}" for s in self.rigid_subchains)))
        if self.rigid_regions:
            rows.append(("rigid regions", len(self.rigid_regions),
                         "; ".join("{" + ", ".join(s) + "}" for s in self.rigid_regions)))
        return rows

    def check(self, rule: str) -> Check:
        """The check whose rule is ``rule`` (``"L = 2P - 4"`` or ``"J + H/2 = 3L/2 - 2"``)."""
        return next(c for c in self.checks if c.rule == rule)

    @property
    def oddities(self) -> list[str]:
        """Sentences on what is odd about the chain (open, in pieces, fractionated...)."""
        odd = []
        if len(self.pieces) > 1:
            odd.append(f"the chain is in {len(self.pieces)} pieces that share no joint: "
                       + "; ".join(", ".join(p) for p in self.pieces))
        for link in self.singular_links:
            odd.append(f"open chain: link {link!r} has a single joint")
        if self.fractionated:
            parts = [f"link {x!r}" for x in self.separating_links]
            parts += [f"joint {x!r}" for x in self.separating_joints]
            odd.append("fractionated: removing " + " or ".join(parts)
                       + " separates the chain into closed parts")
        if self.degenerate:
            odd.append("degenerate: rigid sub-chain(s) "
                       + "; ".join("{" + ", ".join(s) + "}" for s in self.rigid_subchains))
        if not self.rigid_subchains_complete:
            odd.append(f"smallest rigid sub-chains: {len(self.rigid_subchains)} found, the "
                       "search stopped at its bound; more may exist")
        return odd

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``chaingraph classify --json``: the contract's keys first."""
        return {
            "name": self.name,
            "links": self.links,
            "pairs": self.pairs,
            "joint_equivalents": self.joint_equivalents,
            "higher_pairs": self.higher_pairs,
            "joint_orders": dict(self.joint_orders),
            "link_orders": dict(self.link_orders),
            "pair_kinds": dict(self.pair_kinds),
            "loops": self.loops,
            "mobility": self.mobility,
            "checks": [c.to_dict() for c in self.checks],
            "verdict": self.verdict,
            "degenerate": self.degenerate,
            "rigid_subchains": [list(s) for s in self.rigid_subchains],
            "rigid_subchains_complete": self.rigid_subchains_complete,
            "rigid_regions": [list(s) for s in self.rigid_regions],
            "space": self.space,
            "fractionated": self.fractionated,
            "separating_links": list(self.separating_links),
            "separating_joints": list(self.separating_joints),
            "singular_links": list(self.singular_links),
            "pieces": [list(p) for p in self.pieces],
        }


def _orders(counts: Counter[int], *, always: tuple[int, ...] = (2, 3, 4)) -> dict[str, int]:
    keys = sorted(set(always) | {k for k, n in counts.items() if n})
    return {order_name(k): counts.get(k, 0) for k in keys}


def _separators(chain: Chain) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Links and multiple joints whose removal leaves two or more closed parts.

    For each articulation point v of the link-joint graph, each piece of the graph
    without v is joined back to v; the piece is closed when it then holds a cycle
    (as many edges as nodes, or more).
    """
    g = chain.graph
    adj = {n: list(g[n]) for n in g}
    links: list[str] = []
    joints: list[str] = []
    for v in nx.articulation_points(g):
        seen = {v}
        closed_sides = 0
        for start in adj[v]:
            if start in seen:
                continue
            seen.add(start)
            stack, nodes, degree_sum, to_v = [start], 0, 0, 0
            while stack:
                n = stack.pop()
                nodes += 1
                degree_sum += len(adj[n])
                for m in adj[n]:
                    if m == v:
                        to_v += 1
                    elif m not in seen:
                        seen.add(m)
                        stack.append(m)
            edges = (degree_sum - to_v) // 2 + to_v
            if edges >= nodes + 1:
                closed_sides += 1
        if closed_sides >= 2:
            (links if v[0] == "link" else joints).append(v[1])
    order = {name: i for i, name in enumerate(chain.links)}
    return tuple(sorted(links, key=order.__getitem__)), tuple(sorted(joints))


def classify(chain: Chain) -> Classification:
    """Classify a chain: counts, orders, loops, mobility, checks, degeneracy.

    Parameters
    ----------
    chain : Chain

    Returns
    -------
    Classification
        The same facts as ``chaingraph classify --json``.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> c = chaingraph.classify(chaingraph.load(catalog_path("stephenson-six-bar-chain")))
    >>> c.links, c.pairs, c.joint_equivalents, c.mobility, c.verdict
    (6, 7, 7, 1, 'kinematic chain')
    >>> c.check("L = 2P - 4").applicable, c.check("J + H/2 = 3L/2 - 2").verdict
    (False, 'kinematic chain')
    """
    space = chain.space
    d = 3 if space == "planar" else 6
    n_links = len(chain.links)
    n_pairs = len(chain.joints)
    lower = [j for j in chain.joints if j.pair.lower]
    higher = [j for j in chain.joints if not j.pair.lower]
    J = sum(j.order - 1 for j in lower)
    H = len(higher)
    constraint = sum((d - chain.freedom(j)) * (j.order - 1) for j in chain.joints)
    mobility = d * (n_links - 1) - constraint
    g = chain.graph
    # cycle rank of the link-joint graph: edges - nodes + pieces
    loops = sum(j.order for j in chain.joints) - n_links - n_pairs + len(chain.pieces)
    link_degree = Counter(g.degree(("link", x)) for x in chain.links)
    joint_orders = _orders(Counter(j.order for j in chain.joints))
    link_orders = _orders(link_degree)
    if link_degree.get(1):
        link_orders = {"singular": link_degree[1], **{k: v for k, v in link_orders.items()
                                                     if k != "singular"}}
    pair_kinds = dict(Counter(j.kind for j in chain.joints))
    checks = (_two_p_check(chain, n_links, n_pairs, link_degree, H),
              _j_check(chain, n_links, J, H))
    rigid = rigid_parts(chain)
    separating_links, separating_joints = _separators(chain)
    return Classification(
        name=chain.name, links=n_links, pairs=n_pairs, joint_equivalents=J, higher_pairs=H,
        joint_orders=joint_orders, link_orders=link_orders, pair_kinds=pair_kinds,
        loops=loops, mobility=mobility, checks=checks,
        verdict=verdict_for(Fraction(1), Fraction(mobility)),
        degenerate=rigid.degenerate, rigid_subchains=rigid.smallest, space=space,
        fractionated=bool(separating_links or separating_joints),
        separating_links=separating_links, separating_joints=separating_joints,
        singular_links=tuple(x for x in chain.links if g.degree(("link", x)) == 1),
        pieces=chain.pieces, rigid_subchains_complete=rigid.complete,
        rigid_regions=rigid.regions)


def _two_p_check(chain: Chain, n_links: int, n_pairs: int, link_degree: Counter[int],
                 H: int) -> Check:
    rule = "L = 2P - 4"
    lhs, rhs = n_links, 2 * n_pairs - 4
    if chain.space != "planar":
        return Check(rule, lhs, rhs, False, None,
                     "a check for planar chains; this chain is spatial")
    if H:
        return Check(rule, lhs, rhs, False, None,
                     f"counts lower pairs only; this chain has {H} higher pair(s): "
                     "use J + H/2 = 3L/2 - 2")
    others = {k: n for k, n in sorted(link_degree.items()) if k != 2 and n}
    if others:
        listed = ", ".join(f"{n} {order_name(k)}" for k, n in others.items())
        return Check(rule, lhs, rhs, False, None,
                     "applies only when every link is binary (then J = 2L - P); "
                     f"this chain has {listed} link(s)")
    return Check(rule, lhs, rhs, True, verdict_for(lhs, rhs),
                 "every link is binary, so J = 2L - P and Grübler's criterion "
                 "J = 3L/2 - 2 reads L = 2P - 4")


def _j_check(chain: Chain, n_links: int, J: int, H: int) -> Check:
    rule = "J + H/2 = 3L/2 - 2"
    if chain.space != "planar":
        return Check(rule, None, None, False, None,
                     "a check for planar chains; this chain is spatial (see mobility)")
    # each pair counts (3 - f)/2 binary equivalents: 1 for a lower or rolling pair,
    # 1/2 for a cam or gear pair
    lhs = sum((Fraction(3 - chain.freedom(j), 2) * (j.order - 1) for j in chain.joints),
              Fraction(0))
    rhs = Fraction(3 * n_links, 2) - 2
    rolling = sum(1 for j in chain.joints if j.kind == "rolling")
    note = "Grübler's criterion for constrained motion, from F = 3(L - 1) - 2J - H = 1"
    if rolling:
        note += (f"; {rolling} rolling pair(s) counted in J (pure rolling leaves one "
                 "freedom, as a lower pair does)")
    return Check(rule, _num(lhs), _num(rhs), True, verdict_for(lhs, rhs), note)
