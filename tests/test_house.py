"""The house's rules, checked on the code itself (docs/developers.md states them)."""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "chaingraph"
MODULES = sorted(PACKAGE.rglob("*.py"))
HEAVY = ("matplotlib", "pandas", "dask", "distributed", "pynauty", "IPython")


def _trees():
    for path in MODULES:
        yield path.relative_to(PACKAGE.parent), ast.parse(path.read_text(encoding="utf-8"))


def test_the_layers_hold():
    """import-linter's contract (pyproject.toml): each layer imports only from below,
    siblings are independent; `make test` runs it too."""
    lint = Path(sys.executable).with_name("lint-imports")
    if not lint.exists():
        pytest.skip("import-linter is not installed (the test extra installs it)")
    done = subprocess.run([str(lint), "--no-cache"], capture_output=True, text=True,
                          cwd=PACKAGE.parent)
    assert done.returncode == 0, done.stdout[-2000:]


def test_an_underscore_name_is_used_in_its_own_module_only():
    found = [f"{path}:{node.lineno} {node.module}.{alias.name}"
             for path, tree in _trees() for node in ast.walk(tree)
             if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("chaingraph")
             for alias in node.names
             if alias.name.startswith("_") and not alias.name.startswith("__")]
    assert found == []


def test_a_function_imports_only_an_optional_heavy_dependency():
    """Everything else is imported at the top of the module (an import inside a function
    had been dodging a cycle)."""
    found = []
    for path, tree in _trees():
        for fn in ast.walk(tree):
            if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                for node in ast.walk(fn):
                    if isinstance(node, ast.ImportFrom):
                        names = [node.module or ""]
                    elif isinstance(node, ast.Import):
                        names = [a.name for a in node.names]
                    else:
                        continue
                    if not all(n.split(".")[0] in HEAVY for n in names):
                        found.append(f"{path}:{node.lineno} {', '.join(names)}")
    assert found == []


def test_import_chaingraph_loads_no_heavy_part():
    code = ("import sys, chaingraph; print(sorted(m for m in sys.modules if m.split('.')[0] in "
            f"{HEAVY!r} or m.startswith(('chaingraph.structure.atlas', 'chaingraph.drawing', "
            "'chaingraph.report', 'chaingraph.cli'))))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=PACKAGE.parent)
    assert done.stdout.strip() == "[]", done.stdout + done.stderr
