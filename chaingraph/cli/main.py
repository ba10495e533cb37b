"""The ``chaingraph`` command line.

Exit status: 0 on success, 2 on bad input (the message names the file, joint or key),
1 when the analysis fails (for example a mechanism that cannot be assembled). Errors
are printed as one line on stderr, without a traceback.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
import warnings
from pathlib import Path

from chaingraph import __version__
from chaingraph._util.progress import ProgressBar
from chaingraph.drawing.constructions import draw_centres, draw_polygons
from chaingraph.drawing.mechanism import mechanism_svg
from chaingraph.drawing.plots import (
    draw_mechanism,  # PNG and the other raster formats
    plot_motion,
)
from chaingraph.errors import AssemblyError, ChainGraphError, ChainGraphWarning, OutputError
from chaingraph.files import dumps, load, read_file, save
from chaingraph.graphical import instant_centres, velocity_polygon
from chaingraph.kinematics import solve, summary_rows
from chaingraph.kinematics.assembly import measure
from chaingraph.naming.catalog import catalog_dir
from chaingraph.naming.identify import identify
from chaingraph.naming.inversions import inversions
from chaingraph.report.build import build_report
from chaingraph.structure.atlas import (
    DaskRunner,
    atlas_dict,
    process_runner,
    run_atlas,
    write_atlas,
)
from chaingraph.structure.atlas.contracted import joints_for
from chaingraph.structure.atlas.estimate import check_size
from chaingraph.structure.classify import classify
from chaingraph.synthesis.design import KINDS

__all__ = ["main"]


def _print_json(obj) -> None:
    print(json.dumps(obj, indent=2, ensure_ascii=False))


def _table(rows, header) -> str:
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    fmt = lambda r: "  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip()  # noqa: E731
    return "\n".join([fmt(header), fmt(["-" * w for w in widths]), *map(fmt, rows)])


def _classification_text(result, source) -> str:
    rows = [list(row) for row in result.rows()]
    head = f"{result.name}  ({source})"
    body = _table(rows, ["", "", ""]).split("\n", 2)[2]
    lines = [head, body]
    lines += [f"note: {o}" for o in result.oddities if not o.startswith("degenerate")]
    return "\n".join(lines)


def _cmd_classify(args) -> int:
    results, failed = [], 0
    for path in args.files:
        try:
            results.append((path, classify(load(path))))
        except ChainGraphError as e:
            print(f"chaingraph: error: {error_text(e)}", file=sys.stderr)
            failed = exit_status(e) if not failed else failed
    if args.json and results:
        objs = [r.to_dict() for _, r in results]
        _print_json(objs[0] if len(args.files) == 1 else objs)
    elif len(results) == 1 and len(args.files) == 1:
        print(_classification_text(results[0][1], results[0][0]))
    elif results:
        rows = [[r.name, r.links, r.pairs, r.joint_equivalents, r.higher_pairs, r.loops,
                 r.mobility, c2.verdict or "n/a", r.check("J + H/2 = 3L/2 - 2").verdict,
                 r.verdict, "yes" if r.degenerate else "no"]
                for _, r in results for c2 in [r.check("L = 2P - 4")]]
        print(_table(rows, ["chain", "L", "P", "J", "H", "loops", "F", "L = 2P - 4",
                            "J + H/2 = 3L/2 - 2", "verdict", "degenerate"]))
    return failed


def _cmd_inversions(args) -> int:
    result = inversions(load(args.file), with_input=args.with_input)
    if args.json:
        _print_json(result.to_dict())
        return 0
    plural = "class" if result.classes == 1 else "classes"
    print(f"{result.name}: {result.links} links, {len(result.inversions)} inversions "
          f"in {result.classes} {plural} by structure")
    header, *rows = result.rows()
    print(_table([list(r) for r in rows], list(header)))
    if args.with_input:
        print(f"classes with a designated input: {result.classes_with_input}")
    for inv in result.inversions:
        if inv.note:
            print(f"{inv.fixed} fixed: {inv.note}")
    return 0


def _cmd_identify(args) -> int:
    chain = load(args.file)
    found = identify(chain)
    if args.json:
        _print_json(found.to_dict())
        return 0
    where = lambda path: f"  ({path})" if path else ""  # noqa: E731
    print(f"chain:     {found.chain or 'not in the catalog'}{where(found.chain_file)}")
    if chain.mechanism is not None:
        print(f"inversion: {found.inversion or 'not in the catalog'}"
              f"{where(found.inversion_file)}")
    if found.mapping:
        onto = found.inversion or found.chain
        print("mapping:   " + ", ".join(f"{a} -> {b}" for a, b in found.mapping.items())
              + f"  (onto {onto})")
    if found.joint_kinds == "ignored":
        print("joints:    matched with every joint taken as a turning pair")
    if found.orientation == "ignored":
        print("sliding:   matched with P orientation forgotten (which link carries a guide)")
    if found.note:
        print(f"note:      {found.note}")
    return 0


def _fmt(value, unit=""):
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.6g}{unit}"
    return f"{value}{unit}"


def _cmd_solve(args) -> int:
    chain = load(args.file)
    if args.csv:
        output_file(args.csv, what="CSV")
    if args.plot:
        picture_file(args.plot, what="plot")
    if args.draw:
        picture_file(args.draw, what="drawing")
    motion = solve(chain, fixed=args.fixed, driver=args.driver, inputs=args.inputs,
                   start=args.start, stop=args.stop, steps=args.steps)
    if args.csv:
        with _writing(args.csv):
            motion.to_csv(args.csv)
    if args.plot:
        with _writing(args.plot):
            plot_motion(motion, args.plot)
    if args.draw:
        if str(args.draw).lower().endswith(".svg"):
            _write(args.draw, mechanism_svg(motion))
        else:
            with _writing(args.draw):
                draw_mechanism(motion, args.draw)
    if args.json:
        _print_json(motion.to_dict())
        return 0
    rows = [("mechanism", motion.name), *summary_rows(motion)]
    if motion.inputs:
        sweep = "; ".join(f"{i.joint} {motion['input:' + i.joint][0]:.6g} to "
                          f"{motion['input:' + i.joint][-1]:.6g}" for i in motion.inputs)
        unit = "" if len(motion.inputs) > 1 else " " + motion.plan.lead_unit
    else:
        sweep, unit = f"{motion.theta[0]:.6g} to {motion.theta[-1]:.6g}", " degrees"
    rows.insert(3, ("sweep", f"{sweep}{unit}, {motion.steps} steps"))   # after the input
    print(_table(rows, ["", ""]).split("\n", 2)[2])
    return 0


def _instant_arguments(args):
    """The keyword arguments of instant_centres and velocity_polygon from the flags."""
    at = args.at
    return {"at": None if not at else at[0] if len(at) == 1 else at, "fixed": args.fixed,
            "driver": args.driver, "inputs": args.inputs, "omega": args.omega}


def _instant_heading(what, state) -> list[str]:
    lines = [f"{what} of {state.name}",
             f"{state.fixed} fixed, {state.input_text()} ({state.speed_text})"]
    if len(state.plan.inputs) > 1:
        lines.append("the inputs move together at their sweeps' rates (a polygon per "
                     "input, by superposition, is not drawn yet)")
    return lines


def _at_one_value(args, find, draw):
    """The result of ``find`` at the flags' input value, drawn to --draw; None when
    printed as JSON (--json), else the result for the text."""
    chain = load(args.file)
    if args.draw:
        picture_file(args.draw, what="drawing")
    result = find(chain, **_instant_arguments(args))
    if args.draw:
        with _writing(args.draw):
            draw(result, args.draw)
    if args.json:
        _print_json(result.to_dict())
        return None
    return result


def _cmd_centres(args) -> int:
    centres = _at_one_value(args, instant_centres, draw_centres)
    if centres is None:
        return 0
    state = centres.state
    print("\n".join(_instant_heading("Instantaneous centres", state)))
    print("links: " + ", ".join(f"{n} {link}" for link, n in centres.numbers.items()))
    print()
    rows = centres.rows()
    print(_table(rows, ["centre", "links", "x", "y", "found from"]))
    omegas = centres.angular_velocities
    if any(v is None for v in omegas.values()):
        print("\nangular velocities: not determined at this pose (a dead centre)")
    else:
        print("\nangular velocities through the centres (rad/s): " + ", ".join(
            f"{link} {_fmt(float(omegas[link]))}" for link in centres.numbers
            if link != state.fixed))
    return 0


def _cmd_polygons(args) -> int:
    polygons = _at_one_value(args, velocity_polygon, draw_polygons)
    if polygons is None:
        return 0
    state = polygons.state
    unit = state.units or "length units"
    print("\n".join(_instant_heading("Velocity and acceleration polygons", state)))
    print()
    rows = polygons.image_rows()
    print(f"images (velocity in {unit}/s, acceleration in {unit}/s^2, from the pole o)")
    print(_table(rows, ["point", "link", "vx", "vy", "|v|", "ax", "ay", "|a|"]))
    print()
    rows = polygons.vector_rows()
    print("relative vectors (direction in degrees CCW from +x)")
    print(_table(rows, ["vector", "on", "component", "magnitude", "direction"]))
    closure = polygons.closure
    print(f"\nloops: {len(polygons.loops)}, closing to {closure['velocity']:.3g} "
          f"{unit}/s and {closure['acceleration']:.3g} {unit}/s^2")
    return 0


def _mode_lines(assembly) -> list[str]:
    return [f"{m.part}: {m.word} {m.reference} ({m.source})" for m in assembly.modes]


def _cmd_assemble(args) -> int:
    chain, assembly = read_file(args.file)
    if args.json:
        out = {"name": chain.name, "file": args.file,
               "joints": {j.id: list(j.at) for j in chain.joints},
               "axes": {j.id: j.axis for j in chain.joints if j.kind == "P"},
               "points": {p.id: list(p.at) for p in chain.points},
               "modes": [{"part": m.part, "mode": m.word, "reference": m.reference,
                          "source": m.source} for m in assembly.modes] if assembly else [],
               "groups": [list(g) for g in assembly.groups] if assembly else []}
    text = dumps(chain)
    if assembly is not None:
        head = [f"# assembled by chaingraph from the lengths in {args.file}"]
        if assembly.modes:
            head.append("# assembly modes (change them under [assembly] in the lengths file):")
            head += [f"#   {line}" for line in _mode_lines(assembly)]
        text = "\n".join(head) + "\n" + text
    if args.output:
        _write(args.output, text)
    if args.json:
        _print_json(out)
    elif args.output:
        print(f"{chain.name}: drawn pose written to {args.output}")
        for line in (_mode_lines(assembly) if assembly else []):
            print(f"  {line}")
    else:
        sys.stdout.write(text)
    return 0


def _cmd_measure(args) -> int:
    text = measure(load(args.file))
    if args.output:
        _write(args.output, text)
        print(f"dimensions written to {args.output} (chaingraph assemble {args.output} "
              "gives back the drawn pose)")
    else:
        sys.stdout.write(text)
    return 0


def _write(path, text) -> None:
    output_file(path)
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    except OSError as e:
        raise OutputError(path, f"cannot be written ({e.strerror})") from None


class _writing:
    """Turn a write that fails midway (a full disk, a lost mount) into one line naming
    the output."""

    def __init__(self, path):
        self.path = path

    def __enter__(self):
        return self

    def __exit__(self, kind, error, trace):
        if isinstance(error, OSError) and not isinstance(error, ChainGraphError):
            raise OutputError(error.filename or self.path,
                              f"cannot be written ({error.strerror or error})") from None
        return False


def _existing_folder_above(path):
    """The nearest folder above ``path`` that exists, or OutputError when a file is in
    the way."""
    above = Path(os.path.abspath(path)).parent
    while not above.exists():
        above = above.parent
    if not above.is_dir():
        raise OutputError(path, f"{above} is a file, not a folder")
    return above


def output_file(path, *, what="output"):
    """Check a file to write before the work starts, and make its missing folders."""
    p = Path(path)
    if p.is_dir():
        raise OutputError(path, f"is a folder; give a file name for the {what}")
    above = _existing_folder_above(p)
    if not os.access(above, os.W_OK | os.X_OK):
        raise OutputError(path, f"no permission to write in {above}")
    if p.exists() and not os.access(p, os.W_OK):
        raise OutputError(path, "no permission to write it")
    p.parent.mkdir(parents=True, exist_ok=True)
    return p


def output_folder(path, *, what="output"):
    """Check a folder to write into before the work starts, and make it."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise OutputError(path, f"is a file; the {what} needs a folder")
    above = _existing_folder_above(p) if not p.exists() else p
    if not os.access(above, os.W_OK | os.X_OK):
        raise OutputError(path, f"no permission to write in {above}")
    p.mkdir(parents=True, exist_ok=True)
    return p


def picture_file(path, *, what):
    """An output picture: a known format (by the file's ending), then as output_file."""
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix:
        from matplotlib.backend_bases import FigureCanvasBase
        formats = FigureCanvasBase.get_supported_filetypes()
        if suffix not in formats:
            raise OutputError(path, f"unknown picture format '.{suffix}' for the {what}; "
                                    f"one of {', '.join('.' + f for f in sorted(formats))}")
    return output_file(path, what=what)


def _cmd_report(args) -> int:
    paths = args.paths or [catalog_dir()]
    output_folder(args.output, what="report")
    workers = _workers(args.workers) if args.workers is not None else None
    report = build_report(paths, args.output, progress=None if args.quiet else sys.stderr,
                          workers=workers)
    for path, problem in report.failures:
        where = "" if problem.startswith(str(path)) else f"{path}: "
        print(f"chaingraph: error: {where}{problem}", file=sys.stderr)
    done = sum(1 for e in report.entries if not e.error)
    print(f"report of {done} entries written to {report.index}"
          + (f"; {len(report.failures)} could not be included (listed on the index)"
             if report.failures else ""))
    return 0 if report.complete else 1


def _workers(value, *, flag="--workers") -> int:
    """The number of processes asked for, refused below 1 and capped at the CPUs."""
    cpus = os.cpu_count() or 1
    if value < 1:
        raise ChainGraphError(f"{flag} must be 1 or more, got {value}")
    if value > cpus:
        print(f"chaingraph: note: {flag} {value} capped at the {cpus} CPUs of this machine",
              file=sys.stderr)
    return min(value, cpus)


def _cmd_atlas(args) -> int:

    joints_for(args.links, args.dof)   # a size with no chain: exit 2 with the reason
    if args.scheduler is None or args.scheduler == "local":
        workers = _workers(args.workers)
    else:                        # a remote cluster's cores are its own; refused below 1
        workers = args.workers if args.workers >= 1 else _workers(args.workers)
    check_size(args.links, args.dof, cores=workers, cluster=args.scheduler is not None)
    if args.resume and not args.out:
        raise ChainGraphError("--resume continues a run in its output folder: give --out DIR")
    if args.out:
        output_folder(args.out, what="atlas")
    start = time.perf_counter()
    bar = ProgressBar(1000, None if args.quiet else sys.stderr, percent=True, start=start)

    def progress(fraction, text):
        bar.show(int(round(1000 * fraction)), text)
    listing = (args.json and not args.summary) or (not args.out and not args.summary)
    try:
        if args.scheduler is not None:
            with DaskRunner(args.scheduler, workers=workers) as runner:
                result = run_atlas(args.links, args.dof, runner=runner, out=args.out,
                                   resume=args.resume, progress=progress, keep=listing)
        else:
            result = run_atlas(args.links, args.dof, runner=process_runner(workers),
                               out=args.out, resume=args.resume, progress=progress,
                               keep=listing)
    finally:
        bar.close()
    elapsed = time.perf_counter() - start
    paths = None
    if args.out:
        paths = write_atlas(result, args.out, shard_dir=Path(args.out) / "shards",
                            no_fractionated=args.no_fractionated,
                            chain_files=args.chain_files)
    if listing and args.no_fractionated:
        result = result.without_fractionated()
    if args.json or args.summary:
        _print_json(atlas_dict(result, no_fractionated=args.no_fractionated,
                               chains=args.json and not args.summary))
        return 0
    count = result.count_non_fractionated if args.no_fractionated else result.count
    inversions = (result.distinct_inversions_non_fractionated if args.no_fractionated
                  else result.distinct_inversions)
    which = ("non-fractionated " if args.no_fractionated else "")
    also = ("" if args.no_fractionated else
            f" ({result.count_non_fractionated} non-fractionated)")
    print(f"{count} {which}chains of {args.links} links and {args.dof} degree(s) of "
          f"freedom{also}, {inversions} distinct inversions ({elapsed:.2f} s)")
    if listing and count <= 60:
        rows = [[e.id, ", ".join(f"{v} {k}" for k, v in e.link_orders.items()),
                 e.inversion_classes, "yes" if e.fractionated else "no",
                 " ".join(f"{a + 1}-{b + 1}" for a, b in e.edges)] for e in result]
        print(_table(rows, ["id", "link assortment", "inversions", "fractionated",
                            "joints (link pairs)"]))
    if paths:
        chains = (f", {len(paths['chains'])} chain files in {paths['chain_dir']}"
                  if paths["chain_dir"] else "")
        print(f"written: {paths['json']}, {paths['graph6']}, {paths['html']}{chains}; "
              f"shards in {Path(args.out) / 'shards'}")
    return 0


def _cmd_design(args) -> int:
    if args.out:
        output_file(args.out, what="mechanism file")
    design = KINDS[args.kind](time_ratio=args.time_ratio, crank=args.crank, stroke=args.stroke)
    if args.out:
        with _writing(args.out):
            save(design.mechanism, args.out)
    if args.json:
        _print_json(design.to_dict())
        return 0
    rows = [[k.replace("_", " "), _fmt(v)] for k, v in design.to_dict().items() if k != "kind"]
    print(f"{args.kind} quick return drive")
    print(_table(rows, ["", ""]).split("\n", 2)[2])
    if args.out:
        print(f"mechanism written to {args.out} (chaingraph solve {args.out} reproduces it)")
    return 0


class _Parser(argparse.ArgumentParser):
    """argparse, with a usage error as one line (``chaingraph COMMAND: error: ...``)."""

    def error(self, message):
        usage = " ".join(self.format_usage().split())
        self.exit(2, f"{self.prog}: error: {message} ({usage})\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="chaingraph",
        description="Analyse planar kinematic chains as link-joint graphs.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    p = sub.add_parser("classify", help="structural classification of chain files",
                       description="Counts, orders, loops, Kutzbach mobility, the textbook "
                                   "checks and degeneracy of each chain file.")
    p.add_argument("files", nargs="+", metavar="FILE", help="chain files (TOML)")
    p.add_argument("--json", action="store_true", help="print JSON (a list for several files)")
    p.set_defaults(run=_cmd_classify)

    p = sub.add_parser("inversions", help="inversions: fix each link in turn",
                       description="One inversion per link, grouped into classes by the "
                                   "chain's automorphisms, named from the catalog, with "
                                   "their behaviour where the file has dimensions.")
    p.add_argument("file", metavar="FILE", help="a chain file (TOML)")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--with-input", action="store_true",
                   help="also designate the input link (joined to the fixed link by an R joint)")
    p.set_defaults(run=_cmd_inversions)

    p = sub.add_parser("identify", help="which catalog chain (and inversion) a file is",
                       description="Find the file's chain in the catalog by structure and, "
                                   "for a mechanism, which catalog inversion it is.")
    p.add_argument("file", metavar="FILE", help="a chain file (TOML)")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(run=_cmd_identify)

    p = sub.add_parser("solve", help="position, velocity and acceleration over an input sweep",
                       description="Solve the mechanism (the file's [mechanism], or the "
                                   "inversion --fixed and --driver or --input choose) over the "
                                   "input sweep, in the assembly mode of the drawn pose.")
    p.add_argument("file", metavar="FILE", help="a mechanism file (TOML) with a drawn pose")
    p.add_argument("--fixed", metavar="LINK", help="the fixed link")
    given = p.add_mutually_exclusive_group()
    given.add_argument("--driver", metavar="LINK",
                       help="the input link, pinned to the fixed link by an R joint")
    given.add_argument("--input", dest="inputs", action="append", metavar="JOINT",
                       help="an input joint (R or P, between any two links); repeat it, "
                            "one per degree of freedom")
    p.add_argument("--from", dest="start", type=float, metavar="X",
                   help="the first input's first value (degrees, or slide for a P input)")
    p.add_argument("--to", dest="stop", type=float, metavar="X",
                   help="the first input's last value")
    p.add_argument("--steps", type=_whole_number, default=360, metavar="N",
                   help="equal intervals of the sweep (N + 1 rows; default 360)")
    p.add_argument("--json", action="store_true", help="print the JSON summary")
    p.add_argument("--csv", metavar="PATH", help="write every column of every step")
    p.add_argument("--plot", metavar="PATH.svg",
                   help="plot the output's displacement, velocity and acceleration")
    p.add_argument("--draw", metavar="PATH.svg",
                   help="draw the mechanism in its drawn pose with the paths of its points")
    p.set_defaults(run=_cmd_solve)

    for name, run, helptext, description in (
            ("centres", _cmd_centres, "instantaneous centres (Kennedy's theorem)",
             "Every instantaneous centre of the mechanism at one input value: the primary "
             "ones from the joints, the others by Kennedy's theorem (the three centres of "
             "three links lie on one line), each with its position (or direction at "
             "infinity) and how it was found; the angular velocities through them."),
            ("polygons", _cmd_polygons, "velocity and acceleration polygons",
             "The velocity and acceleration polygons of the mechanism at one input value: "
             "every point's image and the relative vectors, with their centripetal, "
             "tangential, sliding and Coriolis components.")):
        p = sub.add_parser(name, help=helptext, description=description)
        p.add_argument("file", metavar="FILE", help="a mechanism file (TOML) with dimensions")
        p.add_argument("--at", action="append", type=float, metavar="X",
                       help="the input value (degrees, or slide for a P input; default: "
                            "the drawn pose); with several inputs the first's value, or "
                            "repeat it, one per input")
        p.add_argument("--fixed", metavar="LINK", help="the fixed link")
        given = p.add_mutually_exclusive_group()
        given.add_argument("--driver", metavar="LINK",
                           help="the input link, pinned to the fixed link by an R joint")
        given.add_argument("--input", dest="inputs", action="append", metavar="JOINT",
                           help="an input joint; repeat it, one per degree of freedom")
        p.add_argument("--omega", type=float, metavar="W",
                       help="the (first) input's speed (default: the file's, else 1)")
        p.add_argument("--json", action="store_true", help="print JSON")
        p.add_argument("--draw", metavar="PATH.svg", help="draw the construction")
        p.set_defaults(run=run)

    p = sub.add_parser("assemble", help="the drawn pose of a mechanism given by its lengths",
                       description="Find every joint's position from the file's lengths, the "
                                   "input's value and the assembly modes, and write the "
                                   "mechanism with coordinates (to standard output, or OUT). "
                                   "The modes used are listed, with where each came from.")
    p.add_argument("file", metavar="FILE", help="a mechanism file (TOML) with [lengths]")
    p.add_argument("-o", "--output", metavar="OUT", help="write the assembled file here")
    p.add_argument("--json", action="store_true",
                   help="print the positions and the assembly modes as JSON")
    p.set_defaults(run=_cmd_assemble)

    p = sub.add_parser("measure", help="the lengths of a drawn mechanism",
                       description="Write a drawn mechanism as its dimensions: the lengths "
                                   "of its links, its sliding lines, the input's value and "
                                   "every assembly mode (the inverse of assemble).")
    p.add_argument("file", metavar="FILE", help="a mechanism file (TOML) with a drawn pose")
    p.add_argument("-o", "--output", metavar="OUT", help="write the file with lengths here")
    p.set_defaults(run=_cmd_measure)

    p = sub.add_parser("report", help="the browsable HTML catalog",
                       description="Write DIR/index.html and a page per entry for the given "
                                   "chain files or folders (by default the bundled catalog). "
                                   "Files that fail are listed and the rest go on (exit 1).")
    p.add_argument("paths", nargs="*", metavar="PATH", help="chain files or folders")
    p.add_argument("-o", "--output", default="report", metavar="DIR",
                   help="output folder (default: report)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.add_argument("--workers", type=int, metavar="K",
                   help="processes that analyse entries side by side (default and at most: "
                        "the CPUs)")
    p.set_defaults(run=_cmd_report)

    p = sub.add_parser("atlas", help="every chain of N links and F degrees of freedom",
                       description="Every non-isomorphic, non-degenerate planar chain with "
                                   "simple revolute joints (non-planar link graphs and "
                                   "fractionated chains included). Sizes estimated to take "
                                   "over an hour here are refused with the estimate.")
    p.add_argument("--links", type=int, required=True, metavar="N")
    p.add_argument("--dof", type=int, default=1, metavar="F")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--summary", action="store_true",
                   help="print the counts alone (JSON without the chains)")
    p.add_argument("--no-fractionated", action="store_true",
                   help="keep only the non-fractionated chains")
    p.add_argument("--out", metavar="DIR",
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
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=_cmd_atlas)

    p = sub.add_parser("design", help="dimensional synthesis of quick return drives",
                       description="From a time ratio, crank and stroke to the centre "
                                   "distance and lever (slotted-lever: the ram's line through "
                                   "the lever end's extremes; whitworth: through the lever's "
                                   "pivot).")
    p.add_argument("kind", choices=["slotted-lever", "whitworth"])
    p.add_argument("--time-ratio", type=float, required=True, metavar="R")
    p.add_argument("--crank", type=float, required=True, metavar="C")
    p.add_argument("--stroke", type=float, required=True, metavar="S")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--out", metavar="FILE", help="write the designed mechanism (TOML)")
    p.set_defaults(run=_cmd_design)
    return parser


def _version() -> str:
    return __version__


# the library's parameters as the command line's options, for its messages
_FLAGS = {"fixed": "--fixed LINK", "driver": "--driver LINK", "inputs": "--input JOINT",
          "steps": "--steps N", "start": "--from", "stop": "--to", "at": "--at",
          "omega": "--omega", "time_ratio": "--time-ratio", "crank": "--crank",
          "stroke": "--stroke", "links": "--links N", "dof": "--dof F",
          "scheduler": "--scheduler ADDRESS", "workers": "--workers K", "out": "--out DIR",
          "resume": "--resume"}


def exit_status(error) -> int:
    """The exit status of an error: 1 for an analysis that failed (a pose that cannot
    be assembled), 2 for bad input."""
    return 1 if isinstance(error, AssemblyError) else 2


def error_text(error) -> str:
    """The error's message, with the flag of the parameter at fault."""
    flag = _FLAGS.get(getattr(error, "parameter", None))
    return f"{error}" if flag is None else f"{error}; on the command line: {flag}"


def _whole_number(text):
    """An option's whole number of 1 or more (a number of steps)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid int value: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be 1 or more, got {value}")
    return value


def main(argv=None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    shown = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, ChainGraphWarning):
            print(f"chaingraph: warning: {message}", file=sys.stderr)
        else:
            shown(message, category, filename, lineno, file, line)

    warnings.showwarning = show
    try:
        return args.run(args)
    except ChainGraphError as e:
        print(f"chaingraph: error: {error_text(e)}", file=sys.stderr)
        return exit_status(e)
    except BrokenPipeError:
        return 0
    except MemoryError:
        print("chaingraph: error: out of memory: the analysis needs more memory than this "
              "machine (or its limit) gives; try a smaller size or fewer steps",
              file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("chaingraph: interrupted", file=sys.stderr)
        return 130
    except OSError as e:             # a write that failed midway: a full disk, a lost mount
        where = f"{e.filename}: " if e.filename else ""
        print(f"chaingraph: error: {where}{e.strerror or e}", file=sys.stderr)
        return 2
    finally:
        warnings.showwarning = shown
