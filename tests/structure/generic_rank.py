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


def random_pose(links, joints, kinds, rnd):
    """(mobility, locked rates) of a chain at a random pose drawn from ``rnd`` (a numpy
    Generator): ``joints`` are tuples of links (a pin of several links at one point),
    ``kinds`` "R"/"P" per joint. The rates are each turning pair's relative turns (one
    per pair of its links) and each sliding pair's slide, in the order of the joints."""
    cols = 3 * (links - 1)
    rows, rates = [], []
    for j, kind in zip(joints, kinds):
        x, y = rnd.normal(size=2)
        if kind == "P":          # turn together; no slip across the line (normal n)
            a, b = j
            angle = rnd.uniform(0, 2 * np.pi)
            nx, ny = np.cos(angle), np.sin(angle)
            for comp in ((1, 0, 0), (-nx * y + ny * x, nx, ny)):
                rows.append(twist(cols, a, comp) - twist(cols, b, comp))
            along = (ny * y + nx * x, -ny, nx)
            rates.append(twist(cols, b, along) - twist(cols, a, along))
            continue
        for other in j[1:]:      # the pin's velocity is one point's on all its links
            for comp in ((-y, 1, 0), (x, 0, 1)):
                rows.append(twist(cols, j[0], comp) - twist(cols, other, comp))
        for i, a in enumerate(j):
            for b in j[i + 1:]:
                rates.append(twist(cols, b, (1, 0, 0)) - twist(cols, a, (1, 0, 0)))
    return mobility_and_locked(rows, rates, cols)
