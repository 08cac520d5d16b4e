"""Quantity strings in case files: ``"52.5 N*m/deg"``, ``"1000 rpm"``, ``"479.15 t*m**2"``.

A numeric key may be written as a string with a unit; it is parsed with pint,
checked against the unit in the field's description and converted to it. pint is
imported only when a case file holds such a string in another unit than its field's
(it costs about 0.15–0.3 s; a number in the field's own unit is that number), and
its registry is built once per process.

pint's stock registry has traps for a machine-dynamics engineer, each handled here
and tested in ``tests/test_quantities.py``:

* **The radian is dimensionless** in pint, so ``"52.5 N*m"`` would pass for a
  stiffness in N·m/rad and ``"50 Hz"`` would become 50 rad/s. Here the angle is a
  base dimension of its own: ``N*m`` is refused where N·m/rad is asked, ``N*m/deg``
  converts with 180/π, ``rpm`` is a revolution per minute (2π/60 rad/s) and ``Hz``
  is a cycle per second (50 Hz = 100π rad/s = 3000 rpm).
* ``Nm`` is pint's textile *number metre* (km/kg); here it is the newton metre
  (and ``kNm`` the kilonewton metre).
* ``PS`` is pint's petasiemens; here it is the metric horsepower, 75 kgf·m/s =
  735.49875 W.
* ``ton`` is pint's short ton (907.18 kg) where a Russian or European document
  means the tonne; it is refused as ambiguous: write ``t`` (tonne) or ``short_ton``.

pint parses with its own tokenizer and evaluator (no Python ``eval``). Powers are
limited to small exponents, so ``"10**10**10 m"`` is refused instead of computed.
"""

from __future__ import annotations

import math
import re
from functools import cache
from typing import Any

#: Unit names refused outright, with what to write instead.
AMBIGUOUS = {
    "ton": "'ton' is ambiguous (pint reads the US short ton, 907.18 kg); "
    "write 't' or 'tonne' for 1000 kg, or 'short_ton'",
    "tons": "'tons' is ambiguous; write 't' or 'tonne' for 1000 kg, or 'short_ton'",
}

#: Redefinitions and additions to pint's English registry (see the module docstring).
_REPLACED = {
    "radian = [] = rad": "radian = [angle] = rad",
    "hertz = 1 / second = Hz": "hertz = revolution / second = Hz",
}
_ADDED = (
    "Nm = newton * meter",
    "PS = 75 * force_kilogram * meter / second",
)

_NAME = re.compile(r"[^\W\d]\w*")
#: Two numbers side by side ("18 609.2"), which pint would multiply.
_SPLIT_NUMBER = re.compile(r"(?<![\w.])[-+]?\d[\d.]*(?:[eE][-+]?\d+)?\s+[-+]?\.?\d")
_POWER_OP = re.compile(r"\*\*|\^")
#: A power with a plain exponent, not itself raised to a power (10**10**10 is refused).
_PLAIN_POWER = re.compile(r"(?:\*\*|\^)\s*([-+]?(?:\d+(?:\.\d*)?|\.\d+))(?![\w.(]|\s*(?:\*\*|\^))")
_MAX_EXPONENT = 4.0
_MAX_LENGTH = 100


class QuantityError(ValueError):
    """A quantity string that cannot be read or does not fit its field."""


@cache
def registry() -> Any:
    """pint's English registry with the changes above; built once per process."""
    import os

    pint = _import_pint()

    folder = os.path.dirname(pint.__file__)
    lines: list[str] = []
    with open(os.path.join(folder, "default_en.txt"), encoding="utf-8") as handle:
        for line in handle.read().splitlines():
            if line.strip() == "@import constants_en.txt":
                with open(os.path.join(folder, "constants_en.txt"), encoding="utf-8") as inner:
                    lines += inner.read().splitlines()
            else:
                lines.append(_REPLACED.get(line.strip(), line))
    missing = [old for old, new in _REPLACED.items() if new not in lines]
    if missing:  # a pint release that words these lines differently
        raise RuntimeError(f"pint's definitions changed; cannot redefine: {missing}")
    ureg: Any = pint.UnitRegistry(None, on_redefinition="ignore")
    ureg.load_definitions(lines)
    for definition in _ADDED:
        ureg.define(definition)
    # units printed in the order written (N·m, not pint's alphabetical m·N)
    ureg.formatter.default_sort_func = None
    return ureg


#: What pint's compat module imports when it is installed, for array types mdcalc
#: never gives it: dask alone is 90 ms of a study's set-up.
_PINT_EXTRAS = ("dask", "xarray")


def _import_pint() -> Any:
    """pint, imported without the array libraries it would wrap (a module not yet
    imported is held back while pint looks for it; one already imported is left)."""
    import sys

    held = [name for name in _PINT_EXTRAS if name not in sys.modules]
    for name in held:
        sys.modules[name] = None  # type: ignore[assignment]  # import raises ImportError
    try:
        import pint
    finally:
        for name in held:
            if sys.modules.get(name, False) is None:
                del sys.modules[name]
    return pint


#: The powers a field description writes as a person reads them (kg·m², m/s³).
_SUPERSCRIPTS = str.maketrans({"²": "**2", "³": "**3", "⁴": "**4", "·": "*", "^": "**"})


def field_unit(unit: str) -> str:
    """A field description's unit (``N·m/rad``, ``kg·m²``, ``-``) in pint's syntax."""
    if unit in ("", "-"):
        return "dimensionless"
    return unit.translate(_SUPERSCRIPTS)


#: A number and a unit: "1500 kg", "-2.5e3 N*m/rad" (ASCII digits, as pint's tokenizer).
_NUMBER_AND_UNIT = re.compile(
    r"\s*([-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)\s*(.*?)\s*"
)
#: A field's unit in pint's syntax made of names, products, quotients and whole
#: powers only ("N*m/rad", "kg*m**2"; not "N*m/radⁿ" or "unit of value").
_PLAIN_UNIT = re.compile(r"[A-Za-z_]+(?:\*\*[0-9]+)?(?:[*/][A-Za-z_]+(?:\*\*[0-9]+)?)*")


def convert(text: str, unit: str) -> float:
    """The value of quantity ``text`` in ``unit`` (a field description's unit).

    A number written in the field's own unit, as its description spells it in pint's
    syntax ("1500 kg" where kg is asked), is that number: pint would convert it by a
    factor of 1, and is not loaded for it (its registry costs 0.15–0.3 s). Any other
    string goes to pint. Raises :class:`QuantityError` with a message for the user.
    """
    _screen(text)
    own = _NUMBER_AND_UNIT.fullmatch(text)
    target_text = field_unit(unit)
    if (
        own is not None
        and own.group(2) == target_text != "dimensionless"
        and _PLAIN_UNIT.fullmatch(target_text)
    ):
        value = float(own.group(1))
        if math.isfinite(value):
            return value
    return by_pint(text, unit)


def by_pint(text: str, unit: str) -> float:
    """:func:`convert` by pint alone (screened already)."""
    ureg = registry()
    import pint

    target_text = field_unit(unit)
    try:
        target = ureg.Unit(target_text)
    except Exception:  # "N·m/rad^n", "unit of value": no fixed unit to convert to
        raise QuantityError(f"got {text!r}; this key takes a plain number in {unit}") from None
    try:
        quantity = ureg.Quantity(text)
    except pint.errors.UndefinedUnitError as exc:
        names = ", ".join(repr(n) for n in exc.unit_names) if exc.unit_names else "a name"
        raise QuantityError(f"got {text!r}; unknown unit {names}") from None
    except Exception:  # pint's parser raises assorted errors on malformed text
        raise QuantityError(
            f'got {text!r}; not a quantity (write a number and a unit, as "52.5 N*m/deg")'
        ) from None
    if not isinstance(quantity, ureg.Quantity):  # a bare number may parse to int
        quantity = ureg.Quantity(quantity, "dimensionless")
    if quantity.unitless and not target.dimensionless:
        raise QuantityError(
            f"got {text!r}; a number in quotes without a unit: "
            f"write {text.strip()} or '{text.strip()} {unit}'"
        )
    try:
        value = quantity.to(target).magnitude
    except pint.errors.DimensionalityError:
        raise QuantityError(_mismatch(text, quantity, target, unit)) from None
    value = float(value.real if isinstance(value, complex) else value)
    if not math.isfinite(value):
        raise QuantityError(f"got {text!r}; {value} {unit} is not a finite number")
    return value


def _screen(text: str) -> None:
    """Refuse what pint would take wrongly or take long over, before it sees it."""
    if len(text) > _MAX_LENGTH:
        raise QuantityError(f"a quantity string of {len(text)} characters; at most {_MAX_LENGTH}")
    if _SPLIT_NUMBER.search(text) or any(c in text for c in ",;[]{}"):
        # pint reads "18 609.2" as 18 × 609.2 and "2,5" as 25: refuse, do not guess.
        raise QuantityError(
            f"got {text!r}; write one number without spaces or commas, with a decimal "
            "point (18609.2, not 18 609.2 or 18609,2), then the unit"
        )
    for name in _NAME.findall(text):
        if name in AMBIGUOUS:
            raise QuantityError(f"got {text!r}; {AMBIGUOUS[name]}")
    powers = _POWER_OP.findall(text)
    plain = [float(m) for m in _PLAIN_POWER.findall(text)]
    if len(plain) != len(powers) or any(abs(e) > _MAX_EXPONENT for e in plain):
        raise QuantityError(
            f"got {text!r}; a power must be a plain number up to {_MAX_EXPONENT:g}, "
            "not another power or a bracket (as m**2, s**-1)"
        )


def _mismatch(text: str, quantity: Any, target: Any, unit: str) -> str:
    given, wanted = quantity.dimensionality, target.dimensionality
    g, w = given.get("[angle]", 0), wanted.get("[angle]", 0)
    rest = {k: v for k, v in given.items() if k != "[angle]"}
    hint = ""
    if g != w and rest == {k: v for k, v in wanted.items() if k != "[angle]"}:
        if w < g:
            hint = f"{unit} is per angle: write the value per rad or per deg"
        elif g < w:
            hint = f"{unit} holds an angle: write rad, deg, rpm or Hz"
        hint = f"; {hint} (pint takes radians as plain numbers, mdcalc does not)"
        if w == 0:
            hint = f"; the value holds an angle and {_named(unit)} does not"
    return f"got {text!r}; does not convert to {_named(unit)}{hint}"


def _named(unit: str) -> str:
    return "a plain number" if unit in ("", "-") else unit
