"""Every failure a clear error, every run bounded (issue 16): fuzzed documents and text,
output paths, adversarial numbers and sizes, each ending in one line and the right exit
status, never a traceback; resource tests under a memory limit."""

import contextlib
import io
import json
import os
import resource
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import chaingraph
from chaingraph.kinematics import tracking
from chaingraph import ChainGraphError
from chaingraph.naming.catalog import catalog_path
from chaingraph.cli.main import main
from ..conftest import children, interruptible, run_console_script, wait_for


CRANK = str(catalog_path("crank-rocker-with-slider"))
FOUR_BAR = catalog_path("four-bar-chain")


def _main(*args):
    """The command line in this process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main([str(a) for a in args])
        except SystemExit as e:                 # argparse's usage errors
            code = e.code
    return code, out.getvalue(), err.getvalue()


def _one_line(err):
    return err.count("\n") <= 1 and "Traceback" not in err and err.startswith("chaingraph")


# -- fuzzing the loader ------------------------------------------------------------
SOURCE = FOUR_BAR.read_text()
DOC = tomllib.loads(SOURCE)

values = st.recursive(
    st.none().map(lambda _: "x") | st.booleans() | st.integers() | st.floats()
    | st.integers(min_value=10**300, max_value=10**400) | st.text(max_size=8)
    | st.sampled_from(["$\\frac{a}{b}$", "R", "P", "", "a b", "crank"]),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=5), inner,
                                                                  max_size=3),
    max_leaves=8)


@st.composite
def mutated_documents(draw):
    doc = json.loads(json.dumps(DOC))
    for _ in range(draw(st.integers(1, 3))):
        node = doc
        path = []
        while isinstance(node, (dict, list)) and node and draw(st.booleans()):
            key = (draw(st.sampled_from(sorted(node))) if isinstance(node, dict)
                   else draw(st.integers(0, len(node) - 1)))
            path.append((node, key))
            node = node[key]
        if path:
            parent, key = path[-1]
            if isinstance(parent, dict) and draw(st.booleans()):
                del parent[key]
            else:
                parent[key] = draw(values)
        else:
            doc[draw(st.text(max_size=6))] = draw(values)
    return doc


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated_documents())
def test_a_mutated_document_loads_or_says_what_is_wrong(doc):
    try:
        chain = chaingraph.from_document(doc, source="fuzz.toml")
    except ChainGraphError as e:
        assert str(e).startswith("fuzz.toml") and "\n" not in str(e)
        return
    chaingraph.classify(chain)


@settings(max_examples=300, deadline=None)
@given(st.data())
def test_mutated_text_loads_or_says_what_is_wrong(data):
    text = SOURCE
    for _ in range(data.draw(st.integers(1, 4))):
        i = data.draw(st.integers(0, len(text)))
        j = data.draw(st.integers(i, min(len(text), i + 12)))
        text = text[:i] + data.draw(st.sampled_from(
            ["", "[", "]", "{", "\"", "=", "\n", "1e999", "9" * 5000, "[[joints]]", "$x$",
             "nan", "-", "\\u0000"])) + text[j:]
    try:
        chaingraph.loads(text, source="fuzz.toml")
    except ChainGraphError as e:
        assert "fuzz.toml" in str(e) and "Traceback" not in str(e)


def test_deep_nesting_is_the_files_error(tmp_path):
    for text in ("x = " + "[" * 5000 + "]" * 5000, "x = " + "{a=" * 3000 + "1" + "}" * 3000):
        path = tmp_path / "deep.toml"
        path.write_text(text)
        code, out, err = _main("classify", path)
        assert code == 2 and _one_line(err) and "nested too deeply" in err


# -- numbers -----------------------------------------------------------------------
@pytest.mark.parametrize("replace, key", [
    ("at = [1" + "0" * 400 + ", 2]", "'at' x"),
    ("at = [1" + "0" * 5000 + ", 2]", "cannot be read"),
    ("at = [1e300, 2]", "too large"),
])
def test_numbers_that_cannot_be_computed_are_refused(tmp_path, replace, key):
    text = SOURCE.replace(SOURCE[SOURCE.index("at = ["):].split("\n")[0], replace, 1)
    path = tmp_path / "big.toml"
    path.write_text(text)
    code, out, err = _main("classify", path)
    assert code == 2 and _one_line(err) and key in err


@pytest.mark.parametrize("args, words", [
    (["design", "slotted-lever", "--time-ratio", "1.5", "--crank", "1e154", "--stroke",
      "1e155"], "--crank"),
    (["design", "whitworth", "--time-ratio", "1.5", "--crank", "100", "--stroke", "1e308"],
     "--stroke"),
    (["solve", CRANK, "--from", "1e308", "--steps", "2"], "too large"),
    (["solve", CRANK, "--steps", "100000000"], "GiB"),
    (["solve", CRANK, "--steps", "1e8"], "invalid int value"),
    (["solve", CRANK, "--steps", "9" * 400], "about 10^399 steps"),
    (["solve", CRANK, "--steps", "0"], "steps"),
])
def test_command_line_numbers_are_refused_up_front(args, words, monkeypatch):
    """Refused before any position is solved."""
    monkeypatch.setattr(tracking, "_evaluate", _no_work)
    code, out, err = _main(*args)
    assert code == 2 and words in err and "Traceback" not in err
    assert err.count("\n") == 1


def _no_work(*args):
    raise AssertionError("positions were solved before the refusal")


class _Counted:
    """Wraps the path evaluation: how many points were solved, and the longest path."""

    def __init__(self, monkeypatch):
        self.points, self.longest, self._evaluate = 0, 0, tracking._evaluate
        monkeypatch.setattr(tracking, "_evaluate", self)

    def __call__(self, plan, theta, start):
        self.points += theta.size
        self.longest = max(self.longest, theta.size)
        return self._evaluate(plan, theta, start)


def test_far_angles_are_taken_modulo_a_turn():
    near = chaingraph.solve(chaingraph.load(CRANK), start=30, stop=40, steps=2)
    far = chaingraph.solve(chaingraph.load(CRANK), start=30 + 360 * 10**6,
                           stop=40 + 360 * 10**6, steps=2)
    for key in near.columns:
        if key not in ("theta",) and not key.startswith("input:"):
            assert far[key] == pytest.approx(near[key], abs=1e-6), key


# -- output paths ------------------------------------------------------------------
def _outputs(tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("x")
    return {
        "a folder": (tmp_path, "is a folder"),
        "under a file": (afile / "x.out", "is a file, not a folder"),
        "a full disk": ("/dev/full", "No space left"),
    }


@pytest.mark.parametrize("case", ["a folder", "under a file", "a full disk"])
@pytest.mark.parametrize("flag", ["--csv", "--plot", "--draw"])
def test_solve_outputs_that_cannot_be_written(tmp_path, flag, case):
    path, words = _outputs(tmp_path)[case]
    if flag != "--csv" and case == "under a file":
        path = str(path) + ".svg"
    code, out, err = _main("solve", CRANK, flag, path)
    assert code == 2 and _one_line(err) and words in err, err


def test_folder_outputs_that_cannot_be_written(tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("x")
    for args in (["report", FOUR_BAR, "-o", afile, "-q"], ["atlas", "--links", "6", "--out",
                                                           afile / "x", "-q"],
                 ["design", "whitworth", "--time-ratio", "1.5", "--crank", "100", "--stroke",
                  "300", "--out", tmp_path]):
        code, out, err = _main(*args)
        assert code == 2 and _one_line(err) and str(tmp_path) in err, (args, err)


def test_unknown_picture_format_lists_the_formats(tmp_path):
    code, out, err = _main("solve", CRANK, "--plot", tmp_path / "x.xyz")
    assert code == 2 and _one_line(err) and ".png" in err and ".svg" in err


def test_missing_folders_of_an_output_are_made(tmp_path):
    path = tmp_path / "a" / "b" / "motion.csv"
    code, out, err = _main("solve", CRANK, "--csv", path, "--steps", "8")
    assert code == 0 and path.exists()


# -- names drawn as text -------------------------------------------------------------
def test_names_with_dollars_are_drawn_as_text(tmp_path):
    text = CRANK_TEXT = open(CRANK).read()
    chain = chaingraph.load(CRANK)
    for link in chain.links:
        text = text.replace(f'"{link}"', f'"$\\\\frac{{{link}}}{{b}}$"')
    path = tmp_path / "dollars.toml"
    path.write_text(text)
    assert text != CRANK_TEXT
    code, out, err = _main("solve", path, "--plot", tmp_path / "p.png", "--draw",
                           tmp_path / "d.png", "--steps", "12")
    assert code == 0, err
    code, out, err = _main("report", path, "-o", tmp_path / "report", "-q")
    assert code == 0, err
    assert "$\\frac{" in (tmp_path / "report" / "dollars.html").read_text()


# -- report pages ------------------------------------------------------------------
def test_a_chain_file_called_index_keeps_its_page(tmp_path):
    for name in ("Index.toml", "img.toml"):
        (tmp_path / name).write_text(FOUR_BAR.read_text())
    code, out, err = _main("report", tmp_path / "Index.toml", tmp_path / "img.toml",
                           "-o", tmp_path / "out", "-q")
    assert code == 0, err
    index = (tmp_path / "out" / "index.html").read_text()
    assert 'href="index-2.html"' in index and 'href="img-2.html"' in index
    assert (tmp_path / "out" / "index-2.html").exists()


@pytest.mark.parametrize("workers, code, words", [("0", 2, "must be 1 or more"),
                                                   ("-3", 2, "must be 1 or more"),
                                                   ("500", 0, "capped")])
def test_report_workers_are_checked_and_capped(tmp_path, workers, code, words):
    got, out, err = _main("report", FOUR_BAR, "-o", tmp_path, "-q", "--workers", workers)
    assert got == code and words in err


# -- sizes ---------------------------------------------------------------------------
def _chain(edges, name):
    from chaingraph.model.chain import Chain, Joint
    return Chain(name, tuple(Joint(f"J{i}", "R", (f"L{a}", f"L{b}"))
                             for i, (a, b) in enumerate(edges)))


def test_structure_commands_refuse_what_they_cannot_finish():
    import itertools
    # classify refuses nothing: 26 links all pinned together have 2,600 triangles, as
    # many smallest rigid sub-chains; it lists those its budget finds, and says so
    complete = _chain(list(itertools.combinations(range(26), 2)), "K26")
    c = chaingraph.classify(complete)
    assert c.degenerate and c.rigid_regions == (complete.links,)
    assert 1 <= len(c.rigid_subchains) <= 2600 and {len(s) for s in c.rigid_subchains} == {3}
    assert c.rigid_subchains_complete is (len(c.rigid_subchains) == 2600)
    long_loop = _chain([(i, (i + 1) % 2001) for i in range(2001)], "loop")
    with pytest.raises(chaingraph.ChainStructureError, match="at most 2,000 links"):
        chaingraph.inversions(long_loop)


def test_structure_commands_finish_on_hundreds_of_links():
    import networkx as nx
    cube = nx.convert_node_labels_to_integers(nx.hypercube_graph(8))
    inv = chaingraph.inversions(_chain(list(cube.edges()), "hypercube"))
    assert inv.classes == 1                            # every link alike
    loop = _chain([(i, (i + 1) % 500) for i in range(500)], "loop")
    assert chaingraph.inversions(loop).classes == 1
    assert chaingraph.identify(loop).chain is None


# -- resource tests: run under a memory limit ------------------------------------------
def _limited(args, *, memory, seconds):
    """Run the command line under an address-space limit (and a time-out that only
    stops a run gone wrong)."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    proc = subprocess.run([sys.executable, "-m", "chaingraph", *map(str, args)],
                          capture_output=True, text=True, preexec_fn=limit,
                          timeout=seconds)
    return proc.returncode, proc.stdout, proc.stderr


def test_many_parallel_joints_classify_in_bounded_memory(tmp_path):
    lines = ['name = "20 links, 10,000 parallel joints"']
    edges = [(i, (i + 1) % 20) for i in range(20)] + [(0, 1)] * 10000
    for i, (a, b) in enumerate(edges):
        lines.append(f'[[joints]]\nid = "J{i}"\nkind = "R"\nlinks = ["L{a}", "L{b}"]')
    path = tmp_path / "parallel.toml"
    path.write_text("\n".join(lines))
    code, out, err = _limited(["classify", path], memory=2 << 30, seconds=120)
    assert code == 0 and "degenerate" in out, err


def test_a_long_sweep_to_csv_streams_in_bounded_memory(tmp_path):
    path = tmp_path / "motion.csv"
    code, out, err = _limited(["solve", CRANK, "--steps", "150000", "--csv", path],
                                       memory=3 << 30, seconds=180)
    assert code == 0, err
    with open(path) as f:
        assert sum(1 for _ in f) == 150002


def test_a_sweep_larger_than_memory_is_refused_under_the_limit():
    code, out, err = _limited(["solve", CRANK, "--steps", "2000000000"],
                                       memory=2 << 30, seconds=60)
    assert code == 2 and "GiB" in err and "Traceback" not in err


# -- interrupts ----------------------------------------------------------------------
@pytest.mark.slow
def test_ctrl_c_in_report_is_one_line_and_exit_130(tmp_path):
    out = tmp_path / "report"
    proc = subprocess.Popen([sys.executable, "-m", "chaingraph", "report", "-o", str(out),
                             "--workers", "2"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=interruptible)
    # interrupted while its workers are at work (not after the last page: a race)
    assert wait_for(lambda: len(children(proc.pid)) >= 2, 120), "no workers started"
    time.sleep(1)
    assert proc.poll() is None, "the report finished before it could be interrupted"
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1] == "chaingraph: interrupted"
    assert "Traceback" not in err
    assert not (out / "index.html").exists()           # no half report shown as whole


def _no_process_with(text):
    """Whether no process's command line holds ``text`` (a worker left behind)."""
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline") as f:
                if text in f.read():
                    return False
        except OSError:
            pass
    return True


@pytest.mark.parametrize("command, group", [
    (["report", "--workers", "2"], False),           # to the command alone: it stops its workers
    (["atlas", "--links", "14", "--workers", "2"], True),   # to its group, as `timeout` does
])
def test_sigterm_is_one_line_and_exit_143(tmp_path, command, group):
    """SIGTERM (a CI timeout, a service manager) is treated as Ctrl-C: the workers
    stopped, one line, exit 143, and no index presented as complete."""
    out = tmp_path / "out"
    flag = "-o" if command[0] == "report" else "--out"
    proc = subprocess.Popen([sys.executable, "-m", "chaingraph", *command, flag, str(out),
                             "-q"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    assert wait_for(lambda: len(children(proc.pid)) >= 2, 120), "no workers started"
    assert proc.poll() is None, "it finished before it could be terminated"
    if group:
        os.killpg(proc.pid, signal.SIGTERM)
    else:
        os.kill(proc.pid, signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 143, err
    assert err.strip() == "chaingraph: terminated (SIGTERM)"
    assert wait_for(lambda: _no_process_with(str(out)), 5), "a worker was left behind"
    assert not (out / "index.html").exists()


@pytest.mark.parametrize("args", [
    ["atlas", "--links", "6", "--out", ""],
    ["atlas", "--links", "4", "--prismatic", "1", "--out", ""],
    ["report", FOUR_BAR, "-o", ""],
    ["solve", CRANK, "--csv", ""], ["solve", CRANK, "--plot", ""],
    ["solve", CRANK, "--draw", ""], ["solve", CRANK, "--limits", ""],
    ["forces", CRANK, "--draw", ""], ["centres", CRANK, "--draw", ""],
    ["assemble", CRANK, "-o", ""], ["measure", CRANK, "--output", ""],
    ["design", "whitworth", "--time-ratio", "1.5", "--crank", "100", "--stroke", "300",
     "--out", ""],
    ["solve", ""], ["classify", FOUR_BAR, ""], ["report", ""],
])
def test_an_empty_path_is_refused_naming_its_option(args, tmp_path, monkeypatch):
    """An empty path would be the current folder (or nothing at all): bad input, one
    line naming the option, exit 2, nothing written."""
    monkeypatch.chdir(tmp_path)
    code, out, err = _main(*args)
    before = str(args[args.index("") - 1])
    assert code == 2 and _one_line(err) and "empty path" in err, err
    assert f"argument {before}" in err or f"/{before}" in err or "argument " in err and \
        not before.startswith("-")
    assert list(tmp_path.iterdir()) == []


def test_an_empty_output_folder_is_refused_by_the_library():
    from chaingraph.structure.atlas import run_atlas
    from chaingraph.report.build import build_report
    with pytest.raises(chaingraph.AtlasRunError, match="out is an empty path"):
        run_atlas(4, 1, out="")
    with pytest.raises(ValueError, match="out_dir is an empty path"):
        build_report([FOUR_BAR], "", progress=None)


# -- fuzzing the command line ---------------------------------------------------------
_FLAG_VALUES = st.sampled_from(["0", "-1", "1e9", "1e308", "nan", "inf", "-inf", "3.5", "x",
                                "", "100000000000", "7", "$x$", "B", "crank", "9" * 400])


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.sampled_from(["--from", "--to", "--steps", "--fixed",
                                            "--driver", "--input", "--json"]),
                          _FLAG_VALUES), max_size=4))
def test_solve_with_any_flags_answers_in_one_line(flags):
    args = ["solve", CRANK]
    for flag, value in flags:
        args += [flag] if flag == "--json" else [flag, value]
    code, out, err = _main(*args)
    assert code in (0, 1, 2)
    if code:
        assert err.count("\n") == 1 and "Traceback" not in err, err


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(["slotted-lever", "whitworth", "crank-rocker", ""]),
       _FLAG_VALUES, _FLAG_VALUES, _FLAG_VALUES)
def test_design_with_any_numbers_answers_in_one_line(kind, ratio, crank, stroke):
    code, out, err = _main("design", kind, "--time-ratio", ratio, "--crank", crank,
                           "--stroke", stroke)
    assert code in (0, 2)
    if code:
        assert err.count("\n") == 1 and "Traceback" not in err, err


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(["--links", "--dof", "--workers"]), _FLAG_VALUES)
def test_atlas_with_any_numbers_answers_in_one_line(flag, value):
    args = ["atlas", "--links", "6", "-q", flag, value]
    code, out, err = _main(*args)
    assert code in (0, 2)
    if code:
        assert err.count("\n") == 1 and "Traceback" not in err, err


def test_a_far_sweep_without_summary_is_taken_within_a_turn(monkeypatch):
    """1e9 degrees away: the angles are taken within a turn, so at most a turn's grid
    is walked (it walked 1e9 degrees and took 24 GB before)."""
    chain = chaingraph.load(CRANK)
    counted = _Counted(monkeypatch)
    far = chaingraph.solve(chain, start=0, stop=1e9, steps=2, summary=False)
    assert counted.longest <= 2 * 361
    with_summary = chaingraph.solve(chain, start=0, stop=1e9, steps=2)
    for key in far.columns:
        assert far[key] == pytest.approx(with_summary[key], nan_ok=True), key


# -- messages that say how to fix -------------------------------------------------------
FOUR_BAR_LENGTHS = Path(__file__).parents[2] / "examples" / "four-bar-lengths.toml"


def test_a_misspelt_link_is_named_with_the_link_it_looks_like(tmp_path):
    path = tmp_path / "misspelt.toml"
    path.write_text(FOUR_BAR_LENGTHS.read_text().replace('links = ["rocker", "frame"]',
                                                         'links = ["rockr", "frame"]'))
    code, out, err = _main("solve", path)
    assert code == 2 and err.count("\n") == 1
    assert "'rocker' has a single joint (C)" in err
    assert "'rockr' has a single joint too (D) and looks like 'rocker'" in err
    assert "C-C" not in err


def test_a_file_with_a_byte_order_mark_is_read(tmp_path):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + FOUR_BAR.read_bytes())
    read = chaingraph.load(path)
    assert (read.name, read.joints) == (chaingraph.load(FOUR_BAR).name,
                                        chaingraph.load(FOUR_BAR).joints)
    path.write_bytes(FOUR_BAR.read_text().encode("utf-16"))
    code, out, err = _main("classify", path)
    assert code == 2 and "UTF-16" in err and "save it as UTF-8" in err


def test_an_unquoted_key_with_a_space_is_told_to_be_quoted(tmp_path):
    path = tmp_path / "spaced.toml"
    path.write_text(FOUR_BAR_LENGTHS.read_text().replace("rocker = 80.0", "big rocker = 80.0"))
    code, out, err = _main("solve", path)
    assert code == 2 and err.count("\n") == 1
    assert 'a key with a space must be quoted, as in "big rocker" = ...' in err


def test_a_driver_without_a_fixed_link_names_the_option():
    code, out, err = _main("solve", FOUR_BAR, "--driver", "crank")
    assert code == 2 and "no fixed link" in err and "--fixed LINK" in err
    with pytest.raises(chaingraph.MechanismError) as caught:
        chaingraph.solve(chaingraph.load(FOUR_BAR), driver="crank")
    assert caught.value.parameter == "fixed" and "--" not in str(caught.value)


def test_steps_below_one_names_the_option():
    code, out, err = _main("solve", FOUR_BAR, "--fixed", "frame", "--driver", "crank",
                           "--steps", "0")
    assert code == 2 and err.count("\n") == 1 and "argument --steps: must be 1 or more" in err


def test_a_piston_input_out_of_its_range_shows_how_to_set_its_value(tmp_path):
    path = tmp_path / "far.toml"
    text = (Path(__file__).parents[1] / "data" / "slider-by-lengths-piston-input.toml").read_text()
    path.write_text(text.replace("at = 180.0", "at = 300.0"))
    code, out, err = _main("solve", path)
    assert code == 2 and "from 100 to 200" in err
    assert 'inputs = [{joint = "S", at = VALUE}' in err


def test_running_out_of_memory_is_one_line_and_exit_1(monkeypatch):
    """A 10,000-dyad solve under a memory limit ended in a MemoryError traceback."""
    import chaingraph.kinematics.motion as motion

    def exhausted(*args, **kwargs):
        raise MemoryError
    monkeypatch.setattr(motion, "cycle", exhausted)
    code, out, err = _main("solve", FOUR_BAR, "--fixed", "frame", "--driver", "crank")
    assert code == 1 and err.count("\n") == 1 and "out of memory" in err
    assert "Traceback" not in err


def test_the_console_script_exits_0_2_and_1():
    """The one check that needs a process: `python -m chaingraph` and its exit statuses
    (the rest of the command line is tested in process through main)."""
    assert run_console_script("classify", FOUR_BAR)[0] == 0
    code, out, err = run_console_script("classify", "no-such-file.toml")
    assert code == 2 and err.strip().startswith("chaingraph: error:")
    code, out, err = run_console_script("solve", catalog_path("watts-indicator-mechanism"),
                                        "--from", "0", "--to", "180")
    assert code == 1 and "can turn only from" in err


# -- issue 35, item 4: a drawing that gives a link no length ---------------------------
DEGENERATE = Path(__file__).parents[1] / "data" / "degenerate"


@pytest.mark.parametrize("command", ["solve", "inversions", "forces", "centres",
                                     "assemble"])
@pytest.mark.parametrize("name, link, joints, at", [
    ("all-joints-at-one-point", "frame", "'A' and 'D'", "(0, 0)"),
    ("coupler-zero-length", "coupler", "'B' and 'C'", "(30, 40)"),
    ("crank-zero-length", "crank", "'A' and 'B'", "(0, 0)"),
    ("engine-all-at-one-point", "crank", "'A' and 'O'", "(0, 0)"),
    ("engine-rod-zero-length", "connecting rod", "'A' and 'B'", "(50, 0)"),
])
def test_a_link_drawn_with_zero_length_is_named_in_one_line(command, name, link, joints,
                                                            at):
    """Joints drawn at one point so that a link has no length (once told "the driver
    'crank' can turn only from 0.000000 to 0.000000 degrees", or "residual nan", or
    answered as a parallelogram): every command names the link, its joints and the
    point, in one line, exit status 2."""
    code, out, err = _main(command, DEGENERATE / f"{name}.toml")
    assert code == 2 and _one_line(err), err
    assert f"link {link!r} has zero length: joints {joints} are both drawn at {at}" in err
    assert "nan" not in err.lower().replace("name", "")
