"""The report's player: one cycle of a mechanism drawn inline, play/pause, a slider per
input and the output's plot with the current point marked, driven by a small inline
script (``player.js``; no network). Without script the drawing plays by SMIL."""

from __future__ import annotations

import html
import json
import math
from importlib import resources
from typing import TYPE_CHECKING

import numpy as np

from chaingraph.drawing.mechanism import frame_steps, mechanism_svg
from chaingraph.drawing.plots import output_series

if TYPE_CHECKING:                       # the runner's record; it imports this module
    from chaingraph.report.build import Entry

__all__ = ["player_html"]

_PLAYER_SCRIPT = resources.files("chaingraph.report").joinpath("player.js").read_text(
    encoding="utf-8")


def player_html(e: Entry) -> list[str]:
    """The interactive cycle of an entry (its ``motion``, ``grid``, ``frames`` and
    ``slug``), as lines of HTML: the animated drawing inline, play/pause, a slider per
    input and the output's plot with the current point marked. With two moving inputs
    the sliders are independent (the drawing holds a pose for every pair of values, the
    entry's ``grid``); otherwise they follow the one sweep together."""
    m = e.grid if e.grid is not None else e.motion
    assert m is not None, "the player is written only for an entry with a motion"
    grid = e.grid is not None
    picks = list(range(m.theta.size)) if grid else frame_steps(m, e.frames)
    drawing = mechanism_svg(m, frames=len(picks), width=480, paths=not grid).split("?>", 1)[-1]
    if m.inputs:
        inputs = [(i.joint, m.values[i.joint]) for i in m.inputs]
    else:
        inputs = [("\u03b8 (degrees)", m.theta)]
    label, u, *_ = output_series(m)
    if grid:
        size = int(round(math.sqrt(m.theta.size)))
        data = {"grid": size, "inputs": [[float(v) for v in inputs[0][1][:size]],
                                         [float(v) for v in inputs[1][1][::size]]]}
    else:
        size = None
        data = {"inputs": [[float(v[k]) for k in picks] for _, v in inputs]}
    out = ["<h3>" + ("Drag each input" if grid else "One cycle: play it, or drag the input")
           + "</h3>",
           f"<div class=\"player\" id=\"player\" data-frame=\"0\" data-frames=\"{len(picks)}\">",
           "<div class=\"controls\"><button type=\"button\" id=\"play\">pause</button>"]
    for n, (name, values) in enumerate(inputs):
        top = (size if size is not None else len(picks)) - 1
        out.append(f"<label>{html.escape(str(name))} <input type=\"range\" "
                   f"class=\"input-slider\" data-index=\"{n}\" min=\"0\" max=\"{top}\" "
                   f"step=\"1\" value=\"0\"> <output>{values[picks[0]]:.4g}</output></label>")
    out.append("</div>")
    out.append(f"<div class=\"stage\" id=\"stage\">{drawing}</div>")
    x = np.asarray(inputs[0][1] if grid else m.theta, dtype=float)
    y = np.asarray(u, dtype=float)
    against = f"{inputs[0][0]}, one line per value of {inputs[1][0]}" if grid else "the input"
    out.append(_output_plot(x, y, picks, size, data, f"{label} against {against}"))
    out.append(f"<p><a href=\"img/{e.slug}-cycle.svg\">the animation alone</a> (SVG, plays "
               "without script)</p></div>")
    out.append("<script>\nvar PLAYER = " + json.dumps(data) + ";\n" + _PLAYER_SCRIPT + "</script>")
    return out


def _output_plot(x, y, picks, size, data, title):
    """The output ``y`` against the input ``x`` as an SVG stage, one line per run of
    ``size`` steps on a grid (``size`` None: one line), a marker at the first pose;
    puts each picked step's place in the plot into ``data`` (``px``, ``py``)."""
    grid = size is not None
    ok = np.isfinite(x) & np.isfinite(y)
    w, h, pad = 480.0, 200.0, 24.0
    x0, x1 = float(x[ok].min()), float(x[ok].max())
    y0, y1 = float(y[ok].min()), float(y[ok].max())

    def px(v):
        return pad + (v - x0) / max(x1 - x0, 1e-12) * (w - 2 * pad)

    def py(v):
        return h - pad - (v - y0) / max(y1 - y0, 1e-12) * (h - 2 * pad)

    runs = [range(r, r + size) for r in range(0, x.size, size)] if grid else [range(x.size)]
    lines = "".join(
        "<polyline points=\"" + " ".join(f"{px(x[k]):.2f},{py(y[k]):.2f}" for k in run if ok[k])
        + "\" fill=\"none\" stroke=\"#1f4e79\" stroke-width=\"" + ("0.8" if grid else "1.5")
        + "\"/>" for run in runs)
    data["px"] = [px(float(x[k])) if ok[k] else None for k in picks]
    data["py"] = [py(float(y[k])) if ok[k] else None for k in picks]
    return (f"<div class=\"stage\"><svg id=\"output-plot\" xmlns=\"http://www.w3.org/2000/svg\" "
            f"width=\"{w:g}\" height=\"{h:g}\" viewBox=\"0 0 {w:g} {h:g}\">"
            f"<rect width=\"100%\" height=\"100%\" fill=\"white\"/>{lines}"
            f"<circle id=\"marker\" cx=\"{data['px'][0] or 0:.2f}\" cy=\"{data['py'][0] or 0:.2f}\" "
            f"r=\"5\" fill=\"#e07b00\"/>"
            f"<text x=\"{pad:g}\" y=\"14\" font-size=\"11\" font-family=\"sans-serif\">"
            f"{html.escape(str(title))}</text></svg></div>")
