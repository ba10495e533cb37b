"""Notebook displays: short reprs, rich HTML and SVG, figures, tables, the walkthrough."""

import json
import sys
import xml.dom.minidom
from html.parser import HTMLParser
from pathlib import Path

import pytest

import chaingraph
from chaingraph.drawing.notebook import register
from chaingraph.drawing.plots import draw_mechanism, plot_motion

from ..conftest import catalog_path

ROOT = Path(__file__).resolve().parents[2]


def well_formed_html(text):
    class Check(HTMLParser):
        def __init__(self):
            super().__init__()
            self.stack = []

        def handle_starttag(self, tag, attrs):
            if tag not in ("br", "img", "meta", "path", "use", "stop"):
                self.stack.append(tag)

        def handle_endtag(self, tag):
            if self.stack and self.stack[-1] == tag:
                self.stack.pop()

    check = Check()
    check.feed(text)
    return "<table>" in text and not [t for t in check.stack if t in ("table", "tr", "td")]


@pytest.fixture(scope="module")
def watt():
    chain = chaingraph.load(catalog_path("watt-i-mechanism"))
    return chain, chaingraph.solve(chain)


def test_reprs_are_short(watt):
    chain, motion = watt
    for obj in (chain, chaingraph.classify(chain), chaingraph.inversions(chain), motion,
                chaingraph.animate(motion, frames=8)):
        assert len(repr(obj)) < 2000, type(obj)
    assert repr(motion).startswith("Motion('Watt I six-bar mechanism', fixed='frame', "
                                   "driver='crank', steps=360, columns=['theta'")
    five = chaingraph.solve(chaingraph.load(ROOT / "examples" / "five-bar-robot.toml"), steps=10)
    assert "inputs=['A', 'E']" in repr(five)


def _registered():
    """The displays as a notebook's formatters hold them: MIME type -> class -> function."""
    class Formatter(dict):
        def for_type(self, cls, fn):
            self[cls] = fn

        def for_type_by_name(self, module, name, fn):
            self[f"{module}.{name}"] = fn

    class Shell:
        class display_formatter:
            formatters = {"text/html": Formatter(), "image/svg+xml": Formatter()}
    assert register(chaingraph.RESULTS, Shell())
    return Shell.display_formatter.formatters


def test_rich_displays_are_valid(watt):
    chain, motion = watt
    shown = _registered()
    svg, html = shown["image/svg+xml"], shown["text/html"]
    xml.dom.minidom.parseString(svg[type(chain)](chain))
    xml.dom.minidom.parseString(chaingraph.animate(motion, frames=8)._repr_svg_())
    for result in (chaingraph.classify(chain), chaingraph.inversions(chain), motion):
        assert well_formed_html(html[type(result)](result))
    page = html[type(motion)](motion)
    assert "<svg" in page and "time ratio" in page


def test_a_synthesis_shows_its_solutions_and_the_best_one_drawn():
    """Registered by its module and name (``import chaingraph`` does not load synthesis):
    a table of the solutions, best first, and the best one's drawing with its
    structural error."""
    from chaingraph.synthesis import Synthesis, function
    found = function(function="log10(x)", x=(1, 2), swing=(60, 90), solutions=3)
    key = f"{Synthesis.__module__}.{Synthesis.__name__}"
    assert key == "chaingraph.synthesis.result.Synthesis"
    page = _registered()["text/html"][key](found)
    assert well_formed_html(page)
    rows = page.split("<table>")[1].split("</table>")[0].count("<tr>")
    assert rows == 1 + len(found.solutions) >= 2              # a header and each solution
    best = found.solutions[0]
    assert f"{best.error.max:.6g}" in page and "crank" in page
    assert page.index(f"{best.error.max:.6g}") < page.index(
        f"{found.solutions[1].error.max:.6g}")                  # best first
    svg = page[page.index("<svg"):page.index("</svg>") + 6]
    xml.dom.minidom.parseString(svg)
    assert "structural error" in svg and "precision points" in svg
    assert "Rejected:" in page and f"{found.searched.candidates} candidates" in page


def test_the_synthesis_display_is_registered_with_ipython_by_name():
    """With a real IPython shell: the formatter holds the display by module and name, and
    uses it for a synthesis once its module is loaded."""
    from IPython.core.formatters import HTMLFormatter          # the notebook extra's
    from chaingraph.synthesis import motion

    class Shell:
        class display_formatter:
            formatters = {"text/html": HTMLFormatter(), "image/svg+xml": HTMLFormatter()}
    assert register(chaingraph.RESULTS, Shell())
    found = motion(poses=[(0, 0, 0), (40, 10, -25)], solutions=1)
    page = Shell.display_formatter.formatters["text/html"](found)
    assert page is not None and well_formed_html(page) and "<svg" in page


def test_without_ipython_nothing_is_registered():
    assert register(chaingraph.RESULTS) is False or "IPython" in sys.modules


def test_plots_return_figures_without_a_path(watt, tmp_path):
    from matplotlib.figure import Figure
    _, motion = watt
    assert isinstance(plot_motion(motion), Figure)
    assert isinstance(draw_mechanism(motion), Figure)
    assert plot_motion(motion, tmp_path / "p.svg") is None and (tmp_path / "p.svg").exists()


def test_to_frame_is_a_dataframe_or_says_what_to_install(watt, monkeypatch):
    import pandas                     # the test extra installs it
    _, motion = watt
    frame = motion.to_frame()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == list(motion.columns) and len(frame) == motion.steps + 1
    monkeypatch.setitem(sys.modules, "pandas", None)          # as where it is not installed
    with pytest.raises(ImportError, match=r"chaingraph\[notebook\]"):
        motion.to_frame()


def test_the_walkthrough_notebook_runs():
    nb = json.loads((ROOT / "docs" / "walkthrough.ipynb").read_text())
    namespace = {}
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            source = "".join(cell["source"])
            exec(compile(source, "walkthrough.ipynb", "exec"), namespace)
    assert round(namespace["motion"].summary["time_ratio"], 3) == 1.71
