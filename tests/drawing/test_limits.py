"""The limit positions drawn: the two extreme poses at the closed-form angles, the input's
arcs with their angles, the stroke marked; from solve and in the report."""

import math
import re

import pytest

import chaingraph
from chaingraph.drawing.limits import limit_shapes, limits_svg
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli


def _inputs(svg):
    return {int(k): float(v) for k, v in
            re.findall(r'data-extreme="(\d)" data-input="([^"]+)"', svg)}


def _angles(svg):
    return sorted({float(v) for v in re.findall(r'class="input-arc" data-angle="([^"]+)"', svg)})


def test_the_slotted_lever_at_the_tangents_from_its_pivot_to_the_crank_circle():
    """Centres 300 (C above A), crank 120: at the extremes the crank is square to the
    lever, at -90 +- acos(120 / 300) degrees; the arcs are 180 +- 2 asin(120 / 300)."""
    m = chaingraph.solve(chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism")))
    svg = limits_svg(m)
    half = math.degrees(math.acos(120.0 / 300.0))
    got = _inputs(svg)
    assert sorted(v % 360 for v in got.values()) == pytest.approx(
        sorted(((-90 - half) % 360, (-90 + half) % 360)), abs=1e-9)
    beta = 2 * math.degrees(math.asin(120.0 / 300.0))
    assert _angles(svg) == pytest.approx([180 - beta, 180 + beta], abs=1e-9)
    assert "forward 227.2" in svg and "return 132.8" in svg and "stroke 47.16\u00b0" in svg
    # the lever passes through the crank pin at each extreme, square to the crank
    scene, shapes = limit_shapes(m)
    two = [(scene.xy["B"][0][k], scene.xy["B"][1][k]) for k in (0, 1)]
    a, c = (0.0, 0.0), (0.0, 300.0)
    for b in two:
        assert (b[0] - c[0]) * (b[0] - a[0]) + (b[1] - c[1]) * (b[1] - a[1]) == \
            pytest.approx(0.0, abs=1e-9)


def test_the_whitworth_drive_s_extremes_and_stroke():
    """C 50 below D, crank 75, the ram's line through D: the extremes where the crank
    pin crosses that line, sin(theta) = 50 / 75; the stroke 87.5 mm."""
    m = chaingraph.solve(chaingraph.load(catalog_path("whitworth-quick-return-with-ram")))
    svg = limits_svg(m)
    t = math.degrees(math.asin(50.0 / 75.0))
    assert sorted(_inputs(svg).values()) == pytest.approx([t, 180 - t], abs=1e-9)
    beta = 2 * math.degrees(math.acos(50.0 / 75.0))
    assert _angles(svg) == pytest.approx([beta, 360 - beta], abs=1e-9)
    assert 'class="stroke" data-stroke="87.5"' in svg


def test_a_rocking_output_gets_its_angle_and_a_rocking_input_one_arc():
    beam = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")))
    svg = limits_svg(beam)
    assert svg.count('class="extreme-line"') == 2 and "stroke" in svg
    four = chaingraph.load(catalog_path("non-grashof-four-bar"))
    rocker = chaingraph.solve(four)                  # a triple rocker: the input rocks
    assert len(rocker.summary.extremes) == 2
    assert limits_svg(rocker).count('class="input-arc"') == 1


def test_limits_from_solve_and_in_the_report(tmp_path):
    out = tmp_path / "limits.svg"
    status, _, err = run_cli("solve", catalog_path("shaper-crank-and-slotted-lever"), "--limits",
                             out)
    assert status == 0, err
    assert "<svg" in out.read_text()
    status, _, err = run_cli("solve", catalog_path("shaper-crank-and-slotted-lever"), "--limits",
                             tmp_path / "x.png")
    assert status == 2 and "give a .svg file" in err
    status, _, err = run_cli("solve", catalog_path("four-bar-chain"), "--limits", out)
    assert status == 2
    from chaingraph.report.build import build_report
    build_report([catalog_path("whitworth-quick-return-with-ram")], tmp_path / "r",
                 progress=None, steps=36, frames=6)
    page = (tmp_path / "r" / "whitworth-quick-return-with-ram.html").read_text()
    assert "<h2>Limit positions</h2>" in page
    assert (tmp_path / "r" / "img" / "whitworth-quick-return-with-ram-limits.svg").exists()
