"""Safe reading and writing of the user's files (issue 20, item 3): case files are
regular files of bounded size; results are created exclusively without --force,
only regular files are replaced with it, and modes are kept."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mdcalc.errors import InputError
from mdcalc.input.files import MAX_CASE_BYTES, read_regular, write_atomic
from tests.conftest import CASES, MDCALC

EXAMPLE = CASES / "coupling" / "example_8_1.toml"


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _one_error_line(stderr: str) -> str:
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in stderr, stderr
    return lines[0]


# -------------------------------------------------------------------- reading


def test_a_fifo_is_refused_at_once_not_waited_on(tmp_path):
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    start = time.perf_counter()
    done = subprocess.run(
        [str(MDCALC), "coupling", str(fifo)], capture_output=True, text=True, timeout=60
    )
    assert time.perf_counter() - start < 30
    assert done.returncode == 2
    assert "FIFO" in _one_error_line(done.stderr)


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero here")
def test_an_endless_device_is_refused_without_reading_it(cli):
    result = cli("coupling", "/dev/zero")
    assert result.exit_code == 2
    assert "is a device, not a regular case file" in _one_error_line(result.stderr)


def test_a_case_file_over_the_cap_is_refused(tmp_path, cli):
    big = tmp_path / "big.toml"
    big.write_bytes(b"# " + b"x" * MAX_CASE_BYTES + b"\n")
    result = cli("coupling", big)
    assert result.exit_code == 2
    assert "larger than 4 MiB" in _one_error_line(result.stderr)


def test_a_case_file_at_the_cap_is_read(tmp_path):
    exact = tmp_path / "exact.toml"
    exact.write_bytes(b"#" * MAX_CASE_BYTES)
    assert len(read_regular(exact)) == MAX_CASE_BYTES


@pytest.mark.parametrize("size", [0, 1, 4095, 4096, 65537])
def test_a_case_file_is_read_whole_whatever_its_size(tmp_path, size):
    body = bytes(range(256)) * (size // 256 + 1)
    path = tmp_path / "case.toml"
    path.write_bytes(body[:size])
    assert read_regular(path) == body[:size]


def test_a_file_that_grows_while_read_is_read_to_the_cap(tmp_path, monkeypatch):
    """fstat said 10 bytes; 40 are there when read: all 40 are read (cap 64), and
    past the cap it is refused as before."""
    from mdcalc.input import files

    path = tmp_path / "case.toml"
    path.write_bytes(b"x" * 40)
    real = os.fstat

    class Small:
        def __init__(self, status):
            self.st_mode, self.st_size = status.st_mode, 10

    monkeypatch.setattr(files.os, "fstat", lambda fd: Small(real(fd)))
    assert read_regular(path, limit=64) == b"x" * 40
    with pytest.raises(InputError, match="larger than"):
        read_regular(path, limit=32)


def test_a_folder_is_named_as_such(tmp_path, cli):
    result = cli("coupling", tmp_path)
    assert result.exit_code == 2
    assert "is a directory" in _one_error_line(result.stderr)


# -------------------------------------------------------------------- writing


def test_new_onto_a_fifo_with_force_leaves_it_alone(tmp_path, cli):
    # The same rule that keeps /dev/full a device: only a regular file is replaced.
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    result = cli("new", "coupling", "-o", fifo, "--force")
    assert result.exit_code == 2
    assert "only a regular file is ever replaced" in _one_error_line(result.stderr)
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_new_onto_a_folder_is_exit_2(tmp_path, cli):
    for force in ([], ["--force"]):
        result = cli("new", "coupling", "-o", tmp_path, *force)
        assert result.exit_code == 2, result.stderr
        assert "is a folder" in _one_error_line(result.stderr)
    assert tmp_path.is_dir()


def test_creation_is_exclusive_when_another_run_gets_there_first(tmp_path):
    target = tmp_path / "saved.toml"

    def other_run_wins(tmp: str) -> None:  # writes ours, then another run makes the file
        Path(tmp).write_text("ours\n", encoding="utf-8")
        target.write_text("theirs\n", encoding="utf-8")

    with pytest.raises(InputError, match="file exists"):
        write_atomic(target, other_run_wins, replace=False)
    assert target.read_text(encoding="utf-8") == "theirs\n"
    assert [p.name for p in tmp_path.iterdir()] == ["saved.toml"]  # no .tmp left


def test_two_saves_at_once_one_wins_and_the_other_says_so(tmp_path):
    out = tmp_path / "saved.toml"
    runs = [
        subprocess.Popen(
            [str(MDCALC), "coupling", str(EXAMPLE), "--save", str(out)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in range(2)
    ]
    codes = sorted(run.wait(timeout=120) for run in runs)
    # Started together, one may finish before the other checks: then it is refused
    # up front; either way exactly one file, never one silently replacing the other.
    assert codes == [0, 2], codes
    for run in runs:
        assert run.stderr is not None
        stderr = run.stderr.read()
        if run.returncode == 2:
            assert "exists" in _one_error_line(stderr)
    assert [p.name for p in tmp_path.iterdir()] == ["saved.toml"]


def test_a_replaced_file_keeps_its_mode_and_a_new_one_gets_the_umasks(tmp_path, cli):
    out = tmp_path / "saved.toml"
    assert cli("coupling", EXAMPLE, "--save", out).exit_code == 0
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o666 & ~_umask()
    os.chmod(out, 0o640)
    assert cli("coupling", EXAMPLE, "--save", out, "--force").exit_code == 0
    assert stat.S_IMODE(os.stat(out).st_mode) == 0o640
    assert [p.name for p in tmp_path.iterdir()] == ["saved.toml"]


def test_files_module_is_light():
    # It serves --help-free paths only, but must not pull anything heavy in.
    code = "import sys, mdcalc.input.files; print(sorted({'pydantic', 'numpy'} & set(sys.modules)))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.stdout.strip() == "[]"
