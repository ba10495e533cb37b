"""Every console block of the README and of docs/ runs and prints what it shows.

A block's commands (lines starting with ``$ ``) run in a scratch folder that holds the
project's ``catalog``, ``examples`` and ``tests`` folders: ``chaingraph ARGS`` in this
process through :func:`chaingraph.cli.main.main`, a pipe into standard text tools (sed,
head, cut, grep) or a redirection to a file after it as the shell would. The lines up
to the next command are its output (standard output and error together), compared with
``...`` standing for any text, as in doctests. A block preceded by the comment
``<!-- not run: REASON -->`` is shown and not run (the two make commands, runs of many
minutes, a cluster); every such block must give its reason.
"""

import contextlib
import doctest
import io
import re
import shlex
import subprocess
from pathlib import Path

import pytest

from chaingraph.cli.main import main

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
_BLOCK = re.compile(r"(<!-- not run: ([^>]*?) -->\s*\n)?```console\n(.*?)```", re.S)


def _blocks():
    out = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for k, m in enumerate(_BLOCK.finditer(text)):
            line = text[:m.start(3)].count("\n") + 1
            out.append(pytest.param(page, line, m.group(2), m.group(3),
                                    id=f"{page.name}:{line}"))
    return out


BLOCKS = _blocks()


def _commands(body):
    """(command, expected output) pairs of a block."""
    pairs, command, lines = [], None, []
    for line in body.splitlines():
        if line.startswith("$ "):
            if command is not None:
                pairs.append((command, "\n".join(lines)))
            command, lines = line[2:], []
        else:
            lines.append(line)
    if command is not None:
        pairs.append((command, "\n".join(lines)))
    return pairs


def _run(command, cwd):
    """Run one command line as the shell would, chaingraph in this process."""
    command = re.sub(r"\s+#.*$", "", command)       # a trailing comment
    first, *filters = [p.strip() for p in command.split(" | ")]
    words = shlex.split(first)
    target = None
    if ">" in words:
        target = words[words.index(">") + 1]
        words = words[:words.index(">")]
    if words[0] != "chaingraph":
        assert words[0] in ("head", "grep", "cat", "cut", "sed"), \
            f"{words[0]}: a block that runs other programs is marked not run, with a reason"
        text = subprocess.run(words, cwd=cwd, capture_output=True, text=True).stdout
        err = ""
    else:
        out = io.StringIO()
        err_out = out if target is None else io.StringIO()   # one stream, as on a terminal
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err_out), \
                contextlib.chdir(cwd):
            try:
                main(words[1:])
            except SystemExit:                    # argparse's usage errors
                pass
        text, err = out.getvalue(), ("" if target is None else err_out.getvalue())
    if target is not None:
        (cwd / target).write_text(text)
        text = err
    for f in filters:
        text = subprocess.run(shlex.split(f), input=text, cwd=cwd, capture_output=True,
                              text=True).stdout
    return text


def test_the_pages_have_console_blocks():
    assert len(BLOCKS) >= 10


@pytest.mark.parametrize("page, line, reason, body", BLOCKS)
def test_console_block(page, line, reason, body, tmp_path):
    if reason is not None:
        assert reason.strip(), f"{page.name}:{line}: a block not run must say why"
        pytest.skip(f"not run: {reason.strip()}")
    for name in ("catalog", "examples", "tests"):
        (tmp_path / name).symlink_to(ROOT / name)
    checker = doctest.OutputChecker()
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    for command, expected in _commands(body):
        got = _run(command, tmp_path)
        want = expected.strip() + "\n" if expected.strip() else ""
        assert checker.check_output(want, got.strip() + "\n" if got.strip() else "", flags), (
            f"{page.name}:{line}: $ {command}\n--- shown ---\n{expected}\n--- printed ---\n{got}")
