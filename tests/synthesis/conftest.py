"""Helpers the synthesis tests share."""

import itertools


def automorphisms(chain):
    """Every automorphism of a small chain, by brute force over the links' permutations:
    (link map, joint map) pairs that carry every joint to a joint of the same kind on
    the mapped links (which link of a sliding pair carries the guide not kept: the
    unoriented automorphisms the space's orbits are taken under)."""
    links = list(chain.links)
    by_links = {(frozenset(j.links), j.kind): j.id for j in chain.joints}
    for image in itertools.permutations(links):
        m = dict(zip(links, image))
        joints = {}
        for j in chain.joints:
            target = by_links.get((frozenset(m[x] for x in j.links), j.kind))
            if target is None:
                break
            joints[j.id] = target
        else:
            yield m, joints
