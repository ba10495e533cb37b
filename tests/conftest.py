import contextlib
import io
import os
import subprocess
import sys
import time

import pytest
from hypothesis import settings

# Every run draws the same examples (CI is reproducible, and a failure found once is not
# replayed from a local database into every later run): the "derandomized" profile is
# the default; HYPOTHESIS_PROFILE=explore draws new examples while working. An example
# that ever failed is kept in its test as an explicit @example.
settings.register_profile("derandomized", derandomize=True, database=None, print_blob=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "derandomized"))

from chaingraph.naming.catalog import catalog_files, catalog_path  # noqa: F401  (used by the tests)
from chaingraph.cli.main import main
from chaingraph.kinematics.gears import is_gear_train

#: the test files that take longest, longest first (``pytest --durations=0``, summed by
#: file): `make test` runs them first, each on one worker (``--dist loadfile
#: --no-loadscope-reorder``), so that no long file starts last while the other worker
#: has nothing left to do; a scheduling order only, nothing is left out
LONGEST_FIRST = (
    "tests/structure/test_atlas.py",
    "tests/report/test_report.py",
    "tests/report/test_atlas_pages.py",
    "tests/kinematics/test_inputs.py",
    "tests/cli/test_errors.py",
    "tests/synthesis/test_type_synthesis.py",
    "tests/kinematics/test_no_silent_wrong.py",
    "tests/structure/test_sliding.py",
    "tests/synthesis/test_path.py",
    "tests/naming/test_bounded_behaviour.py",
    "tests/synthesis/test_sliding_input.py",
    "tests/synthesis/test_six_bar_need.py",
    "tests/test_readme.py",
)


def pytest_collection_modifyitems(config, items):
    """The longest files first (:data:`LONGEST_FIRST`), the rest in their order."""
    rank = {name: i for i, name in enumerate(LONGEST_FIRST)}
    items.sort(key=lambda item: rank.get(item.nodeid.split("::", 1)[0], len(rank)))


@pytest.fixture
def write(tmp_path):
    """Write TOML text to a file in tmp_path and return its path."""
    def _write(text, name="chain.toml"):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path
    return _write


def run_cli(*args, cwd=None):
    """Run `chaingraph ARGS` in this process through ``main`` (from ``cwd`` when given);
    return (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.chdir(cwd or os.getcwd()), contextlib.redirect_stdout(out), \
            contextlib.redirect_stderr(err):
        try:
            code = main([str(a) for a in args])
        except SystemExit as e:              # argparse's usage errors and --help
            code = e.code
    return code, out.getvalue(), err.getvalue()


def run_console_script(*args, cwd=None):
    """Run `python -m chaingraph ARGS` in a fresh process, for what only a process shows
    (the exit status of the console script itself); (exit status, stdout, stderr)."""
    proc = subprocess.run([sys.executable, "-m", "chaingraph", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd)
    return proc.returncode, proc.stdout, proc.stderr


CATALOG = catalog_files()


def solver_takes(chain):
    """Whether the position solver takes the chain's pairs: turning and sliding pairs,
    and cams and gear pairs with their [[cams]] and [[gears]] tables (moved as inputs
    derived from the others: kinematics/higher.py); a higher pair without one (a cam
    and follower written for their structure alone) it refuses in one line. A gear
    train (whose turning pairs close no loop) it solves too (its cycle from its teeth:
    35 turns of the simple train's driver), but its speeds are `chaingraph gears`'."""
    tabled = {c.id for c in chain.cams} | {g.id for g in chain.gears}
    if is_gear_train(chain):
        return False      # a gear train (no loop of lower pairs): `chaingraph gears`
    return all(j.kind in ("R", "P") or (j.kind in ("cam", "gear") and j.id in tabled)
               for j in chain.joints)


# -- processes (the Ctrl-C and SIGKILL tests) ------------------------------------------
def children(pid):
    out = []
    for entry in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            out.append(int(entry))
    return out


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def wait_for(condition, limit):
    """Poll ``condition`` until it holds or ``limit`` seconds pass (a bound on the
    wait, not a measurement); returns whether it held."""
    end = time.monotonic() + limit
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(0.05)
    return condition()


def interruptible():
    """For ``preexec_fn``: Ctrl-C as on a terminal in the child (a shell running a script
    in the background starts its commands with SIGINT ignored, and Python keeps that)."""
    import signal
    signal.signal(signal.SIGINT, signal.SIG_DFL)
