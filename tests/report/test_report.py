"""The HTML report: every entry renders, links back, images exist; a browser sees it."""

import math
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from chaingraph.naming.catalog import catalog_dir, catalog_files
from chaingraph.report.build import build_report

from ..conftest import run_cli


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    # one process: the suite's other worker has the other core (two more processes
    # here only contended with it)
    return build_report([catalog_dir()], out, progress=None, workers=1), out


def test_every_catalog_entry_renders(report):
    result, out = report
    assert result.failures == [] and result.complete
    assert len(result.entries) == len(catalog_files())
    index = (out / "index.html").read_text()
    for row in result.entries:
        page = out / f"{row.slug}.html"
        assert page.exists()
        assert f'href="{row.slug}.html"' in index
        text = page.read_text()
        assert 'href="index.html"' in text                      # links back
        assert 'id="classification"' in text and 'id="checks"' in text
        for src in re.findall(r'src="([^"]+)"', text):
            image = out / src
            assert image.exists() and image.stat().st_size > 500, src


def test_mechanism_pages_have_motion(report):
    result, out = report
    text = (out / "shaper-crank-and-slotted-lever.html").read_text()
    assert 'id="summary"' in text and "450 mm" in text
    for suffix in ("pose", "cycle", "motion", "graph"):
        assert f"img/shaper-crank-and-slotted-lever-{suffix}.svg" in text
    cycle = (out / "img" / "shaper-crank-and-slotted-lever-cycle.svg").read_text()
    assert "<animate" in cycle and 'repeatCount="indefinite"' in cycle
    index = (out / "index.html").read_text()
    assert "Crank and slotted lever quick return mechanism" in index and "1.71" in index


def test_bad_paths_are_listed_and_the_rest_go_on(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "broken"\n[[joints]]\nid = "A"\nkind = "Q"\nlinks = ["a", "b"]\n')
    good = catalog_dir() / "four-bar-chain.toml"
    out = tmp_path / "out"
    code, stdout, stderr = run_cli("report", good, bad, tmp_path / "missing.toml", "-o", out, "-q")
    assert code == 1
    assert "unknown kind 'Q'" in stderr and "missing.toml" in stderr
    index = (out / "index.html").read_text()
    assert 'id="failures"' in index and "unknown kind" in index and "four-bar-chain.html" in index
    assert (out / "four-bar-chain.html").exists()


def test_cli_report_says_where(tmp_path):
    code, out, err = run_cli("report", catalog_dir() / "beam-engine.toml", "-o", tmp_path / "r")
    assert code == 0 and str(tmp_path / "r" / "index.html") in out
    assert "1/1" in err  # the progress bar


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def _rendered(page: Path) -> str:
    proc = subprocess.run([CHROMIUM, *FLAGS, "--virtual-time-budget=10000", "--dump-dom",
                           page.as_uri()], capture_output=True, text=True, timeout=120)
    return proc.stdout


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (.ci/run installs "
                                             "Debian's chromium; install it to run this test)")
def test_pages_in_a_real_browser(report):
    result, out = report
    for name in ("index.html", "shaper-crank-and-slotted-lever.html"):
        dom = _rendered(out / name)
        body = re.search(r"<body[^>]*>", dom).group(0)
        total = int(re.search(r'data-images="(\d+)"', body).group(1))
        loaded = int(re.search(r'data-images-loaded="(\d+)"', body).group(1))
        assert loaded == total, f"{name}: {loaded} of {total} images loaded"
        if name == "index.html":
            assert '<table id="entries">' in dom
            assert dom.count("<tr>") >= len(result.entries)
        else:
            assert total >= 3          # graph, pose, motion; the cycle is inline
            for table in ("classification", "checks", "inversions", "summary"):
                assert f'id="{table}"' in dom


_STATE = """(function () {
  var shown = Array.prototype.filter.call(document.querySelectorAll('#stage g.frame'),
    function (g) { return g.getAttribute('visibility') === 'visible'; });
  var pins = {};
  if (shown.length === 1) {
    Array.prototype.forEach.call(shown[0].querySelectorAll('circle.pin'), function (c) {
      pins[c.getAttribute('data-joint')] = [+c.getAttribute('cx'), +c.getAttribute('cy')];
    });
  }
  var marker = document.getElementById('marker');
  return {shown: shown.length, pins: pins,
          frame: +document.getElementById('player').getAttribute('data-frame'),
          readouts: Array.prototype.map.call(document.querySelectorAll('.player output'),
                                             function (o) { return o.textContent; }),
          marker: [+marker.getAttribute('cx'), +marker.getAttribute('cy')]};
})()"""


def _drag(browser, page, slider, value):
    """Move a slider as a user does (its value, then its ``input`` event) and read the
    drawing back from the DOM."""
    browser.evaluate(page, f"(function () {{ var s = document.querySelectorAll("
                           f"'input.input-slider')[{slider}]; s.value = {value}; "
                           f"s.dispatchEvent(new Event('input')); return true; }})()")
    return browser.evaluate(page, _STATE)


needs_chromium = pytest.mark.skipif(
    CHROMIUM is None, reason="Chromium is not installed (.ci/run installs Debian's "
                             "chromium; install it to run this test)")


@needs_chromium
@pytest.mark.parametrize("name, joint", [("shaper-crank-and-slotted-lever", "P"),
                                         ("elliptical-trammels", "B")])
def test_the_input_slider_moves_the_drawing_and_the_marker(report, name, joint):
    """Dragging the slider shows that frame only, moves the drawing, the read-out and
    the plot's marker; the address can also name a frame."""
    from .browser import Browser
    _, out = report
    page = out / f"{name}.html"
    with Browser() as browser:
        tab = browser.open(page.as_uri())
        first = _drag(browser, tab, 0, 0)
        later = _drag(browser, tab, 0, 12)
        linked = browser.open(page.as_uri() + "#frame=12")
        named = browser.evaluate(linked, _STATE)
    assert (first["frame"], later["frame"], named["frame"]) == (0, 12, 12)
    assert first["shown"] == later["shown"] == 1
    assert first["readouts"] != later["readouts"]
    assert math.dist(first["pins"][joint], later["pins"][joint]) > 1.0   # the drawing moved
    assert first["marker"] != later["marker"]
    assert named["pins"] == later["pins"]
    # without script the drawing still plays by SMIL
    static = page.read_text()
    assert "<animate" in static and "attributeName=\"visibility\"" in static


@needs_chromium
def test_two_inputs_have_two_independent_sliders(tmp_path):
    """The five-bar robot's two cranks: each slider moves its own crank and the arms,
    and leaves the other crank where it is."""
    from .browser import Browser
    example = Path(__file__).parents[2] / "examples" / "five-bar-robot.toml"
    build_report([example], tmp_path, progress=None)
    page = tmp_path / "five-bar-robot.html"
    with Browser() as browser:
        tab = browser.open(page.as_uri())
        start = _drag(browser, tab, 0, 0)
        start = _drag(browser, tab, 1, 0)
        right = _drag(browser, tab, 1, 8)          # the right crank (input E) only
        left = _drag(browser, tab, 0, 5)           # then the left crank (input A)
    assert right["frame"] == 8 * 13 and left["frame"] == 8 * 13 + 5
    assert right["readouts"][0] == start["readouts"][0] != left["readouts"][0]
    assert right["readouts"][1] == left["readouts"][1] != start["readouts"][1]
    assert right["pins"]["B"] == start["pins"]["B"]            # the left crank stayed
    assert math.dist(right["pins"]["D"], start["pins"]["D"]) > 1.0
    assert left["pins"]["D"] == right["pins"]["D"]             # the right crank stayed
    assert math.dist(left["pins"]["B"], right["pins"]["B"]) > 1.0
    assert math.dist(left["pins"]["C"], right["pins"]["C"]) > 1.0   # the pen follows both


# -- an interrupted rewrite --------------------------------------------------------------
def _snapshot(folder):
    """Every file under ``folder`` by its relative path, with its bytes."""
    return {str(p.relative_to(folder)): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


SMALL = [catalog_dir() / f"{name}.toml" for name in
         ("four-bar-chain", "crank-rocker-with-slider")]


@pytest.fixture(scope="module")
def _old_report_built(tmp_path_factory):
    out = tmp_path_factory.mktemp("old") / "out"
    build_report(SMALL, out, progress=None, steps=12, frames=4, workers=1)
    return out


@pytest.fixture
def old_report(_old_report_built, tmp_path):
    """A complete report of two entries, as a reader last saw it (built once, a fresh
    copy for each test)."""
    out = tmp_path / "out"
    shutil.copytree(_old_report_built, out)
    return out, _snapshot(out)


def test_a_report_interrupted_while_pages_are_made_leaves_the_old_one(old_report,
                                                                        monkeypatch):
    """Interrupted after a new page was made (Ctrl-C in the page writer of the second
    entry): the folder is the old complete report, file for file, and nothing half made
    is left beside it."""
    from chaingraph.report import build
    out, before = old_report
    made = []
    real = build.entry_page

    def page(entry):
        made.append(entry.slug)
        if len(made) == 2:
            raise KeyboardInterrupt
        return real(entry)
    monkeypatch.setattr(build, "entry_page", page)
    with pytest.raises(KeyboardInterrupt):
        build_report(SMALL[::-1], out, progress=None, steps=24, frames=6, workers=1)
    assert len(made) == 2                            # a new page was made first
    assert _snapshot(out) == before
    assert not [p for p in out.iterdir() if p.name.startswith(".")]


def test_a_report_interrupted_while_moved_into_place_has_no_index(old_report,
                                                                    monkeypatch):
    """Interrupted while its files are moved into place: new and old pages side by side,
    and no index.html to present them as a report."""
    from chaingraph._util import atomic
    out, before = old_report
    moved = []
    real = atomic.os.replace

    def replace(a, b):
        if Path(b).parent == out and Path(b).suffix == ".html":
            moved.append(b)
            if len(moved) == 2:
                raise KeyboardInterrupt
        return real(a, b)
    monkeypatch.setattr(atomic.os, "replace", replace)
    with pytest.raises(KeyboardInterrupt):
        build_report(SMALL[::-1], out, progress=None, steps=24, frames=6, workers=1)
    after = _snapshot(out)
    assert "index.html" in before and "index.html" not in after
    assert after != {k: v for k, v in before.items() if k != "index.html"}   # some are new
    assert not [p for p in out.iterdir() if p.name.startswith(".")]


def test_a_finished_rewrite_replaces_every_page_and_the_index_last(old_report):
    out, before = old_report
    report = build_report(SMALL[:1], out, progress=None, steps=24, frames=6, workers=1)
    after = _snapshot(out)
    assert report.index == out / "index.html" and report.complete
    assert set(after) == set(before)          # the pages of the two left out stay
    assert after["four-bar-chain.html"] != before["four-bar-chain.html"] or \
        after["index.html"] != before["index.html"]
    assert 'href="crank-rocker-with-slider.html"' not in after["index.html"].decode()
    assert not [p for p in out.iterdir() if p.name.startswith(".")]
