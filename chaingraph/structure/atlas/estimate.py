"""How long an atlas takes, told before it starts, and the sizes refused.

The time goes into the pieces, and a piece's time into its chains (canonical labelling
and the vectorised tests cost about 100 to 130 microseconds of CPU per chain at 12 to 16
links, measured by ``benchmarks/atlas.py``). The number of chains is the published
count where there is one (OEIS A233288 for one degree of freedom, the multi-dof counts
of the tests) and otherwise a fit of the counts measured here, ``log10 count = a + b N +
c l + d N l`` with ``l = (N - 1 - F) / 2`` independent loops, within a factor of two of
every count up to 16 links.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from chaingraph.errors import AtlasSizeError
from chaingraph.structure.atlas.contracted import joints_for

__all__ = ["Estimate", "estimate", "check_size", "LOCAL_HOURS", "CLUSTER_CORE_HOURS",
           "MAX_LINKS"]

#: exact counts (links, dof) -> chains: A233288, and the multi-dof counts of the tests
KNOWN = {(4, 1): 1, (6, 1): 2, (8, 1): 16, (10, 1): 230, (12, 1): 6856, (14, 1): 318162,
         (16, 1): 19819281, (7, 2): 4, (9, 2): 40, (11, 2): 839, (13, 2): 29685,
         (8, 3): 7, (10, 3): 98, (12, 3): 2422}
FIT = (-1.31521923, 0.13475271, 0.05599872, 0.05632598)
#: CPU seconds per chain at 14 links; grows with the chain's size
SECONDS_PER_CHAIN = 130e-6
#: no atlas is tried beyond this many links, whatever the machine
MAX_LINKS = 40
#: without a cluster, a run estimated longer than this (wall clock) is refused
LOCAL_HOURS = 1.0
#: on a cluster, a run estimated at more core-hours than this is refused
CLUSTER_CORE_HOURS = 10_000.0


@dataclass(frozen=True)
class Estimate:
    """``log10_chains`` and ``log10_cpu_seconds`` (logs, so that any size can be told),
    and whether the count is a published one."""

    links: int
    dof: int
    log10_chains: float
    log10_cpu_seconds: float
    published: bool

    @property
    def chains(self) -> float:
        return 10 ** min(self.log10_chains, 300)

    @property
    def cpu_seconds(self) -> float:
        return 10 ** min(self.log10_cpu_seconds, 300)

    def wall_seconds(self, cores: int) -> float:
        return self.cpu_seconds / max(1, cores)

    def describe(self, cores=None) -> str:
        chains = (f"{round(self.chains):,} chains" if self.published else
                  f"about {_big(self.log10_chains)} chains")
        text = f"{chains}, about {_duration(self.log10_cpu_seconds)} of CPU"
        if cores:
            text += (f" ({_duration(self.log10_cpu_seconds - math.log10(cores))} on "
                     f"{cores} core{'s' if cores != 1 else ''})")
        return text


def _big(log10):
    if log10 < 6:
        return f"{round(10 ** log10):,}"
    if log10 < 15:
        return f"{10 ** log10 / 1e6:,.0f} million"
    return f"10^{log10:.0f}"


def _duration(log10_seconds):
    if log10_seconds > 13.5:
        return f"10^{log10_seconds - math.log10(3.156e7):.0f} years"
    s = 10 ** log10_seconds
    for unit, size in (("years", 3.156e7), ("days", 86400), ("hours", 3600),
                       ("minutes", 60)):
        if s >= 2 * size:
            return f"{s / size:,.0f} {unit}"
    return f"{s:.0f} s" if s >= 1 else "under a second"


def estimate(links: int, dof: int = 1) -> Estimate:
    """The estimated size and CPU time of an atlas.

    Examples
    --------
    >>> e = estimate(16, 1)
    >>> round(e.chains), e.published
    (19819281, True)
    >>> estimate(18, 1).describe(cores=2).startswith("about 4,669 million chains")
    True
    """
    joints_for(links, dof)
    if (links, dof) in KNOWN:
        log_chains, published = math.log10(KNOWN[(links, dof)]), True
    else:
        loops = (links - 1 - dof) / 2
        a, b, c, d = FIT
        log_chains, published = a + b * links + c * loops + d * links * loops, False
    log_cpu = log_chains + math.log10(SECONDS_PER_CHAIN * max(1.0, links / 14))
    return Estimate(links, dof, log_chains, log_cpu, published)


def check_size(links: int, dof: int, *, cores: int, cluster: bool) -> Estimate:
    """Refuse, with the estimate and what to do instead, a size that cannot finish in
    reasonable time: over :data:`LOCAL_HOURS` on ``cores`` local processes, or over
    :data:`CLUSTER_CORE_HOURS` on a cluster. Returns the estimate otherwise."""
    joints_for(links, dof)
    if links > MAX_LINKS:
        raise AtlasSizeError(
            f"{links} links is beyond the atlas: at most {MAX_LINKS} links (the number of "
            "chains grows about a hundredfold every two links; 16 links already have "
            "19,819,281)", links=links, dof=dof)
    e = estimate(links, dof)
    if cluster:
        if e.log10_cpu_seconds > math.log10(CLUSTER_CORE_HOURS * 3600):
            raise AtlasSizeError(
                f"an atlas of {links} links and {dof} dof is refused: {e.describe()}, more "
                f"than the {CLUSTER_CORE_HOURS:,.0f} core-hours allowed on a cluster",
                links=links, dof=dof)
        return e
    if e.log10_cpu_seconds - math.log10(max(1, cores)) > math.log10(LOCAL_HOURS * 3600):
        raise AtlasSizeError(
            f"an atlas of {links} links and {dof} dof is refused on this machine: "
            f"{e.describe(cores)}, more than {LOCAL_HOURS:g} hour; run it on a Dask "
            f"cluster (see docs/atlas.md) or with more workers",
            links=links, dof=dof, parameter="scheduler")
    return e
