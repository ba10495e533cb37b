"""The HTML report: every entry renders, links back, images exist; a browser sees it."""

import math
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from chaingraph.catalog import catalog_dir, catalog_files
from chaingraph.report import build_report

from .conftest import run_cli


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    return build_report([catalog_dir()], out, progress=None), out


def test_every_catalog_entry_renders(report):
    result, out = report
    assert result.failures == [] and result.exit_status == 0
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


def _dom_at_frame(page: Path, frame: int) -> str:
    proc = subprocess.run([CHROMIUM, *FLAGS, "--virtual-time-budget=3000", "--dump-dom",
                           page.as_uri() + f"#frame={frame}"],
                          capture_output=True, text=True, timeout=120)
    return proc.stdout


def _visible_frame(dom):
    import xml.etree.ElementTree as ET
    svg = re.search(r'<div class="stage" id="stage">(.*?)</div>', dom, re.S).group(1)
    root = ET.fromstring(svg)
    ns = {"s": "http://www.w3.org/2000/svg"}
    shown = [g for g in root.findall("s:g[@class='frame']", ns) if g.get("visibility") == "visible"]
    assert len(shown) == 1
    return {c.get("data-joint"): (float(c.get("cx")), float(c.get("cy")))
            for c in shown[0].findall("s:circle[@class='pin']", ns)}


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (.ci/run installs "
                                             "Debian's chromium; install it to run this test)")
@pytest.mark.parametrize("name, joint", [("shaper-crank-and-slotted-lever", "P"),
                                         ("elliptical-trammels", "B")])
def test_the_input_slider_moves_the_drawing_and_the_marker(report, name, joint):
    """The page's script reads the frame from the address (as a dragged slider sets it)
    and shows that frame only, moves the slider and the plot's marker."""
    _, out = report
    page = out / f"{name}.html"
    first, later = _dom_at_frame(page, 0), _dom_at_frame(page, 12)
    for dom, frame in ((first, 0), (later, 12)):
        assert f'id="player" data-frame="{frame}"' in dom
    # the slider's read-out shows the input's value at that frame
    shown = [re.search(r'class="input-slider"[^>]*> <output>([^<]*)</output>', d).group(1)
             for d in (first, later)]
    assert shown[0] != shown[1]
    a, b = _visible_frame(first), _visible_frame(later)
    assert math.dist(a[joint], b[joint]) > 1.0          # the drawing moved
    marker = [re.search(r'<circle id="marker" cx="([-\d.]+)"', d).group(1) for d in (first, later)]
    assert marker[0] != marker[1]
    # without script the drawing still plays by SMIL
    static = page.read_text()
    assert "<animate" in static and "attributeName=\"visibility\"" in static
