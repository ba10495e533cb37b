"""One chain of the atlas (its link graph in canonical labels) and its encodings: graph6
lines, the JSON lines of a shard, the link orders."""

from __future__ import annotations

import json
from dataclasses import dataclass
import numpy as np
import numpy.typing as npt

from chaingraph.model.chain import Chain, Joint
from chaingraph.structure.classification import order_name

__all__ = ["AtlasEntry", "graph6_line", "graph6_lines", "encode_chains", "order_counts", "chain_file_name"]


@dataclass(frozen=True)
class AtlasEntry:
    """One chain of the atlas: its link graph in canonical labels."""

    id: int
    edges: tuple[tuple[int, int], ...]
    links: int
    inversion_classes: int
    fractionated: bool = False

    @property
    def link_orders(self) -> dict[str, int]:
        """How many links of each order (``{"binary": 4, ...}``)."""
        return order_counts(self.edges, self.links)

    def chain(self, dof: int | None = None) -> Chain:
        """The chain as a :class:`~chaingraph.model.chain.Chain` (links L1..LN, joints J1..)."""
        joints = tuple(Joint(f"J{i + 1}", "R", (f"L{a + 1}", f"L{b + 1}"))
                       for i, (a, b) in enumerate(self.edges))
        name = f"chain {self.id} of {self.links} links" + (f", {dof} dof" if dof else "")
        return Chain(name, joints, family="atlas")


def graph6_line(n: int, edges: npt.ArrayLike) -> bytes:
    """One graph6 line (with its newline) of a graph on ``n <= 62`` nodes.

    Examples
    --------
    >>> graph6_line(4, [(0, 1), (1, 2), (2, 3), (0, 3)])
    b'Cl\\n'
    """
    return graph6_lines(n, np.asarray(edges, dtype=np.int64).reshape(1, -1, 2))


def graph6_lines(n: int, edges: npt.ArrayLike) -> bytes:
    """The graph6 lines of many graphs on ``n <= 62`` nodes at once: ``edges`` is an
    array (m, J, 2); one line per graph, in order."""
    edges = np.asarray(edges, dtype=np.int64)
    m = len(edges)
    pairs = n * (n - 1) // 2
    size = -(-pairs // 6) * 6
    bits = np.zeros((m, max(size, 1)), dtype=np.uint8)
    if m and edges.shape[1]:
        low, high = edges.min(axis=2), edges.max(axis=2)
        bits[np.arange(m)[:, None], high * (high - 1) // 2 + low] = 1   # column-wise
    values = bits[:, :size].reshape(m, size // 6, 6) @ (1 << np.arange(5, -1, -1))
    line = np.empty((m, values.shape[1] + 2), dtype=np.uint8)
    line[:, 0] = n + 63
    line[:, 1:-1] = values + 63
    line[:, -1] = ord("\n")
    return line.tobytes()


def encode_chains(links: int, edges: npt.NDArray[np.integer], orbits: npt.NDArray[np.integer],
                  fractionated: npt.NDArray[np.bool_], *, block: int = 8192,
                  ) -> tuple[bytes, str]:
    """A shard's chains as graph6 lines (bytes) and JSON lines (str), the JSON line of a
    chain being its record in atlas.json without the id. Encoded in blocks of rows, so
    that the working arrays stay small however many chains a shard holds."""
    g6: list[bytes] = []
    lines: list[str] = []
    for s in range(0, len(orbits), block):
        part = edges[s:s + block]
        orders = orders_rows(part, links)
        for e, o, x, key in zip(part.tolist(), orbits[s:s + block].tolist(),
                                fractionated[s:s + block].tolist(), orders):
            lines.append(f'{{"edges": {json.dumps(e)}, "link_orders": {key}, '
                         f'"inversion_classes": {o}, '
                         f'"fractionated": {"true" if x else "false"}}}\n')
        g6.append(graph6_lines(links, part))
    return b"".join(g6), "".join(lines)


def orders_rows(edges: npt.NDArray[np.integer], links: int) -> list[str]:
    """The link_orders JSON text of each chain (chains of one assortment share it)."""
    if not len(edges):
        return []
    degree = np.zeros((len(edges), links), dtype=np.int64)
    rows = np.repeat(np.arange(len(edges)), edges.shape[1] * 2)
    np.add.at(degree, (rows, np.asarray(edges, dtype=np.int64).reshape(len(edges), -1).ravel()), 1)
    degree.sort(axis=1)
    cache: dict[bytes, str] = {}
    out: list[str] = []
    for row in map(bytes, degree.astype(np.uint8)):
        if row not in cache:
            cache[row] = json.dumps(_orders_of_degrees(list(row)))
        out.append(cache[row])
    return out


def order_counts(edges: npt.ArrayLike, links: int) -> dict[str, int]:
    """How many links of each order the chain of link graph ``edges`` has."""
    degree = np.bincount(np.asarray(edges, dtype=np.int64).ravel(), minlength=links)
    return _orders_of_degrees(degree.tolist())


def _orders_of_degrees(degrees: list[int]) -> dict[str, int]:
    counts: dict[str, int] = {}
    for d in sorted(degrees):
        counts[order_name(d)] = counts.get(order_name(d), 0) + 1
    return counts


def chain_file_name(number: int, count: int) -> str:
    """The name of an atlas's ``number``-th chain file among ``count``, numbered to the
    same width so that they sort in order (``chain-07.toml`` of 12).

    >>> chain_file_name(7, 12), chain_file_name(7, 9)
    ('chain-07.toml', 'chain-7.toml')
    """
    return f"chain-{number:0{len(str(count))}d}.toml"
