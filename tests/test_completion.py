"""Shell completion (issue 9.4): problem names, `new` problems and case files."""

from __future__ import annotations

import os

import pytest

from tests.conftest import MDCALC, ROOT, run_script


def complete(words: str, cwd=ROOT) -> list[str]:
    import subprocess

    env = {
        **os.environ,
        "_MDCALC_COMPLETE": "complete_bash",
        "COMP_WORDS": words,
        "COMP_CWORD": str(len(words.split()) - (0 if words.endswith(" ") else 1)),
    }
    done = subprocess.run(
        [str(MDCALC)], env=env, capture_output=True, text=True, timeout=60, cwd=cwd
    )
    assert done.returncode == 0, done.stderr
    return done.stdout.split()


def test_problem_names_complete():
    assert complete("mdcalc mo") == ["mount"]
    assert set(complete("mdcalc m")) == {"mount", "mine-hoist", "mechanism"}


def test_new_completes_problem_names():
    assert complete("mdcalc new cou") == ["coupling"]


def test_case_files_complete_to_toml_files_and_folders(tmp_path):
    (tmp_path / "a_case.toml").write_text("", encoding="utf-8")
    (tmp_path / "a_notes.txt").write_text("", encoding="utf-8")
    (tmp_path / "a_dir").mkdir()
    assert complete("mdcalc coupling a", cwd=tmp_path) == ["a_case.toml", "a_dir/"]
    assert complete("mdcalc check a", cwd=tmp_path) == ["a_case.toml", "a_dir/"]
    assert complete("mdcalc coupling cases/coupling/example_8_1") == [
        "cases/coupling/example_8_1.toml",
        "cases/coupling/example_8_1_units.toml",
    ]


def test_folders_alone_are_left_to_the_shell(tmp_path):
    # bash would put a space after a lone "cases/"; `complete -o default` does better.
    (tmp_path / "cases").mkdir()
    assert complete("mdcalc coupling ca", cwd=tmp_path) == []


@pytest.mark.parametrize("shell", ["bash", "zsh", "fish"])
def test_show_completion_prints_a_script_for_the_calling_shell(shell):
    # typer finds the shell from the parent process (under make it is sh, which it
    # does not support): run it from the shell itself.
    import shutil
    import subprocess

    if shutil.which(shell) is None:
        pytest.skip(f"{shell} is not installed here")
    done = subprocess.run(
        [shell, "-c", f"'{MDCALC}' --show-completion; exit $?"],  # no exec: a child
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    assert "_MDCALC_COMPLETE" in done.stdout


def test_help_offers_install_completion():
    assert "--install-completion" in run_script("--help").stdout


def test_an_absolute_path_completes_from_the_root():
    from mdcalc.cli.app import complete_case

    assert complete_case("/") == []  # folders only: left to the shell
    top = next(p for p in (ROOT / "cases").iterdir() if p.suffix == "" and p.is_dir())
    found = complete_case(str(top) + "/")
    assert found and all(f.startswith(str(top) + "/") for f in found)
