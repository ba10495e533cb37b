"""The (fixed link, driver) pairs the kinematics tests solve: every link pinned by a
turning pair to the fixed one, for every fixed link, in the chain's order."""


def pinned_pairs(chain):
    """Every (fixed link, link turning about it through an R joint) of ``chain``."""
    for fixed in chain.links:
        for j in chain.joints:
            if j.kind == "R" and fixed in j.links:
                yield from ((fixed, d) for d in j.links if d != fixed)
