"""``chaingraph cam FILE``: a disc cam and its follower over a turn (the command, kept
apart from the others; its arguments are in :mod:`chaingraph.cli.parser`)."""

from __future__ import annotations

import argparse
import csv
import math
import sys

import numpy as np

from chaingraph.cli.outputs import Writing, output_file, picture_file, svg_file, write_text
from chaingraph.cli.text import print_json, table
from chaingraph.drawing.cams import cam_svg, plot_cam
from chaingraph.errors import ChainFileError
from chaingraph.files import load
from chaingraph.kinematics.cams import CSV_COLUMNS, analyse_cam, cam_summary, cam_table
from chaingraph.model.cams import Cam
from chaingraph.model.chain import Chain

__all__ = ["cmd_cam", "chosen_cam"]


def chosen_cam(chain: Chain, cam_id: str | None) -> Cam:
    """The file's cam called ``cam_id``, or its only cam."""
    if not chain.cams:
        raise ChainFileError("has no [[cams]] table: nothing for 'cam' to analyse",
                             source=chain.source)
    if cam_id is None:
        if len(chain.cams) > 1:
            raise ChainFileError("has several cams; choose one by its id: "
                                 + ", ".join(c.id for c in chain.cams), source=chain.source)
        return chain.cams[0]
    for c in chain.cams:
        if c.id == cam_id:
            return c
    raise ChainFileError(f"no cam {cam_id!r} (cams: {', '.join(c.id for c in chain.cams)})",
                         source=chain.source)


def cmd_cam(args: argparse.Namespace) -> int:
    if not math.isfinite(args.at):
        print(f"chaingraph cam: error: --at must be a finite angle, got {args.at}",
              file=sys.stderr)
        return 2
    chain = load(args.file)
    cam = chosen_cam(chain, args.cam_id)
    if args.csv:
        output_file(args.csv, what="CSV")
    if args.draw:
        svg_file(args.draw, what="cam drawings")
    if args.plot:
        picture_file(args.plot, what="plot")
    limit = None if args.max_pressure is None else math.radians(args.max_pressure)
    summary = cam_summary(cam, name=chain.name, limit=limit)
    if args.csv:
        with Writing(args.csv), open(args.csv, "w", newline="", encoding="utf-8") as f:
            out = csv.writer(f)
            out.writerow(CSV_COLUMNS)
            out.writerows([f"{v + 0.0:.10g}" for v in row] for row in cam_table(cam, steps=args.steps))
    if args.draw or args.plot:
        result = analyse_cam(cam, _fine(args.steps))
        if args.draw:
            write_text(args.draw, cam_svg(cam, result, at=math.radians(args.at),
                                          name=chain.name))
        if args.plot:
            omega = chain.mechanism.omega if chain.mechanism is not None else None
            with Writing(args.plot):
                plot_cam(cam, result, args.plot, name=chain.name, omega=omega,
                         units=chain.units)
    if args.json:
        print_json(summary)
        return 0
    print(_text(cam, summary))
    return 0


def _fine(steps: int) -> np.ndarray:
    """The angles the drawings are made at: at least every half degree."""
    return np.linspace(0.0, 2 * math.pi, max(steps, 720) + 1)


def _text(cam: Cam, summary: dict) -> str:
    """What ``chaingraph cam`` prints: a short table."""
    unit = "deg" if cam.moves == "oscillating" else ""
    pa, rho = summary["pressure_angle"], summary["curvature"]
    rows = [("follower", f"{cam.follower} ({cam.moves}, {cam.contact})"),
            ("base circle", f"{cam.base:g}" + (f", roller {cam.roller:g}" if cam.roller else "")),
            ("stroke", f"{summary['stroke']:.6g} {unit}".rstrip()),
            ("largest pressure angle", f"{pa['max']:.4g} deg at {pa['at']:.4g} deg"),
            ("smallest radius of curvature", f"{rho['min']:.6g} at {rho['at']:.4g} deg"),
            ("undercut", "yes" if summary["undercut"] else "no")]
    if summary["min_base"] is not None:
        why = ("the profile nowhere concave" if cam.contact == "flat"
               else "pressure angle within the limit")
        rows.append(("smallest base circle", f"{summary['min_base']:.6g} ({why})"))
    return f"Cam {cam.id} of {summary['name']}\n" + table(rows, ["", ""]).split("\n", 2)[2]
