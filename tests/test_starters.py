"""Starter cases that teach (issue 32.2): ``mdcalc new PROBLEM -o case.toml`` writes a
case that runs as written, with every key of the schema beside it, its schema file
for the editor, and optional sections that run when uncommented (with the sections
they say they need); what a commented key says it is, it is; Taplo reads them."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from mdcalc.cli.schema import problem_schema, schema_file_name, starter
from mdcalc.errors import InputError
from mdcalc.input.casefile import CaseText, validate
from mdcalc.input.schema import key_rows
from mdcalc.problems import PROBLEMS

OPTIONAL = re.compile(r"^# (\[\[?[\w.]+\]\]?)  # optional(?:; needs ((?:\[\w+\](?:, )?)+))?")


def blocks(text: str) -> dict[str, tuple[list[int], list[str]]]:
    """Each commented optional section of a starter: its header, the numbers of its
    lines and the sections it needs."""
    lines = text.splitlines()
    found = {}
    for number, line in enumerate(lines):
        match = OPTIONAL.match(line)
        if not match:
            continue
        end = number
        while end + 1 < len(lines) and lines[end + 1].startswith("#"):
            end += 1
        needs = re.findall(r"\[(\w+)\]", match.group(2) or "")
        found[match.group(1)] = (list(range(number, end + 1)), needs)
    return found


def uncomment(text: str, numbers: list[int]) -> str:
    lines = text.splitlines()
    for number in numbers:
        assert lines[number].startswith("# ")
        lines[number] = lines[number][2:]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_a_starter_runs_as_written_beside_its_schema(cli, tmp_path, problem):
    case = tmp_path / "case.toml"
    result = cli("new", problem, "-o", case)
    assert result.exit_code == 0, result.stderr
    text = case.read_text("utf-8")
    assert text.splitlines()[0] == f"#:schema ./{schema_file_name(problem)}"
    beside = tmp_path / schema_file_name(problem)
    assert json.loads(beside.read_text("utf-8")) == problem_schema(problem)
    run = cli(problem, case)
    assert run.exit_code == 0, run.stderr


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_a_starter_shows_every_key_with_its_unit(problem):
    text = starter(problem)
    keys = {m.group(1) for m in re.finditer(r"^(?:# )*([\w]+) = ", text, re.M)}
    headers = set(re.findall(r"^(?:# )?\[\[?([\w.]+)\]\]?", text, re.M))
    for row in key_rows(problem_schema(problem)):
        name = row.key.replace("[]", "")
        if name.split(".")[0] in ("expect", "saved", "study"):
            continue
        last = name.split(".")[-1]
        if row.default in ("required", "optional") and "." not in row.key and last not in keys:
            assert name in headers, f"{problem}: no section [{name}]"
        elif name not in headers:
            assert last in keys, f"{problem}: no line for {row.key}"
    units = {r.key.replace("[]", ""): r.unit for r in key_rows(problem_schema(problem))}
    section = ""
    for line in text.splitlines():
        header = re.match(r"^(?:# )?\[\[?([\w.]+)\]\]?", line)
        if header:
            section = header.group(1) + "."
        match = re.match(r"^(?:# )*(\w+) = .*?  # (.*)$", line)
        if match and match.group(1) not in ("problem", "title"):
            unit = units.get(section + match.group(1), units.get(match.group(1)))
            if unit:
                assert match.group(2).startswith(f"{unit} · "), line


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_each_optional_section_runs_uncommented(cli, tmp_path, problem):
    text = starter(problem)
    found = blocks(text)
    case = tmp_path / "case.toml"
    for header, (numbers, needs) in found.items():
        lines = list(numbers)
        for need in needs:
            lines += found[f"[{need}]"][0]
        written = uncomment(text, lines)
        if "in place of [hoist]'s two stiffnesses" in text.splitlines()[numbers[0]]:
            # what the mine hoist's height sweep says it needs, done as a reader would
            written = written.replace("# axial_stiffness", "axial_stiffness")
            written = re.sub(r"^(chord_stiffness|rope_stiffness) =", r"# \1 =", written, flags=re.M)
        case.write_text(written, "utf-8")
        result = cli(problem, case)
        assert result.exit_code == 0, f"{problem} {header}: {result.stderr}"


def test_the_optional_sections_are_there():
    """The starters show the optional parts of their scenes (and what they need)."""
    assert set(blocks(starter("braking"))) >= {"[brakes]", "[drag]"}
    assert set(blocks(starter("coupling"))) >= {"[ramp]", "[torque_table]"}
    variator = blocks(starter("variator"))
    assert variator["[antiresonance]"][1] == ["mechanism", "drive"]
    assert variator["[drive]"][1] == ["mechanism"]
    assert "[[drive.shafts]]" in blocks(starter("hoist"))
    assert "[engine.torque_curve]" in blocks(starter("acceleration"))
    assert "[[measured]]" in blocks(starter("resonance"))


def _valid(problem: str, text: str) -> bool:
    try:
        validate(PROBLEMS[problem].load().Case, CaseText(Path("s.toml"), "", tomllib.loads(text)))
    except InputError:
        return False
    return True


LABEL = re.compile(r"^# (\w+) = .*\(([^()]*(?:\([^()]*\))?[^()]*)\)$")


def _section_lines(lines: list[str], number: int) -> range:
    """The lines of the table that holds line ``number`` (from its header on)."""
    start = max((i for i in range(number + 1) if re.match(r"^\[", lines[i])), default=0)
    end = next(
        (i for i in range(start + 1, len(lines)) if re.match(r"^#? ?\[", lines[i])), len(lines)
    )
    return range(start, end)


def _line_of(lines: list[str], span: range, key: str, commented: bool) -> int:
    lead = "# " if commented else ""
    return next(i for i in span if lines[i].startswith(f"{lead}{key} = "))


def _uncommented(changed: list[str], lines: list[str], at: int) -> None:
    """Uncomment the key on line ``at``, and the rows of its array when it spans lines."""
    changed[at] = lines[at][2:]
    if re.match(r"^# \w+ = \[\s*(#.*)?$", lines[at]):
        row = at + 1
        while not lines[row].startswith("# ]"):
            changed[row] = lines[row][2:]
            row += 1
        changed[row] = lines[row][2:]


def _check_labels(problem: str, text: str, only: set[int] | None = None) -> int:
    """Every '# key = ... (label)' line of an active table does what its label says:
    '(optional)' and '(default)' uncomment alone; '(instead of X)' with X commented
    out; '(optional; not with X)' alone but not with X; '(optional, with X, Y)' with
    X and Y; '(with X, instead of Y)' with X and with Y commented out."""
    lines = text.splitlines()
    checked = 0
    for number, line in enumerate(lines):
        match = LABEL.match(line)
        if not match or match.group(1) == "base" or (only is not None and number not in only):
            continue  # (base is read with the file: test_base.py)
        label = match.group(2)
        span = _section_lines(lines, number)
        changed = list(lines)
        _uncommented(changed, lines, number)
        words = re.match(r"(?:optional, )?(?:with (.+?))?(?:, )?(?:instead of (.+))?$", label)
        if label in ("optional", "default"):
            assert _valid(problem, "\n".join(changed)), line
        elif label.startswith("optional; not with "):
            assert _valid(problem, "\n".join(changed)), line
            for other in label.removeprefix("optional; not with ").split(", "):
                at = _line_of(lines, span, other, commented=True)
                both = list(changed)
                _uncommented(both, lines, at)
                assert not _valid(problem, "\n".join(both)), (line, other)
        elif words and (words.group(1) or words.group(2)):
            for other in (words.group(1) or "").split(", ") if words.group(1) else []:
                _uncommented(changed, lines, _line_of(lines, span, other, commented=True))
            for other in (words.group(2) or "").split(", ") if words.group(2) else []:
                at = _line_of(lines, span, other, commented=False)
                changed[at] = "# " + lines[at]
            assert _valid(problem, "\n".join(changed)), line
        else:
            continue  # "another form; alone, mdcalc says: ..." promises nothing more
        checked += 1
    return checked


@pytest.mark.parametrize("problem", list(PROBLEMS))
def test_a_commented_key_is_what_its_comment_says(problem):
    """The labels of the commented keys, in the starter's tables and in each optional
    section uncommented (with what it needs)."""
    text = starter(problem)
    checked = _check_labels(problem, text)
    found = blocks(text)
    for numbers, needs in found.values():
        lines = list(numbers)
        for need in needs:
            lines += found[f"[{need}]"][0]
        checked += _check_labels(problem, uncomment(text, lines), only=set(numbers))
    assert checked >= 2, checked


def test_minimal_and_stdout(cli, tmp_path):
    result = cli("new", "braking", "--minimal")
    assert result.exit_code == 0
    assert tomllib.loads(result.stdout) == PROBLEMS["braking"].load().template()
    assert "#" not in result.stdout
    printed = cli("new", "braking")
    assert printed.stdout == starter("braking")
    # a schema already beside the case is left as it is
    (tmp_path / schema_file_name("braking")).write_text("{}", "utf-8")
    assert cli("new", "braking", "-o", tmp_path / "b.toml").exit_code == 0
    assert (tmp_path / schema_file_name("braking")).read_text("utf-8") == "{}"


# ------------------------------------------------------------------ Taplo, as the editor


def taplo() -> str:
    found = shutil.which("taplo") or str(Path(sys.executable).parent / "taplo")
    if not Path(found).exists():
        pytest.skip("taplo is not installed (pip install taplo)")
    return found


def taplo_check(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [taplo(), "check", "--no-auto-config", path.name],
        cwd=path.parent,
        capture_output=True,
        text=True,
        timeout=60,
    )


def test_taplo_checks_every_starter_and_finds_mistakes(cli, tmp_path):
    for problem in PROBLEMS:
        folder = tmp_path / problem
        case = folder / "case.toml"
        assert cli("new", problem, "-o", case).exit_code == 0
        done = taplo_check(case)
        assert done.returncode == 0, f"{problem}: {done.stderr}"
    folder = tmp_path / "mine-hoist"
    text = (folder / "case.toml").read_text("utf-8")
    misspelt = folder / "misspelt.toml"
    misspelt.write_text(text.replace("drum_inertia =", "drum_inertai ="), "utf-8")
    done = taplo_check(misspelt)
    assert done.returncode != 0 and "drum_inertai" in done.stderr
    negative = folder / "negative.toml"
    negative.write_text(text.replace("drum_inertia = 479150.0", "drum_inertia = -1.0"), "utf-8")
    done = taplo_check(negative)
    assert done.returncode != 0 and "minimum" in done.stderr.lower()


def test_a_link_where_the_schema_would_go_is_left_alone(cli, tmp_path):
    link = tmp_path / schema_file_name("hoist")
    link.symlink_to(tmp_path / "nowhere.json")
    result = cli("new", "hoist", "-o", tmp_path / "c.toml")
    assert result.exit_code == 0, result.stderr
    assert link.is_symlink() and not link.exists()
