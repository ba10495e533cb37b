"""The assembly (position analysis from lengths) on the solver's kernels: the same poses
as before, every catalog mechanism found again from its own measured lengths, and the
range where a mechanism assembles at the solver's exact limits."""

import importlib.util
import json
import math
import warnings
from pathlib import Path

import pytest

import chaingraph
from chaingraph.errors import DimensionError
from chaingraph.kinematics import build_plan, feasible_range
from chaingraph.kinematics.assembly import measure
from chaingraph.naming.catalog import catalog_path

from ..conftest import solver_takes

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
REFERENCE = json.loads((DATA / "assembly-poses.json").read_text(encoding="utf-8"))


def _maker():
    spec = importlib.util.spec_from_file_location("make_assembly_poses",
                                                  DATA / "make_assembly_poses.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def now():
    return _maker().poses(ROOT)


def _size(pose):
    pts = list(pose["joints"].values()) + list(pose["points"].values())
    return max(max(p[0] for p in pts) - min(p[0] for p in pts),
               max(p[1] for p in pts) - min(p[1] for p in pts))


@pytest.mark.parametrize("name", sorted(REFERENCE))
def test_every_mechanism_assembles_to_the_same_pose_as_before(name, now):
    """Every [lengths] file, and every mechanism measured and assembled again, to 1e-9
    of its size (the reference was written before the assembly used the solver's
    dyads, Newton step and limits)."""
    want, got = REFERENCE[name], now[name]
    size = _size(want)
    assert set(got["joints"]) == set(want["joints"])
    for key in ("joints", "points"):
        for j, p in want[key].items():
            assert math.dist(p, got[key][j]) <= 1e-9 * size, (j, p, got[key][j])
    for j, axis in want["axes"].items():
        assert abs(math.remainder(axis - got["axes"][j], 360.0)) <= 1e-9


# (a cam's or gear's link has no lengths to measure: its profile or pitch circle is
# its [[cams]] or [[gears]] table, so chains with higher pairs are not given by lengths)
DRAWN = sorted(p for p in (ROOT / "catalog").glob("*.toml")
               if "[mechanism]" in (text := p.read_text(encoding="utf-8"))
               and "[lengths]" not in text and solver_takes(c := chaingraph.load(p))
               and not (c.cams or c.gears))


@pytest.mark.parametrize("path", DRAWN, ids=lambda p: p.stem)
def test_every_catalog_mechanism_is_found_again_from_its_lengths(path):
    """measure() then load(): the drawn pose again, to 1e-9 of the size."""
    chain = chaingraph.load(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        again = chaingraph.loads(measure(chain))
    size = max(max(j.at[0] for j in chain.joints) - min(j.at[0] for j in chain.joints),
               max(j.at[1] for j in chain.joints) - min(j.at[1] for j in chain.joints))
    for j in chain.joints:
        assert math.dist(j.at, again.joint(j.id).at) <= 1e-9 * size, j.id
    for p in chain.points:
        assert math.dist(p.at, again.point(p.id).at) <= 1e-9 * size, p.id


FOUR_BAR = (DATA.parent.parent / "examples" / "four-bar-lengths.toml").read_text()
PISTON = (DATA / "slider-by-lengths-piston-input.toml").read_text()


def test_a_group_of_higher_class_is_assembled_by_newton_s_method():
    """Stephenson's third inversion: its triad is solved by the solver's Newton step
    from the rough positions measure() writes, to the drawn pose."""
    chain = chaingraph.load(catalog_path("stephenson-iii-mechanism"))
    again, assembly = chaingraph.files.read_text(measure(chain))
    assert assembly.groups and any(m.word == "near" for m in assembly.modes)
    for j in chain.joints:
        assert math.dist(j.at, again.joint(j.id).at) <= 1e-9 * assembly.size


@pytest.mark.parametrize("text, value, want", [
    # a double rocker (crank 40, coupler 50, rocker 30 on 100): the crank reaches the
    # fold where B is 80 from D, at acos((40^2 + 100^2 - 80^2) / (2 40 100)) = acos(0.65)
    (FOUR_BAR.replace("coupler = 120.0", "coupler = 50.0").replace("rocker = 80.0",
                                                                    "rocker = 30.0"),
     120.0, [(-math.degrees(math.acos(0.65)), math.degrees(math.acos(0.65)))]),
    # a slider-crank driven by its piston: B from 150 - 50 to 150 + 50 of the pivot,
    # on either side of it
    (PISTON, 250.0, [(-200.0, -100.0), (100.0, 200.0)]),
])
def test_the_range_that_assembles_is_the_solver_s_exact_one(text, value, want):
    """A mechanism that cannot be assembled at its input's value says where it can:
    the solver's own range, to its folds (to 1e-10 degree or length; the bisection before was 5e-10 off)."""
    bad = text.replace("at = 60.0", f"at = {value}").replace("at = 180.0", f"at = {value}")
    with pytest.raises(DimensionError) as info:
        chaingraph.loads(bad)
    got = info.value.feasible_range
    got = [got] if isinstance(got, tuple) else got
    assert len(got) == len(want)
    for (lo, hi), (a, b) in zip(got, want):
        assert lo == pytest.approx(a, abs=1e-10) and hi == pytest.approx(b, abs=1e-10)
        good = chaingraph.loads(bad.replace(f"at = {value}", f"at = {0.5 * (a + b)}"))
        assert feasible_range(build_plan(good)) == pytest.approx((a, b), abs=1e-9)
