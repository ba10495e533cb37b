"""A function of x as a task gives it, read safely: parsed with :mod:`ast`, never run.

Only ``x``, numbers, ``pi``, ``+ - * / **``, unary minus and plus, and the calls
``sqrt exp log log10 sin cos tan`` (radians) are allowed; anything else is refused with
what and where. The parsed expression is evaluated on numpy arrays.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from chaingraph.errors import DesignError

__all__ = ["Expression", "parse_expression", "FUNCTIONS"]

#: the calls an expression may make (radians for the circular functions)
FUNCTIONS: dict[str, Callable] = {"sqrt": np.sqrt, "exp": np.exp, "log": np.log,
                                  "log10": np.log10, "sin": np.sin, "cos": np.cos,
                                  "tan": np.tan}
_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply,
           ast.Div: np.divide, ast.Pow: np.power}
_UNARY = {ast.USub: np.negative, ast.UAdd: np.positive}
_LONGEST = 1000


@dataclass(frozen=True)
class Expression:
    """``y = EXPR(x)``, parsed: ``text`` as given; call it on a float or an array."""

    text: str
    tree: ast.expr

    def __call__(self, x):
        with np.errstate(all="ignore"):
            return _value(self.tree, np.asarray(x, dtype=float))


def parse_expression(text: str, *, kind: str = "function") -> Expression:
    """Parse ``text`` as a function of ``x``.

    Raises
    ------
    DesignError
        ``parameter == "function"``, naming the first thing not allowed and its column.

    Examples
    --------
    >>> f = parse_expression("log10(x) + 2*x**2")
    >>> float(f(1.0))
    2.0
    >>> parse_expression("__import__('os')")
    Traceback (most recent call last):
    ...
    chaingraph.errors.DesignError: design function: the function "__import__('os')": unknown name '__import__' at column 1 (allowed: x, pi, numbers, + - * / **, sqrt exp log log10 sin cos tan)
    """
    def fail(problem):
        raise DesignError(f"the function {text!r}: {problem}", kind=kind,
                          parameter="function")

    if not isinstance(text, str) or not text.strip():
        fail("give an expression in x, such as log10(x)")
    if len(text) > _LONGEST:
        fail(f"longer than {_LONGEST} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval").body
    except SyntaxError as e:
        fail(f"not an expression ({e.msg} at column {e.offset})")
    except (ValueError, RecursionError, MemoryError):
        fail("not an expression")
    _check(tree, fail)
    return Expression(text, tree)


_ALLOWED = "x, pi, numbers, + - * / **, " + " ".join(FUNCTIONS)


def _check(node, fail):
    where = f" at column {getattr(node, 'col_offset', 0) + 1}"
    if isinstance(node, ast.Constant):
        value = node.value
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            fail(f"{value!r} is not a number{where}")
        elif not math.isfinite(value):
            fail(f"the number {node.value!r} is not finite{where}")
    elif isinstance(node, ast.Name):
        if node.id not in ("x", "pi"):
            hint = " (a call needs parentheses)" if node.id in FUNCTIONS else ""
            fail(f"unknown name {node.id!r}{where}{hint} (allowed: {_ALLOWED})")
    elif isinstance(node, ast.BinOp):
        if type(node.op) not in _BINARY:
            fail(f"the operator {_symbol(node.op)}{where} is not allowed (allowed: {_ALLOWED})")
        _check(node.left, fail)
        _check(node.right, fail)
    elif isinstance(node, ast.UnaryOp):
        if type(node.op) not in _UNARY:
            fail(f"the operator {_symbol(node.op)}{where} is not allowed (allowed: {_ALLOWED})")
        _check(node.operand, fail)
    elif isinstance(node, ast.Call):
        name = node.func.id if isinstance(node.func, ast.Name) else None
        if name not in FUNCTIONS:
            shown = name if name is not None else ast.unparse(node.func)
            fail(f"unknown name {shown!r}{where} (allowed: {_ALLOWED})")
        if node.keywords or len(node.args) != 1:
            fail(f"{name} takes one argument{where}")
        _check(node.args[0], fail)
    else:
        fail(f"{ast.unparse(node)!r}{where} is not allowed (allowed: {_ALLOWED})")


def _symbol(op):
    return {ast.Mod: "%", ast.FloorDiv: "//", ast.MatMult: "@", ast.BitAnd: "&",
            ast.BitOr: "|", ast.BitXor: "^", ast.LShift: "<<", ast.RShift: ">>",
            ast.Invert: "~", ast.Not: "not"}.get(type(op), type(op).__name__)


def _value(node, x):
    if isinstance(node, ast.Constant):
        assert isinstance(node.value, (int, float))      # checked when it was read
        return np.full_like(x, float(node.value))
    if isinstance(node, ast.Name):
        return x if node.id == "x" else np.full_like(x, math.pi)
    if isinstance(node, ast.BinOp):
        return _BINARY[type(node.op)](_value(node.left, x), _value(node.right, x))
    if isinstance(node, ast.UnaryOp):
        return _UNARY[type(node.op)](_value(node.operand, x))
    return FUNCTIONS[node.func.id](_value(node.args[0], x))
