"""The expression of an implicit body, F(x, y, z), as a vectorised NumPy function
(:func:`compile_expression`). An expression is never handed to Python's ``eval``: its syntax
tree is walked and each node turned into a NumPy operation on float64 arrays, so every number,
even ``9**9**9``, is a float64 (that one is inf) and every operation is bounded in time.
"""

from __future__ import annotations

import ast

import numpy as np

from floatfoam.errors import InputError

_FUNCTIONS = {
    name: getattr(np, name)
    for name in ("sin", "cos", "tan", "exp", "log", "sqrt", "abs", "arctan2", "minimum",
                 "maximum", "sinh", "cosh", "tanh", "arcsin", "arccos", "arctan")
}
_TWO_ARGUMENTS = {"arctan2", "minimum", "maximum"}
_CONSTANTS = {"pi": np.float64(np.pi), "e": np.float64(np.e)}
_VARIABLES = ("x", "y", "z")
_UNARY = {ast.UAdd: np.positive, ast.USub: np.negative}
_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply,
           ast.Div: np.true_divide, ast.Pow: np.power}
MAX_EXPRESSION_LENGTH = 2000  # characters: ten times the longest surface written by hand
MAX_EXPRESSION_DEPTH = 100  # operations nested in one another
VALID_EXPRESSION = ("numbers, x, y, z, pi, e, + - * / ** and the functions "
                    + ", ".join(sorted(_FUNCTIONS)))


def compile_expression(text: str, key: str = "body.expression"):
    """A vectorised function F(x, y, z) from ``text``, an expression in x, y, z.

    Valid are numbers, the names x, y, z, pi and e, unary + and −, the operators + − * / **
    and calls of the NumPy functions in ``_FUNCTIONS`` (arctan2, minimum and maximum take two
    arguments, the others one). Every number is a float64 and F is evaluated in float64 with
    NumPy's warnings off: an overflow, ``1/0`` or ``sqrt(-1)`` gives inf or NaN (which
    :func:`implicit_body` refuses), never an exception, and no operation takes longer than
    one array pass (``9**9**9`` is inf at once). ``text`` is at most
    ``MAX_EXPRESSION_LENGTH`` characters, nested at most ``MAX_EXPRESSION_DEPTH`` deep.

    Raises
    ------
    InputError
        One line naming ``key``, the expression and what is valid.
    """
    tree = _parse(text, key)
    evaluate = _node(tree.body, _source(text), key)

    def surface(x, y, z):
        x, y, z = (np.asarray(v, dtype=float) for v in (x, y, z))
        with np.errstate(all="ignore"):
            value = evaluate({"x": x, "y": y, "z": z})
        shape = np.broadcast_shapes(x.shape, y.shape, z.shape)
        return value if np.shape(value) == shape else np.broadcast_to(value, shape).copy()

    return surface


def _parse(text: str, key: str) -> ast.Expression:
    """The syntax tree of ``text``, within the length and depth bounds."""
    if len(text) > MAX_EXPRESSION_LENGTH:
        raise InputError(f"{key} = {text[:40]!r}… is {len(text)} characters long: valid is "
                         f"an expression of at most {MAX_EXPRESSION_LENGTH} characters")
    try:
        tree = ast.parse(_source(text), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as err:
        reason = getattr(err, "msg", None) or str(err) or type(err).__name__
        raise InputError(f"{key} = {text!r} is not a valid expression ({reason}): valid "
                         f"are {VALID_EXPRESSION}") from None
    if _depth(tree.body) > MAX_EXPRESSION_DEPTH:
        raise InputError(f"{key} = {text[:40]!r}… nests operations more than "
                         f"{MAX_EXPRESSION_DEPTH} deep: valid is at most "
                         f"{MAX_EXPRESSION_DEPTH} (each operator and call is a level: group "
                         "the terms of a long sum in parentheses)")
    return tree


def _source(text: str) -> str:
    """``text`` on one line (a TOML multi-line string may span several), stripped."""
    return "".join(" " if c.isspace() else c for c in text).strip()


def _depth(root: ast.AST) -> int:
    """How deep expressions nest below ``root`` (iterative: any depth is safe to measure)."""
    deepest, stack = 0, [(root, 1)]
    while stack:
        node, depth = stack.pop()
        deepest = max(deepest, depth)
        stack.extend((child, depth + 1) for child in ast.iter_child_nodes(node)
                     if isinstance(child, ast.expr))
    return deepest


def _node(node: ast.AST, source: str, key: str):
    """The evaluator of one node: a function of the variables {"x": …, "y": …, "z": …}."""
    if isinstance(node, ast.Constant) and type(node.value) in (int, float):
        value = _float64(node.value)
        return lambda env: value
    if isinstance(node, ast.Name) and node.id in _VARIABLES:
        return lambda env: env[node.id]
    if isinstance(node, ast.Name) and node.id in _CONSTANTS:
        value = _CONSTANTS[node.id]
        return lambda env: value
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        op, operand = _UNARY[type(node.op)], _node(node.operand, source, key)
        return lambda env: op(operand(env))
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        op = _BINARY[type(node.op)]
        left, right = _node(node.left, source, key), _node(node.right, source, key)
        return lambda env: op(left(env), right(env))
    if isinstance(node, ast.Call):
        return _call(node, source, key)
    if isinstance(node, ast.Name):
        raise InputError(f"{key} = {source!r}: unknown name {node.id!r}; valid names are x, y, "
                         f"z, pi, e and the functions {', '.join(sorted(_FUNCTIONS))}")
    raise InputError(f"{key} = {source!r}: {_piece(node, source)!r} is not valid here; valid "
                     f"are {VALID_EXPRESSION}")


def _call(node: ast.Call, source: str, key: str):
    """The evaluator of a call of one of ``_FUNCTIONS`` with its number of arguments."""
    name = node.func.id if isinstance(node.func, ast.Name) else None
    if name not in _FUNCTIONS:
        raise InputError(f"{key} = {source!r}: {_piece(node.func, source)!r} is not a function; "
                         f"valid functions are {', '.join(sorted(_FUNCTIONS))}")
    arity = 2 if name in _TWO_ARGUMENTS else 1
    form = f"{name}(u, v)" if arity == 2 else f"{name}(u)"
    if len(node.args) != arity or node.keywords:
        given = ("keyword arguments" if node.keywords else
                 f"{len(node.args)} argument{'s' * (len(node.args) != 1)}")
        raise InputError(f"{key} = {source!r}: {_piece(node, source)!r} calls {name} with "
                         f"{given}; valid is {form}")
    func, args = _FUNCTIONS[name], [_node(arg, source, key) for arg in node.args]
    return lambda env: func(*(arg(env) for arg in args))


def _float64(value: int | float) -> np.float64:
    """A literal as a float64: an integer beyond float64's range is inf, as ``1e999`` is."""
    try:
        return np.float64(float(value))
    except OverflowError:
        return np.float64(np.inf)


def _piece(node: ast.AST, source: str) -> str:
    """The text of ``node`` in ``source`` (for messages), else its kind."""
    return ast.get_source_segment(source, node) or type(node).__name__
