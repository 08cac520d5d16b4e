"""mdcalc from Python (issue 34): ``mdcalc.solve`` gives what ``mdcalc PROBLEM CASE
--json`` gives, for a case as a file, as TOML text and as a dict; errors are
exceptions carrying the command line's problems, with nothing printed; ``import
mdcalc`` loads nothing heavy."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import threading
import tomllib
from pathlib import Path

import pytest

import mdcalc
from mdcalc.problems import PROBLEMS
from tests.conftest import CASES, comparable_json

#: One case of each problem (the first of its folder; the mechanism's quickest, not
#: the crank press's 2 s of ODE), run the three ways.
QUICKER = {"mechanism": CASES / "mechanism" / "linear_torque.toml"}
SAMPLE = [QUICKER.get(name, sorted((CASES / name).glob("*.toml"))[0]) for name in sorted(PROBLEMS)]
#: Heavy modules a bare ``import mdcalc`` must not load.
HEAVY = ("numpy", "scipy", "pint", "rich", "pydantic", "typer", "matplotlib", "pandas")


def test_import_loads_nothing_heavy_and_is_quick():
    code = (
        "import sys, time\n"
        "t = time.perf_counter()\n"
        "import mdcalc\n"
        "took = time.perf_counter() - t\n"
        f"print(took, [m for m in {HEAVY!r} if m in sys.modules])\n"
    )
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True) for _ in range(3)]  # fmt: skip
    took = min(float(r.stdout.split()[0]) for r in runs)
    assert all(r.stdout.split(maxsplit=1)[1].strip() == "[]" for r in runs), runs[0].stdout
    assert took < 0.05, f"import mdcalc took {took * 1e3:.1f} ms"  # 31 ms here with Python's


@pytest.mark.parametrize("path", SAMPLE, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_solve_gives_the_command_lines_json_from_text_and_a_dict(path, cli, monkeypatch, capsys):
    """A file: every shipped case, tests/test_cases.py."""
    monkeypatch.chdir(path.parent)  # a base = "..." of a text or dict: from here
    problem = tomllib.loads(path.read_text(encoding="utf-8"))["problem"]
    command = json.loads(cli(problem, path, "--json").stdout)
    capsys.readouterr()
    want = comparable_json(command)
    text = path.read_text(encoding="utf-8")
    assert comparable_json(mdcalc.solve(text).to_dict()) == want
    data = tomllib.loads(text)
    data.pop("problem")  # named by the argument instead
    assert comparable_json(mdcalc.solve(data, problem).to_dict()) == want
    assert capsys.readouterr() == ("", "")  # nothing printed


def test_results_are_quantities_in_the_jsons_units():
    calc = mdcalc.solve(CASES / "coupling" / "example_8_1_units.toml")
    document = calc.to_dict()
    for key, result in document["results"].items():
        value = calc.results[key]
        if result["unit"]:
            assert value.magnitude == result["value"], key
            assert value.units == value._REGISTRY.Unit(result["unit"]), key
        else:
            assert value == result["value"], key
    hz = calc.results["natural_frequency"].to("rpm")  # radian per second, to rpm
    assert hz.magnitude == pytest.approx(document["results"]["natural_frequency"]["value"]
                                         * 60 / (2 * 3.141592653589793), rel=1e-12)  # fmt: skip


def test_a_list_result_is_an_array():
    calc = mdcalc.solve(CASES / "acceleration" / "lecture.toml")
    ratios = calc.results["gear_ratios"]
    assert list(ratios) == calc.to_dict()["results"]["gear_ratios"]["value"]


def test_methods_tables_and_frames():
    pytest.importorskip("pandas")
    calc = mdcalc.solve(CASES / "braking" / "lecture.toml")
    stop = calc.methods["stop"]
    frame = stop.to_frame()
    document = next(s for s in calc.to_dict()["sections"] if s.get("key") == "stop")
    assert list(frame.index) == [row["method"] for row in document["rows"]]
    reference = frame[frame["reference"]]
    assert len(reference) == 1
    row = next(r for r in document["rows"] if r["reference"])
    assert reference["stopping_distance"].iloc[0] == row["values"]["stopping_distance"]


@pytest.mark.parametrize(
    ("case", "file"),
    [
        ('problem = "braking"\n[vehicle]\nmass = -3\n', "<string>"),
        ({"problem": "braking", "vehicle": {"mass": -3}}, "<dict>"),
    ],
)
def test_bad_input_raises_the_command_lines_problems_and_prints_nothing(
    case, file, cli, tmp_path, capsys
):
    with pytest.raises(mdcalc.InputError) as caught:
        mdcalc.solve(case)
    assert capsys.readouterr() == ("", "")
    error = caught.value
    assert error.file == file
    path = tmp_path / "bad.toml"
    path.write_text(case if isinstance(case, str) else 'problem = "braking"\n[vehicle]\n'
                    "mass = -3\n", encoding="utf-8")  # fmt: skip
    printed = cli("braking", path).stderr.strip().splitlines()
    mine = [p.format(str(path)) for p in error.problems]
    if file == "<dict>":  # no line: the text was made from the dict
        assert all(p.line is None for p in error.problems)
        printed = [line.replace(f"{path}:3:", f"{path}:") for line in printed]
    assert mine == printed


def test_a_path_that_is_not_there_and_a_wrong_problem_are_input_errors():
    with pytest.raises(mdcalc.InputError, match="no such file"):
        mdcalc.solve(Path("no-such-case.toml"))
    with pytest.raises(mdcalc.InputError, match="this case is for 'braking', not 'hoist'"):
        mdcalc.solve(CASES / "braking" / "lecture.toml", "hoist")
    with pytest.raises(TypeError):
        mdcalc.solve(42)  # type: ignore[arg-type]
    with pytest.raises(mdcalc.InputError, match=r"a str is TOML text: give Path\("):
        mdcalc.solve(str(CASES / "braking" / "lecture.toml"))
    study = CASES / "studies" / "coupling_scatter.toml"
    with pytest.raises(mdcalc.InputError, match=r"run it with mdcalc study "):
        mdcalc.solve(study)  # as the command line says it
    with pytest.raises(mdcalc.InputError, match=r"run it with mdcalc\.study"):
        mdcalc.solve(study.read_text(encoding="utf-8"))


def test_no_answer_is_a_status_or_if_asked_an_exception():
    path = CASES / "hoist" / "cannot_start.toml"
    calc = mdcalc.solve(path)
    assert calc.status == "no-answer" and calc.message
    with pytest.raises(mdcalc.NoAnswer) as caught:
        mdcalc.solve(path, raise_on_no_answer=True)
    assert caught.value.message == calc.message
    assert caught.value.calculation.status == "no-answer"


def test_the_budget_off_the_main_thread_and_the_callers_alarm_handler():
    def mine(signum, frame):  # pragma: no cover - never fires
        raise AssertionError("the caller's handler ran")

    before = signal.signal(signal.SIGALRM, mine)
    try:
        calc = mdcalc.solve(CASES / "mine-hoist" / "seed_1025.toml", time_limit=30.0)
        assert calc.status == "ok"
        assert signal.getsignal(signal.SIGALRM) is mine  # put back
    finally:
        signal.signal(signal.SIGALRM, before)
    found: list = []
    worker = threading.Thread(
        target=lambda: found.append(mdcalc.solve(CASES / "braking" / "lecture.toml"))
    )
    worker.start()
    worker.join(60)
    assert found and found[0].status == "ok"


def test_registry_gives_each_problem_its_model_and_schema(cli):
    problems = mdcalc.registry()
    assert list(problems) == list(PROBLEMS)
    hoist = problems["hoist"]
    assert hoist.summary == PROBLEMS["hoist"].summary
    assert hoist.case_model is PROBLEMS["hoist"].load().Case
    assert hoist.schema() == json.loads(cli("schema", "hoist").stdout)
    assert mdcalc.solve(hoist.template()).status == "ok"


def test_documents_and_charts():
    pytest.importorskip("matplotlib")
    calc = mdcalc.solve(CASES / "hoist" / "crane.toml")
    html = calc._repr_html_()
    assert html.startswith("<!DOCTYPE html>") and calc.title in html and "<svg" in html
    assert calc.to_markdown().startswith(f"# {calc.title.split(',')[0]}")
    figures = calc.charts()
    assert len(figures) == 2 and all(f.axes for f in figures)
    assert mdcalc.solve(CASES / "braking" / "lecture.toml").charts() == []


def test_a_study_gives_the_command_lines_statistics(cli):
    path = CASES / "studies" / "braking_adhesion.toml"
    command = json.loads(cli("study", path, "--json", "--jobs", "1").stdout)
    result = mdcalc.study(path, jobs=1)
    mine = result.to_dict()
    assert mine["results"] == command["results"] and mine["limits"] == command["limits"]
    assert mine["sensitivity"]["indices"] == command["sensitivity"]["indices"]
    assert result.statistics == command["results"] and result.sobol is not None
    frame = result.samples
    assert len(frame["road.adhesion"]) == command["samples"] == len(frame["status"])
    fewer = mdcalc.study(path, samples=500, seed=3, sampler="random", jobs=1)
    assert len(fewer.samples["status"]) == 500
    assert fewer.to_dict()["seed"] == 3 and fewer.to_dict()["sampler"] == "random"
    with pytest.raises(mdcalc.InputError, match="no \\[study\\] table"):
        mdcalc.study(CASES / "braking" / "dry.toml")


def test_a_sweep_gives_the_command_lines_columns(cli, tmp_path):
    path = CASES / "braking" / "dry.toml"
    out = tmp_path / "sweep.json"
    done = cli("sweep", path, "--vary", "vehicle.initial_speed_kmh=40:100:4",
               "--result", "stopping_distance", "--out", out)  # fmt: skip
    assert done.exit_code == 0, done.stderr
    command = json.loads(out.read_text(encoding="utf-8"))
    speeds = [40.0, 60.0, 80.0, 100.0]
    result = mdcalc.sweep(path, {"vehicle.initial_speed_kmh": speeds},
                          results=["stopping_distance"], jobs=1)  # fmt: skip
    assert list(result.columns["vehicle.initial_speed_kmh"]) == speeds
    assert list(result.columns["stopping_distance"]) == command["values"]["stopping_distance"]
    assert list(result.status) == command["status"] == [0, 0, 0, 0]
    for bad in ([], [40.0, float("nan")], ["fast"], 40.0):
        with pytest.raises(mdcalc.InputError, match="finite"):
            mdcalc.sweep(path, {"vehicle.initial_speed_kmh": bad})
