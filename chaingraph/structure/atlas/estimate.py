"""How long an atlas takes, told before it starts, and the sizes refused.

The time goes into the pieces, and a piece's time into its chains (canonical labelling
and the vectorised tests cost about 100 to 130 microseconds of CPU per chain at 12 to 16
links, measured by ``benchmarks/atlas.py``). The number of chains is the published
count where there is one (OEIS A233288 for one degree of freedom, the multi-dof counts
of the tests) and otherwise a fit of the counts measured here, ``log10 count = a + b N +
c l + d N l`` with ``l = (N - 1 - F) / 2`` independent loops, within a factor of two of
every count up to 16 links.

With sliding pairs (``prismatic``), the chains of the turning-pair atlas are then tried,
in one process, with every assignment of K sliding pairs to their joints: a fixed cost
per chain (its automorphism group), a cost per assignment tried (the orbits, the
structure, the exact evaluation) and, with ``oriented``, a cost per orientation of its
guides. Each is measured at 6, 8 and 10 links (``benchmarks/atlas_sliding.py --fit``)
and fitted as ``log10 seconds = a + b N``; with ``multiple``, the chains with multiple
joints are more (their number per turning-pair chain fitted alike) and their merging
costs its own time per turning-pair chain.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from math import comb

from chaingraph.errors import AtlasSizeError
from chaingraph.structure.atlas.contracted import joints_for

__all__ = ["Estimate", "estimate", "check_size", "LOCAL_HOURS", "CLUSTER_CORE_HOURS",
           "MAX_LINKS", "SlidingEstimate", "sliding_estimate", "SLIDING_FIT"]

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
        """The number of chains (capped at 1e300)."""
        return 10 ** min(self.log10_chains, 300)

    @property
    def cpu_seconds(self) -> float:
        """The CPU seconds (capped at 1e300)."""
        return 10 ** min(self.log10_cpu_seconds, 300)

    def wall_seconds(self, cores: int) -> float:
        """The seconds on ``cores`` processes."""
        return self.cpu_seconds / max(1, cores)

    def describe(self, cores: int | None = None) -> str:
        """The estimate in words (on ``cores`` processes, when given)."""
        chains = (f"{round(self.chains):,} chains" if self.published else
                  f"about {_big(self.log10_chains)} chains")
        text = f"{chains}, about {_duration(self.log10_cpu_seconds)} of CPU"
        if cores:
            text += (f" ({_duration(self.log10_cpu_seconds - math.log10(cores))} on "
                     f"{cores} core{'s' if cores != 1 else ''})")
        return text


def _big(log10: float) -> str:
    if log10 < 6:
        return f"{round(10 ** log10):,}"
    if log10 < 15:
        return f"{10 ** log10 / 1e6:,.0f} million"
    return f"10^{log10:.0f}"


def _duration(log10_seconds: float) -> str:
    if log10_seconds > 13.5:
        return f"10^{log10_seconds - math.log10(3.156e7):.0f} years"
    s = 10 ** log10_seconds
    for unit, size in (("years", 3.156e7), ("days", 86400), ("hours", 3600),
                       ("minutes", 60)):
        if s >= 2 * size:
            return f"{s / size:,.0f} {unit}"
    return f"{s:.0f} s" if s >= 1 else "under a second"


def _about(log10_seconds: float) -> str:
    duration = _duration(log10_seconds)
    return duration if duration.startswith("under") else f"about {duration}"


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


def check_size(links: int, dof: int, *, cores: int, cluster: bool, hours: float = LOCAL_HOURS,
               prismatic: tuple[int, ...] | None = None, oriented: bool = False,
               multiple: bool = False) -> Estimate | SlidingEstimate:
    """Refuse, with the estimate and what to do instead, a size that cannot finish in
    reasonable time: over ``hours`` (:data:`LOCAL_HOURS` unless asked) on ``cores``
    local processes, or over :data:`CLUSTER_CORE_HOURS` on a cluster. With sliding
    pairs (``prismatic``, the numbers K asked for; ``oriented``) or ``multiple``
    joints, the estimate is :func:`sliding_estimate`'s. Returns the estimate
    otherwise."""
    joints_for(links, dof)
    if links > MAX_LINKS:
        raise AtlasSizeError(
            f"{links} links is beyond the atlas: at most {MAX_LINKS} links (the number of "
            "chains grows about a hundredfold every two links; 16 links already have "
            "19,819,281)", links=links, dof=dof)
    if not (hours > 0 and math.isfinite(hours)):
        raise AtlasSizeError(f"hours must be a positive number, got {hours!r}", links=links,
                             dof=dof, parameter="hours")
    if prismatic is not None or multiple:
        return _check_sliding(links, dof, cores=cores, hours=hours,
                              prismatic=prismatic or (0,), oriented=oriented,
                              multiple=multiple)
    e = estimate(links, dof)
    if cluster:
        if e.log10_cpu_seconds > math.log10(CLUSTER_CORE_HOURS * 3600):
            raise AtlasSizeError(
                f"an atlas of {links} links and {dof} dof is refused: {e.describe()}, more "
                f"than the {CLUSTER_CORE_HOURS:,.0f} core-hours allowed on a cluster",
                links=links, dof=dof)
        return e
    if e.log10_cpu_seconds - math.log10(max(1, cores)) > math.log10(hours * 3600):
        raise AtlasSizeError(
            f"an atlas of {links} links and {dof} dof is refused on this machine: "
            f"{e.describe(cores)}, more than {_hours(hours)}; run it on a Dask "
            f"cluster (see docs/atlas.md) or with more workers",
            links=links, dof=dof, parameter="scheduler")
    return e


def _hours(hours: float) -> str:
    return f"{hours:g} hour{'s' if hours != 1 else ''}"


#: the largest atlas with multiple joints measured: 10 links in 21 s; at 12 links
#: (``chaingraph atlas --links 12 --multiple --summary``) the enumeration had not
#: finished after 15 minutes of CPU and held 20 GB, so it is refused whatever the hours
MULTIPLE_MEASURED_LINKS = 10


def _check_sliding(links: int, dof: int, *, cores: int, hours: float,
                   prismatic: tuple[int, ...], oriented: bool, multiple: bool,
                   ) -> SlidingEstimate:
    """check_size of an atlas with sliding pairs or multiple joints: refused over
    ``hours`` with the estimate, and the parameter that allows it named."""
    if multiple and links > MULTIPLE_MEASURED_LINKS:
        raise AtlasSizeError(
            f"an atlas of {links} links with multiple joints is refused: their direct "
            f"enumeration is measured to {MULTIPLE_MEASURED_LINKS} links (21 s); at 12 links "
            "it had not finished after 15 minutes of CPU and held 20 GB of memory, more than "
            "this machine has", links=links, dof=dof, parameter="links")
    e = sliding_estimate(links, dof, prismatic=prismatic, oriented=oriented,
                         multiple=multiple)
    if e.wall_seconds(cores) > hours * 3600:
        what = ("sliding pairs" if not multiple else "multiple joints" if prismatic == (0,)
                else "sliding pairs and multiple joints")
        fewer = ", or ask for fewer sliding pairs" if max(prismatic) > 0 else ""
        raise AtlasSizeError(
            f"an atlas of {links} links and {dof} dof with {what} is refused on this "
            f"machine: {e.describe(cores)}, more than {_hours(hours)}; allow the time "
            f"(hours){fewer}", links=links, dof=dof, parameter="hours")
    return e


# -- with sliding pairs and multiple joints ------------------------------------------------
#: ``(a, b)`` of ``log10 seconds = a + b N`` (CPU seconds of one process, N links), fitted
#: to the times measured by ``benchmarks/atlas_sliding.py --fit --sizes 6 8 10
#: --multiple-up-to 10`` on the 2-core machine while it was shared (so they lean high):
#: "chain" per turning-pair chain (its automorphism group; 3.0, 6.3, 5.1 ms at 6, 8, 10
#: links), "assignment" per assignment of sliding pairs tried (12, 20, 48 us),
#: "orientation" per further orientation of their guides with ``oriented`` (0.34, 0.41,
#: 0.42 us), "merge" the direct enumeration of the chains with multiple joints, per
#: turning-pair chain (2.2, 3.3, 13.5 ms), and "multiple_chains" the chains with multiple
#: joints per turning-pair chain (2, 3.75, 11.5)
SLIDING_FIT = {"chain": (-2.794, 0.057), "assignment": (-5.883, 0.155),
               "orientation": (-6.601, 0.024), "merge": (-3.930, 0.199),
               "multiple_chains": (-0.874, 0.190)}


def _fitted(name: str, links: int) -> float:
    a, b = SLIDING_FIT[name]
    return a + b * links


@dataclass(frozen=True)
class SlidingEstimate:
    """The estimate of an atlas with sliding pairs (``prismatic``, the numbers K asked
    for) or multiple joints: the turning-pair atlas ``base`` (run on the workers), then
    its chains tried with ``assignments`` assignments each, in one process, for about
    ``10 ** log10_seconds`` seconds of CPU."""

    base: Estimate
    joints: int
    prismatic: tuple[int, ...]
    oriented: bool
    multiple: bool
    log10_chains_tried: float
    assignments: int
    log10_seconds: float

    def wall_seconds(self, cores: int) -> float:
        """The seconds on ``cores`` processes: the turning-pair atlas's, then this."""
        return self.base.wall_seconds(cores) + 10 ** min(self.log10_seconds, 300)

    def describe(self, cores: int | None = None) -> str:
        """The estimate in words (on ``cores`` processes, when given)."""
        base = self.base
        chains = (f"the {round(base.chains):,} turning-pair chains" if base.published else
                  f"about {_big(base.log10_chains)} turning-pair chains")
        every = set(range(self.joints + 1)) <= set(self.prismatic)
        ks = ("every K" if every else "K = " + ", ".join(map(str, self.prismatic)))
        tried = (f"each tried with up to {self.assignments:,} assignment"
                 f"{'s' if self.assignments != 1 else ''} of sliding pairs ({ks}"
                 f"{', oriented' if self.oriented else ''})")
        if self.multiple and self.prismatic == (0,):
            text = (f"{chains} merged into about {_big(self.log10_chains_tried)} chains "
                    "with multiple joints")
        elif self.multiple:
            text = (f"{chains} (about {_big(self.log10_chains_tried)} with multiple "
                    f"joints), {tried}")
        else:
            text = f"{chains}, {tried}"
        text += f": {_about(self.log10_seconds)} of CPU in one process"
        if cores:
            total = math.log10(self.wall_seconds(cores))
            text += f" ({_duration(total)} with the turning-pair atlas on {cores} " \
                    f"core{'s' if cores != 1 else ''})"
        return text


def sliding_estimate(links: int, dof: int = 1, *, prismatic: Iterable[int] = (0,),
                     oriented: bool = False, multiple: bool = False) -> SlidingEstimate:
    """The estimated CPU time of an atlas with sliding pairs (``prismatic``: the numbers
    of sliding pairs asked for) and, with ``multiple``, multiple joints.

    Examples
    --------
    >>> quick = sliding_estimate(12, 1, prismatic=(1,))
    >>> every = sliding_estimate(12, 1, prismatic=tuple(range(17)))
    >>> every.assignments, every.wall_seconds(2) > 3600 > quick.wall_seconds(2)
    (65536, True)
    """
    base = estimate(links, dof)
    joints = joints_for(links, dof)
    wanted = tuple(sorted(set(prismatic)))
    assignments = sum(comb(joints, k) for k in wanted)
    extra = sum(comb(joints, k) * (2 ** k - 1) for k in wanted) if oriented else 0
    log_chains = base.log10_chains
    seconds = 0.0
    if multiple:
        seconds += 10 ** (base.log10_chains + _fitted("merge", links))
        log_chains += max(0.0, _fitted("multiple_chains", links))
    per_chain = (10 ** _fitted("chain", links) + assignments * 10 ** _fitted("assignment", links)
                 + extra * 10 ** _fitted("orientation", links))
    seconds += 10 ** (log_chains + math.log10(per_chain))
    return SlidingEstimate(base, joints, wanted, bool(oriented), bool(multiple), log_chains,
                           assignments, math.log10(seconds))
