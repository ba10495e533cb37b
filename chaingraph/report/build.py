"""The catalog report: a browsable HTML catalog with drawings, tables and motion.

This module runs the jobs: :func:`build_report` analyses and draws each entry in a
process of its own, builds the report aside and moves it into place, the index last
(``pages`` writes the HTML, ``player`` the animation player). It writes ``index.html``
(a table of every entry) and one page per entry: its link-joint graph, classification
with both textbook checks, inversions, and for a mechanism its drawn pose with the
paths of its points, the output's motion, the summary and an animation of one cycle
(an animated SVG); for a gear train, its drawing and speeds (``gears``) in place of
the skeleton and the motion. Pages and images are plain files that open from disk with no
network. A file that cannot be read or analysed is listed on the index as a failure and
the rest go on.
"""

from __future__ import annotations

import os
import re
import sys
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from collections.abc import Iterable
from typing import Any, TextIO

from chaingraph._util.atomic import staged, write_atomic
from chaingraph._util.parallel import process_runner
from chaingraph._util.progress import ProgressBar
from chaingraph.drawing.constructions import draw_centres, draw_polygons
from chaingraph.drawing.forces import (force_polygon_svg, free_body_svg, plot_shaking,
                                       plot_turning_moment)
from chaingraph.drawing.gears import train_svg
from chaingraph.drawing.graph import draw_link_joint_graph
from chaingraph.drawing.limits import limits_svg
from chaingraph.drawing.mechanism import mechanism_svg, skeleton_svg
from chaingraph.drawing.plots import plot_motion
from chaingraph.drawing.synthesis import draw_synthesis
from chaingraph.dynamics import PoseForces, SweepForces, forces
from chaingraph.errors import ChainGraphError
from chaingraph.files import load
from chaingraph.graphical.centres import InstantCentres, centres_of
from chaingraph.graphical.polygons import Polygons, polygons_of
from chaingraph.kinematics import Motion, solve
from chaingraph.kinematics.gears import is_gear_train
from chaingraph.kinematics.grid import input_grid
from chaingraph.kinematics.pose import pose_motion
from chaingraph.model.chain import Chain
from chaingraph.naming.inversion_classes import Inversions, inversions
from chaingraph.report.gears import TrainWay, train_fixed, train_ways
from chaingraph.report.pages import entry_page, index_page
from chaingraph.structure.classification import Classification, classify
from chaingraph.synthesis.function_generation import structural_error

__all__ = ["Report", "build_report", "chain_paths"]


@dataclass
class Entry:
    """One page of the report."""

    source: str
    slug: str
    chain: Chain
    classification: Classification
    inversions: Inversions | None = None
    motion: Motion | None = None
    error: str | None = None
    warnings: list[str] = field(default_factory=list)
    frames: int = 48
    grid: Motion | None = None         # two moving inputs: the poses over both, row by row
    centres: InstantCentres | None = None   # instantaneous centres at the drawn pose
    polygons: Polygons | None = None   # velocity and acceleration polygons at the drawn pose
    limits: bool = False               # a time ratio: its limit positions drawn
    forces: SweepForces | None = None  # with masses or loads: the forces over the sweep
    pose_forces: PoseForces | None = None   # and at the sweep's first pose (the free bodies)
    task: dict[str, Any] | None = None  # a synthesised mechanism's [task], drawn (task_drawing)
    train: str | None = None            # a gear train: its fixed link (report.gears)
    ways: list[TrainWay] = field(default_factory=list)   # and the ways it is run


@dataclass
class Report:
    """What :func:`build_report` wrote."""

    index: Path
    entries: list[Row]                  # one Row per chain file, in file order
    failures: list[tuple[str, str]]     # (path, problem)

    @property
    def complete(self) -> bool:
        """True when every chain file made its entry."""
        return not self.failures


def chain_paths(paths: Iterable[str | os.PathLike[str]]
                ) -> tuple[list[Path], list[tuple[str, str]]]:
    """The chain files named by ``paths`` (files, or folders of ``*.toml``), and the
    paths that are neither, as (files, problems)."""
    files, problems = [], []
    for p in paths:
        p = Path(p)
        if p.is_dir():
            found = sorted(p.glob("*.toml"))
            if not found:
                problems.append((str(p), "is a folder with no chain files (*.toml)"))
            files += found
        elif p.is_file():
            files.append(p)
        else:
            problems.append((str(p), "no such file or folder"))
    return files, problems


#: names the report itself uses: no entry may take them (a chain file called Index.toml
#: would otherwise overwrite the index, one called img.toml sit beside the image folder)
RESERVED = frozenset({"index", "img"})


def _slug(text: str, taken: set[str]) -> str:
    base = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "entry"
    slug, k = base, 2
    while slug in taken:
        slug, k = f"{base}-{k}", k + 1
    taken.add(slug)
    return slug


def build_report(paths: Iterable[str | os.PathLike[str]], out_dir: str | os.PathLike[str],
                 *, progress: TextIO | None = sys.stderr, steps: int = 180, frames: int = 48,
                 workers: int | None = None) -> Report:
    """Write the HTML catalog of the chain files ``paths`` into ``out_dir``.

    Parameters
    ----------
    paths : sequence of path
        Chain files or folders of them.
    out_dir : path
        Where ``index.html`` and the entry pages and images go (made if missing).
    progress : file, optional
        Where a progress bar goes (stderr by default; None for none).
    steps, frames : int
        Sweep steps of the motion plots, and frames of the animation.
    workers : int, optional
        Processes that analyse and draw entries side by side (default: one per CPU;
        1 works in this process).

    Returns
    -------
    Report
        ``failures`` lists (path, message) of what could not be done; ``complete`` is
        True when there are none.
    """
    if str(out_dir) == "":
        raise ValueError("out_dir is an empty path: give the folder to write the report into")
    cpus = os.cpu_count() or 1
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise ValueError(f"workers must be a whole number of 1 or more, got {workers!r}")
    out = Path(out_dir)
    files, problems = chain_paths(paths)
    failures = list(problems)
    taken = set(RESERVED)
    # built where nobody looks, then moved into place, the index last: an interrupted
    # report leaves the folder as it was (staged)
    with staged(out) as stage:
        (stage / "img").mkdir()
        jobs = [(str(path), _slug(path.stem, taken), str(stage), steps, frames)
                for path in files]
        workers = min(workers or cpus, cpus, max(len(jobs), 1))
        bar = ProgressBar(len(jobs), progress)
        bar.show(0, "")
        results = {}

        def finished(k, row):
            results[jobs[k][1]] = row
            done.append(k)
            bar.show(len(done), Path(jobs[k][0]).name)
        done: list[int] = []
        try:
            process_runner(workers)(_entry_job, jobs, finished)
        finally:
            bar.close()
        entries = [results[job[1]] for job in jobs]
        failures += [(e.source, e.error) for e in entries if e.error]
        write_atomic(stage / "index.html", index_page(entries, failures))
    return Report(index=out / "index.html", entries=entries, failures=failures)


@dataclass
class Row:
    """What the index needs of an entry (small, so that processes can send it back)."""

    source: str
    slug: str
    name: str = ""
    family: str = ""
    links: int = 0
    joint_equivalents: int = 0
    mobility: int = 0
    verdict: str = ""
    classes: int | None = None
    time_ratio: float | None = None
    picture: str = ""                   # its thumbnail: the skeleton, or a train's drawing
    error: str | None = None


def _entry_job(job: tuple[str, str, str, int, int]) -> Row:
    """Analyse one chain file and write its page and images; returns its index row."""
    source, slug, out, steps, frames = job
    row = Row(source=source, slug=slug)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            entry = _analyse(source, slug, steps)
            _write_images(entry, Path(out), frames)
            entry.frames = frames
        write_atomic(Path(out) / f"{slug}.html", entry_page(entry))
    except ChainGraphError as e:
        row.error = str(e)
        return row
    c = entry.classification
    row.name, row.family = entry.chain.name, entry.chain.family or ""
    row.picture = f"img/{slug}-{'train-front' if entry.train is not None else 'skeleton'}.svg"
    row.links, row.joint_equivalents = c.links, c.joint_equivalents
    row.mobility, row.verdict = c.mobility, c.verdict
    row.classes = entry.inversions.classes if entry.inversions is not None else None
    if entry.motion is not None and entry.motion.summary is not None:
        row.time_ratio = entry.motion.summary.time_ratio
    return row


def _analyse(source: str, slug: str, steps: int) -> Entry:
    chain = load(source)
    entry = Entry(source=source, slug=slug, chain=chain, classification=classify(chain))
    if len(chain.pieces) == 1:
        entry.inversions = inversions(chain)
    if is_gear_train(chain):            # its speeds, not a motion: no skeleton, no sweep
        entry.train = train_fixed(chain)
        entry.ways = train_ways(chain, fixed=entry.train)
        if not entry.ways:
            entry.warnings.append(f"speeds not found: no link driven at 1 rpm with "
                                  f"{entry.train} fixed (and a member held) settles the train")
        return entry
    m = chain.mechanism
    if m is not None and (m.driver is not None or m.inputs) and chain.has_pose:
        try:
            entry.motion = solve(chain, steps=steps)
        except ChainGraphError as e:
            entry.warnings.append(f"motion not solved: {e}")
        else:
            entry.grid = input_grid(chain, entry.motion)
            try:
                state = pose_motion(chain)
            except ChainGraphError as e:
                entry.warnings.append(f"centres and polygons not found: {e}")
            else:
                entry.centres, entry.polygons = centres_of(state), polygons_of(state)
            if chain.masses or chain.loads or chain.gravity:
                try:
                    entry.forces = forces(chain, steps=steps)
                    entry.pose_forces = entry.forces.pose(0)   # its first step, not solved again
                except ChainGraphError as e:
                    entry.warnings.append(f"forces not found: {e}")
            if chain.task:
                entry.task = _task_drawing(entry, chain.task)
    return entry


def _task_drawing(entry: Entry, task: dict[str, Any]) -> dict[str, Any] | None:
    """What a synthesised mechanism's [task] asks, as the synthesis draws it: the input's
    value at the drawn pose (its first target), the sweep, the targets or poses, and a
    function generator's structural error over its range (None where it cannot be
    worked out: the task is then only listed)."""
    try:                                    # a synthesis draws its file at the first target
        at = float(pose_motion(entry.chain).input)
    except ChainGraphError as e:
        entry.warnings.append(f"the task not drawn: {e}")
        return None
    drawn: dict[str, Any] = {"at": at, "sweep": None, "curve": None,
                             "targets": [tuple(p) for p in task.get("targets", ())],
                             "poses": [tuple(p) for p in task.get("poses", ())]}
    if task.get("kind") == "function":
        try:
            drawn["curve"] = structural_error(entry.chain)
        except ChainGraphError as e:
            entry.warnings.append(f"the task's structural error not found: {e}")
            return None
        t0 = float(task["start"][0])
        drawn["sweep"] = (t0, t0 + float(task["swing"][0]))
    return drawn


# -- images ----------------------------------------------------------------------------
def _write_images(entry: Entry, out: Path, frames: int) -> None:
    img = out / "img"
    draw_link_joint_graph(entry.chain, img / f"{entry.slug}-graph.svg")
    if entry.train is not None:
        for name, graph in (("train", True), ("train-front", False)):   # page, index
            (img / f"{entry.slug}-{name}.svg").write_text(
                train_svg(entry.chain, fixed=entry.train, graph=graph), encoding="utf-8")
        return
    (img / f"{entry.slug}-skeleton.svg").write_text(skeleton_svg(entry.chain), encoding="utf-8")
    if entry.motion is not None:
        (img / f"{entry.slug}-pose.svg").write_text(mechanism_svg(entry.motion),
                                                     encoding="utf-8")
        plot_motion(entry.motion, img / f"{entry.slug}-motion.svg")
        (img / f"{entry.slug}-cycle.svg").write_text(
            mechanism_svg(entry.motion, frames=frames), encoding="utf-8")
    if entry.motion is not None and entry.motion.summary is not None \
            and entry.motion.summary.time_ratio is not None:
        try:
            (img / f"{entry.slug}-limits.svg").write_text(limits_svg(entry.motion),
                                                          encoding="utf-8")
            entry.limits = True
        except ChainGraphError as e:
            entry.warnings.append(f"limit positions not drawn: {e}")
    if entry.pose_forces is not None:
        (img / f"{entry.slug}-free-bodies.svg").write_text(free_body_svg(entry.pose_forces),
                                                            encoding="utf-8")
        polygons = force_polygon_svg(entry.pose_forces)
        if polygons is not None:
            (img / f"{entry.slug}-force-polygons.svg").write_text(polygons, encoding="utf-8")
        if entry.forces is not None and len(entry.forces.inputs) == 1:
            plot_turning_moment(entry.forces, img / f"{entry.slug}-turning-moment.svg")
        if entry.forces is not None and entry.forces.shaking is not None:
            plot_shaking(entry.forces, img / f"{entry.slug}-shaking.svg")
    if entry.task is not None:
        draw_synthesis(entry.chain, **entry.task, title=entry.chain.name,
                       path=img / f"{entry.slug}-task.svg")
    if entry.centres is not None and entry.polygons is not None:
        draw_centres(entry.centres, img / f"{entry.slug}-centres.svg")
        draw_polygons(entry.polygons, img / f"{entry.slug}-polygons.svg")
