"""The velocity equations of chains at one drawn pose, in exact arithmetic: the proof
that an admissible chain is admissible.

The equations are written at pseudo-random pins and sliding directions and reduced
modulo the prime 2**31 - 1 (products of two residues fit in int64, so numpy reduces
thousands of matrices at once). Their entries are polynomials with integer
coefficients in the pins and directions, so a minor that is not zero at the drawn
values (modulo the prime) is not zero as a polynomial: a rank found here is at most
the generic rank, a full rank is the generic rank, and a rate that is independent of
the equations here is independent at a generic pose. So a chain whose drawn equations
are independent and lock no joint is proven admissible. The converse is not proven by
a draw (it may hit a zero of a minor); :mod:`~chaingraph.structure.atlas.admissibility`
proves rejections by forests and counts.
"""

from __future__ import annotations

import random
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

#: int64 arrays of residues modulo PRIME
_Residues = npt.NDArray[np.int64]

__all__ = ["PRIME", "reduce_mod", "in_row_space", "generic_verdicts", "joint_verdicts"]


PRIME = (1 << 31) - 1          # products of two residues fit in int64


def _modular_inverse(v: _Residues) -> _Residues:
    """Inverses modulo PRIME of an int64 array (Fermat: v ** (PRIME - 2))."""
    out = np.ones_like(v)
    base, e = v % PRIME, PRIME - 2
    while e:
        if e & 1:
            out = out * base % PRIME
        base = base * base % PRIME
        e >>= 1
    return out


def reduce_mod(mats: _Residues) -> tuple[_Residues, _Residues]:
    """Each stacked matrix (int64, entries modulo PRIME) in reduced row echelon form, and
    its rank.

    The rows from the rank down are zero left of the column being reduced (each earlier
    column was either a pivot's, cleared in every other row, or zero in them), so a
    step swaps and subtracts the columns from there on only."""
    m = mats % PRIME
    count, rows, cols = m.shape
    rank = np.zeros(count, dtype=np.int64)
    order = np.arange(rows)[None, :]
    for c in range(cols):
        candidate = (m[:, :, c] != 0) & (order >= rank[:, None])
        has = np.nonzero(candidate.any(axis=1))[0]
        if not has.size:
            continue
        pivot = np.argmax(candidate[has], axis=1)
        top = rank[has]
        sub = m[has, :, c:]
        k = np.arange(has.size)
        sub[k, pivot], sub[k, top] = sub[k, top], sub[k, pivot].copy()
        sub[k, top] = sub[k, top] * _modular_inverse(sub[k, top, 0])[:, None] % PRIME
        factor = sub[:, :, 0].copy()
        factor[k, top] = 0
        sub = (sub - factor[:, :, None] * sub[k, top][:, None, :]) % PRIME
        m[has, :, c:] = sub
        rank[has] += 1
    return m, rank


def in_row_space(reduced: _Residues, rank: _Residues, vectors: _Residues,
                 ) -> npt.NDArray[np.bool_]:
    """Whether each of ``vectors`` (count, k, cols) lies in the row space of its
    matrix, given in reduced row echelon form with its rank.

    A vector is in the row space exactly when it is the sum of the rows, each times
    the vector's entry at the row's pivot (a pivot's column is zero in every other
    row), so the test is one product per matrix; its factors are split into 16-bit
    halves so that no sum of products overflows int64."""
    v = vectors % PRIME
    pivots = np.argmax(reduced != 0, axis=2)            # (count, rows); zero rows: 0
    pivots[np.arange(reduced.shape[1])[None, :] >= rank[:, None]] = 0
    coefficients = np.take_along_axis(v, np.broadcast_to(
        pivots[:, None, :], (v.shape[0], v.shape[1], pivots.shape[1])), axis=2)
    high, low = coefficients >> 16, coefficients & 0xFFFF
    span = ((high @ reduced) % PRIME * (1 << 16) + low @ reduced) % PRIME
    return (v == span).all(axis=2)


def _verdicts(rows: _Residues, rates: _Residues, valid: npt.NDArray[np.bool_] | None = None,
              ) -> tuple[_Residues, npt.NDArray[np.bool_]]:
    """(rank, any joint locked) of each stacked system of velocity equations ``rows``,
    a joint's rate being locked when it lies in their row space (``valid`` marks the
    rates that are joints', where candidates have different numbers of them)."""
    reduced, rank = reduce_mod(rows)
    found = in_row_space(reduced, rank, rates)
    return rank, np.asarray((found if valid is None else found & valid).any(axis=1))


def generic_verdicts(links: int, edges: Sequence[Sequence[int]], masks: npt.ArrayLike, *,
                     draw: int = 0) -> tuple[_Residues, npt.NDArray[np.bool_]]:
    """For each assignment (a bit mask over ``edges``: P where set), the mobility of
    the chain (the first link fixed) and whether a joint is locked, by the rank of its
    velocity equations at the pose ``draw`` (pseudo-random pins and sliding
    directions, exact modulo PRIME): the generic mobility or more, the generic
    verdict where the mobility is the least its joints allow and no joint is locked.
    ``edges`` are the chain's joints, each a tuple of links: a joint of more than two
    links is a pin of them all (a turning pair; its bit is never set).

    A link's velocity is its twist (omega, vx, vy) at the origin. An R joint at (x, y)
    gives the pin one velocity on all its links (2 rows per link past the first); a P
    joint with normal n turns its links together and lets no point slip across its
    line (2 rows). A joint is locked when its rate (an R joint's relative turn, of each
    two of its links; a P joint's slide) is zero in every motion: its row lies in the
    equations' row space.

    Examples
    --------
    >>> ring = [(0, 1), (1, 2), (2, 3), (3, 0)]
    >>> mobility, locked = generic_verdicts(4, ring, [0b0000, 0b0011, 0b1111, 0b0111])
    >>> mobility.tolist(), locked.tolist()
    ([1, 1, 2, 1], [False, False, False, True])
    >>> fan = [(0, 1, 2), (1, 3), (2, 3), (0, 3)]          # a pin of three: rigid
    >>> [v.tolist() for v in generic_verdicts(4, fan, [0b0000, 0b1000])]
    [[0, 0], [True, True]]
    """
    bits = np.asarray(masks, dtype=np.int64)
    cols = 3 * (links - 1)
    rnd = random.Random(f"{draw}:{links}:{edges}")
    values = [[rnd.randrange(1, PRIME) for _ in range(4)] for _ in edges]
    count = bits.size
    rows = np.zeros((count, sum(2 * (len(j) - 1) for j in edges), cols), dtype=np.int64)
    rates = np.zeros((count, sum(len(j) * (len(j) - 1) // 2 for j in edges), cols),
                     dtype=np.int64)

    def put(target: _Residues, index: npt.NDArray[np.int64], row: int, link: int,
            coefficients: Sequence[int], sign: int) -> None:
        if link:
            for k, v in enumerate(coefficients):
                target[index, row, 3 * (link - 1) + k] += sign * v
    everything = np.arange(count)
    row = rate = 0
    for i, (joint, (x, y, nx, ny)) in enumerate(zip(edges, values)):
        sliding = (bits >> i & 1).astype(bool)
        r, s = everything[~sliding], everything[sliding]
        if len(joint) == 2:
            a, b = joint
            for link, sign in ((a, 1), (b, -1)):
                # P: the same turn; no slip across the line at (x, y) (normal n)
                put(rows, s, row, link, (1, 0, 0), sign)
                put(rows, s, row + 1, link, ((-nx * y + ny * x) % PRIME, nx, ny), sign)
                put(rates, s, rate, link, ((ny * y + nx * x) % PRIME, -ny, nx), -sign)
        for other in joint[1:]:
            for link, sign in ((joint[0], 1), (other, -1)):
                # R: the pin's velocity v + omega k x (x, y), both components
                put(rows, r, row, link, (-y, 1, 0), sign)
                put(rows, r, row + 1, link, (x, 0, 1), sign)
            row += 2
        for k, a in enumerate(joint):
            for b in joint[k + 1:]:
                put(rates, r, rate, a, (1, 0, 0), -1)
                put(rates, r, rate, b, (1, 0, 0), 1)
                rate += 1
    rank, locked = _verdicts(rows, rates)
    return cols - rank, locked


def joint_verdicts(links: int, candidates: Sequence[Sequence[Sequence[int]]], *,
                   kinds: Sequence[Sequence[str] | None] | None = None, draw: int = 0,
                   ) -> tuple[_Residues, npt.NDArray[np.bool_]]:
    """For each candidate (a tuple of joints, each a tuple of links), the mobility with
    the first link fixed and whether a joint is locked (two links of a turning pair
    that cannot turn relative to each other, or a sliding pair that cannot slide), by
    the rank of the velocity equations at the pose ``draw``, each joint's pin at one
    place (exact, modulo the prime; as :func:`generic_verdicts`, a proof where the
    mobility is the least and no joint is locked). ``kinds`` gives each candidate's
    joint kinds ("R", or "P" for a joint of two links), all R by default.

    Examples
    --------
    >>> four = ((0, 1), (1, 2), (2, 3), (3, 0))
    >>> fan = ((0, 1, 2), (1, 3), (2, 3), (0, 3))     # a pin of three links: rigid
    >>> mobility, locked = joint_verdicts(4, [four, fan, four], kinds=[None, None, "PRRR"])
    >>> mobility.tolist(), locked.tolist()
    ([1, 0, 1], [False, True, False])
    """
    cols = 3 * (links - 1)
    count = len(candidates)
    each: list[Sequence[str]] = [k or "R" * len(c)
                                 for k, c in zip(kinds or [None] * count, candidates)]
    rows_needed = max(2 * sum(len(j) - 1 for j in c) for c in candidates)
    pairs_needed = max(sum(len(j) * (len(j) - 1) // 2 for j in c) for c in candidates)

    def put(target: _Residues, n: int, r: int, link: int, values: Sequence[int],
            sign: int) -> None:
        if link:
            target[n, r, 3 * (link - 1):3 * link] += [sign * v for v in values]
    rnd = random.Random(f"{draw}:{links}")
    rows = np.zeros((count, rows_needed, cols), dtype=np.int64)
    rates = np.zeros((count, pairs_needed, cols), dtype=np.int64)
    valid = np.zeros((count, pairs_needed), dtype=bool)
    for n, (joints, kind) in enumerate(zip(candidates, each)):
        r = p = 0
        for j, k in zip(joints, kind):
            x, y = rnd.randrange(PRIME), rnd.randrange(PRIME)
            if k == "P":
                nx, ny = rnd.randrange(PRIME), rnd.randrange(PRIME)
                a, b = j
                for link, sign in ((a, 1), (b, -1)):
                    put(rows, n, r, link, (1, 0, 0), sign)
                    put(rows, n, r + 1, link, ((-nx * y + ny * x) % PRIME, nx, ny), sign)
                    put(rates, n, p, link, ((ny * y + nx * x) % PRIME, -ny, nx), -sign)
                valid[n, p] = True
                r, p = r + 2, p + 1
                continue
            for other in j[1:]:
                for link, sign in ((j[0], 1), (other, -1)):
                    put(rows, n, r, link, (-y, 1, 0), sign)
                    put(rows, n, r + 1, link, (x, 0, 1), sign)
                r += 2
            for i, a in enumerate(j):
                for b in j[i + 1:]:
                    put(rates, n, p, a, (1, 0, 0), -1)
                    put(rates, n, p, b, (1, 0, 0), 1)
                    valid[n, p] = True
                    p += 1
    rank, locked = _verdicts(rows, rates, valid)
    return cols - rank, locked
