"""The documentation runs (issue 32.4): every ``console`` block of README.md and docs/
is run, command by command, and what the program prints must be the page's text,
whole, with only run times masked (a Methods table's run-time column, µs/ms figures,
JSON ``seconds``) and runs of spaces and table rules taken as one space.

- A command ``$ mdcalc ...`` without shell syntax runs in-process (as the console
  script, ``COLUMNS`` and ``NO_COLOR`` fixed); any other (a pipe, ``sed``, ``cat``) runs
  in bash with the venv's ``mdcalc`` first on PATH. A page's blocks run in order in a
  folder of their own, where ``cases/`` is the shipped cases.
- A block that cannot run in CI (two machines, ``make bench``, ``pip install``, minutes
  of work) has the line ``<!-- docs: skip (why) -->`` right above it.
- ``MDCALC_DOCS_UPDATE=1 pytest tests/test_docs.py`` (``make docs-update``) rewrites
  the pages' outputs from the program, for review with ``git diff``.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tests.conftest import ROOT, ConsoleScript

PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
SKIP = re.compile(r"^<!-- docs: skip \((.+)\) -->$")
UPDATE = os.environ.get("MDCALC_DOCS_UPDATE") == "1"
#: The terminal the pages are written for (help texts wrap at it; reports on a pipe
#: are 140 columns wide whatever it says).
COLUMNS = "100"
SHELL = re.compile(r"[|><;&$`*]|\(|\)")


@dataclass
class Command:
    line: str  # as the page writes it, after "$ " (continuation lines joined)
    shown: list[str]  # the lines of the command on the page
    output: list[str] = field(default_factory=list)

    @property
    def run(self) -> str:
        """The command without its trailing comment (two spaces, then #)."""
        return re.split(r"\s{2,}# ", self.line, maxsplit=1)[0].strip()


@dataclass
class Block:
    start: int  # index of the ```console line
    end: int  # index of the closing ```
    commands: list[Command]
    skip: str | None


def blocks(lines: list[str]) -> list[Block]:
    found = []
    index = 0
    while index < len(lines):
        if lines[index].strip() != "```console":
            index += 1
            continue
        start = index
        end = next(i for i in range(start + 1, len(lines)) if lines[i].strip() == "```")
        marker = SKIP.match(lines[start - 1].strip()) if start else None
        commands: list[Command] = []
        body = lines[start + 1 : end]
        i = 0
        while i < len(body):
            if body[i].startswith("$ "):
                shown = [body[i]]
                while shown[-1].rstrip().endswith("\\") and i + 1 < len(body):
                    i += 1
                    shown.append(body[i])
                text = " ".join(s.rstrip().rstrip("\\").strip() for s in shown)
                commands.append(Command(text[2:], shown))
            elif commands:
                commands[-1].output.append(body[i])
            i += 1
        found.append(Block(start, end, commands, marker.group(1) if marker else None))
        index = end + 1
    return found


def run(command: str, folder: Path) -> str:
    """What the command prints (stdout, then stderr), run in ``folder``."""
    words = shlex.split(command)
    env = {"COLUMNS": COLUMNS, "NO_COLOR": "1", "TERM": "dumb"}
    if words and words[0] == "mdcalc" and not SHELL.search(command):
        import typer.testing

        from mdcalc.cli.app import app

        saved_cwd, saved_get = os.getcwd(), typer.testing._get_command
        saved_env = {k: os.environ.get(k) for k in env}
        os.environ.update(env)
        typer.testing._get_command = lambda _: ConsoleScript()  # type: ignore[assignment]
        os.chdir(folder)
        try:
            result = CliRunner().invoke(app, words[1:])
        finally:
            os.chdir(saved_cwd)
            typer.testing._get_command = saved_get
            for key, value in saved_env.items():
                if value is None:
                    os.environ.pop(key, None)
                else:
                    os.environ[key] = value
        return result.stdout + result.stderr
    path = f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"
    done = subprocess.run(
        ["bash", "-c", command],
        cwd=folder,
        env={**os.environ, **env, "PATH": path},
        capture_output=True,
        text=True,
        timeout=300,
    )
    return done.stdout + done.stderr


TIME = re.compile(r"\d[\d.]*(?:e[-+]?\d+)?\s?(?:µs|ms|ns)\b")
#: A line that sums up how long a run took (a batch's, a study's): its seconds and
#: rates are masked too; elsewhere a number in s is a result.
TIMED_LINE = re.compile(
    r"\d (?:files|samples|points)/s\b|\bin all:|\bRun time, |Samples per second"
)
SECONDS_OR_RATE = re.compile(
    r"\d[\d.,]*(?:e[-+]?\d+)?\s?(?:(?:files|samples|points)/s|s)\b|(?<=second)\s+[\d,]+\s*$"
)
#: How many worker processes ran: one per core by default.
JOBS = re.compile(r"\b\d+ jobs?\b")
#: Where a study's or sweep's blocks ran is decided by timing a probe (the numbers
#: are the same either way).
SHIPPED = re.compile(r", blocks on [\w .:/-]+?(?:, \d+ jobs)?$")
SECONDS = re.compile(r'("\w*seconds"): [^,}\n]+')
RULES = re.compile(r"[ \t─━═]+")


def masked(text: str) -> list[str]:
    """The text as compared: run times masked, runs of spaces and rules as one space,
    no blank lines at the ends."""
    out = []
    timed: int | None = None  # the run-time column of the table being read
    for line in text.splitlines():
        if "┃" in line:
            cells = line.split("┃")
            hits = [i for i, c in enumerate(cells) if c.strip() == "run time"]
            timed = hits[0] if hits else timed
        elif "│" in line and timed is not None:
            cells = line.split("│")
            if timed < len(cells):
                cells[timed] = " T "
            line = "│".join(cells)
        elif not line.strip() or not any(c in line for c in "┏┗┡└┌"):
            timed = None if not line.strip() else timed
        if TIMED_LINE.search(line):
            line = SECONDS_OR_RATE.sub("T", line)
        line = SHIPPED.sub("", SECONDS.sub(r"\1: T", TIME.sub("T", line)))
        line = JOBS.sub("N jobs", line)
        out.append(RULES.sub(" ", line).strip())
    while out and not out[-1]:
        out.pop()
    while out and not out[0]:
        out.pop(0)
    return out


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_the_page_prints_what_the_program_prints(page, tmp_path):
    (tmp_path / "cases").symlink_to(ROOT / "cases")
    lines = page.read_text("utf-8").splitlines()
    found = blocks(lines)
    changed = False
    # run in page order; rewrite from the end so that line numbers hold
    outputs: list[tuple[Block, list[str]]] = []
    for block in found:
        if block.skip:
            continue
        printed = [run(c.run, tmp_path) for c in block.commands]
        outputs.append((block, printed))
        if not UPDATE:
            for command, text in zip(block.commands, printed, strict=True):
                assert masked(text) == masked("\n".join(command.output)), (
                    f"{page.relative_to(ROOT)}:{block.start + 1}: $ {command.run}\n"
                    f"--- the program printed:\n{text}"
                )
    if UPDATE:
        for block, printed in reversed(outputs):
            body: list[str] = []
            for command, text in zip(block.commands, printed, strict=True):
                body += command.shown
                if masked(text) == masked("\n".join(command.output)):
                    body += command.output  # the same but for run times: left as it is
                else:
                    body += [line.rstrip() for line in text.rstrip("\n").splitlines()]
            if lines[block.start + 1 : block.end] != body:
                lines[block.start + 1 : block.end] = body
                changed = True
        if changed:
            page.write_text("\n".join(lines) + "\n", encoding="utf-8")


def test_every_case_file_a_page_names_is_there():
    for page in PAGES:
        for name in re.findall(r"\bcases/[\w./-]+\.toml\b", page.read_text("utf-8")):
            assert (ROOT / name).is_file(), f"{page.relative_to(ROOT)}: {name}"


def test_the_pages_lists_are_lists():
    # MkDocs' Markdown takes a list only after a blank line, and a nested item only
    # at four spaces: a list right under a paragraph, or nested by two, renders as
    # one run-on paragraph ("... M/R: - the natural ... - the static ...")
    item = re.compile(r"^(\d+\.|[-*]) ")
    for page in PAGES:
        fence = False
        lines = page.read_text("utf-8").splitlines()
        for number, (before, line) in enumerate(zip(["", *lines], lines, strict=False), start=1):
            fence = fence != line.lstrip().startswith("```")
            if fence or line.lstrip().startswith("```"):
                continue
            where = f"{page.relative_to(ROOT)}:{number}"
            if item.match(line):
                paragraph = before.strip() and not before.startswith((" ", "#", "|"))
                assert not (paragraph and not item.match(before)), f"{where}: a blank line first"
            assert not re.match(r"^ {1,3}(\d+\.|[-*]) ", line), f"{where}: nest by 4 spaces"


def test_the_masks_keep_numbers_and_drop_run_times():
    table = (
        "┃ method ┃ value ┃ rel. error ┃ run time ┃\n"
        "│ exact  │ 1.8541 │ reference │ 0.464 µs │\n"
        "│ ODE    │ 1.8541 │   8.9e-11 │  1.2 s   │\n"
    )
    other = table.replace("0.464 µs", "12.5 µs").replace("1.2 s  ", "0.97 s ")
    assert masked(table) == masked(other)
    assert masked(table) != masked(table.replace("1.8541 │ reference", "1.8542 │ reference"))
    assert masked('"seconds": 0.25,') == masked('"seconds": 1.5e-06,')
    run = "mdcalc run: 2 case files in 0.576 s (3.471 files/s, process pool, 2 jobs)"
    assert masked(run) == masked(run.replace("0.576 s (3.471", "0.425 s (4.702"))
    assert masked(run) == masked(run.replace("2 jobs", "4 jobs"))
    study = "braking, 100,000 samples (lhs, seed 2026), vectorized kernel"
    assert masked(study + ", blocks on process pool, 2 jobs") == masked(study)
    assert masked("Stopping time 5.0385 s") != masked("Stopping time 5.0386 s")
    # a study's run times and rate, in its Study section (issue 33.1)
    assert masked(" Run time, in all   1.64 s ") == masked(" Run time, in all   782 ms ")
    assert masked(" Samples per second  3,831,247 ") == masked(" Samples per second  41,002 ")
    assert masked(" Samples   100000 ") != masked(" Samples   100001 ")


#: Pages with Python examples (``pycon`` blocks, ``>>>`` prompts): run by doctest.
PYTHON_PAGES = [page for page in PAGES if "\n>>> " in page.read_text(encoding="utf-8")]


@pytest.mark.parametrize("page", PYTHON_PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_the_pages_python_examples_print_what_they_say(page, monkeypatch):
    """Issue 34.4: every ``>>>`` example of a page runs, in order, in one namespace,
    from the repository's root (``cases/`` is the shipped cases), and prints the
    page's text (doctest; ``...`` matches anything, runs of spaces are one)."""
    import doctest

    monkeypatch.chdir(ROOT)
    text = page.read_text(encoding="utf-8")
    test = doctest.DocTestParser().get_doctest(text, {}, page.name, str(page), 0)
    assert test.examples, "no example found"
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    runner = doctest.DocTestRunner(optionflags=flags)
    out: list[str] = []
    runner.run(test, out=out.append)
    assert runner.failures == 0, "".join(out)


def test_the_python_page_is_run():
    assert ROOT / "docs" / "python.md" in PYTHON_PAGES
