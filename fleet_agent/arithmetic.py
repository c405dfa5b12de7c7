"""A length's value as arithmetic of the request's numbers, worked out by the host ("(8+20)/2", "24/2"): a
small model that computed "halfway between 8 m and 20 m" itself planned legs of 11 m and 12 m."""

from __future__ import annotations

import ast
import contextlib
import math

ACCEPTED = 'a number, or arithmetic of numbers with + - * /, parentheses, min() and max(), e.g. "(8+20)/2"'
MAX_CHARS = 60
_OPERATORS = (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.USub, ast.UAdd)
_NODES = (ast.Expression, ast.BinOp, ast.UnaryOp, ast.Load, *_OPERATORS)  # Load: the context of min, max
_FUNCTIONS = {"min": min, "max": max}  # a 1.5B plan wrote "the tallest of 7, 16 and 10 m" as max(7,16,10)


def evaluate(text: str) -> float:
    """The value of ``text``; a ValueError naming what was given and what is accepted otherwise."""
    tree, value = _tree(text), math.nan
    if tree is not None:  # numbers, + - * /, min() and max() only (checked in _tree): nothing else can run
        with contextlib.suppress(ZeroDivisionError, OverflowError, TypeError):
            value = float(eval(compile(tree, "<value>", "eval"), {"__builtins__": {}, **_FUNCTIONS}))
    if not math.isfinite(value):
        raise ValueError(f"value {text!r} is not {ACCEPTED}")
    return value


def numbers(text: str) -> list[float]:
    """The numbers ``text`` writes (none when it is not arithmetic)."""
    nodes = ast.walk(tree) if (tree := _tree(text)) else []
    return [float(n.value) for n in nodes if isinstance(n, ast.Constant) and isinstance(n.value, int | float)]


def _tree(text: str) -> ast.Expression | None:
    with contextlib.suppress(SyntaxError):
        tree = ast.parse(text.replace("×", "*").replace("÷", "/").strip(), mode="eval")
        return tree if len(text) <= MAX_CHARS and all(map(_allowed, ast.walk(tree))) else None
    return None


def _allowed(node: ast.AST) -> bool:
    if isinstance(node, ast.Call):  # min() or max() of values given one by one, nothing else called
        return isinstance(node.func, ast.Name) and bool(node.args) and not node.keywords
    if isinstance(node, ast.Name):
        return node.id in _FUNCTIONS
    return isinstance(node, _NODES) or (isinstance(node, ast.Constant) and type(node.value) in (int, float))
