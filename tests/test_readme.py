"""The Python examples of the README and of docs/ run and print what they show, and the
README's quick-start file is the one in examples/."""

import doctest
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
WITH_PYTHON = [p for p in PAGES if "```python\n" in p.read_text(encoding="utf-8")]


@pytest.mark.parametrize("page", WITH_PYTHON, ids=lambda p: p.name)
def test_python_examples(page, tmp_path, monkeypatch):
    text = page.read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    monkeypatch.chdir(tmp_path)                    # to_csv writes here
    for name in ("examples", "catalog"):
        (tmp_path / name).symlink_to(ROOT / name)
    test = doctest.DocTestParser().get_doctest("\n".join(blocks), {}, page.name,
                                                str(page), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0 and result.attempted >= 3


def test_the_readme_and_python_page_have_examples():
    assert {p.name for p in WITH_PYTHON} >= {"README.md", "python.md"}


def test_the_quick_start_file_is_the_one_shown():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    shown = re.search(r"```toml\n(.*?)```", text, re.S).group(1)
    assert shown == (ROOT / "examples" / "quick-start.toml").read_text(encoding="utf-8")


def test_every_public_name_the_pages_use_is_there():
    """Each `chaingraph.NAME` and `from chaingraph... import NAME` of the README's and the
    docs' Python blocks resolves (the public face is kept when the house is rearranged)."""
    import importlib

    import chaingraph
    used = set()
    for page in WITH_PYTHON:
        code = "\n".join(re.findall(r"```python\n(.*?)```", page.read_text(encoding="utf-8"),
                                    re.S))
        used |= {("chaingraph", name) for name in re.findall(r"\bchaingraph\.(\w+)", code)}
        for module, names in re.findall(r"from (chaingraph[\w.]*) import ([\w, ]+)", code):
            used |= {(module, n.strip()) for n in names.split(",")}
    assert ("chaingraph", "load") in used and len(used) >= 10
    for module, name in sorted(used):
        assert hasattr(importlib.import_module(module), name), f"{module}.{name}"
    assert {"load", "loads", "classify", "inversions", "identify", "solve"} <= set(
        chaingraph.__all__)
