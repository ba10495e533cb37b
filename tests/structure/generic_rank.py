"""The tests' own reference for generic mobility: the velocity equations of a chain at
a random pose in floating point (a link's twist (omega, vx, vy), the first link fixed),
their rank and kernel by the singular values. Independent of the package's exact
modular rank (chaingraph.structure.atlas.generic)."""

import numpy as np


def twist(cols, link, values):
    """A row of the velocity equations: ``values`` on ``link``'s twist (none for the
    fixed link 0)."""
    row = np.zeros(cols)
    if link:
        row[3 * (link - 1):3 * link] = values
    return row


def mobility_and_locked(rows, rates, cols):
    """(mobility, indices of the ``rates`` that are zero on every motion): the
    dimension of the equations' kernel, and which relative rates it locks."""
    _, s, vt = np.linalg.svd(np.array(rows))
    rank = int((s > 1e-9 * s[0]).sum())
    kernel = vt[rank:]
    locked = [i for i, r in enumerate(rates) if np.abs(kernel @ r).max(initial=0) < 1e-9]
    return cols - rank, locked
