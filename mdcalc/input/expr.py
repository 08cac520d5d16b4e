"""A restricted expression language for formulas in case files.

A case file may give a torque as ``"M0*(1 - omega/w0) - 40*sin(2*phi)"``. The text
is never handed to Python's ``eval``: it is parsed with :mod:`ast` and every node
is checked against a short whitelist -- numbers, the variables the field allows,
named parameters from the case, the arithmetic operators ``+ - * / % **``,
comparisons (giving 1.0 or 0.0), ``a if c else b`` and the functions in
:data:`FUNCTIONS`. Everything else -- attribute access, subscripts, imports,
lambdas, comprehensions, keyword arguments, strings, dunder names -- is rejected
with the reason. The checked tree is compiled into nested closures, so evaluation
costs a few function calls per node and never touches the interpreter's ``eval``.

Exponents are limited: a literal exponent beyond :data:`MAX_EXPONENT` is rejected
at parse time and every power is computed in floating point (no giant integers),
so ``9**9**9`` is an error, not a hang.
"""

from __future__ import annotations

import ast
import math
import unicodedata
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

MAX_LENGTH = 2000
MAX_NODES = 500
MAX_EXPONENT = 64.0

Env = Mapping[str, float]
Compiled = Callable[[Env], float]


class ExpressionError(ValueError):
    """A formula that is not allowed or cannot be parsed; the message says why."""


def _sign(x: float) -> float:
    return (x > 0.0) - (x < 0.0)


def _clip(x: float, low: float, high: float) -> float:
    return min(max(x, low), high)


#: Whitelisted functions: name -> (function, smallest and largest argument count).
FUNCTIONS: dict[str, tuple[Callable[..., float], int, int]] = {
    "sin": (math.sin, 1, 1),
    "cos": (math.cos, 1, 1),
    "tan": (math.tan, 1, 1),
    "asin": (math.asin, 1, 1),
    "acos": (math.acos, 1, 1),
    "atan": (math.atan, 1, 1),
    "atan2": (math.atan2, 2, 2),
    "sinh": (math.sinh, 1, 1),
    "cosh": (math.cosh, 1, 1),
    "tanh": (math.tanh, 1, 1),
    "exp": (math.exp, 1, 1),
    "log": (math.log, 1, 1),
    "log10": (math.log10, 1, 1),
    "sqrt": (math.sqrt, 1, 1),
    "abs": (abs, 1, 1),
    "hypot": (math.hypot, 2, 2),
    "floor": (lambda x: float(math.floor(x)), 1, 1),
    "ceil": (lambda x: float(math.ceil(x)), 1, 1),
    "sign": (_sign, 1, 1),
    "min": (min, 2, 8),
    "max": (max, 2, 8),
    "clip": (_clip, 3, 3),
}

#: Named constants every formula may use.
CONSTANTS: dict[str, float] = {"pi": math.pi, "e": math.e, "tau": math.tau}

_BINARY: dict[type, Callable[[float, float], float]] = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Mod: lambda a, b: a % b,
    ast.Pow: lambda a, b: _power(a, b),
}
_SYMBOL = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Mod: "%", ast.Pow: "**"}
_COMPARE: dict[type, Callable[[float, float], bool]] = {
    ast.Lt: lambda a, b: a < b,
    ast.LtE: lambda a, b: a <= b,
    ast.Gt: lambda a, b: a > b,
    ast.GtE: lambda a, b: a >= b,
}


def _power(a: float, b: float) -> float:
    # float ** float cannot hang; a real overflow raises OverflowError
    result = float(a) ** float(b)
    if isinstance(result, complex):
        raise ValueError("negative number to a fractional power")
    return result


@dataclass(frozen=True)
class Expression:
    """A checked formula: ``text``, the variables it may use, and its compiled tree."""

    text: str
    variables: tuple[str, ...]
    names: frozenset[str]  # the variables and parameters it actually uses
    _run: Compiled
    _tree: ast.expr
    _parameters: Mapping[str, float]

    def __call__(self, **values: float) -> float:
        """Evaluate; raises ArithmeticError or ValueError for a domain error
        (``log(0)``, a division by zero, an overflow), never returns NaN or inf."""
        try:
            result = self._run(values)
        except ZeroDivisionError:
            raise ArithmeticError("division by zero") from None
        except OverflowError as exc:
            raise ArithmeticError(f"overflow ({exc})") from None
        except ValueError as exc:
            raise ArithmeticError(f"math domain error ({exc})") from None
        if not math.isfinite(result):
            raise ArithmeticError(f"value is {result}")
        return result

    def uses(self, name: str) -> bool:
        return name in self.names

    def on_arrays(self) -> Callable[[dict[str, Any]], Any]:
        """The same formula over numpy arrays, for a block of scenes: called with the
        variables and any parameter given as an array (``{"phi": ..., "a": ...}``, the
        rest keep their values) and ``"_bad"``, a bool array the evaluation marks
        where this formula's scalar form would raise (a domain error, a division by
        zero, an overflow at any node; a branch ``a if c else b`` does not take
        counts only where it is not taken)."""
        compiler = _Compiler(self.variables, dict(self._parameters), set(), arrays=True)
        return compiler.compile(self._tree)


def parse(text: str, variables: tuple[str, ...], parameters: Env | None = None) -> Expression:
    """Check and compile ``text``; ``variables`` are supplied at each evaluation,
    ``parameters`` are fixed named numbers (a case file's ``[parameters]``)."""
    parameters = dict(parameters or {})
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"formula longer than {MAX_LENGTH} characters")
    if not text.strip():
        raise ExpressionError("formula is empty")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        where = f" at column {exc.offset}" if exc.offset else ""
        raise ExpressionError(f"not a formula: {exc.msg}{where}") from None
    except (RecursionError, MemoryError, ValueError):
        raise ExpressionError("formula nested too deeply") from None
    nodes = sum(1 for _ in ast.walk(tree))
    if nodes > MAX_NODES:
        raise ExpressionError(f"formula has {nodes} parts; at most {MAX_NODES} are allowed")
    used: set[str] = set()
    compiler = _Compiler(variables, parameters, used)
    run = compiler.compile(tree.body)
    return Expression(text, variables, frozenset(used), run, tree.body, parameters)


def check_name(name: str, variables: tuple[str, ...] = ()) -> None:
    """A parameter name must be a plain identifier that hides nothing.

    Python reads the names in a formula in their NFKC form (fullwidth ``ｏｍｅｇａ`` is
    ``omega``, ``ℯ`` is ``e``), so a parameter written otherwise could never be
    reached, or would silently stand for another name: it must be written in that
    form already."""
    if not name.isidentifier() or name.startswith("_"):
        raise ExpressionError(f"parameter name {name!r} is not a plain identifier")
    normal = unicodedata.normalize("NFKC", name)
    if normal != name:
        raise ExpressionError(
            f"parameter name {name!r} is read as {normal!r} in a formula; write it as {normal!r}"
        )
    if name in FUNCTIONS or name in CONSTANTS or name in variables:
        raise ExpressionError(f"parameter name {name!r} is taken by a function or variable")


def _array_functions() -> dict[str, Callable[..., Any]]:
    """numpy's forms of :data:`FUNCTIONS` (same names, same meaning)."""
    import functools

    import numpy as np

    return {
        "sin": np.sin,
        "cos": np.cos,
        "tan": np.tan,
        "asin": np.arcsin,
        "acos": np.arccos,
        "atan": np.arctan,
        "atan2": np.arctan2,
        "sinh": np.sinh,
        "cosh": np.cosh,
        "tanh": np.tanh,
        "exp": np.exp,
        "log": np.log,
        "log10": np.log10,
        "sqrt": np.sqrt,
        "abs": np.abs,
        "hypot": np.hypot,
        "floor": np.floor,
        "ceil": np.ceil,
        "sign": np.sign,
        "min": lambda *a: functools.reduce(np.minimum, a),
        "max": lambda *a: functools.reduce(np.maximum, a),
        "clip": lambda x, low, high: np.minimum(np.maximum(x, low), high),
    }


def _mark(env: Any, value: Any) -> Any:
    """Array mode: mark in ``env["_bad"]`` the rows where ``value`` is not finite."""
    import numpy as np

    env["_bad"] |= ~np.isfinite(value)
    return value


class _Compiler:
    """Compiles a checked tree into closures over floats, or (``arrays``) over numpy
    arrays: the same checks, node by node, either way."""

    def __init__(
        self,
        variables: tuple[str, ...],
        parameters: dict[str, float],
        used: set[str],
        arrays: bool = False,
    ):
        self.variables = variables
        self.parameters = parameters
        self.used = used
        self.arrays = arrays

    def compile(self, node: ast.AST) -> Compiled:
        method = getattr(self, f"_{type(node).__name__}", None)
        if method is None:
            raise ExpressionError(f"{_describe(node)} is not allowed in a formula")
        result: Compiled = method(node)
        return result

    def _Constant(self, node: ast.Constant) -> Compiled:
        value = node.value
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ExpressionError(f"{value!r} is not a number")
        try:
            number = float(value)
        except OverflowError:
            number = math.inf
        if not math.isfinite(number):
            raise ExpressionError(f"number {str(value)[:12]}... is out of range")
        return lambda env: number

    def _Name(self, node: ast.Name) -> Compiled:
        name = node.id
        if name.startswith("_"):
            raise ExpressionError(f"name {name!r} is not allowed (no underscore names)")
        if name in self.variables:
            self.used.add(name)
            return lambda env: env[name]
        if name in self.parameters:
            self.used.add(name)
            value = float(self.parameters[name])
            if self.arrays:  # a study may draw a parameter
                return lambda env: env.get(name, value)
            return lambda env: value
        if name in CONSTANTS:
            constant = CONSTANTS[name]
            return lambda env: constant
        if name in FUNCTIONS:
            raise ExpressionError(f"{name} is a function; call it as {name}(...)")
        known = ", ".join([*self.variables, *sorted(self.parameters), *CONSTANTS])
        raise ExpressionError(f"unknown name {name!r}; known: {known}")

    def _UnaryOp(self, node: ast.UnaryOp) -> Compiled:
        operand = self.compile(node.operand)
        if isinstance(node.op, ast.USub):
            return lambda env: -operand(env)
        if isinstance(node.op, ast.UAdd):
            return operand
        raise ExpressionError(f"operator {type(node.op).__name__} is not allowed")

    def _BinOp(self, node: ast.BinOp) -> Compiled:
        operation = _BINARY.get(type(node.op))
        if operation is None:
            raise ExpressionError(
                f"operator {type(node.op).__name__} is not allowed; use + - * / % **"
            )
        if isinstance(node.op, ast.Pow):
            exponent = _literal(node.right)
            if exponent is not None and abs(exponent) > MAX_EXPONENT:
                raise ExpressionError(f"exponent {exponent:g} is beyond ±{MAX_EXPONENT:g}")
        left, right = self.compile(node.left), self.compile(node.right)
        if self.arrays:  # numpy's ufuncs, also on constant operands (0.0 % 0.0 is nan)
            import numpy as np

            ufunc = {
                ast.Add: np.add,
                ast.Sub: np.subtract,
                ast.Mult: np.multiply,
                ast.Div: np.divide,
                ast.Mod: np.mod,
                ast.Pow: np.power,
            }[type(node.op)]
            return lambda env: _mark(env, ufunc(left(env), right(env)))

        def binary(env: Env) -> float:
            value = operation(left(env), right(env))
            if not math.isfinite(value):  # an overflow must not hide in min(), 0*x, a < b
                raise OverflowError(f"{_SYMBOL[type(node.op)]} gave {value}")
            return value

        return binary

    def _Compare(self, node: ast.Compare) -> Compiled:
        parts = [self.compile(node.left), *(self.compile(c) for c in node.comparators)]
        tests = []
        for op in node.ops:
            test = _COMPARE.get(type(op))
            if test is None:
                raise ExpressionError("only < <= > >= comparisons are allowed")
            tests.append(test)
        if self.arrays:
            import numpy as np

            def compare_arrays(env: Any) -> Any:
                values = [p(env) for p in parts]
                held = [t(a, b) for t, a, b in zip(tests, values, values[1:], strict=False)]
                return np.logical_and.reduce(np.broadcast_arrays(*held)).astype(float)

            return compare_arrays

        def compare(env: Env) -> float:
            values = [p(env) for p in parts]
            return float(all(t(a, b) for t, a, b in zip(tests, values, values[1:], strict=False)))

        return compare

    def _IfExp(self, node: ast.IfExp) -> Compiled:
        test, body, other = (
            self.compile(node.test),
            self.compile(node.body),
            self.compile(node.orelse),
        )
        if self.arrays:
            import numpy as np

            def choose(env: Any) -> Any:
                taken = test(env) != 0.0
                bad = env["_bad"]
                env["_bad"] = np.zeros_like(bad)
                first = body(env)
                env["_bad"], first_bad = np.zeros_like(bad), env["_bad"]
                second = other(env)
                env["_bad"] = bad | np.where(taken, first_bad, env["_bad"])
                return np.where(taken, first, second)

            return choose
        return lambda env: body(env) if test(env) != 0.0 else other(env)

    def _Call(self, node: ast.Call) -> Compiled:
        if not isinstance(node.func, ast.Name):
            raise ExpressionError(f"{_describe(node.func)} cannot be called; only named functions")
        name = node.func.id
        if name not in FUNCTIONS:
            raise ExpressionError(
                f"unknown function {name!r}; allowed: {', '.join(sorted(FUNCTIONS))}"
            )
        if node.keywords:
            raise ExpressionError(f"{name}() takes no keyword arguments")
        if any(isinstance(a, ast.Starred) for a in node.args):
            raise ExpressionError(f"{name}() takes no *arguments")
        function, low, high = FUNCTIONS[name]
        if not low <= len(node.args) <= high:
            count = str(low) if low == high else f"{low} to {high}"
            raise ExpressionError(f"{name}() takes {count} arguments, got {len(node.args)}")
        args = [self.compile(a) for a in node.args]
        if self.arrays:
            array_function = _array_functions()[name]
            return lambda env: _mark(env, array_function(*(a(env) for a in args)))

        def call(env: Env) -> float:
            value = float(function(*(a(env) for a in args)))
            if not math.isfinite(value):
                raise OverflowError(f"{name}() gave {value}")
            return value

        return call


def _literal(node: ast.AST) -> float | None:
    """The value of a literal number, possibly signed, or None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, int | float):
        try:
            return float(node.value)
        except OverflowError:
            return math.inf
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        inner = _literal(node.operand)
        if inner is not None:
            return -inner if isinstance(node.op, ast.USub) else inner
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
        # a**b**c: the right operand is itself a power; bound its size
        base, exponent = _literal(node.left), _literal(node.right)
        if base is not None and exponent is not None:
            try:
                return float(abs(base) ** min(abs(exponent), 1e3))
            except OverflowError:
                return math.inf
    return None


def _describe(node: ast.AST) -> str:
    kinds = {
        "Attribute": "attribute access (a.b)",
        "Subscript": "indexing (a[b])",
        "Lambda": "lambda",
        "ListComp": "a comprehension",
        "GeneratorExp": "a generator",
        "NamedExpr": "assignment (:=)",
        "JoinedStr": "a string",
        "List": "a list",
        "Tuple": "a tuple",
        "Dict": "a dict",
        "Set": "a set",
        "BoolOp": "and/or (use min/max or comparisons)",
        "Await": "await",
        "Yield": "yield",
    }
    name = type(node).__name__
    return kinds.get(name, name)
