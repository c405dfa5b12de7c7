"""A length's value as arithmetic of the request's numbers, worked out by the host ("(8+20)/2", "24/2"): a
small model that computed "halfway between 8 m and 20 m" itself planned legs of 11 m and 12 m."""

from __future__ import annotations

import ast
import contextlib
import math

ACCEPTED = 'a number, or arithmetic of numbers with + - * / and parentheses, e.g. "(8+20)/2"'
MAX_CHARS = 60
_NODES = (ast.Expression, ast.BinOp, ast.UnaryOp, ast.Add, ast.Sub, ast.Mult, ast.Div, ast.USub, ast.UAdd)


def evaluate(text: str) -> float:
    """The value of ``text``; a ValueError naming what was given and what is accepted otherwise."""
    tree, value = _tree(text), math.nan
    if tree is not None:  # numbers and + - * / only (checked in _tree): nothing else can run
        with contextlib.suppress(ZeroDivisionError, OverflowError):
            value = float(eval(compile(tree, "<value>", "eval"), {"__builtins__": {}}))
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
    return isinstance(node, _NODES) or (isinstance(node, ast.Constant) and type(node.value) in (int, float))
