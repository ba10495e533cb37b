"""The command line's arguments: one parser, its commands and their flags."""

from __future__ import annotations

import argparse
from typing import NoReturn

from chaingraph import __version__
from chaingraph.structure.atlas.estimate import LOCAL_HOURS
from chaingraph.cli.cam import cmd_cam
from chaingraph.cli.commands import (
    cmd_assemble,
    cmd_atlas,
    cmd_centres,
    cmd_classify,
    cmd_design,
    cmd_design_function,
    cmd_design_path,
    cmd_design_motion,
    cmd_forces,
    cmd_identify,
    cmd_inversions,
    cmd_measure,
    cmd_polygons,
    cmd_report,
    cmd_solve,
    cmd_vary,
)

from chaingraph.cli.export import export_command
from chaingraph.cli.gears import gears_command
from chaingraph.cli.interchange import import_command
from chaingraph.cli.lint import lint_command

__all__ = ['build_parser', 'whole_number', 'path_argument']


class _Parser(argparse.ArgumentParser):
    """argparse, with a usage error as one line (``chaingraph COMMAND: error: ...``)."""

    def error(self, message: str) -> NoReturn:
        usage = " ".join(self.format_usage().split())
        self.exit(2, f"{self.prog}: error: {message} ({usage})\n")


def _inversion_arguments(p: argparse.ArgumentParser, *,
                         input_help: str = "an input joint; repeat it, one per degree of "
                                           "freedom") -> None:
    """--fixed, and --driver or --input: the inversion and its inputs, as solve takes them."""
    p.add_argument("--fixed", metavar="LINK", help="the fixed link")
    given = p.add_mutually_exclusive_group()
    given.add_argument("--driver", metavar="LINK",
                       help="the input link, pinned to the fixed link by an R joint")
    given.add_argument("--input", dest="inputs", action="append", metavar="JOINT",
                       help=input_help)


def _sweep_arguments(p: argparse.ArgumentParser, *,
                     first: str = "the first input's first value (degrees, or slide for "
                                  "a P input)",
                     last: str = "the first input's last value") -> None:
    """--from, --to and --steps: the sweep, as solve takes it."""
    p.add_argument("--from", dest="start", type=float, metavar="X", help=first)
    p.add_argument("--to", dest="stop", type=float, metavar="X", help=last)
    p.add_argument("--steps", type=whole_number, default=360, metavar="N",
                   help="equal intervals of the sweep (N + 1 rows; default 360)")

def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="chaingraph",
        description="Analyse planar kinematic chains as link-joint graphs.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for add in (_classify_command, _inversions_command, _identify_command,
                _solve_command, _vary_command, _forces_command,
                _centres_and_polygons_command, _assemble_command, _measure_command,
                _report_command, _atlas_command, _design_command, _cam_command):
        add(sub)
    gears_command(sub, path_argument)
    export_command(sub, path_argument, positive_number)
    import_command(sub, path_argument)
    lint_command(sub, path_argument)
    return parser


def _classify_command(sub) -> None:
    """The arguments of ``chaingraph classify``."""
    p = sub.add_parser("classify", help="structural classification of chain files",
                       description="Counts, orders, loops, Kutzbach mobility, the textbook "
                                   "checks and degeneracy of each chain file.")
    p.add_argument("files", nargs="+", type=path_argument, metavar="FILE",
                   help="chain files (TOML)")
    p.add_argument("--json", action="store_true", help="print JSON (a list for several files)")
    p.set_defaults(run=cmd_classify)


def _inversions_command(sub) -> None:
    """The arguments of ``chaingraph inversions``."""
    p = sub.add_parser("inversions", help="inversions: fix each link in turn",
                       description="One inversion per link, grouped into classes by the "
                                   "chain's automorphisms, named from the catalog, with "
                                   "their behaviour where the file has dimensions.")
    p.add_argument("file", type=path_argument, metavar="FILE", help="a chain file (TOML)")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--with-input", action="store_true",
                   help="also designate the input link (joined to the fixed link by an R joint)")
    p.set_defaults(run=cmd_inversions)


def _identify_command(sub) -> None:
    """The arguments of ``chaingraph identify``."""
    p = sub.add_parser("identify", help="which catalog chain (and inversion) a file is",
                       description="Find the file's chain in the catalog by structure and, "
                                   "for a mechanism, which catalog inversion it is.")
    p.add_argument("file", type=path_argument, metavar="FILE", help="a chain file (TOML)")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(run=cmd_identify)


def _solve_command(sub) -> None:
    """The arguments of ``chaingraph solve``."""
    p = sub.add_parser("solve", help="position, velocity and acceleration over an input sweep",
                       description="Solve the mechanism (the file's [mechanism], or the "
                                   "inversion --fixed and --driver or --input choose) over the "
                                   "input sweep, in the assembly mode of the drawn pose.")
    p.add_argument("file", type=path_argument, metavar="FILE",
                   help="a mechanism file (TOML) with a drawn pose")
    _inversion_arguments(p, input_help="an input joint (R or P, between any two links); "
                                       "repeat it, one per degree of freedom")
    _sweep_arguments(p)
    p.add_argument("--output", metavar="NAME",
                   help="the summary's output instead of the file's: a link, a point or "
                        "a joint")
    p.add_argument("--json", action="store_true", help="print the JSON summary")
    p.add_argument("--csv", type=path_argument, metavar="PATH",
                   help="write every column of every step")
    p.add_argument("--plot", type=path_argument, metavar="PATH.svg",
                   help="plot the output's displacement, velocity and acceleration")
    p.add_argument("--draw", type=path_argument, metavar="PATH.svg",
                   help="draw the mechanism in its drawn pose with the paths of its points")
    p.add_argument("--limits", type=path_argument, metavar="PATH.svg",
                   help="draw the limit positions: the two extreme poses of the output, the "
                        "input's arcs between them with their angles, the stroke")
    p.set_defaults(run=cmd_solve)


def _vary_command(sub) -> None:
    """The arguments of ``chaingraph vary``."""
    p = sub.add_parser("vary", help="the summary over the values of one link's length",
                       description="Solve the mechanism once per value of one link's length "
                                   "(the rest of its dimensions and its assembly modes kept) "
                                   "and tabulate the summary: time ratio, stroke, "
                                   "transmission angle, range. A value where it cannot be "
                                   "assembled is a row that says so.")
    p.add_argument("file", type=path_argument, metavar="FILE",
                   help="a mechanism file (TOML) with dimensions")
    p.add_argument("--length", required=True, metavar="LINK=FROM:TO:STEP",
                   help="the link and its lengths: FROM, FROM + STEP, ... up to TO")
    p.add_argument("--steps", type=whole_number, default=360, metavar="N",
                   help="the sweep's intervals for each value (default 360)")
    p.add_argument("--output", metavar="NAME", help="the summary's output instead of the file's")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--plot", type=path_argument, metavar="PATH",
                   help="plot the time ratio and stroke")
    p.set_defaults(run=cmd_vary)


def _forces_command(sub) -> None:
    """The arguments of ``chaingraph forces``."""
    p = sub.add_parser("forces", help="joint reactions and input efforts, static or "
                                      "kinetostatic",
                       description="The force that each joint carries and the effort each "
                                   "input needs, from the file's masses ([[links]]), "
                                   "gravity ([forces]), loads ([[loads]]) and friction, at "
                                   "one pose (--at) or over the sweep of solve; kinetostatic "
                                   "(with the links' inertia at the input speed) unless "
                                   "--static.")
    p.add_argument("file", type=path_argument, metavar="FILE",
                   help="a mechanism file (TOML) with units and masses "
                                               "or loads")
    _inversion_arguments(p)
    p.add_argument("--at", action="append", type=float, metavar="X",
                   help="one pose: the input value (degrees, or slide for a P input); with "
                        "several inputs the first's value, or repeat it, one per input")
    _sweep_arguments(p, first="the first input's first value of the sweep",
                     last="the first input's last value of the sweep")
    p.add_argument("--omega", type=float, metavar="W",
                   help="the (first) input's speed (default: the file's, else 1)")
    p.add_argument("--static", action="store_true", help="leave out the links' inertia")
    p.add_argument("--speed-fluctuation", dest="speed_fluctuation", type=float, metavar="CS",
                   help="for a crank turning fully: the flywheel inertia that holds the "
                        "speed within this coefficient of fluctuation")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--csv", type=path_argument, metavar="PATH",
                   help="write every column of every step")
    p.add_argument("--draw", type=path_argument, metavar="PATH.svg",
                   help="draw the free bodies at the pose (--at; else the sweep's first)")
    p.add_argument("--plot", type=path_argument, metavar="PATH.svg",
                   help="plot each input's effort over the sweep (a crank's: the "
                        "turning-moment diagram)")
    p.add_argument("--polygon", type=path_argument, metavar="PATH.svg",
                   help="draw the force polygon of each dyad at the pose of --draw")
    p.add_argument("--polar", type=path_argument, metavar="PATH.svg",
                   help="plot the polar diagram of the shaking force over the sweep")
    p.add_argument("--balance", action="store_true",
                   help="counterweights that cancel a four-bar's shaking force or a slider "
                        "crank's primary force, and what remains (a sweep)")
    p.set_defaults(run=cmd_forces)


def _centres_and_polygons_command(sub) -> None:
    """The arguments of centres and polygons: one input value, a construction."""
    for name, run, helptext, description in (
            ("centres", cmd_centres, "instantaneous centres (Kennedy's theorem)",
             "Every instantaneous centre of the mechanism at one input value: the primary "
             "ones from the joints, the others by Kennedy's theorem (the three centres of "
             "three links lie on one line), each with its position (or direction at "
             "infinity) and how it was found; the angular velocities through them."),
            ("polygons", cmd_polygons, "velocity and acceleration polygons",
             "The velocity and acceleration polygons of the mechanism at one input value: "
             "every point's image and the relative vectors, with their centripetal, "
             "tangential, sliding and Coriolis components.")):
        p = sub.add_parser(name, help=helptext, description=description)
        p.add_argument("file", type=path_argument, metavar="FILE",
                       help="a mechanism file (TOML) with dimensions")
        p.add_argument("--at", action="append", type=float, metavar="X",
                       help="the input value (degrees, or slide for a P input; default: "
                            "the drawn pose); with several inputs the first's value, or "
                            "repeat it, one per input")
        _inversion_arguments(p)
        p.add_argument("--omega", type=float, metavar="W",
                       help="the (first) input's speed (default: the file's, else 1)")
        p.add_argument("--json", action="store_true", help="print JSON")
        p.add_argument("--draw", type=path_argument, metavar="PATH.svg",
                       help="draw the construction")
        p.set_defaults(run=run)


def _assemble_command(sub) -> None:
    """The arguments of ``chaingraph assemble``."""
    p = sub.add_parser("assemble", help="the drawn pose of a mechanism given by its lengths",
                       description="Find every joint's position from the file's lengths, the "
                                   "input's value and the assembly modes, and write the "
                                   "mechanism with coordinates (to standard output, or OUT). "
                                   "The modes used are listed, with where each came from.")
    p.add_argument("file", type=path_argument, metavar="FILE",
                   help="a mechanism file (TOML) with [lengths]")
    p.add_argument("-o", "--output", type=path_argument, metavar="OUT",
                   help="write the assembled file here")
    p.add_argument("--json", action="store_true",
                   help="print the positions and the assembly modes as JSON")
    p.set_defaults(run=cmd_assemble)


def _measure_command(sub) -> None:
    """The arguments of ``chaingraph measure``."""
    p = sub.add_parser("measure", help="the lengths of a drawn mechanism",
                       description="Write a drawn mechanism as its dimensions: the lengths "
                                   "of its links, its sliding lines, the input's value and "
                                   "every assembly mode (the inverse of assemble).")
    p.add_argument("file", type=path_argument, metavar="FILE",
                   help="a mechanism file (TOML) with a drawn pose")
    p.add_argument("-o", "--output", type=path_argument, metavar="OUT",
                   help="write the file with lengths here")
    p.set_defaults(run=cmd_measure)


def _report_command(sub) -> None:
    """The arguments of ``chaingraph report``."""
    p = sub.add_parser("report", help="the browsable HTML catalog",
                       description="Write DIR/index.html and a page per entry for the given "
                                   "chain files or folders (by default the bundled catalog). "
                                   "Files that fail are listed and the rest go on (exit 1).")
    p.add_argument("paths", nargs="*", type=path_argument, metavar="PATH",
                   help="chain files or folders")
    p.add_argument("-o", "--output", default="report", type=path_argument, metavar="DIR",
                   help="output folder (default: report)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.add_argument("--workers", type=int, metavar="K",
                   help="processes that analyse entries side by side (default and at most: "
                        "the CPUs)")
    p.set_defaults(run=cmd_report)


def _atlas_command(sub) -> None:
    """The arguments of ``chaingraph atlas``."""
    p = sub.add_parser("atlas", help="every chain of N links and F degrees of freedom",
                       description="Every non-isomorphic, non-degenerate planar chain with "
                                   "simple revolute joints (non-planar link graphs and "
                                   "fractionated chains included). Sizes estimated to take "
                                   "over an hour here (--max-hours) are refused with the "
                                   "estimate.")
    p.add_argument("--links", type=int, required=True, metavar="N")
    p.add_argument("--dof", type=int, default=1, metavar="F")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--summary", action="store_true",
                   help="print the counts alone (JSON without the chains)")
    p.add_argument("--no-fractionated", action="store_true",
                   help="keep only the non-fractionated chains")
    p.add_argument("--out", type=path_argument, metavar="DIR",
                   help="write atlas.json, a graph6 file, index.html and (up to 10,000 "
                        "chains) chain files, with the run's shards under DIR/shards")
    files = p.add_mutually_exclusive_group()
    files.add_argument("--chain-files", dest="chain_files", action="store_true",
                       default=None, help="write one chain file per chain whatever the size")
    files.add_argument("--no-chain-files", dest="chain_files", action="store_false",
                       help="write no chain files")
    p.add_argument("--workers", type=int, default=1, metavar="K",
                   help="local processes that run the pieces side by side (at most the "
                        "CPUs); with --scheduler local, the embedded cluster's workers")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the pieces on a Dask cluster (tcp://host:8786), or 'local' "
                        "for an embedded one (pip install 'chaingraph[cluster]')")
    p.add_argument("--resume", action="store_true",
                   help="continue an interrupted run in its --out folder")
    p.add_argument("--prismatic", type=prismatic_count, metavar="K",
                   help="chains whose joints are K sliding pairs and the rest turning pairs "
                        "('all': every K together)")
    p.add_argument("--oriented", action="store_true",
                   help="with --prismatic: which link of a sliding pair carries its guide "
                        "tells chains apart")
    p.add_argument("--multiple", action="store_true",
                   help="turning pairs may join three links or more (a joint of d links "
                        "counts as d - 1); with --prismatic, only simple joints slide")
    p.add_argument("--gears", action="store_true",
                   help="the epicyclic gear trains of N links and F degrees of freedom "
                        "(graphs of turning and gear pairs, each gear pair with its "
                        "carrier) instead of the chains of turning pairs")
    p.add_argument("--illustrate", action="store_true",
                   help="with --out and --prismatic or --multiple: draw and animate every "
                        "chain whatever the size (by default drawn up to 8 links, and "
                        "animated where that is estimated to take at most an hour on the "
                        "workers)")
    p.add_argument("--max-hours", dest="max_hours", type=positive_number, default=LOCAL_HOURS,
                   metavar="H",
                   help=f"run what is estimated to take up to H hours on the workers "
                        f"(default {LOCAL_HOURS:g}); longer runs are refused with the estimate")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=cmd_atlas)


def _cam_command(sub) -> None:
    """The arguments of ``chaingraph cam``."""
    p = sub.add_parser("cam", help="a disc cam and its follower over a turn",
                       description="The follower's displacement, velocity, acceleration and "
                                   "jerk over a turn of the cam ([[cams]] in the file), the "
                                   "pressure angle, the profile by the envelope of the "
                                   "follower's positions, its smallest radius of curvature "
                                   "and the undercut check.")
    p.add_argument("file", type=path_argument, metavar="FILE", help="a chain file with [[cams]]")
    p.add_argument("--cam", dest="cam_id", metavar="ID",
                   help="the cam's id (needed when the file has several)")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--csv", type=path_argument, metavar="PATH",
                   help="write the motion, pressure angle, pitch curve and profile, one row "
                        "per step")
    p.add_argument("--draw", type=path_argument, metavar="PATH.svg",
                   help="draw the profile with the follower at --at")
    p.add_argument("--at", type=float, default=0.0, metavar="DEG",
                   help="the cam's angle for --draw (degrees, default 0)")
    p.add_argument("--plot", type=path_argument, metavar="PATH.svg",
                   help="plot displacement, velocity, acceleration and jerk over a turn")
    p.add_argument("--max-pressure-angle", dest="max_pressure", type=float, metavar="DEG",
                   help="also find the smallest base circle that keeps the pressure angle "
                        "under DEG")
    p.add_argument("--steps", type=whole_number, default=360, metavar="N",
                   help="equal steps of the turn in the CSV (N + 1 rows; default 360)")
    p.set_defaults(run=cmd_cam)


def _design_command(sub) -> None:
    """The arguments of ``chaingraph design``: a parser per kind of design."""
    p = sub.add_parser("design", help="dimensional synthesis: quick return drives, "
                                      "function generators",
                       description="Dimensional synthesis: quick return drives from a time "
                                   "ratio, crank and stroke; function generators from a "
                                   "function (every solution certified by the solver).")
    kinds = p.add_subparsers(dest="kind", required=True, metavar="KIND",
                             parser_class=_Parser)
    for kind, where in (("slotted-lever", "the ram's line through the lever end's extremes"),
                        ("whitworth", "the ram's line through the lever's pivot")):
        q = kinds.add_parser(kind, help=f"a quick return drive ({where})",
                             description="From a time ratio, crank and stroke to the centre "
                                         f"distance and lever ({where}).")
        q.add_argument("--time-ratio", type=float, required=True, metavar="R")
        q.add_argument("--crank", type=float, required=True, metavar="C")
        q.add_argument("--stroke", type=float, required=True, metavar="S")
        q.add_argument("--json", action="store_true", help="print JSON")
        q.add_argument("--out", type=path_argument, metavar="FILE",
                       help="write the designed mechanism (TOML)")
        q.set_defaults(run=cmd_design)
    _design_function_command(kinds)
    _design_path_command(kinds)
    _design_motion_command(kinds)


def _design_function_command(kinds) -> None:
    """The arguments of ``chaingraph design function``."""
    q = kinds.add_parser(
        "function", help="a function generator (four-bar or slider crank)",
        description="A four-bar (input crank, output rocker) or slider crank (input crank, "
                    "output slide) whose output follows y = EXPR(x): three precision points "
                    "exactly (Freudenstein's equation), more fitted over the whole range; "
                    "every solution certified by the solver from its written chain file.")
    q.add_argument("--function", required=True, metavar="EXPR",
                   help="y in x: + - * / **, sqrt exp log log10 sin cos tan (radians), pi")
    q.add_argument("--x", required=True, type=pair_argument, metavar="A:B",
                   help="the range of x")
    q.add_argument("--swing", required=True, type=pair_argument, metavar="IN:OUT",
                   help="the input's turn (degrees) and the output's (degrees, or a "
                        "slide's travel in file units) over the range")
    q.add_argument("--start", type=pair_argument, metavar="IN0:OUT0",
                   help="the input's and output's values at x = A (default: searched)")
    q.add_argument("--points", type=int, default=3, metavar="N",
                   help="precision points (default 3, matched exactly; more are fitted)")
    q.add_argument("--spacing", default="chebyshev", metavar="chebyshev|even",
                   help="the precision points' spacing (default chebyshev)")
    q.add_argument("--kind", dest="mechanism", default="four-bar",
                   metavar="four-bar|slider-crank", help="the mechanism (default four-bar)")
    _synthesis_arguments(q)
    q.set_defaults(run=cmd_design_function)


def _design_path_command(kinds) -> None:
    """The arguments of ``chaingraph design path``."""
    q = kinds.add_parser(
        "path", help="a path generator (four-bar): a coupler point through points",
        description="A four-bar whose coupler point passes through the points in order: up "
                    "to five exactly (least squares from a coarse search), more or a closed "
                    "curve fitted (differential evolution, then least squares); every "
                    "solution certified by the solver from its written chain file.")
    given = q.add_mutually_exclusive_group(required=True)
    given.add_argument("--points", type=points_argument, metavar='"X,Y; X,Y; ..."',
                       help="the targets, in order")
    given.add_argument("--points-file", dest="points_file", type=path_argument,
                       metavar="CSV", help="the targets, one x,y per line (a header line "
                                           "allowed)")
    q.add_argument("--timing", type=numbers_argument, metavar='"DEG; DEG; ..."',
                   help="the input's value at each target (its turn between targets is "
                        "kept; its value at the first is chosen; a sliding input's: its "
                        "slide, in file units)")
    q.add_argument("--closed", action="store_true",
                   help="the targets lie on a closed curve traced over a full turn")
    q.add_argument("--seed", type=int, metavar="S",
                   help="the random search's seed (the same seed, the same solutions)")
    _type_arguments(q)
    _synthesis_arguments(q)
    q.set_defaults(run=cmd_design_path)


def _type_arguments(q) -> None:
    """The options of type synthesis through the atlas (design path and motion)."""
    q.add_argument("--links", type=int, default=4, metavar="4|6|8",
                   help="the mechanism's links: 4 the four-bar (default); 6 or 8 every "
                        "1-dof chain of that size in the atlas, every inversion and every "
                        "link that can carry the point or pose")
    q.add_argument("--prismatic", type=prismatic_count, metavar="K|all",
                   help="chains with K sliding pairs ('all': any), searched through the "
                        "atlas (with --links 4: the slider-crank chains)")
    q.add_argument("--workers", type=int, default=1, metavar="K",
                   help="with --links 6 or 8: local processes that search the families "
                        "side by side (at most the CPUs); with --scheduler local, the "
                        "embedded cluster's workers")
    q.add_argument("--scheduler", metavar="ADDRESS",
                   help="with --links 6 or 8: search on a Dask cluster (tcp://host:8786), "
                        "or 'local' for an embedded one (pip install 'chaingraph[cluster]')")


def points_argument(text: str) -> list[tuple[float, float]]:
    """Points written "X,Y; X,Y; ..." (the library checks that they are finite)."""
    try:
        return [(x, y) for x, y in _number_rows(text, 2)]
    except _BadRow as e:
        raise argparse.ArgumentTypeError(f"point {e.row} is not two numbers X,Y: "
                                         f"{e.part!r}") from None


def numbers_argument(text: str) -> list[float]:
    """Numbers written "A; B; ..." (the library checks them)."""
    out = []
    for k, part in enumerate(text.split(";"), 1):
        try:
            out.append(float(part))
        except ValueError:
            raise argparse.ArgumentTypeError(f"value {k} is not a number: "
                                             f"{part.strip()!r}") from None
    return out


def _design_motion_command(kinds) -> None:
    """The arguments of ``chaingraph design motion``."""
    q = kinds.add_parser(
        "motion", help="a motion generator (four-bar or slider crank; with --links 6 or 8 "
                       "any chain of the atlas) through 2 to 5 poses",
        description="A four-bar or slider crank whose coupler passes through the poses in "
                    "order: two and three poses by the classical constructions, four and "
                    "five by Burmester theory; every pair of dyads tried, each driving. "
                    "With --links 6 or 8, every chain of that size, inversion and link "
                    "that can carry the pose, searched by the path optimiser. Every "
                    "solution certified by the solver from its written chain file.")
    q.add_argument("--poses", required=True, type=poses_argument, metavar='"X,Y,DEG; ..."',
                   help="the coupler's poses in order: its point P at X,Y and its angle DEG")
    q.add_argument("--seed", type=int, metavar="S",
                   help="with --links 6 or 8: the random search's seed (the same seed, the "
                        "same solutions)")
    _type_arguments(q)
    _synthesis_arguments(q)
    q.set_defaults(run=cmd_design_motion)


def poses_argument(text: str) -> list[tuple[float, float, float]]:
    """Poses written X,Y,DEG; X,Y,DEG; ... (the library checks that they are finite)."""
    try:
        return [(x, y, a) for x, y, a in _number_rows(text, 3)]
    except _BadRow as e:
        raise argparse.ArgumentTypeError(f"poses X,Y,DEG; X,Y,DEG; ..., got {e.part!r} "
                                         f"in {text!r}") from None


class _BadRow(ValueError):
    """Row ``row`` (from 1) of a "A,B; A,B; ..." option, ``part``, is not its numbers."""

    def __init__(self, row: int, part: str) -> None:
        super().__init__(row, part)
        self.row, self.part = row, part


def _number_rows(text: str, width: int) -> list[tuple[float, ...]]:
    """Rows of ``width`` numbers written "A,B; A,B; ..." (a trailing ';' allowed)."""
    parts = text.split(";")
    if len(parts) > 1 and not parts[-1].strip():
        parts.pop()
    rows = []
    for k, part in enumerate(parts, 1):
        fields = part.split(",")
        try:
            if len(fields) != width:
                raise ValueError
            rows.append(tuple(float(f) for f in fields))
        except ValueError:
            raise _BadRow(k, part.strip()) from None
    return rows


def _synthesis_arguments(q) -> None:
    """The options every synthesis takes."""
    q.add_argument("--solutions", type=int, default=5, metavar="K",
                   help="list at most K certified solutions (default 5)")
    q.add_argument("--units", default="mm", metavar="U", help="length unit (default mm)")
    q.add_argument("--min-transmission", dest="min_transmission", type=float, default=30.0,
                   metavar="DEG", help="the transmission angle stays within [DEG, 180 - DEG] "
                                       "between the first target and the last (default 30)")
    q.add_argument("--json", action="store_true", help="print JSON")
    q.add_argument("--out", type=path_argument, metavar="DIR",
                   help="write solution-K.toml for each solution")
    q.add_argument("--draw", type=path_argument, metavar="PATH.svg",
                   help="draw the best solution and its error (SVG)")


def _version() -> str:
    return __version__

def prismatic_count(text: str) -> int | str:
    """--prismatic: a whole number of sliding pairs, 0 or more, or 'all'."""
    if text == "all":
        return text
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"a number of sliding pairs or 'all', got {text!r}") \
            from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"a number of sliding pairs is 0 or more, got {value}")
    return value


def path_argument(text: str) -> str:
    """A file or folder named on the command line: not empty (an empty path names
    nothing, and a folder made from it would be the current one)."""
    if text == "":
        raise argparse.ArgumentTypeError("an empty path names no file or folder")
    return text


def positive_number(text: str) -> float:
    """An option's finite number above 0 (a number of hours)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid number: {text!r}") from None
    if not (value > 0 and value < float("inf")):
        raise argparse.ArgumentTypeError(f"must be a number above 0, got {text}")
    return value


def pair_argument(text: str) -> tuple[float, float]:
    """Two numbers written A:B (the library checks that they are finite)."""
    parts = text.split(":")
    try:
        if len(parts) != 2:
            raise ValueError
        return float(parts[0]), float(parts[1])
    except ValueError:
        raise argparse.ArgumentTypeError(f"two numbers A:B, got {text!r}") from None


def whole_number(text: str) -> int:
    """An option's whole number of 1 or more (a number of steps)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid int value: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be 1 or more, got {value}")
    return value
