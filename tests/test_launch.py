"""The console script's direct path: a plain problem run skips typer, with the same
output, messages and exit codes as the typer application gives the same line."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from typer.testing import CliRunner

from mdcalc.cli.launch import direct_run
from tests.conftest import CASES, assert_no_traceback

LECTURE = str(CASES / "braking" / "lecture.toml")


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["braking", "a.toml"], ("braking", "a.toml", False, False)),
        (["braking", "a.toml", "--json"], ("braking", "a.toml", True, False)),
        (["hoist", "--debug", "a.toml", "--json"], ("hoist", "a.toml", True, True)),
        (["mine-hoist", "--json", "--json", "a.toml"], ("mine-hoist", "a.toml", True, False)),
    ],
)
def test_plain_problem_runs_take_the_direct_path(argv, expected):
    assert direct_run(argv) == expected


@pytest.mark.parametrize(
    "argv",
    [
        [],
        ["--help"],
        ["--version"],
        ["braking"],  # the case missing: typer says so
        ["braking", "--help"],
        ["braking", "-h"],
        ["braking", "a.toml", "b.toml"],  # an extra argument
        ["braking", ""],
        ["braking", "a.toml", "--time-limit", "5"],
        ["braking", "a.toml", "--time-limit=5"],
        ["braking", "a.toml", "--jsn"],  # a misspelt flag: typer's message
        ["braking", "--", "a.toml"],
        ["braking", "a.toml", "--plot", "p.png"],
        ["brakes", "a.toml"],  # no such problem
        ["run", "a.toml"],
        ["check", "cases"],
    ],
)
def test_everything_else_goes_through_typer(argv):
    assert direct_run(argv) is None


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["run", "cases"], (["cases"], 0, False, False)),
        (["run", "a.toml", "b", "--json"], (["a.toml", "b"], 0, True, False)),
        (["run", "--jobs", "2", "cases", "--debug"], (["cases"], 2, False, True)),
        (["run", "-j", "0", "cases"], (["cases"], 0, False, False)),
        (["run", "--jobs=3", "cases", "--jobs", "1"], (["cases"], 1, False, False)),
    ],
)
def test_plain_batches_take_the_direct_path(argv, expected):
    from mdcalc.cli.launch import direct_batch

    assert direct_batch(argv) == expected


@pytest.mark.parametrize(
    "argv",
    [
        ["run"],  # no path: typer says so
        ["run", "--json"],
        ["run", "cases", "--jobs"],  # the value missing
        ["run", "cases", "--jobs", "-1"],  # typer: below the minimum
        ["run", "cases", "--jobs", "two"],
        ["run", "cases", "--jobs", "٢"],  # a digit, but not 0-9
        ["run", "cases", "-j2"],
        ["run", "cases", "--jobs", "9" * 5000],  # typer: too large (int() would refuse it)
        ["run", "cases", "--jobs", "1234567890"],
        ["run", "cases", "--out", "out"],
        ["run", "cases", "--report-dir", "out"],
        ["run", "cases", "--time-limit", "5"],
        ["run", "cases", "--scheduler", "local:1"],
        ["run", "cases", "--help"],
        ["run", "cases", ""],
        ["run", "--", "cases"],
        ["braking", "a.toml"],  # the other direct path's
    ],
)
def test_every_other_batch_goes_through_typer(argv):
    from mdcalc.cli.launch import direct_batch

    assert direct_batch(argv) is None


def test_an_unreadable_path_goes_to_typer_which_refuses_it(monkeypatch, tmp_path):
    """click.Path(readable=True): a path that is there but may not be read is exit 2
    before anything runs; the direct paths leave it to typer (root reads anything,
    so the permission is faked)."""
    from mdcalc.cli import launch
    from mdcalc.cli.launch import direct_batch

    there = tmp_path / "b.toml"
    there.write_text("x = 1\n", encoding="utf-8")
    monkeypatch.setattr(launch.os, "access", lambda path, mode: str(path) != str(there))
    assert direct_batch(["run", str(there)]) is None
    assert direct_batch(["run", LECTURE, str(there)]) is None
    assert direct_run(["braking", str(there)]) is None
    assert direct_batch(["run", str(tmp_path / "missing.toml")]) is not None  # the body says
    assert direct_run(["braking", LECTURE]) is not None


def test_a_batch_completing_goes_through_typer(monkeypatch):
    from mdcalc.cli.launch import direct_batch

    monkeypatch.setenv("_MDCALC_COMPLETE", "complete_bash")
    assert direct_batch(["run", "cases"]) is None


def test_shell_completion_goes_through_typer(monkeypatch):
    monkeypatch.setenv("_MDCALC_COMPLETE", "complete_bash")
    assert direct_run(["braking", "a.toml"]) is None


SCENES = [
    ["braking", LECTURE],
    ["braking", LECTURE, "--json"],
    ["hoist", str(CASES / "hoist" / "cannot_start.toml")],  # no answer: exit 3
    ["hoist", LECTURE],  # a case of another problem: exit 2
    ["braking", str(CASES / "no-such-case.toml")],  # exit 2
    ["mount", str(CASES / "mount"), "--json"],  # a folder: exit 2
]


def _console_script(argv: list[str], monkeypatch):
    """``argv`` through the console script (mdcalc.cli.launch.main), in-process."""
    import typer.testing

    from mdcalc.cli.app import app
    from mdcalc.cli.launch import main

    class Script:
        name = "mdcalc"

        def main(self, args, prog_name, **extra):
            sys.argv = [prog_name, *args]
            main()

    monkeypatch.setattr(sys, "argv", list(sys.argv))
    monkeypatch.setattr(typer.testing, "_get_command", lambda _: Script())
    return CliRunner().invoke(app, argv)


@pytest.mark.parametrize("argv", SCENES, ids=[" ".join(a[:1] + a[2:]) for a in SCENES])
def test_the_direct_path_and_typer_give_the_same(argv, monkeypatch, write_case):
    from mdcalc import methods
    from mdcalc.cli.app import app

    monkeypatch.setattr(methods, "timed", lambda run: (run(), 1e-6))  # no timer noise
    typer_way = CliRunner().invoke(app, argv)

    direct = _console_script(argv, monkeypatch)
    assert direct_run(argv) is not None
    assert (direct.exit_code, direct.stdout, direct.stderr) == (
        typer_way.exit_code,
        typer_way.stdout,
        typer_way.stderr,
    )
    assert typer_way.exit_code in (0, 2, 3)


BATCHES = [
    ["run", str(CASES / "braking"), "--jobs", "1", "--json"],
    ["run", str(CASES / "hoist"), "-j", "1"],  # text reports, a no-answer among them
    ["run", LECTURE, str(CASES / "no-such-case.toml"), "--jobs=1"],  # exit 2 for one file
    ["run", str(CASES / "no-such-folder"), "--jobs", "1"],  # no case files: exit 2
]


@pytest.mark.parametrize("argv", BATCHES, ids=[" ".join(a[2:]) for a in BATCHES])
def test_a_direct_batch_and_typer_give_the_same(argv, monkeypatch):
    import re

    from mdcalc import methods
    from mdcalc.cli.app import app
    from mdcalc.cli.launch import direct_batch

    monkeypatch.setattr(methods, "timed", lambda run: (run(), 1e-6))  # no timer noise
    monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", methods.MIN_TIMING_SECONDS)
    typer_way = CliRunner().invoke(app, argv)

    direct = _console_script(argv, monkeypatch)
    assert direct_batch(argv) is not None

    def timeless(text: str) -> str:  # the summary's own seconds and files/s
        return re.sub(r"in \S+ s \(\S+ files/s", "in T s (R files/s", text)

    assert (direct.exit_code, timeless(direct.stdout), timeless(direct.stderr)) == (
        typer_way.exit_code,
        timeless(typer_way.stdout),
        timeless(typer_way.stderr),
    )
    assert typer_way.exit_code in (0, 2, 3)


def test_a_bug_on_the_direct_path_is_one_line_and_the_traceback_with_debug(cli, monkeypatch):
    from mdcalc.problems import braking

    def broken(case):
        raise RuntimeError("boom")

    monkeypatch.setattr(braking, "solve", broken)
    plain = cli("braking", LECTURE)
    assert plain.exit_code == 70
    assert plain.stderr.count("\n") == 1 and "internal error: RuntimeError: boom" in plain.stderr
    debug = cli("braking", LECTURE, "--debug")
    assert debug.exit_code == 70 and "Traceback" in debug.stderr


PROBE = """
import sys
sys.argv = ["mdcalc", *{args!r}]
from mdcalc.cli.launch import main
try:
    main()
except SystemExit as exit:
    code = exit.code
print("TYPER", "typer" in sys.modules, code, file=sys.stderr)
"""


@pytest.mark.parametrize(
    ("args", "typer", "code"),
    [
        (["braking", LECTURE, "--json"], False, 0),
        (["braking", LECTURE, "--time-limit", "5"], True, 0),
        (["braking", LECTURE, "--jsn"], True, 2),
        (["run", LECTURE, "--json", "--jobs", "1"], False, 0),
        (["run", LECTURE, "--json", "--time-limit", "5"], True, 0),
        ([LECTURE, "--json"], False, 0),  # mdcalc CASE.toml: the problem the file names
        ([LECTURE, "--time-limit", "5"], True, 0),
    ],
)
def test_a_plain_run_does_not_import_typer(args, typer, code):
    done = subprocess.run(
        [sys.executable, "-c", PROBE.format(args=args)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.stderr.strip().splitlines()[-1] == f"TYPER {typer} {code}"


# ------------------------------------------------------ mdcalc CASE.toml (issue 32.3)


@pytest.mark.parametrize("options", [[], ["--json"], ["--time-limit", "5"]])
def test_a_case_file_runs_the_problem_it_names(cli, options):
    from tests.test_docs import masked  # run times differ from run to run

    named = cli(LECTURE, *options)
    explicit = cli("braking", LECTURE, *options)
    assert named.exit_code == explicit.exit_code == 0
    assert masked(named.stdout) == masked(explicit.stdout)
    assert named.stderr == explicit.stderr


def test_a_study_file_runs_its_study(cli):
    study = str(CASES / "studies" / "hoist_load.toml")
    named = cli(study, "--json")
    assert named.exit_code == 0, named.stderr
    assert json.loads(named.stdout)["kind"] == "study"


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ('title = "x"\n[vehicle]\nproblem = "braking"\n', "the file names no problem"),
        ('problem = "brakes"\n', "unknown problem 'brakes'; allowed: hoist"),
        (None, "no such file"),
    ],
)
def test_a_case_file_that_names_no_problem_is_exit_2(cli, tmp_path, text, says):
    path = tmp_path / "case.toml"
    if text is not None:
        path.write_text(text, encoding="utf-8")
    result = cli(path)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{path}: error: ") and says in result.stderr
    assert_no_traceback(result)


def test_the_commands_the_case_form_leaves_alone_are_the_apps():
    from mdcalc.cli.app import app
    from mdcalc.cli.launch import COMMANDS
    from mdcalc.problems import PROBLEMS

    names = {c.name for c in app.registered_commands} - set(PROBLEMS)
    assert names == set(COMMANDS)


def test_a_file_named_like_a_command_does_not_take_its_place(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "check").write_text("not a case\n", "utf-8")
    result = cli("check", LECTURE)
    assert result.exit_code == 0, result.stderr
    assert "passed" in result.stdout


def test_a_pipe_named_as_a_case_is_refused_not_read(cli, tmp_path):
    import os

    fifo = tmp_path / "f.toml"
    os.mkfifo(fifo)
    result = cli(fifo)  # would block on open() if it were read
    assert result.exit_code == 2
    assert "FIFO" in result.stderr


def test_a_study_written_with_dotted_keys_is_a_study(cli, tmp_path):
    case = tmp_path / "dotted.toml"
    case.write_text(
        'problem = "braking"\nstudy.samples = 50\n[vehicle]\nmass = 1500.0\n'
        'initial_speed_kmh = 100.0\n[road]\nsurface = "dry-asphalt"\n'
        '[study.inputs."vehicle.mass"]\nnominal = 1500.0\ntol = "±5 %"\n',
        "utf-8",
    )
    result = cli(case, "--json")
    assert result.exit_code == 0, result.stderr
    assert json.loads(result.stdout)["kind"] == "study"


def test_a_case_form_with_a_broken_base_says_what_the_loader_says(cli, tmp_path):
    (tmp_path / "a.toml").write_text('base = "b.toml"\n', "utf-8")
    (tmp_path / "b.toml").write_text('base = "a.toml"\n', "utf-8")
    result = cli(tmp_path / "a.toml")
    assert result.exit_code == 2 and "a cycle of bases" in result.stderr
    assert_no_traceback(result)
