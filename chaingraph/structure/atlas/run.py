"""Running the atlas: the plan, the pieces on local processes or a Dask cluster, the
results as compact arrays, and the shards that make a run resumable.

Stage 1 (the plan) finds the contracted graphs of every link assortment, one task per
assortment; stage 2 runs the pieces (one per contracted graph) in shards, groups of
consecutive pieces of about equal work. Tasks run where ``workers``/``scheduler`` say
and come back in any order; the results are put back in plan order, so the atlas is the
same however it was run. With an output folder each finished shard is written at once
(graph6 and JSON lines, under a temporary name and then renamed), so memory stays flat
and a run that dies can be resumed without redoing the shards already written.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from chaingraph._util.atomic import write_atomic
from chaingraph._util.parallel import Runner, process_runner, serial
from chaingraph.errors import AtlasRunError
from chaingraph.structure.atlas.contracted import (
    assortments,
    contracted_graphs,
    joints_for,
)
from chaingraph.structure.atlas.entry import AtlasEntry, encode_chains
from chaingraph.structure.atlas.labelling import default_backend, graph_form
from chaingraph.structure.atlas.pieces import piece, piece_work

__all__ = ["Atlas", "plan", "run_atlas", "SHARDS"]

#: a piece of the atlas: (the degrees of the contracted graph's multiple links, its
#: edges (pairs of those links), how many binary links its chains have)
PlanJob = tuple[tuple[int, ...], tuple[tuple[int, int], ...], int]

#: shards a run is cut into (about; each holds whole pieces)
SHARDS = 400


class Atlas:
    """Every chain of one size, as arrays (chains in plan order, numbered from 1).

    Attributes
    ----------
    links, dof : int
    edges : ndarray (count, J, 2) of uint8
        Each chain's link graph, in canonical labels.
    inversion_classes : ndarray (count,)
        Distinct inversions (link orbits) of each chain.
    fractionated : ndarray (count,) of bool
    labelling : str
        ``"nauty"`` or ``"own"``: the canonical labelling the edges are in.

    Indexing or iterating gives :class:`~chaingraph.structure.atlas.AtlasEntry` objects, made on
    demand (the arrays of 14 links take 14 MB; as objects they would take 40 times that).
    """

    def __init__(self, links, dof, edges, inversion_classes, fractionated, *,
                 labelling="nauty"):
        self.links, self.dof, self.labelling = links, dof, labelling
        self.edges = edges
        self.inversion_classes = inversion_classes
        self.fractionated = fractionated

    def __len__(self):
        return len(self.inversion_classes)

    @property
    def count(self) -> int:
        return len(self)

    @property
    def count_non_fractionated(self) -> int:
        return int(len(self) - self.fractionated.sum())

    @property
    def distinct_inversions(self) -> int:
        return int(self.inversion_classes.sum())

    @property
    def distinct_inversions_non_fractionated(self) -> int:
        return int(self.inversion_classes[~self.fractionated].sum())

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(len(self)))]
        if i < 0:
            i += len(self)
        if not 0 <= i < len(self):
            raise IndexError(f"chain index {i} out of range (the atlas has {len(self)})")
        return AtlasEntry(id=i + 1, edges=tuple(map(tuple, self.edges[i].tolist())),
                          links=self.links, inversion_classes=int(self.inversion_classes[i]),
                          fractionated=bool(self.fractionated[i]))

    def __iter__(self):
        for i in range(len(self)):
            yield self[i]

    def without_fractionated(self) -> "Atlas":
        """The non-fractionated chains alone, renumbered."""
        keep = ~self.fractionated
        return Atlas(self.links, self.dof, self.edges[keep], self.inversion_classes[keep],
                     self.fractionated[keep], labelling=self.labelling)

    def __repr__(self):
        return (f"Atlas(links={self.links}, dof={self.dof}, count={self.count}, "
                f"distinct_inversions={self.distinct_inversions})")


# -- the plan ------------------------------------------------------------------------
def _degrees(assortment):
    return tuple(sorted((order for order, count in enumerate(assortment[1:], start=3)
                         for _ in range(count)), reverse=True))


def _plan_task(task):
    """Stage 1 task: the pieces of one assortment."""
    degrees, binaries, backend = task
    return [(degrees, edges, binaries) for edges in contracted_graphs(degrees, backend=backend)]


def plan(links: int, dof: int, *, backend: str | None = None, runner: Runner | None = None
         ) -> list[PlanJob]:
    """The pieces of the atlas in their fixed order: ``(degrees, edges, binaries)``,
    by link assortment, then contracted graph.

    Examples
    --------
    >>> for degrees, edges, binaries in plan(6, 1, backend="own"):
    ...     print(degrees, edges, binaries)
    (3, 3) ((0, 0), (0, 1), (1, 1)) 4
    (3, 3) ((0, 1), (0, 1), (0, 1)) 4
    (4,) ((0, 0), (0, 0)) 5
    """
    backend = backend or default_backend()
    joints = joints_for(links, dof)
    tasks = [(_degrees(a), a[0], backend) for a in assortments(links, joints) if _degrees(a)]
    results: list[list[PlanJob]] = [[] for _ in tasks]   # each set as its task reports
    (runner or serial)(_plan_task, tasks, lambda i, r: results.__setitem__(i, r))
    return [job for r in results for job in r]


def _shards(jobs, count=SHARDS):
    """Cut the pieces, in order, into about ``count`` runs of about equal work."""
    work = [piece_work(j) for j in jobs]
    target = max(1, sum(work) / count)
    shards, start, acc = [], 0, 0
    for i, w in enumerate(work):
        acc += w
        if acc >= target:
            shards.append((start, i + 1))
            start, acc = i + 1, 0
    if start < len(jobs):
        shards.append((start, len(jobs)))
    return shards, work


def _shard_task(task):
    """Stage 2 task: the chains of consecutive pieces, as arrays ``(edges, orbits,
    fractionated)``, and encoded (graph6 bytes, JSON lines) for the shard files."""
    jobs, links, joints, backend, encode = task
    edges = [np.zeros((0, joints, 2), np.uint8)]
    orbits = [np.zeros(0, np.int32)]
    fractionated = [np.zeros(0, bool)]
    for job in jobs:
        found = piece(job, backend=backend)
        edges.append(found.edges)
        orbits.append(found.orbits)
        fractionated.append(np.full(len(found), found.fractionated))
    arrays = np.concatenate(edges), np.concatenate(orbits), np.concatenate(fractionated)
    return arrays + (encode_chains(links, *arrays) if encode else (b"", ""))


def ring_of(links: int, backend: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The single loop of ``links`` binary links (the one chain with no contracted
    graph), as a shard result."""
    canon, orbits = graph_form(links, [(i, (i + 1) % links) for i in range(links)],
                               backend=backend)
    return (np.array([canon], dtype=np.uint8), np.array([orbits], np.int32),
            np.array([False]))


# -- runners: where the tasks run --------------------------------------------------------
#: seconds to wait for a Dask scheduler to answer
CONNECT_TIMEOUT = 10.0


class DaskRunner:
    """A runner on a Dask distributed cluster: ``address`` of a running scheduler
    (``tcp://host:8786``), or ``"local"`` for an embedded LocalCluster of ``workers``
    single-threaded processes, waiting ``timeout`` seconds (default
    :data:`CONNECT_TIMEOUT`) for it to answer. Use as a context manager (it closes what
    it opened)."""

    def __init__(self, address, *, workers=1, timeout=None):
        timeout = CONNECT_TIMEOUT if timeout is None else timeout
        try:
            from distributed import Client, LocalCluster
        except ImportError as error:
            raise AtlasRunError(
                "a Dask scheduler needs Dask distributed: pip install 'chaingraph[cluster]'",
                reason="missing", parameter="scheduler") from error
        self.cluster = None
        try:
            if address == "local":
                self.cluster = LocalCluster(n_workers=max(1, workers), threads_per_worker=1,
                                            processes=True, dashboard_address=None)
                self.client = Client(self.cluster, timeout=timeout)
            else:
                self.client = Client(address, timeout=timeout)
        except (OSError, TimeoutError, ValueError) as error:
            if self.cluster is not None:
                self.cluster.close()
            raise AtlasRunError(f"cannot reach the Dask scheduler at {address}: "
                                f"{str(error).splitlines()[0] if str(error) else type(error).__name__}",
                                reason="unreachable") from None

    def __call__(self, fn: Callable[[Any], Any], tasks: Sequence[Any],
                 on_result: Callable[[int, Any], None]) -> None:
        from distributed import as_completed
        futures = self.client.map(fn, tasks, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        try:
            for future in as_completed(futures):
                on_result(index[future.key], future.result())
                future.release()
        except BaseException:
            self.client.cancel(futures)
            raise

    def close(self) -> None:
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


# -- the run -----------------------------------------------------------------------------
def _digest(links, dof, backend, jobs, shards):
    h = hashlib.sha256(json.dumps([links, dof, backend, jobs, shards]).encode())
    return h.hexdigest()[:16]


def run_atlas(links: int, dof: int = 1, *, workers: int = 1, runner: Runner | None = None,
              out: str | os.PathLike[str] | None = None, resume: bool = False,
              backend: str | None = None,
              progress: Callable[[float, str], None] | None = None, keep: bool = True
              ) -> Atlas:
    """Enumerate the atlas, stage by stage; see the module's description.

    Parameters
    ----------
    links, dof : int
    workers : int
        Local processes (ignored when ``runner`` is given).
    runner : callable, optional
        ``runner(fn, tasks, on_result)``: where the tasks run (:func:`process_runner`,
        :class:`DaskRunner`).
    out : path, optional
        Folder for the shards (``out/shards``) and the plan (``out/run.json``).
    resume : bool
        Take the shards already in ``out`` instead of computing them again (the folder
        must hold a run of the same size).
    progress : callable, optional
        ``progress(fraction_done, text)``, at each stage and finished shard.
    keep : bool
        Keep the chains' link graphs (False: counts only, for sizes too large to hold).

    Returns
    -------
    Atlas
    """
    backend = backend or default_backend()
    joints = joints_for(links, dof)
    if out is not None and str(out) == "":
        raise AtlasRunError("out is an empty path: give the folder to write the run into",
                            reason="out", parameter="out")
    runner = runner or process_runner(workers)
    say = progress or (lambda fraction, text: None)
    shard_dir = Path(out) / "shards" if out is not None else None
    state_path = Path(out) / "run.json" if out is not None else None
    stored = _read_state(state_path, links, dof, backend) if resume else None
    if resume and out is None:
        raise AtlasRunError("resuming needs the output folder of the run (out)",
                            reason="resume", parameter="out")
    say(0.0, "plan: contracted graphs")
    if stored:
        jobs = [(tuple(d), tuple(tuple(e) for e in edges), b) for d, edges, b in stored["jobs"]]
    else:
        jobs = plan(links, dof, backend=backend, runner=runner)
    shards, work = _shards(jobs)
    digest = _digest(links, dof, backend, jobs, shards)
    if stored and stored["digest"] != digest:
        raise AtlasRunError(f"{state_path}: the run there was cut differently; start it "
                            "again without resuming", reason="resume", parameter="resume")
    if shard_dir is not None:
        shard_dir.mkdir(parents=True, exist_ok=True)
        if not stored:
            _start_folder(shard_dir, state_path, {
                "links": links, "dof": dof, "labelling": backend, "digest": digest,
                "shards": len(shards), "pieces": len(jobs), "jobs": jobs})
    run = _Run(shards, [sum(work[a:b]) for a, b in shards], shard_dir, keep, say)
    run.take_done(joints if resume else None)
    encode = shard_dir is not None
    runner(_shard_task, [(jobs[slice(*shards[s])], links, joints, backend, encode)
                         for s in run.todo], run.finished)
    parts = ([ring_of(links, backend)] if links == dof + 3 else []) + run.results
    return _gathered(links, dof, joints, backend, parts, keep=keep)


def _start_folder(shard_dir, state_path, state):
    """A new run in ``shard_dir``: the shards of an earlier one removed, the plan
    (``state``) written to ``state_path``."""
    for old in shard_dir.glob("shard-*"):
        old.unlink()
    write_atomic(state_path, json.dumps(state))


class _Run:
    """The shards of a run as they finish: ``results`` in plan order (counts only
    unless ``keep``), ``todo`` the shards still to run, each finished one written to
    ``shard_dir`` (if any) and its progress said."""

    def __init__(self, shards, shard_work, shard_dir, keep, say):
        self.shards, self.shard_work, self.shard_dir = shards, shard_work, shard_dir
        self.keep, self.say = keep, say
        self.total = sum(shard_work) or 1
        self.results = [None] * len(shards)
        self.counts = {"chains": 0, "done": 0, "work": 0}
        self.todo = []

    def take_done(self, joints):
        """Take the shards already written (when resuming: ``joints`` given); the others
        are to do."""
        counts = self.counts
        for s in range(len(self.shards)):
            if joints is not None and self.shard_dir is not None \
                    and _shard_done(self.shard_dir, s):
                found = _read_shard(self.shard_dir, s, joints)
                self.results[s] = found if self.keep else _counts(found)
                counts["chains"] += len(found[1])
                counts["done"] += 1
                counts["work"] += self.shard_work[s]
            else:
                self.todo.append(s)
        if counts["done"]:
            self.say(counts["work"] / self.total,
                     f"{counts['done']} of {len(self.shards)} shards already done")

    def finished(self, i, result):
        """Task ``i`` (of ``todo``) came back with ``result``."""
        s, counts = self.todo[i], self.counts
        if self.shard_dir is not None:
            _write_shard(self.shard_dir, s, result)
        self.results[s] = result[:3] if self.keep else _counts(result[:3])
        counts["done"] += 1
        counts["work"] += self.shard_work[s]
        counts["chains"] += len(result[1])
        self.say(counts["work"] / self.total, f"shard {counts['done']}/{len(self.shards)}, "
                                              f"{counts['chains']:,} chains")


def _gathered(links, dof, joints, backend, parts, *, keep):
    """The atlas from its parts in plan order (the counts alone unless ``keep``)."""
    if not keep:
        return AtlasCounts(links, dof, [p if isinstance(p[0], int) else _counts(p)
                                        for p in parts], labelling=backend)
    return Atlas(links, dof,
                 np.concatenate([p[0] for p in parts]) if parts else np.zeros((0, joints, 2), np.uint8),
                 np.concatenate([p[1] for p in parts]) if parts else np.zeros(0, np.int32),
                 np.concatenate([p[2] for p in parts]) if parts else np.zeros(0, bool),
                 labelling=backend)


class AtlasCounts:
    """The counts of an atlas whose chains were not kept in memory."""

    def __init__(self, links, dof, parts, *, labelling="nauty"):
        self.links, self.dof, self.labelling = links, dof, labelling
        self.count = sum(p[0] for p in parts)
        self.count_non_fractionated = sum(p[1] for p in parts)
        self.distinct_inversions = sum(p[2] for p in parts)
        self.distinct_inversions_non_fractionated = sum(p[3] for p in parts)

    def __len__(self):
        return self.count


def _counts(result):
    edges, orbits, fractionated = result
    return (len(orbits), int(len(orbits) - fractionated.sum()), int(orbits.sum()),
            int(orbits[~fractionated].sum()))


# -- shards on disk ----------------------------------------------------------------------
def _shard_path(shard_dir, s, suffix):
    return shard_dir / f"shard-{s:05d}{suffix}"


def _shard_done(shard_dir, s):
    return _shard_path(shard_dir, s, ".jsonl").exists() and \
        _shard_path(shard_dir, s, ".g6").exists()


def _write_shard(shard_dir, s, result):
    """The shard's graph6 lines, then its JSON lines; the JSON lines file appears (by
    rename) only when both are complete: it marks the shard done."""
    write_atomic(_shard_path(shard_dir, s, ".g6"), result[3], encoding=None)
    write_atomic(_shard_path(shard_dir, s, ".jsonl"), result[4])


def _read_shard(shard_dir, s, joints):
    edges, orbits, fractionated = [], [], []
    with open(_shard_path(shard_dir, s, ".jsonl"), encoding="utf-8") as f:
        for line in f:
            d = json.loads(line)
            edges.append(d["edges"])
            orbits.append(d["inversion_classes"])
            fractionated.append(d["fractionated"])
    return (np.array(edges, dtype=np.uint8).reshape(len(edges), joints, 2),
            np.array(orbits, dtype=np.int32), np.array(fractionated, dtype=bool))


def _read_state(path, links, dof, backend):
    """The stored plan of a run to resume, checked against the size asked for."""
    if path is None:
        return None
    if not path.exists():
        raise AtlasRunError(f"{path.parent}: no run to resume there (no run.json)",
                            reason="resume")
    try:
        state = json.loads(path.read_text(encoding="utf-8"))
        size = (state["links"], state["dof"], state["labelling"])
    except (ValueError, KeyError, TypeError):
        raise AtlasRunError(f"{path}: not a run of chaingraph atlas", reason="resume") from None
    if size != (links, dof, backend):
        raise AtlasRunError(
            f"{path.parent} holds a run of {size[0]} links and {size[1]} dof "
            f"({size[2]} labelling), not {links} links and {dof} dof", reason="resume")
    return state

