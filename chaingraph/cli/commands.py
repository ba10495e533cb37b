"""The command line's commands: each reads its arguments, calls the library and prints."""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

from chaingraph._util import ProgressBar, freedom
from chaingraph.cli.outputs import (
    Writing,
    output_file,
    output_folder,
    picture_file,
    svg_file,
    write_text,
)
from chaingraph.cli.gears import cmd_gear_atlas
from chaingraph.cli.text import (
    classification_text,
    error_text,
    exit_status,
    figure,
    instant_heading,
    mode_lines,
    print_json,
    table,
)
from chaingraph.drawing import (
    draw_centres,
    draw_mechanism,  # PNG and the other raster formats
    draw_polygons,
    force_polygon_svg,
    free_body_svg,
    limits_svg,
    mechanism_svg,
    plot_motion,
    plot_shaking,
    plot_turning_moment,
    plot_variation,
)
from chaingraph.dynamics import forces
from chaingraph.dynamics.balance import balance
from chaingraph.errors import ChainGraphError, DesignError, OutputError
from chaingraph.files import dumps, load, read_file, save
from chaingraph.graphical import instant_centres, velocity_polygon
from chaingraph.kinematics import measure, solve, summary_rows
from chaingraph.naming import atlas_names, catalog_dir, identify, inversions
from chaingraph.report import (
    animated_by_default,
    animation_seconds,
    build_report,
    write_illustrated,
)
from chaingraph.structure import classify
from chaingraph.structure.atlas import (
    LOCAL_HOURS,
    REASONS,
    DaskRunner,
    SlidingCounts,
    SlidingEntry,
    atlas_dict,
    check_size,
    joints_for,
    multiple_atlas,
    prismatic_counts,
    process_runner,
    run_atlas,
    sliding_atlas,
    sliding_chains,
    sliding_dict,
    write_atlas,
    write_sliding,
)
from chaingraph import synthesis
from chaingraph.drawing.synthesis import draw_solution
from chaingraph.synthesis import KINDS, PathTask
from chaingraph.synthesis.path_generation import EXACT
from chaingraph.variation import length_values, vary

__all__ = ['cmd_classify', 'cmd_inversions', 'cmd_identify', 'cmd_solve', 'cmd_centres', 'cmd_polygons', 'cmd_assemble', 'cmd_measure', 'cmd_report', 'cmd_atlas', 'atlas_workers', 'cmd_design', 'cmd_design_function', 'cmd_design_motion']


def cmd_classify(args: argparse.Namespace) -> int:
    results, failed = [], 0
    for path in args.files:
        try:
            results.append((path, classify(load(path))))
        except ChainGraphError as e:
            print(f"chaingraph: error: {error_text(e)}", file=sys.stderr)
            failed = exit_status(e) if not failed else failed
    if args.json and results:
        objs = [r.to_dict() for _, r in results]
        print_json(objs[0] if len(args.files) == 1 else objs)
    elif len(results) == 1 and len(args.files) == 1:
        print(classification_text(results[0][1], results[0][0]))
    elif results:
        rows = [[r.name, r.links, r.pairs, r.joint_equivalents, r.higher_pairs, r.loops,
                 r.mobility, c2.verdict or "n/a", r.check("J + H/2 = 3L/2 - 2").verdict,
                 r.verdict, "yes" if r.degenerate else "no"]
                for _, r in results for c2 in [r.check("L = 2P - 4")]]
        print(table(rows, ["chain", "L", "P", "J", "H", "loops", "F", "L = 2P - 4",
                            "J + H/2 = 3L/2 - 2", "verdict", "degenerate"]))
    return failed

def cmd_inversions(args: argparse.Namespace) -> int:
    result = inversions(load(args.file), with_input=args.with_input)
    if args.json:
        print_json(result.to_dict())
        return 0
    plural = "class" if result.classes == 1 else "classes"
    print(f"{result.name}: {result.links} links, {len(result.inversions)} inversions "
          f"in {result.classes} {plural} by structure")
    header, *rows = result.rows()
    print(table([list(r) for r in rows], list(header)))
    if args.with_input:
        print(f"classes with a designated input: {result.classes_with_input}")
    for inv in result.inversions:
        if inv.note:
            print(f"{inv.fixed} fixed: {inv.note}")
    return 0

def cmd_identify(args: argparse.Namespace) -> int:
    chain = load(args.file)
    found = identify(chain)
    if args.json:
        print_json(found.to_dict())
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

def cmd_solve(args: argparse.Namespace) -> int:
    chain = load(args.file)
    if args.csv:
        output_file(args.csv, what="CSV")
    if args.plot:
        picture_file(args.plot, what="plot")
    if args.draw:
        picture_file(args.draw, what="drawing")
    if args.limits:
        svg_file(args.limits, what="limit positions")
    motion = solve(chain, fixed=args.fixed, driver=args.driver, inputs=args.inputs,
                   start=args.start, stop=args.stop, steps=args.steps, output=args.output)
    if args.csv:
        with Writing(args.csv):
            motion.to_csv(args.csv)
    if args.plot:
        with Writing(args.plot):
            plot_motion(motion, args.plot)
    if args.draw:
        if str(args.draw).lower().endswith(".svg"):
            write_text(args.draw, mechanism_svg(motion))
        else:
            with Writing(args.draw):
                draw_mechanism(motion, args.draw)
    if args.limits:
        write_text(args.limits, limits_svg(motion))
    if args.json:
        print_json(motion.to_dict())
        return 0
    rows = [("mechanism", motion.name), *summary_rows(motion)]
    if motion.inputs:
        sweep = "; ".join(f"{i.joint} {motion['input:' + i.joint][0]:.6g} to "
                          f"{motion['input:' + i.joint][-1]:.6g}" for i in motion.inputs)
        unit = "" if len(motion.inputs) > 1 else " " + motion.plan.lead_unit
    else:
        sweep, unit = f"{motion.theta[0]:.6g} to {motion.theta[-1]:.6g}", " degrees"
    rows.insert(3, ("sweep", f"{sweep}{unit}, {motion.steps} steps"))   # after the input
    print(table(rows, ["", ""]).split("\n", 2)[2])
    return 0

def cmd_vary(args: argparse.Namespace) -> int:
    chain = load(args.file)
    if args.plot:
        picture_file(args.plot, what="plot")
    link, sep, span = args.length.rpartition("=")
    parts = span.split(":")
    if not sep or not link or len(parts) != 3:
        print(f"chaingraph vary: error: --length {args.length!r}: write LINK=FROM:TO:STEP, "
              "such as crank=30:120:30", file=sys.stderr)
        return 2
    try:
        start, stop, step = (float(x) for x in parts)
    except ValueError:
        print(f"chaingraph vary: error: --length {args.length!r}: FROM, TO and STEP must be "
              "numbers", file=sys.stderr)
        return 2
    result = vary(chain, link, length_values(start, stop, step), steps=args.steps,
                  output=args.output)
    if args.plot:
        with Writing(args.plot):
            plot_variation(result, args.plot)
    if args.json:
        print_json(result.to_dict())
        return 0
    unit = f", {chain.units}" if chain.units else ""
    print(f"{result.name}: over the length of {link}")
    print(table(result.table(), [f"{link}{unit}", "time ratio", "stroke",
                                 "transmission angle", "input range (or why not)"]))
    return 0

def cmd_forces(args: argparse.Namespace) -> int:
    chain = load(args.file)
    if args.csv:
        output_file(args.csv, what="CSV")
    for path, what in ((args.draw, "free bodies"), (args.polygon, "force polygons")):
        if path:
            svg_file(path, what=what)
    if args.plot:
        picture_file(args.plot, what="plot")
    if args.polar:
        picture_file(args.polar, what="plot")
    at = args.at
    common = dict(static=args.static, fixed=args.fixed, driver=args.driver,
                  inputs=args.inputs, omega=args.omega)
    if at:
        if args.csv or args.start is not None or args.stop is not None or \
                args.speed_fluctuation is not None or args.plot or args.balance or args.polar:
            flag = ("--csv" if args.csv else "--from/--to" if args.start is not None
                    or args.stop is not None else "--plot" if args.plot
                    else "--balance" if args.balance else "--polar" if args.polar
                    else "--speed-fluctuation")
            print(f"chaingraph forces: error: {flag} is for a sweep; --at gives one pose",
                  file=sys.stderr)
            return 2
        result = forces(chain, at=at[0] if len(at) == 1 else at, **common)
    else:
        result = forces(chain, start=args.start, stop=args.stop, steps=args.steps,
                        speed_fluctuation=args.speed_fluctuation, **common)
        if args.csv:
            with Writing(args.csv):
                result.to_csv(args.csv)
        if args.plot:
            with Writing(args.plot):
                plot_turning_moment(result, args.plot)

    if args.draw or args.polygon:
        # the pose solved, or the sweep's first, as solved: nothing is solved again
        pose = result if at else result.pose(0)
        if args.draw:
            write_text(args.draw, free_body_svg(pose))
        if args.polygon:
            svg = force_polygon_svg(pose)
            if svg is None:
                raise OutputError(args.polygon, "the mechanism has no dyad with forces on "
                                                "both its links to draw a polygon of")
            write_text(args.polygon, svg)
    balanced = balance(result) if args.balance and not at else None
    if args.polar and not at:                  # with --balance, the balanced one too
        with Writing(args.polar):
            plot_shaking(result, args.polar,
                         balanced=None if balanced is None else balanced.result)
    if args.json:
        data = result.to_dict()
        if balanced is not None:
            data["balance"] = balanced.to_dict()
        print_json(data)
        return 0
    kind = "static" if args.static else "kinetostatic"
    if at:
        values = ", ".join(f"{j} = {v:.6g}" for j, v in zip(result.inputs, result.at))
        print(f"Forces ({kind}) of {result.name}, {result.fixed} fixed, {values}")
        print()
        print(table(result.rows(), ["joint", "on", "by", "Fx N", "Fy N", "|F| N",
                                    "normal N", "couple N m"]))
        print()
        for e in result.efforts:
            print(f"effort {e.joint}: " + ("unbounded or not determined" if e.value is None
                                           else f"{e.value:.6g} {e.unit}"))
        if result.power_balance is not None:
            print(f"power balance: {result.power_balance:.3g} W")
    else:
        print(f"Forces ({kind}) of {result.name}, {result.fixed} fixed, {result.steps} steps")
        rows = result.rows() + (balanced.rows() if balanced is not None else [])
        print(table(rows, ["", ""]).split("\n", 2)[2])
    for note in result.notes + (balanced.notes if balanced is not None else ()):
        print(f"note: {note}")
    return 0

def _instant_arguments(args):
    """The keyword arguments of instant_centres and velocity_polygon from the flags."""
    at = args.at
    return {"at": None if not at else at[0] if len(at) == 1 else at, "fixed": args.fixed,
            "driver": args.driver, "inputs": args.inputs, "omega": args.omega}

def _at_one_value(args, find, draw):
    """The result of ``find`` at the flags' input value, drawn to --draw; None when
    printed as JSON (--json), else the result for the text."""
    chain = load(args.file)
    if args.draw:
        picture_file(args.draw, what="drawing")
    result = find(chain, **_instant_arguments(args))
    if args.draw:
        with Writing(args.draw):
            draw(result, args.draw)
    if args.json:
        print_json(result.to_dict())
        return None
    return result

def cmd_centres(args: argparse.Namespace) -> int:
    centres = _at_one_value(args, instant_centres, draw_centres)
    if centres is None:
        return 0
    state = centres.state
    print("\n".join(instant_heading("Instantaneous centres", state)))
    print("links: " + ", ".join(f"{n} {link}" for link, n in centres.numbers.items()))
    print()
    rows = centres.rows()
    print(table(rows, ["centre", "links", "x", "y", "found from"]))
    omegas = centres.angular_velocities
    if any(v is None for v in omegas.values()):
        print("\nangular velocities: not determined at this pose (a dead centre)")
    else:
        print("\nangular velocities through the centres (rad/s): " + ", ".join(
            f"{link} {figure(float(omegas[link]))}" for link in centres.numbers
            if link != state.fixed))
    return 0

def cmd_polygons(args: argparse.Namespace) -> int:
    polygons = _at_one_value(args, velocity_polygon, draw_polygons)
    if polygons is None:
        return 0
    state = polygons.state
    unit = state.units or "length units"
    print("\n".join(instant_heading("Velocity and acceleration polygons", state)))
    print()
    rows = polygons.image_rows()
    print(f"images (velocity in {unit}/s, acceleration in {unit}/s^2, from the pole o)")
    print(table(rows, ["point", "link", "vx", "vy", "|v|", "ax", "ay", "|a|"]))
    print()
    rows = polygons.vector_rows()
    print("relative vectors (direction in degrees CCW from +x)")
    print(table(rows, ["vector", "on", "component", "magnitude", "direction"]))
    closure = polygons.closure
    print(f"\nloops: {len(polygons.loops)}, closing to {closure['velocity']:.3g} "
          f"{unit}/s and {closure['acceleration']:.3g} {unit}/s^2")
    return 0

def cmd_assemble(args: argparse.Namespace) -> int:
    chain, assembly = read_file(args.file)
    if args.json:
        out = {"name": chain.name, "file": args.file,
               "joints": {j.id: None if j.at is None else list(j.at) for j in chain.joints},
               "axes": {j.id: j.axis for j in chain.joints if j.kind == "P"},
               "points": {p.id: None if p.at is None else list(p.at) for p in chain.points},
               "modes": [{"part": m.part, "mode": m.word, "reference": m.reference,
                          "source": m.source} for m in assembly.modes] if assembly else [],
               "groups": [list(g) for g in assembly.groups] if assembly else []}
    text = dumps(chain)
    if assembly is not None:
        head = [f"# assembled by chaingraph from the lengths in {args.file}"]
        if assembly.modes:
            head.append("# assembly modes (change them under [assembly] in the lengths file):")
            head += [f"#   {line}" for line in mode_lines(assembly)]
        text = "\n".join(head) + "\n" + text
    if args.output:
        write_text(args.output, text)
    if args.json:
        print_json(out)
    elif args.output:
        print(f"{chain.name}: drawn pose written to {args.output}")
        for line in (mode_lines(assembly) if assembly else []):
            print(f"  {line}")
    else:
        sys.stdout.write(text)
    return 0

def cmd_measure(args: argparse.Namespace) -> int:
    text = measure(load(args.file))
    if args.output:
        write_text(args.output, text)
        print(f"dimensions written to {args.output} (chaingraph assemble {args.output} "
              "gives back the drawn pose)")
    else:
        sys.stdout.write(text)
    return 0

def cmd_report(args: argparse.Namespace) -> int:
    paths = args.paths or [catalog_dir()]
    output_folder(args.output, what="report")
    workers = workers_asked(args.workers) if args.workers is not None else None
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

def workers_asked(value: int, *, flag: str = "--workers") -> int:
    """The number of processes asked for, refused below 1 and capped at the CPUs."""
    cpus = os.cpu_count() or 1
    if value < 1:
        raise ChainGraphError(f"{flag} must be 1 or more, got {value}")
    if value > cpus:
        print(f"chaingraph: note: {flag} {value} capped at the {cpus} CPUs of this machine",
              file=sys.stderr)
    return min(value, cpus)

def atlas_workers(args: argparse.Namespace) -> int:
    """The workers an atlas runs on: local ones capped at the CPUs, a remote cluster's
    as asked (its cores are its own), refused below 1."""
    if args.scheduler is None or args.scheduler == "local":
        return workers_asked(args.workers)
    return args.workers if args.workers >= 1 else workers_asked(args.workers)


def cmd_atlas(args: argparse.Namespace) -> int:
    if args.gears:
        return cmd_gear_atlas(args, workers=atlas_workers(args))
    joints = joints_for(args.links, args.dof)   # a size with no chain: exit 2 with the reason
    wanted = prismatic_counts(args.links, args.dof, joints, args.prismatic, args.oriented)
    if wanted is not None or args.multiple:
        return _sliding(args, wanted or (0,))
    workers = atlas_workers(args)
    check_size(args.links, args.dof, cores=workers, cluster=args.scheduler is not None,
               hours=args.max_hours)
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
        print_json(atlas_dict(result, no_fractionated=args.no_fractionated,
                               chains=args.json and not args.summary))
        return 0
    count = result.count_non_fractionated if args.no_fractionated else result.count
    inversions = (result.distinct_inversions_non_fractionated if args.no_fractionated
                  else result.distinct_inversions)
    which = ("non-fractionated " if args.no_fractionated else "")
    also = ("" if args.no_fractionated else
            f" ({result.count_non_fractionated} non-fractionated)")
    print(f"{count} {which}chains of {args.links} links and {freedom(args.dof)}{also}, "
          f"{inversions} distinct inversions ({elapsed:.2f} s)")
    if listing and count <= 60:
        rows = [[e.id, ", ".join(f"{v} {k}" for k, v in e.link_orders.items()),
                 e.inversion_classes, "yes" if e.fractionated else "no",
                 " ".join(f"{a + 1}-{b + 1}" for a, b in e.edges)] for e in result]
        print(table(rows, ["id", "link assortment", "inversions", "fractionated",
                            "joints (link pairs)"]))
    if paths:
        chains = (f", {len(paths['chains'])} chain files in {paths['chain_dir']}"
                  if paths["chain_dir"] else "")
        print(f"written: {paths['json']}, {paths['graph6']}, {paths['html']}{chains}; "
              f"shards in {Path(args.out) / 'shards'}")
    return 0

def cmd_design(args: argparse.Namespace) -> int:
    if args.out:
        output_file(args.out, what="mechanism file")
    design = KINDS[args.kind](time_ratio=args.time_ratio, crank=args.crank, stroke=args.stroke)
    if args.out:
        with Writing(args.out):
            save(design.mechanism, args.out)
    if args.json:
        print_json(design.to_dict())
        return 0
    rows = [[k.replace("_", " "), figure(v)] for k, v in design.to_dict().items() if k != "kind"]
    print(f"{args.kind} quick return drive")
    print(table(rows, ["", ""]).split("\n", 2)[2])
    if args.out:
        print(f"mechanism written to {args.out} (chaingraph solve {args.out} reproduces it)")
    return 0


def cmd_design_function(args: argparse.Namespace) -> int:
    """``chaingraph design function``: certified function generators, best first."""
    if args.out:
        output_folder(args.out, what="solutions")
    if args.draw:
        svg_file(args.draw, what="solution and its error")
    found = synthesis.function(
        function=args.function, x=args.x, swing=args.swing, start=args.start,
        points=args.points, spacing=args.spacing, kind=args.mechanism,
        solutions=args.solutions, units=args.units, min_transmission=args.min_transmission)
    return _synthesis_output(args, found)


def cmd_design_path(args: argparse.Namespace) -> int:
    """``chaingraph design path``: certified path generators, best first."""
    synthesis.check_links(args.links, args.prismatic, kind="path")
    if args.out:
        output_folder(args.out, what="solutions")
    if args.draw:
        svg_file(args.draw, what="solution and its path")
    points = args.points if args.points is not None else points_file(args.points_file)
    options = dict(points=points, timing=args.timing, closed=args.closed,
                   solutions=args.solutions, seed=args.seed, units=args.units,
                   min_transmission=args.min_transmission)
    if args.links == 4 and args.prismatic in (None, 0):
        return _synthesis_output(args, synthesis.path(**options))
    return _synthesis_output(args, _through_atlas(args, synthesis.path, options))


def _through_atlas(args, synthesise, options):
    """A type synthesis (``synthesise``: synthesis.path or .motion with ``options``)
    over the atlas's chains of ``--links`` links, on local processes or a Dask cluster."""
    if args.scheduler is not None:
        workers = args.workers if args.workers >= 1 else workers_asked(args.workers)
        with DaskRunner(args.scheduler, workers=workers) as runner:
            return synthesise(**options, links=args.links, prismatic=args.prismatic,
                              runner=runner)
    return synthesise(**options, links=args.links, prismatic=args.prismatic,
                      runner=process_runner(workers_asked(args.workers)))


def points_file(path: str | os.PathLike[str]) -> list[tuple[float, float]]:
    """The targets of a CSV file: one ``x,y`` per line, a first line of names allowed,
    blank lines skipped; a bad line is a DesignError naming it."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        raise DesignError(f"cannot read {path}: {getattr(e, 'strerror', None) or e}",
                          kind="path", parameter="points_file") from None
    out = []
    for n, line in enumerate(text.splitlines(), 1):
        fields = [f.strip() for f in line.split(",")]
        if not line.strip():
            continue
        try:
            if len(fields) != 2:
                raise ValueError
            out.append((float(fields[0]), float(fields[1])))
        except ValueError:
            if n == 1 and len(fields) == 2 and not out:
                continue             # a header: x,y
            raise DesignError(f"{path}, line {n}: expected two numbers x,y, got "
                              f"{line.strip()!r}", kind="path",
                              parameter="points_file") from None
    return out
def cmd_design_motion(args: argparse.Namespace) -> int:
    """``chaingraph design motion``: certified motion generators, best first."""
    if args.out:
        output_folder(args.out, what="solutions")
    if args.draw:
        svg_file(args.draw, what="solution and its poses")
    synthesis.check_links(args.links, args.prismatic, kind="motion")
    options = dict(poses=args.poses, solutions=args.solutions, units=args.units,
                   min_transmission=args.min_transmission)
    if args.links == 4 and args.prismatic in (None, 0):
        return _synthesis_output(args, synthesis.motion(**options))
    return _synthesis_output(args, _through_atlas(args, synthesis.motion,
                                                  {**options, "seed": args.seed}))


def _task_line(task) -> str:
    """The first line of a synthesis's text: its task."""
    if task.kind == "path":
        return synthesis_heading(task)
    t = task.to_dict()
    if t["kind"] == "motion":
        return (f"motion generator: {len(t['poses'])} poses (x, y, degrees) "
                + "; ".join(", ".join(f"{v:g}" for v in p) for p in t["poses"]))
    return (f"{t['kind']} generator: y = {t['function']} for {t['x'][0]:g} <= x <= "
            f"{t['x'][1]:g}, {t['mechanism']}, {t['points']} {t['spacing']} points")


def _synthesis_output(args, found) -> int:
    """A synthesis's files, drawing and text or JSON; exit 1 when nothing is certified."""
    rejected = ", ".join(f"{k} {v}" for k, v in found.rejected.items()) or "none"
    if not found.solutions:
        print(f"chaingraph: error: design {found.task.kind}: no certified solution of "
              f"{found.searched.candidates} candidates (rejected: {rejected})",
              file=sys.stderr)
        return 1
    if args.out:
        for s in found.solutions:
            target = Path(args.out) / f"solution-{s.rank}.toml"
            with Writing(target):
                save(s.mechanism, target)
    if args.draw:
        with Writing(args.draw):
            draw_solution(found.solutions[0], path=args.draw)
    if args.json:
        print_json(found.to_dict())
        return 0
    print(_task_line(found.task))
    error = _error_text(found)
    angles = any(s.error.angle is not None for s in found.solutions)
    rows = [[s.rank, error(s.error.max), error(s.error.rms)]
            + ([error(s.error.angle or 0.0)] if angles else []) + [
             "-" if s.transmission_angle is None else
             f"{s.transmission_angle[0]:.1f}..{s.transmission_angle[1]:.1f}", s.input,
             ", ".join(f"{k.replace('_', ' ')} {figure(v)}" for k, v in s.dimensions.items())]
            for s in found.solutions]
    if any(s.atlas for s in found.solutions):
        for row, s in zip(rows, found.solutions):
            row.insert(1, _atlas_text(s))
    print(table(rows, ["rank"] + (["mechanism"] if any(s.atlas for s in found.solutions)
                                  else []) + ["error max", "error rms"]
                + (["angle error"] if angles else [])
                + ["transmission", "input", "dimensions"]))
    searched = found.searched
    space = (f"{searched.chains} chains, {searched.inversions} inversions, "
             if any(s.atlas for s in found.solutions) else "")
    print(f"rejected: {rejected}; searched {space}{searched.candidates} candidates")
    if args.out:
        n = len(found.solutions)
        files = "solution-1.toml" if n == 1 else f"solution-1.toml .. solution-{n}.toml"
        print(f"written: {files} in {args.out} (chaingraph solve reproduces "
              f"{'it' if n == 1 else 'each'})")
    return 0


def _atlas_text(s) -> str:
    """Where a type synthesis found a solution: its catalog name, else its chain and
    inversion in the atlas."""
    a = s.atlas
    where = f"chain {a['chain']}, inversion {a['inversion']}"
    return f"{s.names[-1]} ({where})" if s.names else where


def _error_text(found):
    """How a synthesis's errors are printed: an exact path's error is rounding ("exact");
    a motion's errors below 1e-9 are rounding (0); else the figure."""
    if getattr(found.task, "exact", False):
        bound = EXACT * found.task.size
        return lambda v: "exact" if v <= bound else figure(v)
    if any(s.error.angle is not None for s in found.solutions):
        return lambda v: figure(round(v, 9))
    return figure


def synthesis_heading(task: PathTask) -> str:
    """The first line of a path synthesis's text."""
    n = len(task.points)
    how = (f"{n} points on a closed curve" if task.closed else f"{n} points")
    fit = "passed exactly" if task.exact else "fitted"
    timing = ", with timing" if task.timing is not None else ""
    return f"path generator: {task.mechanism}, {how}{timing}, {fit} (seed {task.seed})"


def _sliding(args, wanted) -> int:
    """atlas --prismatic: the chains with sliding pairs, from the turning-pair atlas."""
    if args.scheduler is not None or args.resume:
        raise ChainGraphError("--prismatic runs here, from the turning-pair atlas in memory: "
                              "leave out --scheduler and --resume")
    workers = workers_asked(args.workers)
    check_size(args.links, args.dof, cores=workers, cluster=False, hours=args.max_hours,
               prismatic=wanted, oriented=args.oriented, multiple=args.multiple)
    if args.out:
        output_folder(args.out, what="atlas")
    start = time.perf_counter()
    simple = run_atlas(args.links, args.dof, runner=process_runner(workers))
    base = multiple_atlas(simple) if args.multiple else simple
    def names(chain):
        return atlas_names(chain, oriented=args.oriented)
    if args.out or (args.json and not args.summary):
        result = sliding_atlas(base, prismatic=wanted, oriented=args.oriented)
        shown = result = result.without_fractionated() if args.no_fractionated else result
    else:                   # counted as found: memory stays flat whatever the size
        result, shown = _counted(base, wanted, args)
    record = sliding_dict(result, prismatic=args.prismatic, chains=False)
    elapsed = time.perf_counter() - start
    if args.out:
        paths = write_sliding(result, args.out, record=sliding_dict(
            result, prismatic=args.prismatic, names=names))
        if args.links <= 8 or args.illustrate:
            animate = args.illustrate or animated_by_default(result, workers=workers)
            pages = write_illustrated(result, args.out, animate=animate, workers=workers)
            paths["pages"] = pages
    if args.json or args.summary:
        print_json(record if args.summary else
                   sliding_dict(result, prismatic=args.prismatic, names=names))
        return 0
    kinds = ("any number of sliding pairs" if args.prismatic == "all" else
             "turning pairs only" if args.prismatic is None else
             f"{args.prismatic} sliding pair{'s' if args.prismatic != 1 else ''}")
    if args.multiple:
        kinds += ", multiple joints allowed"
    print(f"{len(result)} chains of {args.links} links and {freedom(args.dof)} with "
          f"{kinds}{' (oriented)' if args.oriented else ''}, "
          f"{result.distinct_inversions} distinct inversions ({elapsed:.2f} s)")
    for reason, n in result.rejected.items():
        if n:
            print(f"rejected: {n} with {REASONS[reason]}")
    if shown is not None and len(shown) <= LISTED_UP_TO:
        rows = [[e.id, ", ".join(f"{v} {k}" for k, v in e.link_orders.items()),
                 e.inversion_classes,
                 " ".join(("-" if k == "R" else ">" if args.oriented else "=").join(
                     str(x + 1) for x in j) for j, k in zip(e.edges, e.kinds)),
                 ", ".join(names(e.chain(args.dof))["chain"]) or "-"]
                for e in shown]
        print(table(rows, ["id", "link assortment", "inversions",
                           "joints (R a-b, P a=b" + (", guide on a: a>b" if args.oriented
                                                     else "") + ")", "catalog name"]))
    if args.out:
        print(f"written: {paths['json']} and {len(paths['chains'])} chain files in "
              f"{paths['chain_dir']}")
        if paths.get("pages") is not None:
            pages = paths["pages"]
            failed = sum(len(p.failed) for p in pages)
            print(f"illustrated: {Path(args.out) / 'index.html'}, {len(pages)} chain pages, "
                  f"{sum(len(p.chain_files) for p in pages)} inversion chain files, "
                  f"{sum(p.animated for p in pages)} animations"
                  + (f" ({failed} inversions did not solve: listed on their pages)"
                     if failed else ""))
            if not animate:
                hours = animation_seconds(result, workers=workers) / 3600
                print(f"not animated: {result.distinct_inversions:,} inversions of "
                      f"{args.links} links, about {hours:.1f} hours on {workers} "
                      f"worker{'s' if workers != 1 else ''}, more than the "
                      f"{LOCAL_HOURS:g} hour a run takes without asking (--illustrate "
                      "animates them)")
    return 0


#: the text of atlas --prismatic lists the chains up to this many
LISTED_UP_TO = 60


def _counted(base, wanted, args):
    """The counts of the chains with sliding pairs, counted as they are found, and the
    chains themselves when there are few enough to list (else None)."""
    counts = SlidingCounts(base.links, base.dof, wanted, args.oriented, {})
    first: list[SlidingEntry] = []
    for entry in sliding_chains(base, prismatic=wanted, oriented=args.oriented,
                                rejected=counts.rejected):
        if args.no_fractionated and entry.fractionated:
            continue
        counts.add(entry)
        if len(first) <= LISTED_UP_TO:
            first.append(entry)
    listed = first if len(counts) <= LISTED_UP_TO else None
    return counts, listed
