"""``mdcalc run`` (many case files in a process pool) and ``mdcalc check --jobs``.

The contract under test: every file is reported, one bad file does not stop the rest;
``--json`` gives one strict-JSON line per file in input order whatever the number of
jobs; ``--out DIR`` writes ``DIR/<name>.json`` atomically and nothing else; the exit
code is the worst file's (70 bug > 2 input error > 3 no answer > 0). Expected values
are computed here by hand, never copied from mdcalc's output.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import CASES, assert_no_traceback, run_script, strict_json, walk_finite

G = 9.80665  # standard gravity, the default of every case

GOOD = """\
problem = "braking"
title = "hand-checked stop"

[vehicle]
mass = 1200.0
initial_speed = 20.0

[road]
adhesion = 0.6
resistance = 0.02

[driver]
reaction_time = 0.8
"""

# Line 3 carries the bad value; the JSON error must point there.
BAD_VALUE = """\
problem = "braking"
[vehicle]
mass = -5.0
initial_speed = 3.0
[road]
adhesion = 0.7
"""

BAD_SYNTAX = 'problem = "braking"\nx = = 3\n'


def hand_stop(v0: float, phi: float, psi: float, t_r: float) -> tuple[float, float]:
    """No drag, brakes at the adhesion limit, no build-up: during the reaction only the
    road resistance ψ·g decelerates, then (φ + ψ)·g to the stop."""
    a_r, a_b = psi * G, (phi + psi) * G
    v1 = v0 - a_r * t_r
    assert v1 > 0.0
    distance = v0 * t_r - 0.5 * a_r * t_r**2 + v1**2 / (2.0 * a_b)
    return distance, t_r + v1 / a_b


def make_folder(root: Path) -> tuple[Path, list[str]]:
    """A folder of five files, one of each kind; returns it and the files' names in the
    (sorted) order mdcalc runs them."""
    folder = root / "cases"
    folder.mkdir()
    (folder / "a_good.toml").write_text(GOOD, encoding="utf-8")
    shutil.copy(CASES / "hoist" / "cannot_start.toml", folder / "b_no_answer.toml")
    (folder / "c_bad_value.toml").write_text(BAD_VALUE, encoding="utf-8")
    (folder / "d_bad_syntax.toml").write_text(BAD_SYNTAX, encoding="utf-8")
    (folder / "e_empty.toml").write_text("", encoding="utf-8")
    names = ["a_good", "b_no_answer", "c_bad_value", "d_bad_syntax", "e_empty"]
    return folder, names


STATUSES = ["ok", "no-answer", "input-error", "input-error", "input-error"]


def json_lines(stdout: str) -> list[dict[str, Any]]:
    lines = stdout.splitlines()
    documents = [strict_json(line) for line in lines]
    for document in documents:
        walk_finite(document)
    return documents


def without_timings(node: Any) -> Any:
    """Drop the measured run times, the only thing two runs may differ in."""
    if isinstance(node, dict):
        return {k: without_timings(v) for k, v in node.items() if k != "seconds"}
    if isinstance(node, list):
        return [without_timings(v) for v in node]
    return node


@pytest.fixture(autouse=True)
def _restore_timing_budget(monkeypatch):
    """An in-process batch (--jobs 1) lowers methods.MIN_TIMING_SECONDS for its own run;
    put it back for the tests that follow."""
    from mdcalc import methods

    monkeypatch.setattr(methods, "MIN_TIMING_SECONDS", methods.MIN_TIMING_SECONDS)


def tree(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


# ----------------------------------------------------------------------- mixed folder


def test_real_script_reports_every_file_of_a_mixed_folder(tmp_path):
    folder, names = make_folder(tmp_path)
    done = run_script("run", folder, "--json", "--jobs", "2")
    assert done.returncode == 2, done.stderr  # the worst: an input error
    assert "Traceback" not in done.stderr
    documents = json_lines(done.stdout)
    assert [Path(d["case"]).stem for d in documents] == names
    assert [d["status"] for d in documents] == STATUSES
    # The summary goes to stderr with --json; stdout is only the JSON lines.
    assert "mdcalc run: 5 case files" in done.stderr
    rows = [line.replace("│", " ").split() for line in done.stderr.splitlines()]
    for status, count in [("ok", 1), ("no-answer", 1), ("input-error", 3), ("internal-error", 0)]:
        assert [status, str(count)] in rows


def test_json_lines_carry_the_errors_with_their_places(cli, tmp_path):
    folder, _ = make_folder(tmp_path)
    result = cli("run", folder, "--json", "--jobs", "1")
    assert result.exit_code == 2
    assert_no_traceback(result)
    good, no_answer, bad_value, bad_syntax, empty = json_lines(result.stdout)

    distance, time = hand_stop(20.0, 0.6, 0.02, 0.8)
    assert good["problem"] == "braking" and good["message"] is None
    assert good["results"]["stopping_distance"]["value"] == pytest.approx(distance, rel=1e-12)
    assert good["results"]["stopping_time"]["value"] == pytest.approx(time, rel=1e-12)

    assert no_answer["problem"] == "hoist" and "cannot start" in no_answer["message"]

    for document in (bad_value, bad_syntax, empty):
        assert set(document) >= {"case", "status", "errors"}
        for error in document["errors"]:
            assert set(error) == {"line", "column", "path", "message"}
    assert bad_value["errors"] == [
        {"line": 3, "column": None, "path": "vehicle.mass", "message": "got -5.0; must be > 0 kg"}
    ]
    [syntax] = bad_syntax["errors"]
    assert (syntax["line"], syntax["column"]) == (2, 5)
    assert syntax["message"].startswith("TOML syntax")
    [missing] = empty["errors"]
    assert missing["path"] == "problem" and missing["message"].startswith("missing")

    # One stderr message per bad file, file:line: error: ..., in input order.
    stderr = result.stderr
    places = [
        f"{folder / 'b_no_answer.toml'}: error: no answer: ",
        f"{folder / 'c_bad_value.toml'}:3: error: vehicle.mass: got -5.0",
        f"{folder / 'd_bad_syntax.toml'}:2:5: error: TOML syntax",
        f"{folder / 'e_empty.toml'}: error: problem: missing",
    ]
    positions = [stderr.index(place) for place in places]
    assert positions == sorted(positions)


def test_text_mode_reports_every_file_and_ends_with_the_summary(cli, tmp_path):
    folder, _ = make_folder(tmp_path)
    result = cli("run", folder, "--jobs", "2")
    assert result.exit_code == 2
    assert_no_traceback(result)
    out = result.stdout
    assert "hand-checked stop" in out and "Goods lift, motor too weak to start" in out
    assert "mdcalc run: 5 case files" in out  # the summary: stdout without --json
    assert out.index("hand-checked stop") < out.index("mdcalc run: 5 case files")
    for name in ("c_bad_value", "d_bad_syntax", "e_empty"):
        assert f"input-error: {folder / name}.toml" in out
        assert f"{folder / name}.toml" in result.stderr


def test_jobs_do_not_change_the_output(cli, tmp_path):
    folder, _ = make_folder(tmp_path)
    # More files than workers, so that the pool really interleaves them.
    for source in sorted((CASES / "braking").glob("*.toml")) + [CASES / "mount" / "stiff.toml"]:
        shutil.copy(source, folder / f"f_{source.parent.name}_{source.name}")
    one = cli("run", folder, "--json", "--jobs", "1", "--out", tmp_path / "out1")
    two = cli("run", folder, "--json", "--jobs", "2", "--out", tmp_path / "out2")
    assert one.exit_code == two.exit_code == 2
    first, second = json_lines(one.stdout), json_lines(two.stdout)
    assert len(first) == len(list(folder.glob("*.toml")))
    assert [without_timings(d) for d in first] == [without_timings(d) for d in second]

    def messages(stderr: str) -> list[str]:
        return [line for line in stderr.splitlines() if not line.startswith("mdcalc run:")]

    assert messages(one.stderr) == messages(two.stderr)
    assert tree(tmp_path / "out1") == tree(tmp_path / "out2")
    for name in tree(tmp_path / "out1"):
        a = strict_json((tmp_path / "out1" / name).read_text(encoding="utf-8"))
        b = strict_json((tmp_path / "out2" / name).read_text(encoding="utf-8"))
        assert without_timings(a) == without_timings(b)


def test_out_writes_one_valid_json_file_per_case_and_no_temp_files(cli, tmp_path):
    folder, names = make_folder(tmp_path)
    nested = folder / "deeper"
    nested.mkdir()
    (nested / "a_good.toml").write_text(GOOD.replace("20.0", "25.0"), encoding="utf-8")
    out = tmp_path / "results"
    result = cli("run", folder, "--out", out, "--jobs", "2")
    assert result.exit_code == 2
    assert_no_traceback(result)
    # Files found in a folder keep their path inside it, so the two a_good do not clash.
    expected = {f"{n}.json" for n in names} | {"deeper", "deeper/a_good.json"}
    assert tree(out) == expected  # and no hidden temporary files
    statuses = {}
    for name in sorted(expected - {"deeper"}):
        text = (out / name).read_text(encoding="utf-8")
        assert text.endswith("\n") and text.count("\n") == 1
        document = strict_json(text)
        walk_finite(document)
        statuses[name] = document["status"]
    assert [statuses[f"{n}.json"] for n in names] == STATUSES
    deeper = strict_json((out / "deeper" / "a_good.json").read_text(encoding="utf-8"))
    distance, _ = hand_stop(25.0, 0.6, 0.02, 0.8)
    assert deeper["results"]["stopping_distance"]["value"] == pytest.approx(distance, rel=1e-12)


def test_nothing_is_written_outside_the_out_dir(cli, tmp_path, monkeypatch):
    folder, _ = make_folder(tmp_path)
    monkeypatch.chdir(tmp_path)
    before = tree(tmp_path)
    result = cli("run", "cases", "--out", "out", "--jobs", "2", "--json")
    assert result.exit_code == 2
    added = tree(tmp_path) - before
    assert added and all(p == "out" or p.startswith("out/") for p in added), added
    assert tree(tmp_path) - added == before
    # The case files were not touched.
    assert (folder / "a_good.toml").read_text(encoding="utf-8") == GOOD


# ----------------------------------------------------------------------- exit codes


def test_all_good_exits_0(cli, tmp_path):
    for name in ("dry", "wet", "lecture"):
        shutil.copy(CASES / "braking" / f"{name}.toml", tmp_path / f"{name}.toml")
    result = cli("run", tmp_path, "--json", "--jobs", "2")
    assert result.exit_code == 0, result.stderr
    assert [d["status"] for d in json_lines(result.stdout)] == ["ok"] * 3


def test_worst_no_answer_exits_3(cli, tmp_path):
    (tmp_path / "a.toml").write_text(GOOD, encoding="utf-8")
    shutil.copy(CASES / "hoist" / "cannot_start.toml", tmp_path / "b.toml")
    result = cli("run", tmp_path / "a.toml", tmp_path / "b.toml", "--json", "--jobs", "2")
    assert result.exit_code == 3
    assert [d["status"] for d in json_lines(result.stdout)] == ["ok", "no-answer"]
    assert f"{tmp_path / 'b.toml'}: error: no answer:" in result.stderr


def test_a_bug_in_one_file_is_exit_70_and_the_rest_still_run(cli, tmp_path, monkeypatch):
    """The worst of all: 70 over 2 and 3. In-process (--jobs 1) so the patch applies."""
    from mdcalc.problems import PROBLEMS

    module = PROBLEMS["mount"].load()

    def broken(case: Any) -> Any:
        raise RuntimeError("planted")  # arithmetic errors are exit 3, out of float range

    monkeypatch.setattr(module, "solve", broken)
    folder, _ = make_folder(tmp_path)
    shutil.copy(CASES / "mount" / "stiff.toml", folder / "z_bug.toml")
    result = cli("run", folder, "--json", "--jobs", "1")
    assert result.exit_code == 70
    documents = json_lines(result.stdout)
    assert [d["status"] for d in documents] == [*STATUSES, "internal-error"]
    assert "RuntimeError: planted" in documents[-1]["errors"][0]["message"]
    assert f"{folder / 'z_bug.toml'}: internal error: RuntimeError: planted" in result.stderr


def test_a_missing_path_is_reported_and_the_rest_run(cli, tmp_path):
    (tmp_path / "a.toml").write_text(GOOD, encoding="utf-8")
    missing = tmp_path / "nope.toml"
    result = cli("run", missing, tmp_path / "a.toml", "--json", "--jobs", "2")
    assert result.exit_code == 2
    assert_no_traceback(result)
    lost, good = json_lines(result.stdout)
    assert lost["status"] == "input-error" and good["status"] == "ok"
    assert f"{missing}: error: no such file" in result.stderr


def test_a_folder_without_case_files_is_exit_2(cli, tmp_path):
    (tmp_path / "empty").mkdir()
    result = cli("run", tmp_path / "empty")
    assert result.exit_code == 2
    assert_no_traceback(result)
    assert "no *.toml case files" in result.stderr


def test_out_clash_is_exit_2_and_writes_nothing(cli, tmp_path):
    for sub in ("x", "y"):
        (tmp_path / sub).mkdir()
        (tmp_path / sub / "same.toml").write_text(GOOD, encoding="utf-8")
    out = tmp_path / "out"
    for args in (
        [tmp_path / "x" / "same.toml", tmp_path / "y" / "same.toml"],  # two files
        [tmp_path / "x", tmp_path / "y"],  # two folders, same path inside each
    ):
        result = cli("run", *args, "--out", out, "--jobs", "2")
        assert result.exit_code == 2
        assert_no_traceback(result)
        assert "would both write same.json" in result.stderr
        assert not out.exists()
        assert result.stdout == ""
    # Without --out there is nothing to clash: both run.
    result = cli("run", tmp_path / "x", tmp_path / "y", "--json")
    assert result.exit_code == 0
    assert len(json_lines(result.stdout)) == 2


# ----------------------------------------------------------------------- agreement


def test_json_line_agrees_with_the_single_run(cli, tmp_path):
    case = tmp_path / "good.toml"
    case.write_text(GOOD, encoding="utf-8")
    lecture = CASES / "braking" / "lecture.toml"
    batch = json_lines(cli("run", case, lecture, "--json", "--jobs", "2").stdout)
    for path, line in zip((case, lecture), batch, strict=True):
        single = cli("braking", path, "--json")
        assert single.exit_code == 0
        document = strict_json(single.stdout)
        assert line["case"] == document["case"] == str(path)
        assert line["results"] == document["results"]  # values, units and labels
        assert without_timings(line) == without_timings(document)
    # and the lecture numbers by hand, (7.48): t = V0·m/(k·P_D), S = V0·t/2
    t = 27.8 * 1500.0 / (10.0 * 1644.0)
    assert batch[1]["results"]["lecture_time"]["value"] == pytest.approx(t, rel=1e-12)
    assert batch[1]["results"]["lecture_distance"]["value"] == pytest.approx(27.8 * t / 2, 1e-12)
    assert batch[1]["results"]["adhesion_limited_distance"]["value"] == pytest.approx(
        27.8**2 / (2 * 0.7 * G), rel=1e-12
    )


# ----------------------------------------------------------------------- check --jobs


def counts(stdout: str) -> tuple[int, int]:
    line = next(x for x in stdout.splitlines() if x.endswith(" failed"))
    passed, failed = line.split(" passed, ")
    return int(passed), int(failed.split()[0])


def test_check_jobs_gives_the_same_result(cli):
    one = cli("check", CASES / "braking", "--jobs", "1")
    two = cli("check", CASES / "braking", "--jobs", "2")
    assert one.exit_code == two.exit_code == 0
    assert counts(one.stdout) == counts(two.stdout)
    files = len(list((CASES / "braking").rglob("*.toml")))
    assert f"{files} case files checked" in two.stdout
    assert counts(two.stdout)[0] > 0


def test_check_jobs_fails_on_a_wrong_expectation(cli, tmp_path):
    for name in ("dry", "wet", "ice"):
        shutil.copy(CASES / "braking" / f"{name}.toml", tmp_path / f"{name}.toml")
    distance, _ = hand_stop(20.0, 0.6, 0.02, 0.8)
    wrong = GOOD + (
        "\n[expect]\n"
        f"stopping_distance = {{ value = {distance!r}, rel = 1e-12, source = 'hand' }}\n"
        f"stopping_time = {{ value = {math.pi!r}, rel = 1e-6, source = 'wrong on purpose' }}\n"
    )
    (tmp_path / "wrong.toml").write_text(wrong, encoding="utf-8")
    one = cli("check", tmp_path, "--jobs", "1")
    two = cli("check", tmp_path, "--jobs", "2")
    assert one.exit_code == two.exit_code == 1
    assert_no_traceback(two)
    passed, failed = counts(two.stdout)
    assert failed == 1  # the time; the hand distance passes
    assert (passed, failed) == counts(one.stdout)
    assert "4 case files checked" in two.stdout


def test_check_jobs_reports_an_unreadable_file(cli, tmp_path):
    shutil.copy(CASES / "braking" / "dry.toml", tmp_path / "dry.toml")
    (tmp_path / "broken.toml").write_text(BAD_SYNTAX, encoding="utf-8")
    result = cli("check", tmp_path, "--jobs", "2")
    assert result.exit_code == 2
    assert_no_traceback(result)
    assert f"{tmp_path / 'broken.toml'}:2:5: error: TOML syntax" in result.stderr
    assert "1 case files checked, 0 without [expect], 1 unreadable" in result.stdout
