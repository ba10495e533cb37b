"""Mechanisms written as the textbook gives them: lengths, the input's angle, the mode.

Every pose here is derived by hand in the test (circle and line intersections), or, for
the triad of Stephenson's third inversion, which has no closed form, taken from a drawn
pose whose lengths were measured.
"""

import json
import math
from dataclasses import replace
import warnings

import numpy as np
import pytest

import chaingraph
from chaingraph.errors import DegenerateDrawingError, DimensionError
from chaingraph.kinematics.assembly import measure
from chaingraph.kinematics.plan import build_plan
from chaingraph.model.snap import check_link_sizes
from chaingraph.naming.catalog import catalog_files
from chaingraph.model.chain import Chain, Input, Joint, Mechanism, Point
from chaingraph.files import loads, read_text
from chaingraph.errors import ChainFileError, DimensionError, PoseAdjustedWarning

from ..conftest import CATALOG, catalog_path, run_cli


# -- hand geometry -------------------------------------------------------------------
def circles(p, r, q, s, side):
    """The point at r from p and s from q, left (side=+1) or right of p -> q."""
    d = math.dist(p, q)
    a = (d * d + r * r - s * s) / (2 * d)
    h = math.sqrt(r * r - a * a)
    ux, uy = (q[0] - p[0]) / d, (q[1] - p[1]) / d
    return (p[0] + a * ux - side * h * uy, p[1] + a * uy + side * h * ux)


def polar(p, r, degrees):
    t = math.radians(degrees)
    return (p[0] + r * math.cos(t), p[1] + r * math.sin(t))


def R(id_, links, at=None):
    return Joint(id_, "R", tuple(links), at=at)


def toml_joint(id_, links, at=None, kind="R", extra=""):
    text = f'[[joints]]\nid = "{id_}"\nkind = "{kind}"\nlinks = {json.dumps(list(links))}\n'
    if at is not None:
        text += f"at = [{at[0]!r}, {at[1]!r}]\n"
    return text + extra + "\n"


def close(a, b, tol=1e-9):
    return math.dist(a, b) <= tol


def same_motion(m1, m2, tol=1e-9):
    """Every column of two solved motions agrees at every step."""
    assert list(m1.columns) == list(m2.columns)
    for column in m1.columns:
        a, b = np.asarray(m1[column]), np.asarray(m2[column])
        both = np.isfinite(a) & np.isfinite(b)
        assert np.array_equal(np.isfinite(a), np.isfinite(b)), column
        scale = max(1.0, float(np.abs(a[both]).max(initial=0.0)))
        assert np.allclose(a[both], b[both], atol=tol * scale, rtol=0), column


# -- the four-bar 100/40/120/80, crank at 60 degrees, both modes -------------------------
FOUR_BAR = (toml_joint("A", ["frame", "crank"], (0.0, 0.0))
            + toml_joint("B", ["crank", "coupler"])
            + toml_joint("C", ["coupler", "rocker"])
            + toml_joint("D", ["rocker", "frame"], (100.0, 0.0)))


def four_bar_text(mode=None, angle=60.0, lengths=(40.0, 120.0, 80.0), extra=""):
    crank, coupler, rocker = lengths
    text = f'name = "crank-rocker"\nunits = "mm"\n\n{FOUR_BAR}{extra}'
    text += f"[lengths]\ncrank = {crank}\ncoupler = {coupler}\nrocker = {rocker}\n\n"
    if mode:
        text += f'[assembly]\nC = "{mode}"\n\n'
    text += (f'[mechanism]\nfixed = "frame"\ndriver = "crank"\nat = {angle}\n'
             'output = "rocker"\n')
    return text


@pytest.mark.parametrize("mode, side", [(None, 1), ("left", 1), ("right", -1)])
def test_four_bar_from_lengths_is_the_hand_pose_and_solves_alike(mode, side):
    A, D = (0.0, 0.0), (100.0, 0.0)
    B = polar(A, 40.0, 60.0)
    C = circles(B, 120.0, D, 80.0, side)       # left of B -> D: the open four-bar
    chain = loads(four_bar_text(mode))
    for name, at in zip("ABCD", (A, B, C, D)):
        assert close(chain.joint(name).at, at)
    drawn = Chain("crank-rocker", (R("A", ["frame", "crank"], A), R("B", ["crank", "coupler"], B),
                                   R("C", ["coupler", "rocker"], C), R("D", ["rocker", "frame"], D)),
                  units="mm", mechanism=Mechanism("frame", "crank", output="rocker"))
    same_motion(chaingraph.solve(chain), chaingraph.solve(drawn))
    assert chaingraph.solve(chain).summary["time_ratio"] == pytest.approx(
        chaingraph.solve(drawn).summary["time_ratio"], rel=1e-12)


def test_the_default_mode_is_left_and_assemble_says_so(tmp_path):
    path = tmp_path / "four.toml"
    path.write_text(four_bar_text())
    chain, assembly = chaingraph.files.read_file(path)
    (mode,) = assembly.modes
    assert (mode.part, mode.word, mode.source) == ("C", "left", "default")
    assert "B\u2192D" in mode.reference
    code, out, err = run_cli("assemble", path)
    assert code == 0 and "C: left of the line B\u2192D (default)" in out
    assembled = loads(out)
    assert close(assembled.joint("C").at, chain.joint("C").at, 0)
    code, out, _ = run_cli("assemble", path, "--json")
    data = json.loads(out)
    assert data["modes"] == [{"part": "C", "mode": "left", "reference": "of the line B\u2192D",
                              "source": "default"}]
    assert data["joints"]["C"] == pytest.approx(list(chain.joint("C").at), abs=1e-12)
    out_path = tmp_path / "drawn.toml"
    code, out, _ = run_cli("assemble", path, "-o", out_path)
    assert code == 0 and chaingraph.load(out_path).joint("C").at == pytest.approx(
        chain.joint("C").at, abs=1e-12)


def test_a_rough_position_chooses_the_mode():
    # C sketched below the frame: the crossed mode
    chain = loads(four_bar_text(extra="").replace(
        'links = ["coupler", "rocker"]\n', 'links = ["coupler", "rocker"]\nnear = [130.0, -60.0]\n'))
    B = polar((0.0, 0.0), 40.0, 60.0)
    assert close(chain.joint("C").at, circles(B, 120.0, (100.0, 0.0), 80.0, -1))


def test_every_command_takes_the_lengths_file(tmp_path):
    path = tmp_path / "four.toml"
    path.write_text(four_bar_text())
    for args in (["classify", path], ["inversions", path], ["identify", path],
                 ["solve", path, "--json"]):
        code, out, err = run_cli(*args)
        assert code == 0, (args, err)
    code, out, _ = run_cli("inversions", path, "--json")
    assert json.loads(out)["inversions"][0]["behaviour"] == "crank-rocker"


# -- the offset slider crank: crank 40, rod 120, offset 10 -------------------------------
def slider_text(mode=None, angle=60.0, offset_key=""):
    text = ('name = "offset slider crank"\nunits = "mm"\n\n'
            + toml_joint("O", ["frame", "crank"], (0.0, 0.0))
            + toml_joint("A", ["crank", "rod"])
            + toml_joint("B", ["rod", "slider"])
            + toml_joint("S", ["frame", "slider"], (0.0, 10.0), "P", "axis = 0.0\n" + offset_key)
            + "[lengths]\ncrank = 40.0\nrod = 120.0\n\n")
    if mode:
        text += f'[assembly]\nB = "{mode}"\n\n'
    return text + f'[mechanism]\nfixed = "frame"\ndriver = "crank"\nat = {angle}\noutput = "slider"\n'


@pytest.mark.parametrize("mode, sign", [(None, 1), ("ahead", 1), ("behind", -1)])
def test_offset_slider_crank_from_lengths(mode, sign):
    A = polar((0.0, 0.0), 40.0, 60.0)
    B = (A[0] + sign * math.sqrt(120.0 ** 2 - (A[1] - 10.0) ** 2), 10.0)
    chain = loads(slider_text(mode))
    assert close(chain.joint("A").at, A) and close(chain.joint("B").at, B)
    assert close(chain.joint("S").at, B) and chain.joint("S").axis == 0.0
    drawn = Chain("offset slider crank", (
        R("O", ["frame", "crank"], (0.0, 0.0)), R("A", ["crank", "rod"], A),
        R("B", ["rod", "slider"], B), Joint("S", "P", ("frame", "slider"), at=B, axis=0.0)),
        units="mm", mechanism=Mechanism("frame", "crank", output="slider"))
    same_motion(chaingraph.solve(chain), chaingraph.solve(drawn))
    if sign > 0:
        exact = math.sqrt(160 ** 2 - 10 ** 2) - math.sqrt(80 ** 2 - 10 ** 2)
        assert chaingraph.solve(chain).summary["stroke"] == pytest.approx(exact, rel=1e-12)


# -- Watt I: two ternary links given by their three sides -----------------------------------
def test_watt_i_with_ternary_links_by_three_sides():
    A, D = (0.0, 0.0), (100.0, 0.0)
    B = polar(A, 40.0, 60.0)
    C = circles(B, 120.0, D, 80.0, 1)
    E = circles(B, 70.0, C, 90.0, 1)           # coupler B, C, E: E left of B -> C
    F = circles(C, 50.0, D, 60.0, -1)          # rocker C, D, F: F right of C -> D
    G = circles(E, 110.0, F, 95.0, 1)          # dyad E-G-F: G left of E -> F
    text = ('name = "Watt I"\nunits = "mm"\n\n'
            + toml_joint("A", ["frame", "crank"], A) + toml_joint("B", ["crank", "coupler"])
            + toml_joint("C", ["coupler", "rocker"]) + toml_joint("D", ["rocker", "frame"], D)
            + toml_joint("E", ["coupler", "link 4"]) + toml_joint("F", ["rocker", "link 5"])
            + toml_joint("G", ["link 4", "link 5"])
            + "[lengths]\ncrank = 40.0\ncoupler = {B-C = 120.0, B-E = 70.0, C-E = 90.0}\n"
              "rocker = {C-D = 80.0, C-F = 50.0, D-F = 60.0}\n"
              '"link 4" = 110.0\n"link 5" = 95.0\n\n'
              '[assembly]\nrocker = "right"\n\n'
              '[mechanism]\nfixed = "frame"\ndriver = "crank"\nat = 60.0\noutput = "link 5"\n')
    chain = loads(text)
    for name, at in zip("ABCDEFG", (A, B, C, D, E, F, G)):
        assert close(chain.joint(name).at, at), name
    assert chaingraph.classify(chain).links == 6
    drawn = Chain("Watt I", tuple(Joint(j.id, "R", j.links, at=at) for j, at in
                                  zip(chain.joints, (A, B, C, D, E, F, G))),
                  units="mm", mechanism=chain.mechanism)
    same_motion(chaingraph.solve(chain, steps=72), chaingraph.solve(drawn, steps=72))
    # two lengths and the angle between them give the same link
    by_angle = text.replace("coupler = {B-C = 120.0, B-E = 70.0, C-E = 90.0}",
                            "coupler = {B-C = 120.0, B-E = 70.0, C-B-E = %r}"
                            % math.degrees(math.acos((120 ** 2 + 70 ** 2 - 90 ** 2)
                                                     / (2 * 120 * 70))))
    assert close(loads(by_angle).joint("G").at, G)


# -- Stephenson III: a triad, assembled from rough positions ---------------------------------
def test_stephenson_iii_triad_from_three_sides_and_rough_positions():
    drawn = chaingraph.load(catalog_path("stephenson-iii-mechanism"))
    text = measure(drawn)
    assert '"ternary link" = {B-D = ' in text          # the ternary link by its three sides
    # rough positions, to the millimetre, choose the assembly of the triad
    rough = text
    for j in drawn.joints:
        exact = f"near = [{j.at[0]!r}, {j.at[1]!r}]"
        rough = rough.replace(exact, f"near = [{round(j.at[0])}.0, {round(j.at[1])}.0]")
    assert rough != text
    chain, assembly = read_text(rough)
    assert assembly.groups and len(assembly.groups[0]) == 4
    for j in drawn.joints:
        assert close(chain.joint(j.id).at, j.at), j.id
    same_motion(chaingraph.solve(chain, steps=36), chaingraph.solve(drawn, steps=36))


def test_a_triad_without_rough_positions_asks_for_them():
    text = measure(chaingraph.load(catalog_path("stephenson-iii-mechanism")))
    bare = "\n".join(line for line in text.splitlines() if not line.startswith("near"))
    with pytest.raises(DimensionError, match=r"Assur group of higher class.*near = \[x, y\]"):
        loads(bare)


# -- the five-bar: two inputs --------------------------------------------------------------
def test_five_bar_with_two_inputs_at_their_angles():
    A, E = (0.0, 0.0), (80.0, 0.0)
    B, D = polar(A, 60.0, 100.0), polar(E, 60.0, 70.0)
    C = circles(B, 100.0, D, 100.0, -1)        # right of B -> D: above
    text = ('name = "five-bar"\nunits = "mm"\n\n'
            + toml_joint("A", ["frame", "left crank"], A)
            + toml_joint("B", ["left crank", "left arm"])
            + toml_joint("C", ["left arm", "right arm"])
            + toml_joint("D", ["right arm", "right crank"])
            + toml_joint("E", ["right crank", "frame"], E)
            + '[[points]]\nid = "pen"\nlink = "left arm"\n\n'
            + '[lengths]\n"left crank" = 60.0\n"right crank" = 60.0\n'
              '"right arm" = 100.0\n"left arm" = {B-C = 100.0, B-pen = 120.0, C-pen = 20.0}\n\n'
              '[assembly]\nC = "right"\n\n'
              '[mechanism]\nfixed = "frame"\noutput = "pen"\n'
              'inputs = [{joint = "A", at = 100.0, from = 90.0, to = 110.0}, '
              '{joint = "E", at = 70.0, from = 80.0, to = 60.0}]\n')
    chain = loads(text)
    pen = (B[0] + 1.2 * (C[0] - B[0]), B[1] + 1.2 * (C[1] - B[1]))
    for name, at in zip("ABCDE", (A, B, C, D, E)):
        assert close(chain.joint(name).at, at), name
    assert close(chain.point("pen").at, pen)
    drawn = Chain("five-bar", tuple(Joint(j.id, "R", j.links, at=at) for j, at in
                                    zip(chain.joints, (A, B, C, D, E))),
                  points=(Point("pen", "left arm", pen),), units="mm",
                  mechanism=Mechanism("frame", output="pen", inputs=(
                      Input("A", 90.0, 110.0), Input("E", 80.0, 60.0))))
    same_motion(chaingraph.solve(chain, steps=20), chaingraph.solve(drawn, steps=20))


# -- the textbook's worked examples, in its own dimensions ------------------------------------
@pytest.mark.parametrize("name, ratio, stroke", [
    ("crank-and-slotted-lever-mechanism", None, None),
    ("shaper-crank-and-slotted-lever", 2.0, 450.0),
    ("quick-return-worked-example-3", 1.7, 120.0),
    ("quick-return-assignment-3", None, 375.0),
])
def test_catalog_quick_returns_are_written_in_lengths_and_solve_exactly(name, ratio, stroke):
    text = catalog_path(name).read_text()
    assert "[lengths]" in text
    s = chaingraph.solve(chaingraph.load(catalog_path(name))).summary
    if ratio is None:
        # the lever's extremes are tangent to the crank circle: cos(alpha/2) = crank/AC
        crank, centres = {"crank-and-slotted-lever-mechanism": (120, 300),
                          "quick-return-assignment-3": (75, 200)}[name]
        alpha = 2 * math.degrees(math.acos(crank / centres))
        ratio = (360 - alpha) / alpha
    assert s["time_ratio"] == pytest.approx(ratio, rel=1e-9)
    if stroke is not None:
        assert s["stroke"] == pytest.approx(stroke, rel=1e-9)


def test_the_300_120_drive_gives_1_710():
    s = chaingraph.solve(chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))).summary
    assert round(s["time_ratio"], 3) == 1.710


@pytest.mark.parametrize("path, centres, crank", [
    ("catalog/whitworth-assignment-4.toml", 100.0, 150.0),
    ("catalog/whitworth-quick-return-with-ram.toml", 50.0, 75.0),
])
def test_whitworth_time_ratio_from_crank_and_centres(path, centres, crank):
    beta = 2 * math.degrees(math.acos(centres / crank))
    s = chaingraph.solve(chaingraph.load(path)).summary
    assert s["time_ratio"] == pytest.approx((360 - beta) / beta, rel=1e-9)


def test_assignment_1_example():
    s = chaingraph.solve(chaingraph.load("examples/quick-return-assignment-1.toml")).summary
    assert s["time_ratio"] == pytest.approx(2.0, rel=1e-12)


# -- round trip: every catalog mechanism ----------------------------------------------------
MECHANISMS = [p for p in CATALOG if (c := chaingraph.load(p)).mechanism is not None
              and c.has_pose and all(j.kind in "RP" for j in c.joints)]


@pytest.mark.parametrize("path", MECHANISMS, ids=[p.stem for p in MECHANISMS])
def test_round_trip_measure_then_assemble_gives_the_same_pose(path):
    drawn = chaingraph.load(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        again = loads(measure(drawn))
    for j in drawn.joints:
        assert close(again.joint(j.id).at, j.at), j.id
        if j.kind == "P":
            assert abs(math.remainder(again.joint(j.id).axis - j.axis, 360)) < 1e-9
    for p in drawn.points:
        assert close(again.point(p.id).at, p.at), p.id
    # a P input of a file by lengths measures its values from its guide's origin (its
    # 'at'), where the file of coordinates measured them from the drawn pose
    assert replace(again.mechanism, inputs=tuple(replace(i, at=None) for i in
                                                 again.mechanism.inputs)) == drawn.mechanism
    for item in again.mechanism.inputs:
        if item.at is not None:
            assert again.joint(item.joint).kind == "P"


# -- drawing-level rounding -------------------------------------------------------------------
def test_typed_pose_within_rounding_assembles_with_one_warning_beyond_refused():
    chain = loads(four_bar_text())
    size = max(j.at[0] for j in chain.joints) - min(j.at[0] for j in chain.joints)
    C = chain.joint("C").at
    for off, refused in ((1e-7, False), (1e-4, False), (1e-2, True)):
        typed = f"at = [{C[0]!r}, {C[1] + off * size!r}]\n"
        text = four_bar_text().replace('links = ["coupler", "rocker"]\n',
                                       'links = ["coupler", "rocker"]\n' + typed)
        with warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always")
            if refused:
                with pytest.raises(DimensionError, match=r"joint 'C'.*typed at .* from where "
                                                         r"the lengths put it") as info:
                    loads(text)
                assert info.value.part == "C"
                continue
            got = loads(text)
        assert close(got.joint("C").at, C)
        warned = [w for w in said if issubclass(w.category, PoseAdjustedWarning)]
        assert len(warned) == (1 if off > 1e-6 else 0)
        if warned:
            assert warned[0].message.joint == "C"
            assert warned[0].message.distance == pytest.approx(off * size, rel=1e-6)


def test_snapping_a_pin_onto_its_line_keeps_every_joint_s_other_fields():
    """A guide whose friction and closure are given, on a link that is not fixed (so
    the guide's point moves too): snapped, only the positions change."""
    from chaingraph.model.snap import snap_to_lines
    engine = Chain("engine", (
        Joint("O", "R", ("frame", "crank"), at=(0.0, 0.0)),
        Joint("A", "R", ("crank", "rod"), at=(20.0, 34.64)),
        Joint("B", "R", ("rod", "piston"), at=(176.2, 0.01)),
        Joint("S", "P", ("rod", "piston"), at=(150.0, 0.0), axis=0.0, friction=0.2,
              closure="form")),
        mechanism=Mechanism("frame", "crank"))
    with pytest.warns(PoseAdjustedWarning):
        snapped = snap_to_lines(engine)
    assert snapped.joint("B").at[1] == pytest.approx(snapped.joint("S").at[1], abs=1e-12)
    for before, after in zip(engine.joints, snapped.joints):
        assert replace(after, at=before.at) == before


def test_pin_within_rounding_of_its_line_is_put_on_it(tmp_path):
    engine = chaingraph.load(catalog_path("reciprocating-engine"))
    size = 176.20499351813308 + 20.0
    for off in (1e-4, 1e-2):
        joints = [j if j.id != "B" else Joint("B", "R", j.links, at=(j.at[0], off * size))
                  for j in engine.joints]
        path = tmp_path / "engine.toml"
        chaingraph.save(Chain(engine.name, tuple(joints), units="mm",
                              mechanism=engine.mechanism), path)
        code, out, err = run_cli("solve", path, "--json")
        assert code == 0
        lines = [x for x in err.splitlines() if x]
        if off == 1e-4:
            # rounding: the pin goes onto the cylinder's line, and the user is told
            assert len(lines) == 1 and lines[0].startswith("chaingraph: warning:")
            assert "joint 'B'" in lines[0] and "off the sliding line of S" in lines[0]
            with pytest.warns(PoseAdjustedWarning):
                assert chaingraph.load(path).joint("B").at[1] == 0.0
        else:
            # farther off: an offset slider, as drawn (issue 10, item 7)
            assert lines == []
            assert chaingraph.load(path).joint("B").at[1] == pytest.approx(off * size)


# -- bad input: one clear line, exit 2 ---------------------------------------------------------
def test_unassemblable_input_names_the_part_and_the_range(tmp_path):
    text = four_bar_text(angle=120.0, lengths=(40.0, 50.0, 30.0))
    with pytest.raises(DimensionError) as info:
        loads(text)
    limit = math.degrees(math.acos((40 ** 2 + 100 ** 2 - 80 ** 2) / (2 * 40 * 100)))
    e = info.value
    assert e.part == "C" and e.feasible_range == pytest.approx((-limit, limit), abs=1e-7)
    assert "the dyad of links 'coupler' and 'rocker' at joint C does not close" in str(e)
    path = tmp_path / "bad.toml"
    path.write_text(text)
    code, out, err = run_cli("solve", path)
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err
    assert f"from {-limit:.6g} to {limit:.6g} degrees" in err


@pytest.mark.parametrize("change, words", [
    (("coupler = 120.0\n", ""), "no length given for link 'coupler' (joints and points: B, C)"),
    (("crank = 40.0", "crank = 0.0"), "a length must be positive, got 0"),
    (("crank = 40.0", "crank = -5.0"), "a length must be positive, got -5"),
    (('[mechanism]', '[assembly]\nX = "left"\n\n[mechanism]'),
     "[assembly] 'X': names no part with two assembly modes"),
    (('[mechanism]', '[assembly]\nC = "up"\n\n[mechanism]'), "an assembly mode is one of"),
    (("crank = 40.0", "crank = {A-Q = 40.0}"), "'A-Q' names no pair of its joints"),
    (("crank = 40.0", "crank = 40.0\nwheel = 3.0"), "[lengths] 'wheel': names no link"),
    (('at = [100.0, 0.0]\n', ''), "'D' is on the fixed link 'frame': give its 'at'"),
    (('driver = "crank"\n', 'driver = "crank"\ninputs = ["A"]\n'), "'at' in [mechanism] is the driver's"),
])
def test_bad_lengths_get_one_clear_line(tmp_path, change, words):
    text = four_bar_text().replace(*change)
    with pytest.raises(ChainFileError) as info:
        loads(text, source="bad.toml")
    assert words in str(info.value)
    path = tmp_path / "bad.toml"
    path.write_text(text)
    code, _, err = run_cli("assemble", path)
    assert code == 2 and err.startswith("chaingraph: error:") and err.count("\n") == 1


def test_triangle_inequality_is_named():
    text = ('name = "plate"\n' + toml_joint("A", ["frame", "crank"], (0.0, 0.0))
            + toml_joint("B", ["crank", "plate"]) + toml_joint("C", ["plate", "rocker"])
            + toml_joint("D", ["rocker", "frame"], (100.0, 0.0))
            + toml_joint("E", ["plate", "arm"]) + toml_joint("F", ["arm", "frame"], (50.0, 90.0))
            + "[lengths]\ncrank = 40.0\nrocker = 80.0\narm = 50.0\n"
              "plate = {B-C = 60.0, B-E = 100.0, C-E = 10.0}\n"
              '[mechanism]\nfixed = "frame"\ndriver = "crank"\nat = 60.0\n')
    with pytest.raises(DimensionError, match=r"link 'plate' violate the triangle inequality: "
                                             r"B-E = 100 is longer than C-E \+ B-C = 70"):
        loads(text)


def test_dimension_keys_need_a_lengths_table():
    text = four_bar_text().replace("[lengths]\ncrank = 40.0\ncoupler = 120.0\nrocker = 80.0\n",
                                   "")
    with pytest.raises(ChainFileError, match="belongs to a mechanism given by its lengths"):
        loads(text)


def test_measure_command_writes_a_file_that_assembles_back(tmp_path):
    out = tmp_path / "lengths.toml"
    code, text, err = run_cli("measure", catalog_path("watt-i-mechanism"), "-o", out)
    assert code == 0 and "[lengths]" in out.read_text()
    drawn, again = chaingraph.load(catalog_path("watt-i-mechanism")), chaingraph.load(out)
    for j in drawn.joints:
        assert close(again.joint(j.id).at, j.at)


def test_malformed_dimension_keys_raise_only_file_errors():
    """A fuzz of the dimension keys: every value of the wrong type, size or sign gives a
    ChainFileError (one clear line on the command line), never another exception."""
    import copy
    import random
    import tomllib

    from chaingraph.files import read_document
    bases = [tomllib.loads(open(p).read()) for p in
             ("examples/four-bar-lengths.toml", "catalog/shaper-crank-and-slotted-lever.toml")]
    values = [0, -1, 1e308, -1e308, 1e-308, "x", [1], [1, 2], {"a": 1}, {}, True, 3.5, [],
              [[1]], {"B-C": 1}, {"A-B-C": 400}, "left", "ahead", {"C": "left"}, 1e200]
    rng = random.Random(7)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(600):
            doc = copy.deepcopy(rng.choice(bases))
            for _ in range(rng.randint(1, 3)):
                where, value = rng.choice(["lengths", "assembly", "mechanism", "joint"]), \
                    rng.choice(values)
                if where == "lengths":
                    doc["lengths"][rng.choice(["crank", "coupler", "link", "frame", "zz"])] = value
                elif where == "assembly":
                    doc.setdefault("assembly", {})[rng.choice(["C", "R", "crank", "X"])] = value
                elif where == "mechanism":
                    doc["mechanism"][rng.choice(["at", "inputs", "driver"])] = value
                else:
                    rng.choice(doc["joints"])[rng.choice(
                        ["at", "near", "offset", "angle", "block_offset", "axis"])] = value
            try:
                read_document(doc, source="fuzz.toml")
            except ChainFileError:
                pass


def test_fixed_link_by_its_length_and_direction():
    """The fixed pivots by a distance and the direction of the line between them."""
    A = (10.0, 5.0)
    D = polar(A, 100.0, 30.0)
    text = four_bar_text().replace("at = [100.0, 0.0]\n", "").replace(
        "at = [0.0, 0.0]", "at = [10.0, 5.0]").replace(
        "[lengths]\n", "[lengths]\nframe = {A-D = 100.0, direction = 30.0}\n")
    chain = loads(text)
    B = polar(A, 40.0, 60.0)
    for name, at in zip("ABCD", (A, B, circles(B, 120.0, D, 80.0, 1), D)):
        assert close(chain.joint(name).at, at), name
    with pytest.raises(ChainFileError, match="'direction' places the fixed link"):
        loads(text.replace("crank = 40.0", "crank = {A-B = 40.0, direction = 5.0}"))


# -- measure on mutated files: one clear error or a file that reads back -----------------------
def test_measure_of_mutated_mechanisms_is_a_file_or_one_clear_error():
    """The fuzzing pass: one joint's link changed in a catalog mechanism (a link left
    with one joint, a driver no longer pinned to the frame) ended in IndexError."""
    import random
    import tomllib

    from chaingraph.files import read_document
    rng = random.Random(25)
    files = [p for p in catalog_files() if "[mechanism]" in p.read_text()]
    tried = 0
    for _ in range(300):
        path = rng.choice(files)
        doc = tomllib.loads(path.read_text())
        names = sorted({x for j in doc["joints"] for x in j["links"]}) + ["new"]
        joint = rng.choice(doc["joints"])
        joint["links"][rng.randrange(len(joint["links"]))] = rng.choice(names)
        try:
            chain = read_document(doc, source=str(path))[0]
        except chaingraph.ChainGraphError:
            continue
        tried += 1
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                loads(measure(chain))
            except chaingraph.ChainGraphError as e:
                assert "\n" not in str(e)
    assert tried >= 150


def test_measure_names_a_link_with_a_single_joint():
    text = catalog_path("watt-ii-mechanism").read_text().replace(
        'links = ["frame", "crank"]', 'links = ["frame", "dangle"]', 1)
    with pytest.raises(chaingraph.DimensionError, match="'dangle' has a single joint"):
        measure(loads(text))


def test_a_point_on_a_joint_is_measured_and_read_back():
    """The five-bar robot's pen sits on the pin C: its distance from C is 0, which the
    reader takes for a point (measure wrote it, then refused its own file); a joint-to-
    joint length of 0, or a negative distance, is still refused."""
    robot = chaingraph.load("examples/five-bar-robot.toml")
    text = measure(robot)
    assert "C-pen = 0.0" in text
    again = loads(text)
    for j in robot.joints:
        assert math.dist(j.at, again.joint(j.id).at) <= 1e-9 * 200
    assert math.dist(robot.point("pen").at, again.point("pen").at) <= 1e-9 * 200
    with pytest.raises(ChainFileError, match="must not be negative"):
        loads(text.replace("C-pen = 0.0", "C-pen = -1.0"))
    with pytest.raises(ChainFileError, match="a length must be positive"):
        loads(text.replace("B-C = 100.0", "B-C = 0.0"))


def test_the_whitworth_worked_example_gives_the_text_s_ratio_and_stroke():
    """Worked example 4: centres 50, crank 75, rod 135; the text measures a stroke of
    87.5 mm, which with the ram's line through the lever's pivot is twice the arm the
    file takes (43.75 mm; the text's 150 mm is the whole slotted lever)."""
    chain = chaingraph.load(catalog_path("whitworth-quick-return-with-ram"))
    s = chaingraph.solve(chain).summary
    assert round(s["time_ratio"], 3) == 2.735
    assert s["stroke"] == pytest.approx(87.5, rel=1e-9)
    assert "43.75" in chain.notes and "87.5" in chain.notes and "not give" in chain.notes


# -- issue 35, item 4: a drawing that gives a link no length ---------------------------
def _drawn(*joints):
    return Chain("drawn", tuple(Joint(*j[:3], at=j[3], axis=j[4] if len(j) > 4 else None)
                                for j in joints))


def test_a_link_with_its_joints_at_one_point_is_a_dimension_error_with_its_fields():
    chain = _drawn(("A", "R", ("frame", "crank"), (0.0, 0.0)),
                   ("B", "R", ("crank", "coupler"), (20.0, 0.0)),
                   ("C", "R", ("coupler", "rocker"), (20.0, 1e-13)),
                   ("D", "R", ("rocker", "frame"), (100.0, 0.0)))
    with pytest.raises(DegenerateDrawingError) as caught:
        check_link_sizes(chain)
    e = caught.value
    assert isinstance(e, DimensionError) and isinstance(e, ValueError)
    assert (e.link, e.part, e.joints, e.at) == ("coupler", "coupler", ("B", "C"), (20.0, 0.0))
    assert str(e) == "drawn: link 'coupler' has zero length: joints 'B' and 'C' are both " \
                     "drawn at (20, 0)"
    # the same chain through the solver's front door
    with pytest.raises(DegenerateDrawingError):
        build_plan(chain, fixed="frame", driver="crank")


def test_short_links_and_joints_that_share_a_point_on_purpose_are_not_refused():
    """A link of 1e-9 of the size is short, not degenerate; a block's R joint on its
    sliding pair's point, and two R joints of a ternary link at one point (a multiple
    joint written as two) give the link its direction by other joints."""
    check_link_sizes(_drawn(("A", "R", ("frame", "crank"), (0.0, 0.0)),
                            ("B", "R", ("crank", "coupler"), (1e-7, 0.0)),
                            ("C", "R", ("coupler", "rocker"), (60.0, 50.0)),
                            ("D", "R", ("rocker", "frame"), (100.0, 0.0))))
    check_link_sizes(_drawn(("O", "R", ("frame", "crank"), (0.0, 0.0)),
                            ("A", "R", ("crank", "rod"), (20.0, 30.0)),
                            ("B", "R", ("rod", "block"), (150.0, 0.0)),
                            ("S", "P", ("frame", "block"), (150.0, 0.0), 0.0)))
    check_link_sizes(_drawn(("A", "R", ("frame", "plate"), (0.0, 0.0)),
                            ("B", "R", ("plate", "x"), (40.0, 0.0)),
                            ("C", "R", ("plate", "y"), (40.0, 0.0)),
                            ("D", "R", ("x", "frame"), (80.0, 10.0)),
                            ("E", "R", ("y", "frame"), (80.0, -10.0))))
