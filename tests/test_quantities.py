"""Quantity strings in case files (issue 9.1): conversions, pint's traps, the CLI.

Expected values are worked by hand from the unit definitions (1 kgf = 9.80665 N,
1 deg = π/180 rad, 1 rev = 2π rad, 1 PS = 75 kgf·m/s), never read off pint.
"""

from __future__ import annotations

import math
import time

import pytest

from mdcalc.input.quantities import QuantityError, convert, registry
from tests.conftest import CASES, assert_no_traceback, strict_json

G0 = 9.80665


@pytest.mark.parametrize(
    ("text", "unit", "expected"),
    [
        # The five examples.
        ("52.5 N*m/deg", "N·m/rad", 52.5 * 180.0 / math.pi),
        ("100 km/h", "m/s", 100.0 / 3.6),
        ("1000 rpm", "rad/s", 1000.0 * 2.0 * math.pi / 60.0),
        ("2.785e5 kgf*m/rad", "N·m/rad", 2.785e5 * G0),
        ("479.15 t*m**2", "kg·m²", 479.15e3),
        # Into fields kept in the catalogue's units.
        ("3008.0284 N*m/rad", "N·m/deg", 3008.0284 * math.pi / 180.0),
        ("104.72 rad/s", "rpm", 104.72 * 60.0 / (2.0 * math.pi)),
        ("27.78 m/s", "km/h", 27.78 * 3.6),
        ("0.5 rad", "deg", 0.5 * 180.0 / math.pi),
        # Other spellings engineers use.
        ("4000 g*m^2", "kg·m²", 4.0),
        ("1 MN*m", "N·m", 1e6),
        ("12 %", "-", 0.12),
        ("7", "-", 7.0),
        ("2 tf", "N", 2000.0 * G0),
        ("30 °", "deg", 30.0),
        ("1.5 kN*m*s/rad", "N·m·s/rad", 1500.0),
        ("9.81 m/s**2", "m/s²", 9.81),
    ],
)
def test_conversion(text, unit, expected):
    assert convert(text, unit) == pytest.approx(expected, rel=1e-12)


# ---------------------------------------------------------------- pint's traps


def test_radians_are_not_dimensionless():
    # pint alone would take a torque for a torsional stiffness, 52.5 "N*m/rad".
    with pytest.raises(QuantityError, match="per angle"):
        convert("52.5 N*m", "N·m/rad")
    with pytest.raises(QuantityError, match="holds an angle"):
        convert("50 /s", "rad/s")
    with pytest.raises(QuantityError, match="holds an angle"):
        convert("0.3 rad", "-")


def test_deg_and_rad_convert_with_180_over_pi():
    assert convert("1 N*m/deg", "N·m/rad") == pytest.approx(180.0 / math.pi, rel=1e-14)
    assert convert("1 N*m/rad", "N·m/deg") == pytest.approx(math.pi / 180.0, rel=1e-14)


def test_rpm_and_hz_are_revolutions():
    # pint alone: 50 Hz -> 50 rad/s. A cycle is 2π rad; 3000 rpm is 50 Hz.
    assert convert("50 Hz", "rad/s") == pytest.approx(100.0 * math.pi, rel=1e-14)
    assert convert("3000 rpm", "Hz") == pytest.approx(50.0, rel=1e-14)
    assert convert("1 rpm", "rad/s") == pytest.approx(math.pi / 30.0, rel=1e-14)


def test_nm_is_the_newton_metre_not_the_textile_number():
    # pint alone: "Nm" is the number metre (km/kg), which would not fit a torque.
    assert convert("250 Nm", "N·m") == pytest.approx(250.0, rel=1e-15)
    assert convert("2.5 kNm", "N·m") == pytest.approx(2500.0, rel=1e-15)
    assert convert("893.45 kNm/rad", "N·m/rad") == pytest.approx(893.45e3, rel=1e-15)


def test_ton_is_refused_as_ambiguous_and_t_is_the_tonne():
    # pint alone: "ton" is the short ton, 907.18474 kg.
    with pytest.raises(QuantityError, match="ambiguous"):
        convert("5 ton", "kg")
    with pytest.raises(QuantityError, match="ambiguous"):
        convert("5 ton*m**2", "kg·m²")
    assert convert("5 t", "kg") == pytest.approx(5000.0, rel=1e-15)
    assert convert("5 tonne", "kg") == pytest.approx(5000.0, rel=1e-15)
    assert convert("1 short_ton", "kg") == pytest.approx(2000 * 0.45359237, rel=1e-14)


def test_ps_is_the_metric_horsepower_not_petasiemens():
    assert convert("1 PS", "W") == pytest.approx(75.0 * G0, rel=1e-14)  # 735.49875 W
    # hp stays the imperial horsepower, 550 ft·lbf/s.
    assert convert("1 hp", "W") == pytest.approx(550 * 0.3048 * 0.45359237 * G0, rel=1e-12)


# ------------------------------------------------------------- refused strings


@pytest.mark.parametrize(
    ("text", "unit", "match"),
    [
        ("abc", "m", "unknown unit 'abc'"),
        # pint would read these as 18 × 609.2 kN·m/rad, 25 m and 0 N·m: refused.
        ("18 609.2 kN*m/rad", "N·m/rad", "without spaces or commas"),
        ("2,5 m", "m", "without spaces or commas"),
        ("12 000 N*m", "N·m", "without spaces or commas"),
        ("[1, 2] m", "m", "without spaces or commas"),
        ("5 furlongz", "m", "unknown unit"),
        ("", "m", "not a quantity"),
        ("__import__('os') m", "m", "not a quantity"),
        ("3 kg", "N", "does not convert to N"),
        ("nan m", "m", "not a finite number"),
        ("1e999 m", "m", "not a finite number"),
        ("10**10**10 m", "m", "a power must be a plain number"),
        ("2**2**2**2**2**2 m", "m", "a power must be a plain number"),
        ("m**(10)", "m", "a power must be a plain number"),
        ("1 m**9", "m", "a power must be a plain number"),
        ("1" * 200 + " m", "m", "at most 100"),
        ("3 N", "N·m/radⁿ", "takes a plain number"),
    ],
)
def test_refused(text, unit, match):
    with pytest.raises(QuantityError, match=match):
        convert(text, unit)


def test_a_tower_of_powers_is_refused_at_once():
    start = time.perf_counter()
    with pytest.raises(QuantityError):
        convert("9**9**9**9 m", "m")
    assert time.perf_counter() - start < 1.0


def test_the_registry_is_built_once():
    assert registry() is registry()


#: Units of numeric fields that are no fixed unit (strings are refused there).
NOT_FIXED = {"N·m/radⁿ", "kgf·m/radⁿ", "unit of value"}


def numeric_field_units() -> set[str]:
    """The unit in the description of every numeric field of every problem."""
    from pydantic import BaseModel

    from mdcalc.input.casefile import _unit, takes_numbers
    from mdcalc.problems import PROBLEMS

    seen: set[str] = set()

    def visit(model: type[BaseModel]) -> None:
        for info in model.model_fields.values():
            for arg in _models_in(info.annotation):
                visit(arg)
            if takes_numbers(info.annotation):
                seen.add(_unit(info))

    def _models_in(annotation):
        if isinstance(annotation, type) and issubclass(annotation, BaseModel):
            yield annotation
        for arg in getattr(annotation, "__args__", ()) or ():
            yield from _models_in(arg)

    for spec in PROBLEMS.values():
        visit(spec.load().Case)
    return seen


def test_every_numeric_field_unit_is_understood():
    # Written once for all problems: the unit in each numeric field's description
    # must be one pint reads (else strings are refused there: listed, on purpose).
    from mdcalc.input.quantities import field_unit

    ureg = registry()
    seen = numeric_field_units()
    for unit in seen - NOT_FIXED:
        ureg.Unit(field_unit(unit))  # raises if pint cannot read it
    assert {"N·m/rad", "rpm", "kg·m²", "km/h"} <= seen


NUMBERS = ["1500", "-2.5e3", ".5", "7.", "+3E-2", "0", "1e-300", "123456789.123456789", "-0.0"]


def test_a_number_in_the_fields_own_unit_is_pints_value_bit_for_bit():
    # convert reads "1500 kg" for a kg field without pint; pint alone must agree
    from mdcalc.input.quantities import by_pint, field_unit

    units = numeric_field_units() - NOT_FIXED - {""}
    assert len(units) > 20
    for unit in sorted(units):
        for number in NUMBERS:
            for text in (f"{number} {field_unit(unit)}", f"  {number}{field_unit(unit)} "):
                fast, slow = convert(text, unit), by_pint(text, unit)
                assert math.copysign(1.0, fast) == math.copysign(1.0, slow), (text, unit)
                assert fast == slow and type(fast) is float, (text, unit, fast, slow)


@pytest.mark.parametrize(
    ("text", "unit"),
    [
        ("5 N*m/radⁿ", "N·m/radⁿ"),  # no fixed unit: refused, as pint refuses it
        ("5 unit of value", "unit of value"),
        ("1e999 kg", "kg"),  # not finite: pint's message
    ],
)
def test_a_string_the_shortcut_must_not_take_gets_pints_answer(text, unit):
    with pytest.raises(QuantityError):
        convert(text, unit)


# ---------------------------------------------------------------------- the CLI


def test_a_case_with_units_gives_the_plain_case_results(cli):
    plain = cli("coupling", CASES / "coupling" / "example_8_1.toml", "--json")
    units = cli("coupling", CASES / "coupling" / "example_8_1_units.toml", "--json")
    assert plain.exit_code == 0 and units.exit_code == 0, units.stderr
    a, b = strict_json(plain.stdout)["results"], strict_json(units.stdout)["results"]
    for key in ("natural_frequency", "reduced_inertia", "step_dynamic_factor"):
        assert b[key]["value"] == pytest.approx(a[key]["value"], rel=1e-13), key


def test_the_report_shows_what_was_written(cli):
    result = cli("coupling", CASES / "coupling" / "example_8_1_units.toml", "--json")
    section = next(s for s in strict_json(result.stdout)["sections"] if s["key"] == "units")
    rows = {row[0]: row[1:] for row in section["rows"]}
    written, value, unit = rows["coupling.stiffness"]
    # the JSON: the text as written, the unit in its ASCII form (issue 33.2); the
    # terminal: both as a person reads them
    assert written == "52.5 N*m/deg" and unit == "N*m/rad"
    assert value == pytest.approx(52.5 * 180.0 / math.pi, rel=1e-12)
    text = cli("coupling", CASES / "coupling" / "example_8_1_units.toml").stdout
    assert "Inputs written with units" in text and "52.5 N·m/deg" in text
    # with the digits to check the conversion by eye: 52.5·180/π = 3008.02842444
    assert f" {52.5 * 180.0 / math.pi:.12g} " in text


def test_a_wrong_unit_is_exit_2_with_line_and_key(cli, write_case):
    path = write_case(
        'problem = "coupling"\n'
        "[coupling]\n"
        "driving_inertia = 10.0\n"
        'driven_inertia = "4 ton*m**2"\n'
        'stiffness = "52.5 N*m"\n'
        "absorption = 0.63\n"
        "[step]\n"
    )
    result = cli("coupling", path)
    assert result.exit_code == 2
    assert_no_traceback(result)
    lines = result.stderr.strip().splitlines()
    assert lines[0].startswith(f"{path}:4: error: coupling.driven_inertia: ")
    assert "ambiguous" in lines[0]
    assert lines[1].startswith(f"{path}:5: error: coupling.stiffness: ")
    assert len(lines) == 2  # pydantic's "expected a number" is not said again


def test_converted_values_still_meet_the_bounds(cli, write_case):
    path = write_case(
        'problem = "coupling"\n[coupling]\ndriving_inertia = "-10 kg*m**2"\n'
        "driven_inertia = 4.0\nstiffness = 3000.0\nabsorption = 0.63\n[step]\n"
    )
    result = cli("coupling", path)
    assert result.exit_code == 2
    assert f"{path}:3: error: coupling.driving_inertia: got -10.0; must be > 0" in result.stderr


def test_an_integer_key_takes_a_whole_number_only(cli, write_case):
    base = (CASES / "variator" / "vk_variator.toml").read_text(encoding="utf-8")
    good = write_case(base.replace("pole_pairs = 3", 'pole_pairs = "3"'), "good.toml")
    bad = write_case(base.replace("pole_pairs = 3", 'pole_pairs = "2.5"'), "bad.toml")
    assert cli("variator", good).exit_code == 0
    result = cli("variator", bad)
    assert result.exit_code == 2
    assert "motor.pole_pairs: got '2.5' = 2.5; expected a whole number" in result.stderr


def test_strings_in_text_keys_are_not_units(cli):
    # title and surface names are strings: they must not go through pint.
    result = cli("braking", CASES / "braking" / "lecture.toml")
    assert result.exit_code == 0, result.stderr


def test_sweep_over_a_key_written_with_a_unit(cli, tmp_path):
    # The grid is in the field's SI unit; the key's string in the case is replaced.
    out = tmp_path / "sweep.json"
    result = cli(
        "sweep",
        CASES / "coupling" / "example_8_1_units.toml",
        "--vary",
        "coupling.driving_inertia=5:10:3",
        "--result",
        "natural_frequency",
        "--out",
        out,
    )
    assert result.exit_code == 0, result.stderr
    columns = strict_json(out.read_text(encoding="utf-8"))["values"]
    c = 52.5 * 180.0 / math.pi
    for j1, beta in zip(
        columns["coupling.driving_inertia"], columns["natural_frequency"], strict=True
    ):
        assert beta == pytest.approx(math.sqrt(c * (1.0 / j1 + 1.0 / 4.0)), rel=1e-12)


def test_integer_list_items_take_quantity_strings(cli, write_case):
    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.problems import PROBLEMS

    module = PROBLEMS["resonance"].load()
    import tomllib

    data = tomllib.loads((CASES / "resonance" / "inline_six.toml").read_text(encoding="utf-8"))
    cranks = data["chain"]["cranks"]
    data["chain"]["cranks"] = [str(cranks[0]), *cranks[1:]]
    case = validate(module.Case, CaseText(CASES / "x.toml", "", data))
    assert list(case.chain.cranks) == cranks


def test_pint_is_imported_without_dask_and_dask_still_imports():
    # pint's compat module imports dask (90 ms) when it is installed; mdcalc hands
    # pint no dask arrays. In a fresh process: a conversion loads no dask, and dask
    # (the --scheduler extra) imports as usual afterwards.
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from mdcalc.input.quantities import convert\n"
        "assert abs(convert('52.5 N*m/deg', 'N·m/rad') - 52.5 * 180 / 3.141592653589793) < 1e-9\n"
        "print('dask' in sys.modules)\n"
        "try:\n"
        "    import dask.array\n"
        "    print(dask.array.ones(3).sum().compute())\n"
        "except ImportError:\n"
        "    print('no dask here')\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded, after = done.stdout.split("\n", 1)
    assert loaded == "False"
    assert after.strip() in ("3.0", "no dask here")
