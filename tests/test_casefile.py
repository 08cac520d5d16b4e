"""Case-file reading: key lines for messages, TOML writing."""

from __future__ import annotations

from pathlib import Path

import pytest

from mdcalc.errors import InputError
from mdcalc.input.casefile import _key_lines, write_toml_atomic
from tests.conftest import CASES


def test_key_lines_follow_tables_and_arrays_of_tables():
    text = """problem = "hoist"
# comment
[load]
mass = 1.0

[[drive.shafts]]
name = "a"

[[drive.shafts]]
name = "b"
"""
    lines = _key_lines(text)
    assert lines[("problem",)] == 1
    assert lines[("load",)] == 3
    assert lines[("load", "mass")] == 4
    assert lines[("drive", "shafts", 0, "name")] == 7
    assert lines[("drive", "shafts", 1, "name")] == 10


def test_key_lines_of_a_table_under_an_array_of_tables_name_its_last_item():
    # [drive.shafts.inertia] after the second [[drive.shafts]] is shafts[1].inertia
    # (found by tests/test_fuzz.py: the message pointed at the [[drive.shafts]]
    # header, line 6, instead of line 9); a nested array of tables is counted
    # within its own item
    text = """[[drive.shafts]]
name = "a"
[drive.shafts.inertia]
x = 1

[[drive.shafts]]
name = "b"

[drive.shafts.inertia]
x = 2
[[drive.shafts.pieces]]
y = 1
[[drive.shafts.pieces]]
y = 2
"""
    lines = _key_lines(text)
    assert lines[("drive", "shafts", 0, "inertia")] == 3
    assert lines[("drive", "shafts", 0, "inertia", "x")] == 4
    assert lines[("drive", "shafts", 1, "inertia")] == 9
    assert lines[("drive", "shafts", 1, "inertia", "x")] == 10
    assert lines[("drive", "shafts", 1, "pieces", 0, "y")] == 12
    assert lines[("drive", "shafts", 1, "pieces", 1, "y")] == 14
    assert ("drive", "shafts", "inertia") not in lines


def test_key_lines_skip_the_lines_of_a_multi_line_array_or_string():
    # "  [2.0, 0.3]" inside points = [...] is no table header, nor "[x]" inside a
    # multi-line string (found by review: keys after such an array got no line)
    text = """[mathieu]
points = [
  [1.0, 0.5],   # a [comment
  [2.0, 0.3]
]
damping = 0.1
title = \"\"\"a
[not.a.table]
\"\"\"
x = 'a[b'
[next]
y = 1
"""
    lines = _key_lines(text)
    assert lines[("mathieu", "points")] == 2
    assert lines[("mathieu", "damping")] == 6
    assert lines[("mathieu", "title")] == 7
    assert lines[("mathieu", "x")] == 10
    assert lines[("next", "y")] == 12
    assert not any("not" in key or "2.0, 0.3" in key for key in lines)


def test_write_toml_atomic_never_overwrites(tmp_path: Path):
    path = tmp_path / "x.toml"
    write_toml_atomic(path, {"a": 1})
    assert path.read_text() == "a = 1\n"
    with pytest.raises(InputError):
        write_toml_atomic(path, {"a": 2})
    write_toml_atomic(path, {"a": 2}, force=True)
    assert path.read_text() == "a = 2\n"
    assert [p.name for p in tmp_path.iterdir()] == ["x.toml"]  # no temporary left behind


def test_a_bad_expectation_names_its_key_in_the_expect_table(write_case, cli):
    # A dict[str, Model] key is part of the path, not a pydantic union tag.
    text = (CASES / "braking" / "lecture.toml").read_text(encoding="utf-8")
    bad = text.replace(
        "lecture_time = { value = 2.54, abs = 0.005,", "lecture_time = { value = 2.54, abs = -1.0,"
    )
    assert bad != text
    path = write_case(bad)
    lines = bad.splitlines()
    line = next(n for n, text in enumerate(lines, start=1) if text.startswith("lecture_time"))
    result = cli("braking", path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}:{line}: error: expect.lecture_time.abs: got -1.0")


@pytest.mark.parametrize(
    "body",
    [
        "[vehicle]\nx = {\n  a = 1,\n}\n",  # TOML 1.1: newlines and a trailing comma
        "[vehicle]\nx = {a = 1,}\n",
        'title = "\\e"\n',  # TOML 1.1 escapes
        'title = "\\x41"\n',
        "[vehicle]\nx = 07:32\n",  # TOML 1.1: a time without seconds
    ],
    ids=["inline-newline", "inline-comma", "escape-e", "escape-x", "time-hh-mm"],
)
def test_case_files_are_toml_1_0_as_pythons_tomllib_reads_them(write_case, cli, body):
    """tomli reads the case files (compiled: faster); pinned below 2.4, which reads TOML
    1.1, so that a file is valid exactly when Python 3.11's tomllib says so."""
    import tomllib

    text = 'problem = "braking"\n' + body
    with pytest.raises(tomllib.TOMLDecodeError):
        tomllib.loads(text)
    result = cli("braking", write_case(text))
    assert result.exit_code == 2 and "TOML syntax" in result.stderr


# Inputs that crashed the reader (exit 70) before issue 20: each is exit 2, one line.
HEAD = 'problem = "coupling"\n'


@pytest.mark.parametrize(
    ("body", "says"),
    [
        ("x = " + "[" * 5000 + "]" * 5000 + "\n", "nested more than 16 deep"),
        ("x = " + "{a=" * 3000 + "1" + "}" * 3000 + "\n", "nested more than 16 deep"),
        (".".join(["a"] * 10_000) + " = 1\n", "nested more than 16 deep"),
        ("[" + ".".join(["t"] * 40) + "]\nx = 1\n", "nested more than 16 deep"),
        ("x = " + "9" * 4301 + "\n", "Exceeds the limit (4300 digits)"),
    ],
    ids=["list-5000", "inline-table-3000", "dotted-key-10000", "table-header-40", "int-4301"],
)
def test_pathological_toml_is_a_plain_input_error(write_case, cli, body, says):
    result = cli("coupling", write_case(HEAD + body))
    assert result.exit_code == 2, result.stderr[-300:]
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr
    assert says in lines[0]


def test_the_deepest_shipped_case_is_well_inside_the_depth_limit():
    import tomllib

    from mdcalc.input.casefile import MAX_DEPTH, _depth

    deepest = max(_depth(tomllib.loads(p.read_text("utf-8"))) for p in CASES.rglob("*.toml"))
    assert deepest <= MAX_DEPTH // 2, deepest
