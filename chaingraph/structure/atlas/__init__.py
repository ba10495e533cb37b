"""The atlas: every kinematic chain of N links and F degrees of freedom.

The chains are planar, with simple (binary) revolute joints, non-degenerate (no proper
sub-chain with mobility <= 0), connected, and counted once up to isomorphism; non-planar
link graphs and fractionated chains are included (each chain says whether it is
fractionated: a link or a joint whose removal splits it). A chain is its link graph: a
simple graph on N links with J = (3 (N - 1) - F) / 2 joints as edges.

Method (structural synthesis by contracted graphs):

1. Number synthesis: the link assortments (how many links of each order) with N links
   and 2J joint ends, every link of order 2 or more (:mod:`.contracted`).
2. For each assortment, the contracted graphs: connected multigraphs (loops allowed: a
   loop of binary links on one link makes a fractionated chain) on the links of order 3
   or more, with those orders as degrees, up to isomorphism (:mod:`.contracted`).
3. For each contracted graph (a piece), the binary links distributed on its edges in
   every way, one per orbit of the contracted graph's automorphisms, kept when no proper
   sub-chain is rigid, each then labelled canonically with its link orbits counted
   (:mod:`.pieces`, vectorised with numpy; nauty labels, :mod:`.labelling`).

The pieces are independent: they run on local processes or a Dask cluster, in shards
written as they finish, so that a run can be resumed (:mod:`.run`). :mod:`.estimate`
tells the cost of a size before it starts and refuses the sizes that cannot finish;
:mod:`.output` writes atlas.json, graph6, the HTML index and chain files.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

from chaingraph.model.chain import Chain
from chaingraph.structure.atlas.admissibility import REASONS
from chaingraph.structure.atlas.contracted import assortments, joints_for
from chaingraph.structure.atlas.entry import AtlasEntry
from chaingraph.structure.atlas.estimate import LOCAL_HOURS, MAX_LINKS, check_size
from chaingraph.structure.atlas.illustrate import (
    generic_pose,
    inversion_mechanism,
    link_layout,
    natural_input,
)
from chaingraph.structure.atlas.multiple import MultipleAtlas, MultipleEntry, multiple_atlas
from chaingraph.structure.atlas.output import atlas_dict, write_atlas
from chaingraph.structure.atlas.run import (
    Atlas,
    AtlasCounts,
    DaskRunner,
    process_runner,
    run_atlas,
)
from chaingraph.structure.atlas.sliding import (
    SlidingAtlas,
    SlidingCounts,
    SlidingEntry,
    prismatic_counts,
    sliding_atlas,
    sliding_chains,
    sliding_dict,
    write_sliding,
)

__all__ = ["atlas", "atlas_graphs", "AtlasEntry", "Atlas", "AtlasCounts", "joints_for",
           "assortments", "atlas_dict", "write_atlas", "run_atlas", "process_runner",
           "DaskRunner", "check_size", "LOCAL_HOURS", "MAX_LINKS", "REASONS",
           "multiple_atlas", "MultipleAtlas", "MultipleEntry", "sliding_atlas",
           "sliding_chains", "prismatic_counts", "sliding_dict", "write_sliding",
           "SlidingAtlas", "SlidingCounts", "SlidingEntry", "generic_pose",
           "inversion_mechanism", "link_layout", "natural_input"]


def atlas_graphs(links: int, dof: int = 1, *, workers: int = 1,
                 progress: Callable[[float, str], None] | None = None,
                 labelling: str | None = None) -> Atlas:
    """Every chain of the atlas, numbered by link assortment and contracted graph.

    Parameters
    ----------
    links, dof : int
    workers : int
        Local processes that run the pieces side by side.
    progress : callable, optional
        Called as ``progress(fraction_done, text)`` as the run goes.
    labelling : {"nauty", "own"}, optional
        The canonical labelling of the edges (nauty when pynauty is installed).

    Returns
    -------
    Atlas
        A sequence of :class:`AtlasEntry` backed by arrays.

    Examples
    --------
    >>> [len(atlas_graphs(n, 1)) for n in (4, 6, 8)]
    [1, 2, 16]
    >>> sum(e.inversion_classes for e in atlas_graphs(6, 1))
    5
    >>> a = atlas_graphs(9, 2)
    >>> a.count, a.count_non_fractionated
    (40, 35)
    """
    return run_atlas(links, dof, workers=workers, progress=progress, backend=labelling)


def atlas(*, links: int, dof: int = 1, workers: int = 1,
          prismatic: int | str | None = None, oriented: bool = False,
          multiple: bool = False) -> Iterator[Chain]:
    """Yield every chain of ``links`` links and ``dof`` degrees of freedom as a Chain.

    ``prismatic`` (a number, or "all") gives the chains whose joints are that many
    sliding pairs and the rest turning pairs (see
    :func:`~chaingraph.structure.atlas.sliding.sliding_atlas`); ``oriented`` tells them
    apart by which link carries each guide; ``multiple`` lets a turning pair join three
    links or more (:func:`~chaingraph.structure.atlas.multiple.multiple_atlas`).

    Examples
    --------
    >>> [c.name for c in atlas(links=6, dof=1)]
    ['chain 1 of 6 links, 1 dof', 'chain 2 of 6 links, 1 dof']
    >>> [[j.kind for j in c.joints] for c in atlas(links=4, prismatic=2)]
    [['P', 'P', 'R', 'R'], ['R', 'P', 'P', 'R']]
    >>> [max(len(j.links) for j in c.joints) for c in atlas(links=6, multiple=True)]
    [2, 2, 3, 3]
    """
    wanted = prismatic_counts(links, dof, joints_for(links, dof), prismatic, oriented)
    simple = atlas_graphs(links, dof, workers=workers)
    base: Atlas | MultipleAtlas = simple
    if multiple:
        base, wanted = multiple_atlas(simple), wanted or (0,)
    if wanted is None:
        for entry in base:
            yield entry.chain(dof)
        return
    for entry in sliding_chains(base, prismatic=wanted, oriented=oriented):
        yield entry.chain(dof)
