"""Independent tests of the restricted formula evaluator ``mdcalc.input.expr`` (brief §8:
"formulas must be evaluated by a restricted expression evaluator -- arithmetic and
whitelisted math functions only, never Python ``eval`` of file content").

The property tests build a random expression TREE (hypothesis), print it as text
(with minimal parentheses from Python's precedence rules, or with extra ones, and
random spacing) and evaluate the same tree with the reference written here -- never by
``eval`` of the text. The reference follows IEEE float arithmetic as Python does:
``/`` and ``%`` by zero raise, ``%`` takes the sign of the divisor (written out with
``fmod``), powers by ``math.pow``, ``min``/``max``/``clip``/``sign`` written out,
comparisons give 1.0/0.0 with every operand evaluated, ``a if c else b`` evaluates
only the branch taken. A reference that raises, or ends non-finite, must make the
evaluator raise ArithmeticError; otherwise the two values must be equal.

Everything the language does not allow must be rejected at parse time with
ExpressionError, quickly (no hang on ``9**9**9``), and the ``mechanism`` command must
turn such a formula into exit 2 naming ``torque.formula`` (or ``inertia.formula``).
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tomli_w import dumps as toml_dumps

from mdcalc.input.expr import ExpressionError, check_name, parse
from tests.conftest import assert_no_traceback

VARIABLES = ("phi", "omega")
PARAMETER_NAMES = ("a", "M0", "k_2", "wSync")
FAST = 1.0  # seconds: a rejection (or a domain error) must come at once

# ------------------------------------------------------------------ the reference


def _sign(x: float) -> float:
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return 0.0  # also for nan, as any comparison-based sign


def _least(*xs: float) -> float:
    best = xs[0]
    for x in xs[1:]:
        if x < best:
            best = x
    return best


def _most(*xs: float) -> float:
    best = xs[0]
    for x in xs[1:]:
        if x > best:
            best = x
    return best


def _clip(x: float, low: float, high: float) -> float:
    value = low if low > x else x
    return high if high < value else value


def _floor(x: float) -> float:
    return float(math.floor(x))


def _ceil(x: float) -> float:
    return float(math.ceil(x))


def _divide(a: float, b: float) -> float:
    if b == 0.0:
        raise ZeroDivisionError("division by zero")
    return a / b


def _remainder(a: float, b: float) -> float:
    """IEEE-style remainder with the sign of the divisor, as C's fmod plus a shift."""
    if b == 0.0:
        raise ZeroDivisionError("modulo by zero")
    if math.isnan(a) or math.isnan(b) or math.isinf(a):
        return math.nan
    if math.isinf(b):
        if a == 0.0 or (a < 0.0) == (b < 0.0):
            return a
        return b  # -1 % inf is inf, 1 % -inf is -inf
    r = math.fmod(a, b)
    if r != 0.0:
        if (r < 0.0) != (b < 0.0):
            r += b
    else:
        r = math.copysign(0.0, b)
    return r


REFERENCE_FUNCTIONS: dict[str, tuple[Callable[..., float], int, int]] = {
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
    "abs": (math.fabs, 1, 1),
    "hypot": (math.hypot, 2, 2),
    "floor": (_floor, 1, 1),
    "ceil": (_ceil, 1, 1),
    "sign": (_sign, 1, 1),
    "min": (_least, 2, 8),
    "max": (_most, 2, 8),
    "clip": (_clip, 3, 3),
}
BINARY = {
    "+": lambda a, b: a + b,
    "-": lambda a, b: a - b,
    "*": lambda a, b: a * b,
    "/": _divide,
    "%": _remainder,
}
COMPARE = {
    "<": lambda a, b: a < b,
    "<=": lambda a, b: a <= b,
    ">": lambda a, b: a > b,
    ">=": lambda a, b: a >= b,
}
CONSTANTS = {"pi": math.pi, "e": math.e, "tau": 2.0 * math.pi}

# A tree is a tuple: ("num", x) x >= 0 | ("name", s) | ("neg", t) | ("pos", t) |
# ("bin", op, l, r) | ("pow", base, exponent) exponent a literal | ("cmp", ops, parts) |
# ("if", body, test, orelse) | ("call", f, args) | ("paren", t).
Tree = tuple[Any, ...]


def reference(tree: Tree, env: dict[str, float]) -> float:
    kind = tree[0]
    if kind == "num":
        return float(tree[1])
    if kind == "name":
        return env[tree[1]] if tree[1] in env else CONSTANTS[tree[1]]
    if kind == "neg":
        return -reference(tree[1], env)
    if kind in ("pos", "paren"):
        return reference(tree[1], env)
    if kind == "bin":
        left = reference(tree[2], env)
        right = reference(tree[3], env)
        value = BINARY[tree[1]](left, right)
        if not math.isfinite(value):  # the formula's rule: an overflow may not hide in a < b
            raise OverflowError(f"{tree[1]} gave {value}")
        return value
    if kind == "pow":
        return math.pow(reference(tree[1], env), tree[2])
    if kind == "cmp":
        values = [reference(p, env) for p in tree[2]]
        ok = all(COMPARE[op](x, y) for op, x, y in zip(tree[1], values, values[1:], strict=False))
        return 1.0 if ok else 0.0
    if kind == "if":
        test = reference(tree[2], env)
        return reference(tree[1] if test != 0.0 else tree[3], env)
    if kind == "call":
        function = REFERENCE_FUNCTIONS[tree[1]][0]
        return float(function(*(reference(a, env) for a in tree[2])))
    raise AssertionError(kind)


def names_of(tree: Tree) -> set[str]:
    """Variables and parameters anywhere in the tree (constants excluded)."""
    if tree[0] == "name":
        return set() if tree[1] in CONSTANTS else {tree[1]}
    found: set[str] = set()
    for part in tree[1:]:
        if isinstance(part, tuple) and part and isinstance(part[0], str):
            found |= names_of(part)
        elif isinstance(part, list):
            for item in part:
                if isinstance(item, tuple):
                    found |= names_of(item)
    return found


# ------------------------------------------------------------------ the printer

ATOM, POWER, UNARY, PRODUCT, SUM, COMPARISON, CONDITIONAL = 6, 5, 4, 3, 2, 1, 0


def _number_text(x: float | int) -> str:
    return str(x) if isinstance(x, int) else repr(x)


def show(tree: Tree, spaced: bool) -> tuple[str, int]:
    """Text of the tree with the fewest parentheses Python's grammar needs, and the
    precedence of its top operator."""
    sp = " " if spaced else ""

    def at_least(child: Tree, level: int) -> str:
        text, prec = show(child, spaced)
        return text if prec >= level else f"({text})"

    kind = tree[0]
    if kind == "num":
        return _number_text(tree[1]), ATOM
    if kind == "name":
        return tree[1], ATOM
    if kind in ("neg", "pos"):
        sign = "-" if kind == "neg" else "+"
        return sign + at_least(tree[1], UNARY), UNARY
    if kind == "paren":
        return "(" + show(tree[1], spaced)[0] + ")", ATOM
    if kind == "bin":
        level = SUM if tree[1] in "+-" else PRODUCT
        left = at_least(tree[2], level)
        right = at_least(tree[3], level + 1)
        return f"{left}{sp}{tree[1]}{sp}{right}", level
    if kind == "pow":
        base = at_least(tree[1], ATOM)
        exponent = tree[2]
        text = _number_text(abs(exponent))
        if exponent < 0 or (exponent == 0 and math.copysign(1.0, exponent) < 0):
            text = "-" + text
        return f"{base}{sp}**{sp}{text}", POWER
    if kind == "cmp":
        parts = [at_least(p, SUM) for p in tree[2]]
        text = parts[0]
        for op, part in zip(tree[1], parts[1:], strict=True):
            text += f"{sp}{op}{sp}{part}"
        return text, COMPARISON
    if kind == "if":
        body = at_least(tree[1], COMPARISON)
        test = at_least(tree[2], COMPARISON)
        other = at_least(tree[3], CONDITIONAL)
        return f"{body} if {test} else {other}", CONDITIONAL
    if kind == "call":
        args = f",{sp}".join(at_least(a, CONDITIONAL) for a in tree[2])
        return f"{tree[1]}({args})", ATOM
    raise AssertionError(kind)


# ------------------------------------------------------------------ the strategies

numbers = st.one_of(
    st.integers(min_value=0, max_value=10**6),
    st.floats(min_value=0.0, max_value=1e3, allow_nan=False, allow_infinity=False),
    st.sampled_from([0.5, 1.0, 2.0, 3.0, 1e-3, 0.1, 1e2]),
)
leaves = st.one_of(
    numbers.map(lambda x: ("num", x)),
    st.sampled_from([*VARIABLES, *PARAMETER_NAMES, *CONSTANTS]).map(lambda s: ("name", s)),
)
EXPONENTS = [0, 1, 2, 3, 4, -1, -2, 0.5, 1.5, -0.5, 64, -64, 2.5]


def _extend(children: st.SearchStrategy[Tree]) -> st.SearchStrategy[Tree]:
    def call(name: str) -> st.SearchStrategy[Tree]:
        low, high = REFERENCE_FUNCTIONS[name][1:]
        return st.lists(children, min_size=low, max_size=min(high, 4)).map(
            lambda args: ("call", name, args)
        )

    return st.one_of(
        st.tuples(st.just("neg"), children),
        st.tuples(st.just("pos"), children),
        st.tuples(st.just("paren"), children),
        st.tuples(st.just("bin"), st.sampled_from(sorted(BINARY)), children, children),
        st.tuples(st.just("pow"), children, st.sampled_from(EXPONENTS)),
        st.integers(min_value=1, max_value=3).flatmap(
            lambda k: st.tuples(
                st.just("cmp"),
                st.lists(st.sampled_from(sorted(COMPARE)), min_size=k, max_size=k),
                st.lists(children, min_size=k + 1, max_size=k + 1),
            )
        ),
        st.tuples(st.just("if"), children, children, children),
        st.sampled_from(sorted(REFERENCE_FUNCTIONS)).flatmap(call),
    )


trees = st.recursive(leaves, _extend, max_leaves=24)
values = st.floats(min_value=-1e3, max_value=1e3, allow_nan=False, allow_infinity=False)
environments = st.fixed_dictionaries({name: values for name in (*VARIABLES, *PARAMETER_NAMES)})


def _split(env: dict[str, float]) -> tuple[dict[str, float], dict[str, float]]:
    return (
        {k: env[k] for k in VARIABLES},
        {k: env[k] for k in PARAMETER_NAMES},
    )


def _check_against_reference(text: str, tree: Tree, env: dict[str, float]) -> None:
    variables, parameters = _split(env)
    expression = parse(text, VARIABLES, parameters)
    assert expression.names == frozenset(names_of(tree)), text
    try:
        expected: float | None = reference(tree, env)
    except (ArithmeticError, ValueError):
        expected = None
    if expected is None or not math.isfinite(expected):
        with pytest.raises(ArithmeticError):
            expression(**variables)
        return
    got = expression(**variables)
    assert isinstance(got, float)
    assert got == expected, (text, got, expected)


@settings(max_examples=250, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tree=trees, env=environments, spaced=st.booleans())
def test_random_expression_matches_reference(tree: Tree, env: dict[str, float], spaced: bool):
    """Minimal parentheses: the evaluator must honour Python's precedence and
    associativity (``-x**2``, ``a - b - c``, ``2**-1``, chained comparisons)."""
    text, _ = show(tree, spaced)
    _check_against_reference(text, tree, env)


def _fully_parenthesized(tree: Tree) -> Tree:
    if tree[0] in ("num", "name"):
        return tree
    parts: list[Any] = []
    for part in tree[1:]:
        if isinstance(part, tuple) and part and isinstance(part[0], str):
            parts.append(_fully_parenthesized(part))
        elif isinstance(part, list) and part and isinstance(part[0], tuple):
            parts.append([_fully_parenthesized(p) for p in part])
        else:
            parts.append(part)
    return ("paren", (tree[0], *parts))


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tree=trees, env=environments)
def test_fully_parenthesized_expression_matches_reference(tree: Tree, env: dict[str, float]):
    full = _fully_parenthesized(tree)
    text, _ = show(full, spaced=True)
    _check_against_reference(text, full, env)


@settings(max_examples=100, deadline=None)
@given(tree=trees, env=environments)
def test_result_is_finite_or_arithmetic_error(tree: Tree, env: dict[str, float]):
    """Whatever the values, a call returns a finite float or raises ArithmeticError:
    never NaN, never inf, never another exception."""
    variables, parameters = _split(env)
    expression = parse(show(tree, True)[0], VARIABLES, parameters)
    try:
        value = expression(**variables)
    except ArithmeticError:
        return
    assert isinstance(value, float) and math.isfinite(value)


# ------------------------------------------------------------------ unit: evaluation


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1 + 2*3", 7.0),
        ("(1 + 2)*3", 9.0),
        ("10 - 4 - 3", 3.0),  # left associative
        ("2**3**2", 512.0),  # right associative
        ("-2**2", -4.0),  # unary minus binds looser than **
        ("(-2)**2", 4.0),
        ("2**-1", 0.5),
        ("7 % 3", 1.0),
        ("-7 % 3", 2.0),  # sign of the divisor
        ("7 % -3", -2.0),
        ("7.5 / 2.5", 3.0),
        ("1 < 2 < 3", 1.0),
        ("1 < 3 < 2", 0.0),
        ("2 >= 2", 1.0),
        ("2 > 2", 0.0),
        ("5 if 1 < 2 else 6", 5.0),
        ("5 if 0 else 6", 6.0),
        ("1 if 0 else 2 if 1 else 3", 2.0),
        ("max(1, 5, 3)", 5.0),
        ("min(4, -1, 3, 2, 8, 9, 0, 7)", -1.0),
        ("clip(5, 0, 2)", 2.0),
        ("clip(-5, 0, 2)", 0.0),
        ("clip(1.5, 0, 2)", 1.5),
        ("sign(-3)", -1.0),
        ("sign(0)", 0.0),
        ("sign(2e-300)", 1.0),
        ("floor(-1.5)", -2.0),
        ("ceil(-1.5)", -1.0),
        ("abs(-3)", 3.0),
        ("hypot(3, 4)", 5.0),
        ("atan2(1, 1)", math.pi / 4),
        ("log(e)", 1.0),
        ("log10(1000)", 3.0),
        ("sqrt(2)**2", 2.0000000000000004),
        ("tau - 2*pi", 0.0),
        ("1_000 + 0x10", 1016.0),
        ("1e3 + .5 + 5.", 1005.5),
        ("2**64", 2.0**64),
        ("2**-64", 2.0**-64),
        ("  1 +\t2  ", 3.0),
    ],
)
def test_constant_formula(text: str, expected: float):
    assert parse(text, ())() == expected


def test_variables_and_parameters():
    expression = parse(
        "M0*(1 - omega/w0) - Mr*max(sin(phi), 0)",
        VARIABLES,
        {"M0": 400.0, "w0": 105.0, "Mr": 300.0},
    )
    phi, omega = 1.1, 80.0
    assert expression(phi=phi, omega=omega) == pytest.approx(
        400.0 * (1.0 - omega / 105.0) - 300.0 * max(math.sin(phi), 0.0), rel=1e-15
    )
    assert expression.uses("omega") and expression.uses("phi") and expression.uses("Mr")
    assert not parse("3*sin(phi)", VARIABLES).uses("omega")
    assert not parse("pi*phi", VARIABLES).uses("pi")  # a constant is no parameter


def test_variable_wins_over_a_parameter_of_the_same_name():
    """A variable is supplied at each call; a parameter of the same name (which the
    case file refuses anyway) must not freeze it."""
    expression = parse("phi", ("phi",), {"phi": 5.0})
    assert expression(phi=1.0) == 1.0


def test_result_is_a_float_even_for_integer_literals():
    value = parse("2 + 3", ())()
    assert type(value) is float


# ------------------------------------------------------------------ unit: runtime errors


@pytest.mark.parametrize(
    ("text", "env"),
    [
        ("log(0)", {}),
        ("log(phi)", {"phi": -1.0}),
        ("log10(-1)", {}),
        ("1/0", {}),
        ("1/phi", {"phi": 0.0}),
        ("1 % 0", {}),
        ("0**-1", {}),
        ("exp(1000)", {}),
        ("cosh(1000)", {}),
        ("sinh(-1000)", {}),
        ("sqrt(-1)", {}),
        ("asin(2)", {}),
        ("acos(-1.5)", {}),
        ("(-8)**(1/3)", {}),
        ("phi**0.5", {"phi": -4.0}),
        ("1e308*10", {}),
        ("-1e308 - 1e308", {}),
        ("10.0**64 * 10.0**64 * 10.0**64 * 10.0**64 * 10.0**64", {}),
        ("phi**64", {"phi": 1e10}),
        ("floor(1e308*10)", {}),
        ("sin(1e308*10)", {}),
        ("0*(1e308*10)", {}),
        ("2**phi", {"phi": 1e6}),
    ],
)
def test_domain_error_is_arithmetic_error_quickly(text: str, env: dict[str, float]):
    expression = parse(text, ("phi",))
    start = time.perf_counter()
    with pytest.raises(ArithmeticError):
        expression(phi=env.get("phi", 1.0))
    assert time.perf_counter() - start < FAST


@pytest.mark.parametrize(
    "text",
    [
        "min(5, (1e200*1e200)*0)",  # mathematically min(5, 0) = 0; returns 5
        "(1e200*1e200 - 2*(1e200*1e200)) < 0",  # mathematically 1; returns 0
        "1 if 0*(1e200*1e200) else 2",  # mathematically 2; returns 1
    ],
)
def test_overflow_inside_a_formula_is_not_swallowed(text: str):
    with pytest.raises(ArithmeticError):
        parse(text, ())()


# ------------------------------------------------------------------ unit: rejections

FORBIDDEN = [
    "().__class__",
    "().__class__.__bases__[0].__subclasses__()",
    "phi.real",
    "__import__('os')",
    "__import__",
    "__builtins__",
    "__class__",
    "_x",
    "_",
    "[1][0]",
    "phi[0]",
    "[phi]",
    "{1: 2}",
    "{1}",
    "(1, 2)",
    "lambda: 1",
    "(lambda x: x)(1)",
    "[i for i in (1,)]",
    "max(i for i in (1, 2))",
    "{i: 1 for i in (1,)}",
    "sin(x=1)",
    "sin(*[1])",
    "max(**{})",
    "'text'",
    "b'x'",
    "f'{phi}'",
    "(z := 3)",
    "9**9**9",
    "2**1000",
    "10**(10**10)",
    "10**-(10**10)",
    "2**65",
    "2**-65",
    "phi**100",
    "1e400",
    "9" * 400,
    "open('x')",
    "eval('1')",
    "exec('1')",
    "getattr(phi, 'real')",
    "globals()",
    "print(1)",
    "foo(1)",
    "unknown",
    "φ",
    "sin(1, 2)",
    "atan2(1)",
    "min(1)",
    "max(1, 2, 3, 4, 5, 6, 7, 8, 9)",
    "clip(1, 2)",
    "sin",
    "sin.__call__(1)",
    "True",
    "None",
    "1j",
    "...",
    "phi and omega",
    "phi or omega",
    "not phi",
    "~1",
    "phi == 1",
    "phi != 1",
    "phi is omega",
    "phi in omega",
    "1 << 2",
    "7 // 2",
    "1 @ 2",
    "1 | 2",
    "1 & 2",
    "1 ^ 2",
    "await phi",
    "(yield)",
    "phi if phi",
    "import os",
    "x = 1",
    "1; 2",
]


@pytest.mark.parametrize("snippet", FORBIDDEN)
def test_forbidden_alone_is_expression_error_quickly(snippet: str):
    start = time.perf_counter()
    with pytest.raises(ExpressionError):
        parse(snippet, VARIABLES, {"M0": 1.0})
    assert time.perf_counter() - start < FAST


CONTEXTS = [
    "{s}",
    "1 + {s}",
    "M0*(1 - omega/w0) + {s}",
    "sin({s})",
    "({s})*2",
    "max(phi, {s})",
    "{s} if phi > 0 else 1",
    "1 if {s} else 0",
    "-({s})",
    "clip({s}, 0, 1)",
]


@settings(max_examples=300, deadline=None)
@given(snippet=st.sampled_from(FORBIDDEN), context=st.sampled_from(CONTEXTS))
def test_forbidden_embedded_is_expression_error(snippet: str, context: str):
    text = context.replace("{s}", snippet)
    start = time.perf_counter()
    with pytest.raises(ExpressionError):
        parse(text, VARIABLES, {"M0": 1.0, "w0": 2.0})
    assert time.perf_counter() - start < FAST


@pytest.mark.parametrize(
    "text",
    [
        "",
        "   ",
        "# comment only",
        "1 +",
        "(1",
        "1)",
        "sin(",
        "omega\n+1",
        "(" * 1000 + "1" + ")" * 1000,  # longer than the limit
        "(" * 300 + "1" + ")" * 300,  # deeper than Python's parser takes
        "1" + "+1" * 1200,  # too long
        "+".join(["phi"] * 400),  # too many parts
        "-" * 600 + "1",  # too many parts
        "sin(" * 200 + "1" + ")" * 200,  # too many parts
    ],
)
def test_malformed_or_oversized_is_expression_error_quickly(text: str):
    start = time.perf_counter()
    with pytest.raises(ExpressionError):
        parse(text, VARIABLES)
    assert time.perf_counter() - start < FAST


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("-" * 240 + "1", 1.0),  # within the limits: nested, but allowed
        ("(" * 150 + "2" + ")" * 150, 2.0),
        ("+".join(["1"] * 160), 160.0),
        ("**".join(["1"] * 100), 1.0),
    ],
)
def test_deep_but_allowed_formula_evaluates(text: str, expected: float):
    assert parse(text, ())() == expected


def test_unknown_name_message_lists_the_known_ones():
    with pytest.raises(ExpressionError, match=r"unknown name 'x'.*phi.*omega.*M0"):
        parse("x + 1", VARIABLES, {"M0": 1.0})


def test_unknown_function_message_lists_the_allowed_ones():
    with pytest.raises(ExpressionError, match=r"unknown function 'open'.*sin"):
        parse("open(1)", VARIABLES)


def test_wrong_arity_message():
    with pytest.raises(ExpressionError, match=r"hypot\(\) takes 2 arguments, got 3"):
        parse("hypot(1, 2, 3)", VARIABLES)


def test_parse_never_executes_code(tmp_path):
    """A formula that would write a file if it were eval'ed leaves no file behind."""
    target = tmp_path / "pwned"
    with pytest.raises(ExpressionError):
        parse(f"open({str(target)!r}, 'w').write('x')", VARIABLES)
    with pytest.raises(ExpressionError):
        parse(f"__import__('pathlib').Path({str(target)!r}).touch()", VARIABLES)
    assert not target.exists()


# ------------------------------------------------------------------ parameter names


@pytest.mark.parametrize("name", ["a", "M0", "k_2", "wSync", "Ml", "ω0"])
def test_plain_parameter_names_are_accepted(name: str):
    check_name(name, VARIABLES)


@pytest.mark.parametrize(
    "name",
    [
        "sin",
        "max",
        "clip",
        "pi",
        "e",
        "tau",
        "phi",
        "omega",
        "_x",
        "__class__",
        "1a",
        "a-b",
        "a b",
        "",
    ],
)
def test_taken_or_improper_parameter_names_are_refused(name: str):
    with pytest.raises(ExpressionError):
        check_name(name, VARIABLES)


# ------------------------------------------------------------------ CLI: exit 2

BASE_CASE: dict[str, Any] = {
    "problem": "mechanism",
    "parameters": {"M0": 400.0, "w0": 105.0},
    "torque": {"formula": "M0*(1 - omega/w0)"},
    "inertia": {"value": 2.0},
    "motion": {"start_speed": 80.0, "revolutions": 1.0},
}
ERROR_LINE = re.compile(r"^\S+\.toml:\d+: error: (\S+): .+$", re.M)


def _case_with(section: str, formula: str) -> dict[str, Any]:
    data = {
        key: (dict(value) if isinstance(value, dict) else value) for key, value in BASE_CASE.items()
    }
    if section == "torque":
        data["torque"] = {"formula": formula}
    else:
        data["inertia"] = {"formula": formula}
    return data


@settings(
    max_examples=30,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(snippet=st.sampled_from(FORBIDDEN), context=st.sampled_from(CONTEXTS))
def test_cli_rejects_forbidden_torque_formula(cli, write_case, snippet: str, context: str):
    path = write_case(toml_dumps(_case_with("torque", context.replace("{s}", snippet))))
    start = time.perf_counter()
    result = cli("mechanism", path)
    assert time.perf_counter() - start < 5.0
    assert result.exit_code == 2, (snippet, context, result.stdout, result.stderr)
    assert_no_traceback(result)
    fields = ERROR_LINE.findall(result.stderr)
    assert "torque.formula" in fields, result.stderr
    assert result.stdout.strip() == ""


@settings(
    max_examples=10,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
@given(snippet=st.sampled_from(FORBIDDEN))
def test_cli_rejects_forbidden_inertia_formula(cli, write_case, snippet: str):
    path = write_case(toml_dumps(_case_with("inertia", f"2 + 0.1*cos(phi) + {snippet}")))
    result = cli("mechanism", path, "--json")
    assert result.exit_code == 2, (snippet, result.stdout, result.stderr)
    assert_no_traceback(result)
    assert "inertia.formula" in ERROR_LINE.findall(result.stderr), result.stderr


@pytest.mark.parametrize(
    "formula",
    [
        "M0*log(omega - 80)",
        "M0/(omega - 80)",
        "sqrt(phi - 1)",
        "exp(omega*100)",
        "(-8)**(phi + 1/3)",
    ],
)
def test_cli_formula_not_evaluable_at_start_is_exit_2(cli, write_case, formula: str):
    result = cli("mechanism", write_case(toml_dumps(_case_with("torque", formula))))
    assert result.exit_code == 2, (result.stdout, result.stderr)
    assert_no_traceback(result)
    assert "torque.formula" in ERROR_LINE.findall(result.stderr)


def test_cli_formula_failing_later_in_the_run_is_exit_3(cli, write_case):
    """sqrt(3 - phi) is fine at φ₀ = 0 and undefined past 3 rad: no answer, no traceback."""
    result = cli("mechanism", write_case(toml_dumps(_case_with("torque", "10*sqrt(3 - phi)"))))
    assert result.exit_code == 3, (result.stdout, result.stderr)
    assert_no_traceback(result)


def test_cli_parameter_names_are_checked(cli, write_case):
    for name in ("sin", "_x", "omega", "pi"):
        data = _case_with("torque", "M0*(1 - omega/w0)")
        data["parameters"] = {**data["parameters"], name: 1.0}
        result = cli("mechanism", write_case(toml_dumps(data)))
        assert result.exit_code == 2, name
        assert_no_traceback(result)
        assert f"parameters.{name}" in ERROR_LINE.findall(result.stderr), result.stderr


@pytest.mark.parametrize(
    ("name", "folded"),
    [("ｏｍｅｇａ", "omega"), ("ｗ0", "w0"), ("ℯ", "e"), ("ﬁ", "fi"), ("Ｍ0", "M0")],
)
def test_parameter_names_python_would_fold_are_refused(cli, write_case, name, folded):
    # Python reads identifiers in a formula in NFKC: a fullwidth "ｏｍｅｇａ" is the variable
    # omega, "ℯ" the constant e. Taken as written, the parameter's value was silently
    # ignored (issue 20) or unreachable; now the name must be written as Python reads it.
    with pytest.raises(ExpressionError, match=f"read as '{folded}'"):
        check_name(name, VARIABLES)
    data = _case_with("torque", "M0*(1 - omega/w0)")
    data["parameters"] = {**data["parameters"], name: 1.0}
    result = cli("mechanism", write_case(toml_dumps(data)))
    assert result.exit_code == 2, (name, result.stdout, result.stderr)
    assert_no_traceback(result)
    assert f"parameters.{name}" in ERROR_LINE.findall(result.stderr), result.stderr
    assert folded in result.stderr


def test_the_folding_was_real():
    # Why the rule above: without it the formula's "ｏｍｅｇａ" is the variable omega.
    assert parse("ｏｍｅｇａ*2", ("omega",))(omega=3.0) == 6.0


def test_computed_exponent_beyond_64_is_a_plain_power():
    # Only literal exponents are limited (9**9**9 must fail at once); a computed one is
    # an ordinary float power: 2**90 is fine, 2**-1e6 underflows to 0, 2**1e6 overflows.
    assert parse("2**(3*30)", ())() == 2.0**90
    assert parse("400*0.99**omega - 100", ("omega",))(omega=80.0) == 400 * 0.99**80.0 - 100
    assert parse("2**phi", ("phi",))(phi=-1e6) == 0.0
    with pytest.raises(ArithmeticError):
        parse("2**phi", ("phi",))(phi=1e6)


# ------------------------------------------------------------ the same formula on arrays


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tree=trees, block=st.lists(environments, min_size=1, max_size=6))
def test_array_form_matches_the_float_form_row_by_row(tree: Tree, block: list[dict[str, float]]):
    """A block of scenes (a study's samples) evaluates a formula on arrays, each row
    with its own variables and parameters: each row gives the float form's value, and
    is marked bad exactly where the float form raises."""
    import numpy as np

    text, _ = show(tree, True)
    expression = parse(text, VARIABLES, _split(block[0])[1])
    env: dict[str, Any] = {k: np.array([e[k] for e in block]) for k in block[0]}
    env["_bad"] = np.zeros(len(block), dtype=bool)
    with np.errstate(all="ignore"):
        got = np.broadcast_to(expression.on_arrays()(env), (len(block),))
    for row, values in enumerate(block):
        want = _float_form(text, values)
        if not _well_conditioned(text, values, want):
            continue  # numpy's exp and math's may round an ulp apart: cos(exp(677)) is noise
        if want is None:
            assert env["_bad"][row], (text, values, got[row])
        else:
            assert not env["_bad"][row], (text, values, want)
            assert math.isclose(float(got[row]), want, rel_tol=1e-9, abs_tol=1e-12), (
                text,
                values,
                got[row],
                want,
            )


def _float_form(text: str, values: dict[str, float]) -> float | None:
    """The float form's value at ``values``; None where it raises."""
    variables, parameters = _split(values)
    try:
        return parse(text, VARIABLES, parameters)(**variables)
    except ArithmeticError:
        return None


def _well_conditioned(text: str, values: dict[str, float], want: float | None) -> bool:
    """The float form gives the same answer (raises again, or a value within 1e-9) with
    every input an ulp up, and an ulp down: a row where an ulp of an input, and so an
    ulp of an intermediate, changes the answer cannot hold two evaluations to 1e-9."""
    for direction in (math.inf, -math.inf):
        other = _float_form(text, {k: math.nextafter(v, direction) for k, v in values.items()})
        if (other is None) != (want is None):
            return False
        if other is not None and want is not None:
            if not math.isclose(other, want, rel_tol=1e-9, abs_tol=1e-12):
                return False
    return True


def test_ill_conditioned_rows_are_told_apart():
    # cos(exp(ω)) at ω = 677: exp is 1e294, whose ulp is 1e278 radians
    at = dict.fromkeys((*VARIABLES, *PARAMETER_NAMES), 1.0) | {"omega": 677.0}
    assert not _well_conditioned("cos(exp(omega))", at, math.cos(math.exp(677.0)))
    assert _well_conditioned("cos(omega)", at, math.cos(677.0))


def test_array_form_counts_an_error_only_in_the_branch_taken():
    import numpy as np

    expression = parse("1/phi if phi > 0 else log(-phi + 1)", VARIABLES, {"a": 2.0})
    env = {"phi": np.array([0.0, 2.0, -1.0]), "omega": np.zeros(3), "_bad": np.zeros(3, bool)}
    with np.errstate(all="ignore"):
        got = expression.on_arrays()(env)
    assert not env["_bad"].any()
    assert got.tolist() == [0.0, 0.5, math.log(2.0)]
    bad = parse("a*log(phi)", VARIABLES, {"a": 2.0}).on_arrays()
    env = {"phi": np.array([1.0, 0.0, math.e]), "a": np.array([1.0, 1.0, 3.0])}
    env["_bad"] = np.zeros(3, bool)
    with np.errstate(all="ignore"):
        got = bad(env)
    assert env["_bad"].tolist() == [False, True, False]
    assert got[2] == pytest.approx(3.0)  # the parameter drawn per row
