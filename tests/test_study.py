"""``mdcalc study``: statistics, limits and Sobol indices over the scatter of inputs.

Expected values come from closed forms and direct integrals worked out here, with
tolerances from the sample count (4 standard errors of a plain Monte Carlo
estimate), never from the program's own output. Also: the same seed gives the same
numbers bit for bit however the samples are split or where they run; the
refusals (exit 2 naming the place), samples without an answer, the files written.
"""

from __future__ import annotations

import csv
import math
import textwrap
import tomllib
from pathlib import Path
from statistics import NormalDist

import numpy as np
import pytest

from tests.conftest import CASES, MINE_STUDY, run_script, strict_json, walk_finite

G = 9.80665


def assert_no_traceback(done) -> None:
    assert "Traceback" not in done.stderr and "internal error" not in done.stderr


def study_file(tmp_path: Path, text: str, name: str = "study.toml") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def run_study(path: Path, jobs: int = 1):
    from mdcalc.input.casefile import read_case
    from mdcalc.runs.cluster import PoolMapper
    from mdcalc.runs.study import run

    return run(read_case(path), PoolMapper(jobs), time_limit=10.0)


BRAKING = """\
problem = "braking"
title = "adhesion spread"

[vehicle]
mass = 1500.0
initial_speed = 25.0

[road]
adhesion = 0.6

[study]
samples = {samples}
sampler = "{sampler}"
seed = 11
results = ["adhesion_limited_distance"]

[study.inputs]
"road.adhesion" = {{ dist = "uniform", low = 0.3, high = 0.9 }}

[study.limits]
adhesion_limited_distance = {{ above = 60.0 }}
"""


@pytest.mark.parametrize("sampler", ["random", "lhs", "sobol"])
def test_braking_adhesion_spread_matches_the_closed_form(tmp_path, sampler):
    # D = v0²/(2·φ·g), φ ~ U(a, b): mean K·ln(b/a)/(b - a), quantile K/(b - q(b - a)),
    # P(D > L) = (K/L - a)/(b - a).
    n = 20_000
    result = run_study(study_file(tmp_path, BRAKING.format(samples=n, sampler=sampler)))
    a, b, v0 = 0.3, 0.9, 25.0
    k = v0 * v0 / (2.0 * G)
    mean = k * math.log(b / a) / (b - a)
    sd = math.sqrt(k * k * (1 / a - 1 / b) / (b - a) - mean * mean)
    s = result.stats["adhesion_limited_distance"]
    assert s is not None and s.count == n
    assert abs(s.mean - mean) < 4 * sd / math.sqrt(n)
    assert abs(s.sd - sd) < 4 * sd / math.sqrt(2 * n) * 2  # kurtosis: a wider bound
    for q in (5, 50, 95):
        x = k / (b - q / 100 * (b - a))
        density = k / (b - a) / x**2
        assert abs(s.percentiles[q] - x) < 4 * math.sqrt(q / 100 * (1 - q / 100) / n) / density
    p = (k / 60.0 - a) / (b - a)
    limit = result.limits[0]
    assert abs(limit.probability - p) < 4 * math.sqrt(p * (1 - p) / n)
    assert limit.low <= limit.probability <= limit.high
    assert result.evaluated.vectorized and not result.evaluated.counts


def test_sobol_indices_of_a_linear_scene(tmp_path):
    # A rope-less hoist's reduced inertia J = J1 + J_a/u_a² + J_b·(ω_b/ω1)² + m(V/ω1)²
    # is linear in J1, J_a, J_b: with independent normals S1 = ST = c_i²σ_i²/Σ c_j²σ_j².
    path = study_file(
        tmp_path,
        """\
        problem = "hoist"
        [load]
        mass = 10000.0
        lifting_speed = 0.2
        [drive]
        motor_speed_rpm = 960.0
        motor_inertia = 0.35
        stage_efficiencies = [0.97, 0.97, 0.98]
        pulley_efficiency = 0.97
        brake_safety_factor = 1.75
        [[drive.shafts]]
        name = "gear"
        inertia = 0.5
        ratio = 5.0
        [[drive.shafts]]
        name = "drum"
        inertia = 40.0
        speed_rpm = 15.279
        [start]
        time = 1.5
        machine = "crane"
        [study]
        samples = 1000
        seed = 3
        results = ["reduced_inertia"]
        sensitivity = true
        sensitivity_samples = 8192
        [study.inputs]
        "drive.motor_inertia" = { dist = "normal", mean = 0.35, sd = 0.002 }
        "drive.shafts.0.inertia" = { dist = "normal", mean = 0.5, sd = 0.05 }
        "drive.shafts.1.inertia" = { dist = "normal", mean = 40.0, sd = 4.0 }
        """,
    )
    result = run_study(path)
    c = {"drive.motor_inertia": 1.0, "drive.shafts.0.inertia": 1 / 25.0,
         "drive.shafts.1.inertia": (15.279 / 960.0) ** 2}  # fmt: skip
    sd = {"drive.motor_inertia": 0.002, "drive.shafts.0.inertia": 0.05,
          "drive.shafts.1.inertia": 4.0}  # fmt: skip
    total = sum((c[k] * sd[k]) ** 2 for k in c)
    indices = result.sensitivity[0]
    assert not indices.note
    for key in c:
        expected = (c[key] * sd[key]) ** 2 / total
        # The 95 % interval over the designs is about 2σ: 4σ is twice it.
        assert abs(indices.first[key] - expected) < 2 * indices.first_conf[key] + 0.01, key
        assert abs(indices.total[key] - expected) < 2 * indices.total_conf[key] + 0.01, key
    assert result.evaluated.vectorized


def test_mount_tail_probability_against_the_integral_of_the_density(tmp_path):
    # Undamped amplitude of the first harmonic A(c) = m_p·r·ω²/|c - M·ω²|; with c
    # normal, P(A > L) is the integral of the normal density where A(c) > L.
    from scipy import integrate, optimize, stats

    mu, sigma, n = 1.0e6, 1.0e5, 100_000
    path = study_file(
        tmp_path,
        f"""\
        problem = "mount"
        gravity = 9.81
        [engine]
        weight = 10000.0
        [mounts]
        stiffness = 1.0e6
        [crank]
        piston_weight = 100.0
        radius = 0.050
        rod_ratio = 0.2
        speed = 150.0
        [study]
        samples = {n}
        seed = 5
        results = ["amplitude_1"]
        [study.inputs]
        "mounts.stiffness" = {{ dist = "normal", mean = {mu}, sd = {sigma} }}
        [study.limits]
        amplitude_1 = {{ above = 5.28e-4 }}
        """,
    )
    result = run_study(path)
    engine, piston = 10000.0 / 9.81, 100.0 / 9.81
    w = 150.0

    def amplitude(c: float) -> float:
        return piston * 0.05 * w * w / abs(c - engine * w * w)

    edge = optimize.brentq(lambda c: amplitude(c) - 5.28e-4, mu, mu + 10 * sigma)
    p = integrate.quad(lambda c: stats.norm.pdf(c, mu, sigma), edge, mu + 12 * sigma)[0]
    assert 1e-3 < p < 0.05  # a tail
    limit = result.limits[0]
    assert abs(limit.probability - p) < 4 * math.sqrt(p * (1 - p) / n)


def test_the_same_seed_gives_bit_identical_results_however_the_samples_are_split(
    tmp_path, monkeypatch
):
    import importlib

    evaluate = importlib.import_module("mdcalc.runs.study.evaluate")
    path = study_file(tmp_path, BRAKING.format(samples=3000, sampler="random"))
    first = run_study(path)
    monkeypatch.setattr(evaluate, "KERNEL_CHUNK", 7)
    second = run_study(path)
    column = "adhesion_limited_distance"
    assert np.array_equal(first.samples, second.samples)
    assert np.array_equal(first.evaluated.values[column], second.evaluated.values[column])
    assert first.values() == second.values()


def test_point_by_point_samples_are_the_same_in_process_and_on_the_pool(tmp_path, monkeypatch):
    from mdcalc.problems import PROBLEMS

    monkeypatch.setattr(PROBLEMS["mine-hoist"].load(), "sweep", None)  # one by one
    path = study_file(tmp_path, MINE_STUDY.format(samples=40, seed=9))
    alone, pooled = run_study(path, jobs=1), run_study(path, jobs=2)
    assert not alone.evaluated.vectorized
    for key in alone.keys:
        assert np.array_equal(alone.evaluated.values[key], pooled.evaluated.values[key])
    # and each sample is the single-scene solver's answer for its inputs
    import copy
    import tomllib

    from mdcalc.input.casefile import CaseText, validate
    from mdcalc.problems import PROBLEMS

    module = PROBLEMS["mine-hoist"].load()
    data = tomllib.loads(path.read_text())
    data.pop("study")
    for index in (0, 17, 39):
        scene = copy.deepcopy(data)
        scene["hoist"]["rope_stiffness"] = float(alone.samples[index, 0])
        scene["loads"]["load_torque"] = float(alone.samples[index, 1])
        solved = module.solve(validate(module.Case, CaseText(path, "", scene)))
        reference = solved.methods.rows[0].values
        assert alone.evaluated.values["mu23_first_swing"][index] == reference["mu23"]


#: A hoist whose motor gives 80 N·m at start: it lifts m only while the static torque
#: m·g·V/(ω1·η) is below 80 N·m, m < 80·ω1·η/(g·V) = 1557.9 kg.
WEAK_HOIST = """\
problem = "hoist"
[load]
mass = 1000.0
lifting_speed = 0.5
[drive]
motor_speed_rpm = 960.0
motor_inertia = 0.35
stage_efficiencies = [0.95]
brake_safety_factor = 1.75
[start]
starting_torque = 80.0
[study]
"""


def test_samples_without_an_answer_are_counted_and_the_study_goes_on(tmp_path):
    # A hoist motor with a fixed starting torque cannot start the heavier loads.
    path = study_file(
        tmp_path,
        WEAK_HOIST
        + """\
        samples = 200
        seed = 1
        results = ["static_torque"]
        [study.inputs]
        "load.mass" = { dist = "uniform", low = 500.0, high = 3000.0 }
        [study.limits]
        static_torque = { above = 70.0 }
        """,
    )
    done = run_script("study", path, "--json", "--jobs", "1")
    assert done.returncode == 0, done.stderr
    document = strict_json(done.stdout)
    walk_finite(document)
    failed = document["failed"]
    heaviest = 80.0 * (960.0 * math.pi / 30.0) * 0.95 / (G * 0.5)
    answered = 200 - failed["samples"]
    p = (heaviest - 500.0) / 2500.0  # the share of U(500, 3000) below it
    assert abs(answered - 200 * p) < 4 * math.sqrt(200 * p * (1 - p))
    assert failed["by_kind"] == {"no answer": failed["samples"]}
    assert "cannot" in failed["first_reasons"]["no answer"][0]
    assert document["results"]["static_torque"]["count"] == answered
    assert document["results"]["static_torque"]["max"] < 80.0  # only the loads it starts
    # the limit's share is over the samples with a value, and the note says so
    assert document["limits"][0]["of"] == answered
    assert f"{failed['samples']} had none" in document["limits"][0]["note"]


def test_a_study_where_no_sample_answers_is_exit_3(tmp_path):
    path = study_file(
        tmp_path,
        WEAK_HOIST
        + """\
        samples = 20
        results = ["static_torque"]
        [study.inputs]
        "load.mass" = { dist = "uniform", low = 5000.0, high = 6000.0 }
        """,
    )
    done = run_script("study", path, "--jobs", "1", "--plot", tmp_path / "none.png")
    assert done.returncode == 3, done.stderr
    assert "no sample" in done.stderr and not (tmp_path / "none.png").exists()
    assert_no_traceback(done)


@pytest.mark.parametrize(
    "line, message",
    [
        ('"vehicle.mass" = { dist = "normal", mean = 1500, sd = 400 }',
         f"must be > 0 kg: a probability of {NormalDist(1500, 400).cdf(0):.3g} lies outside"),
        ('"road.adhesion" = { nominal = 0.6, tol = "±1e400 %" }', "a finite size"),
        ('"road.adhesion" = { nominal = 0.6, tol = "±-5 %" }', "a tolerance is a size"),
        ('"vehicle.mass" = { dist = "normal", mean = 1500 }', "needs sd"),
        ('"vehicle.mass" = { dist = "uniform", low = 1500, high = 1400 }', "not below"),
        ('"vehicle.mas" = { dist = "uniform", low = 1400, high = 1500 }', "not a number of this"),
        ('"vehicle.mass" = { nominal = 1500, tol = "±10 parsecs" }', "tol"),
        ('"vehicle.mass" = { dist = "normal", mean = "1.5 t", sd = "2 m" }', "sd"),
        ('"road.resistance" = { nominal = 0.9, tol = "±20 %" }', "must be < 1"),
    ],
)  # fmt: skip
def test_bad_inputs_are_exit_2_naming_the_key(tmp_path, line, message):
    text = BRAKING.format(samples=10, sampler="random").replace(
        '"road.adhesion" = { dist = "uniform", low = 0.3, high = 0.9 }', line
    )
    done = run_script("study", study_file(tmp_path, text))
    assert done.returncode == 2, done.stderr
    assert message in done.stderr, done.stderr
    assert done.stderr.startswith(str(tmp_path / "study.toml") + ":")
    assert_no_traceback(done)


def test_a_truncated_normal_is_accepted_and_stays_inside(tmp_path):
    text = BRAKING.format(samples=5000, sampler="random").replace(
        '"road.adhesion" = { dist = "uniform", low = 0.3, high = 0.9 }',
        '"road.adhesion" = { dist = "normal", mean = 0.7, sd = 0.2, low = 0.3, high = 1.0 }',
    )
    result = run_study(study_file(tmp_path, text))
    assert 0.3 <= result.samples.min() and result.samples.max() <= 1.0


@pytest.mark.parametrize(
    "table, message",
    [
        ("samples = 0", "must be > 0"),
        ('samples = 10\nsampler = "halton"', "allowed"),
        ("samples = 10\nsensitivity = true\nsensitivity_samples = 1000", "power of 2"),
        ("samples = 10\nsamplez = 3", "unknown key"),
    ],
)
def test_a_bad_study_table_is_exit_2(tmp_path, table, message):
    text = BRAKING.format(samples=10, sampler="random").replace(
        'samples = 10\nsampler = "random"', table
    )
    done = run_script("study", study_file(tmp_path, text))
    assert done.returncode == 2, done.stderr
    assert message in done.stderr, done.stderr
    assert_no_traceback(done)


def test_a_study_file_and_a_case_file_are_not_confused(tmp_path):
    study = study_file(tmp_path, BRAKING.format(samples=10, sampler="random"))
    done = run_script("braking", study)
    assert done.returncode == 2 and "mdcalc study" in done.stderr
    case = tmp_path / "case.toml"
    case.write_text(BRAKING.format(samples=10, sampler="random").split("[study]")[0])
    done = run_script("study", case)
    assert done.returncode == 2 and "no [study] table" in done.stderr


def test_json_csv_and_plot(tmp_path):
    study = study_file(tmp_path, BRAKING.format(samples=500, sampler="lhs"))
    out, plot = tmp_path / "samples.csv", tmp_path / "study.png"
    done = run_script("study", study, "--json", "--out", out, "--plot", plot)
    assert done.returncode == 0, done.stderr
    document = strict_json(done.stdout)
    walk_finite(document)
    assert document["kind"] == "study" and document["samples"] == 500
    assert set(document["results"]["adhesion_limited_distance"]) >= {"mean", "p1", "p99"}
    rows = list(csv.reader(out.open()))
    assert rows[0] == ["road.adhesion", "adhesion_limited_distance [m]", "status"]
    assert len(rows) == 501
    # each row: the closed form of its own adhesion, to the last digit written
    for row in rows[1:50]:
        assert float(row[1]) == pytest.approx(25.0**2 / (2 * float(row[0]) * G), rel=1e-15)
    assert plot.stat().st_size > 10_000
    again = run_script("study", study, "--out", out)
    assert again.returncode == 2 and "--force" in again.stderr


def test_check_verifies_a_study_and_fails_a_wrong_expectation(tmp_path):
    text = BRAKING.format(samples=2000, sampler="random")
    k = 25.0**2 / (2 * G)
    mean = k * math.log(3.0) / 0.6
    good = (
        text
        + '\n[expect]\n"adhesion_limited_distance.mean" = '
        + f'{{ value = {mean}, abs = 2.0, source = "hand: 4·sd/√n = 1.7" }}\n'
    )
    bad = good.replace(f"value = {mean}", f"value = {mean + 10}")
    assert run_script("check", study_file(tmp_path, good, "good.toml")).returncode == 0
    failed = run_script("check", study_file(tmp_path, bad, "bad.toml"))
    assert failed.returncode == 1 and "FAIL" in failed.stdout


def test_run_runs_a_study_file_in_a_batch(tmp_path):
    study_file(tmp_path, BRAKING.format(samples=100, sampler="random"))
    done = run_script("run", tmp_path, "--json", "--jobs", "1")
    assert done.returncode == 0, done.stderr
    assert strict_json(done.stdout.splitlines()[0])["kind"] == "study"


@pytest.mark.parametrize("low_sigmas", [0.13, 2.0, 7.0])
def test_a_normal_truncated_in_its_upper_tail_has_the_truncated_mean(tmp_path, low_sigmas):
    # E[X | X > a] = μ + σ·φ(α)/(1 - Φ(α)), α = (a - μ)/σ (upper-tail windows are
    # drawn from the survival function: 1 - q would round to 1 at 7σ).
    from scipy import stats

    mu, sigma, n = 1500.0, 75.0, 20_000
    low = mu + low_sigmas * sigma
    text = BRAKING.format(samples=n, sampler="random").replace(
        '"road.adhesion" = { dist = "uniform", low = 0.3, high = 0.9 }',
        f'"vehicle.mass" = {{ dist = "normal", mean = {mu}, sd = {sigma}, low = {low} }}',
    )
    result = run_study(study_file(tmp_path, text))
    drawn = result.samples[:, 0]
    assert drawn.min() >= low and np.isfinite(drawn).all()
    alpha = low_sigmas
    mean = mu + sigma * stats.norm.pdf(alpha) / stats.norm.sf(alpha)
    sd = sigma * math.sqrt(
        1
        + alpha * stats.norm.pdf(alpha) / stats.norm.sf(alpha)
        - (stats.norm.pdf(alpha) / stats.norm.sf(alpha)) ** 2
    )
    assert abs(drawn.mean() - mean) < 4 * sd / math.sqrt(n)


def test_a_list_item_is_held_to_the_bounds_of_its_item_type(tmp_path):
    # stage efficiencies are list[Annotated[float, Field(gt=0, le=1)]]
    path = study_file(
        tmp_path,
        WEAK_HOIST.replace("starting_torque = 80.0", "time = 1.5")
        + """\
samples = 10
[study.inputs]
"drive.stage_efficiencies.0" = { dist = "uniform", low = 0.9, high = 1.1 }
""",
    )
    done = run_script("study", path)
    assert done.returncode == 2, done.stderr
    assert "must be <= 1" in done.stderr and "0.5 lies outside" in done.stderr


def test_parquet_keeps_every_sample(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")  # an optional extra: skipped without it
    study = study_file(tmp_path, BRAKING.format(samples=300, sampler="sobol"))
    done = run_script("study", study, "--out", tmp_path / "s.parquet")
    assert done.returncode == 0, done.stderr
    table = pq.read_table(tmp_path / "s.parquet")
    assert table.num_rows == 300
    assert table.column_names == ["road.adhesion", "adhesion_limited_distance [m]", "status"]


# Ishigami's function on x ~ U(-π, π)³, with a = 7, b = 0.1: indices in closed form
# (Ishigami & Homma 1990; Sobol' & Levitan 1999): V = a²/8 + bπ⁴/5 + b²π⁸/18 + 1/2,
# V₁ = (1 + bπ⁴/5)²/2, V₂ = a²/8, V₃ = 0, V₁₃ = b²π⁸(1/18 - 1/50).
ISHIGAMI_A, ISHIGAMI_B = 7.0, 0.1


def ishigami(u):
    x = -math.pi + 2.0 * math.pi * u
    a, b = ISHIGAMI_A, ISHIGAMI_B
    return np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0])


def ishigami_indices() -> dict[str, tuple[float, float]]:
    a, b, pi = ISHIGAMI_A, ISHIGAMI_B, math.pi
    v = a**2 / 8 + b * pi**4 / 5 + b**2 * pi**8 / 18 + 0.5
    v1, v2, v13 = 0.5 * (1 + b * pi**4 / 5) ** 2, a**2 / 8, b**2 * pi**8 * (1 / 18 - 1 / 50)
    return {"x1": (v1 / v, (v1 + v13) / v), "x2": (v2 / v, v2 / v), "x3": (0.0, v13 / v)}


def test_sobol_intervals_cover_the_truth_and_match_the_scatter_over_seeds():
    # 40 seeds of a 1024-base-sample analysis of a function with known indices: each
    # index's 95 % interval holds the truth in at least 34 of 40, and its mean
    # half-width is at most twice the 95 % half-width of the estimates' scatter over
    # the seeds. SALib's bootstrap on one Sobol' design was 3 to 6 times that here.
    from mdcalc.runs.study.sample import sobol_design
    from mdcalc.runs.study.summary import sobol

    names = ["x1", "x2", "x3"]
    problem = {"num_vars": 3, "names": names, "bounds": [[0.0, 1.0]] * 3}
    truth = ishigami_indices()
    runs = {(name, kind): ([], []) for name in names for kind in ("S1", "ST")}
    for seed in range(40):
        u, replicates = sobol_design(problem, 1024, seed)
        assert replicates == 16 and len(u) == 1024 * (3 + 2)
        found = sobol("y", names, problem, ishigami(u), replicates)
        for name in names:
            runs[name, "S1"][0].append(found.first[name])
            runs[name, "S1"][1].append(found.first_conf[name])
            runs[name, "ST"][0].append(found.total[name])
            runs[name, "ST"][1].append(found.total_conf[name])
    for (name, kind), (estimates, halves) in runs.items():
        exact = truth[name][0 if kind == "S1" else 1]
        covered = sum(abs(e - exact) <= h for e, h in zip(estimates, halves, strict=True))
        assert covered >= 34, (name, kind, covered)
        scatter = 1.96 * float(np.std(estimates, ddof=1))
        assert float(np.mean(halves)) <= 2.0 * scatter, (name, kind, np.mean(halves), scatter)


def test_sensitivity_samples_divide_among_replicates():
    from mdcalc.runs.study.sample import sobol_replicates

    # 16 designs where each gets 8 base samples or more; never fewer than 2.
    assert [sobol_replicates(n) for n in (16, 32, 64, 128, 256, 8192)] == [2, 4, 8, 16, 16, 16]


def test_timing_splits_set_up_samples_and_sobol(tmp_path):
    # seconds is the whole; set-up, samples and Sobol are its parts, and the rate
    # counts the study's samples (not the design's runs) over their evaluation only.
    text = BRAKING.format(samples=4096, sampler="random").replace(
        "[study]\n", "[study]\nsensitivity = true\nsensitivity_samples = 256\n"
    )
    done = run_script("study", study_file(tmp_path, text), "--json", "--jobs", "1")
    assert done.returncode == 0, done.stderr
    document = strict_json(done.stdout)
    parts = [document[k] for k in ("setup_seconds", "sampling_seconds", "sensitivity_seconds")]
    assert all(p > 0 for p in parts)
    assert sum(parts) <= document["seconds"] <= sum(parts) + 0.5
    assert document["samples_per_second"] == pytest.approx(4096 / parts[1], rel=1e-12)
    assert (
        document["sensitivity"]["runs"] == 256 * 3 and document["sensitivity"]["replicates"] == 16
    )


def test_a_design_whose_result_does_not_change_is_left_out_and_said():
    # A result that changes only in a rare corner (x1 > 0.995): several of the 16
    # designs see no change, and their indices would be 0/0. They are left out, the
    # interval uses the others, and a note says so; with fewer than 2 left, no indices.
    from mdcalc.runs.study.sample import sobol_design
    from mdcalc.runs.study.summary import sobol

    names = ["x1", "x2"]
    problem = {"num_vars": 2, "names": names, "bounds": [[0.0, 1.0]] * 2}
    u, replicates = sobol_design(problem, 1024, 5)
    rare = np.where(u[:, 0] > 0.995, 1.0 + u[:, 1], 0.0)
    per_design = np.split(rare, replicates)
    flat = sum(float(np.std(part)) == 0.0 for part in per_design)
    assert 2 <= flat <= replicates - 2  # the case this test is about
    found = sobol("y", names, problem, rare, replicates)
    assert f"within {flat} of the {replicates} designs" in found.note
    assert set(found.first) == set(names) and all(math.isfinite(v) for v in found.first.values())
    almost_never = np.zeros(len(u))
    almost_never[len(u) - 1] = 1.0  # one change, in the last design
    none = sobol("y", names, problem, almost_never, replicates)
    assert none.first == {} and "changed in 1 of the 16 designs" in none.note


def test_samples_run_each_reference_alone_with_the_same_values(tmp_path, monkeypatch):
    # A sample one by one runs each Methods table's reference alone (no ODE check
    # rows, no timing repeats): the study's values are the very ones of samples run
    # with every method, and the Methods rows besides the reference are not run.
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs import sweep

    monkeypatch.setattr(PROBLEMS["resonance"].load(), "sweep", None)  # one by one
    text = (CASES / "studies" / "resonance_flywheel.toml").read_text(encoding="utf-8")
    path = study_file(tmp_path, text.split("[expect]")[0].replace("samples = 128", "samples = 16"))
    alone = run_study(path, jobs=1)
    monkeypatch.setattr(sweep, "reference_only_fits", lambda *args: False)
    every = run_study(path, jobs=1)
    assert not alone.evaluated.vectorized and not alone.evaluated.counts
    for key in alone.keys:
        assert list(alone.evaluated.values[key]) == list(every.evaluated.values[key]), key


def test_reference_alone_keeps_the_scenes_own_results():
    # A sample runs each Methods table's reference alone when that gives every result
    # asked (reference_only_fits compares the two runs). mechanism's Kovylin path at
    # the user's n is a result of the scene, computed when its Methods row does not
    # run: asked for, it is there, and equal to the full run's.
    from mdcalc import methods
    from mdcalc.input.casefile import read_case, validate
    from mdcalc.problems import PROBLEMS
    from mdcalc.runs.runner import solve_model
    from mdcalc.runs.sweep import point_results, reference_only_fits

    module = PROBLEMS["mechanism"].load()
    path = CASES / "mechanism" / "linear_torque.toml"
    model = validate(module.Case, read_case(path))
    assert reference_only_fits("mechanism", module, model, ["final_speed"], 10.0)
    assert reference_only_fits("mechanism", module, model, ["kovylin_final_speed"], 10.0)
    assert methods.REFERENCE_ONLY is False  # put back after the tries
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("expect", None)
    code, values, _ = point_results((str(path), "mechanism", data, 10.0, True))
    _, report = solve_model("mechanism", module, model, 10.0)
    assert code == 0 and values["final_speed"] == report.results()["final_speed"].value
    full = report.results()["kovylin_final_speed"].value
    assert values["kovylin_final_speed"] == full and methods.REFERENCE_ONLY is False


def test_a_study_draws_a_formula_parameter_and_refuses_a_name_the_case_lacks(tmp_path):
    # parameters.a of M = a - b·ω drawn through the kernel: the end speed rises with
    # the stall torque a (a by-hand bound: ω_end < a/b, the no-load speed); a name
    # the case's [parameters] does not hold would change nothing: exit 2, no traceback.
    import json

    study = CASES / "studies" / "mechanism_motor_torque.toml"
    text = study.read_text(encoding="utf-8").split("[expect]")[0]
    good = tmp_path / "good.toml"
    good.write_text(text.replace("samples = 1024", "samples = 64"), encoding="utf-8")
    done = run_script("study", good, "--json", "--out", tmp_path / "s.csv")
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader((tmp_path / "s.csv").open(encoding="utf-8")))
    pairs = sorted((float(r["parameters.a"]), float(r["final_speed [rad/s]"])) for r in rows)
    assert all(w < a / 2.0 for a, w in pairs)
    assert all(w1 < w2 for (_, w1), (_, w2) in zip(pairs, pairs[1:], strict=False))
    assert "vectorized kernel" in json.loads(done.stdout)["how"]
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace('"parameters.a"', '"parameters.zz"'), encoding="utf-8")
    refused = run_script("study", bad)
    assert refused.returncode == 2
    assert "parameters.zz" in refused.stderr and "it has: a, b" in refused.stderr
    assert "Traceback" not in refused.stderr


def test_samples_that_break_a_cross_field_rule_are_refused_alone_and_the_rest_vectorized(
    tmp_path, monkeypatch
):
    # Gear ratios drawn independently overlap: some samples have U₂ <= U₃, which the
    # case's rule refuses ("must decrease"). Each such sample is an invalid scene with
    # that reason; the others run through the kernel and equal the one-by-one run.
    from mdcalc.problems import PROBLEMS

    text = (CASES / "studies" / "acceleration_lecture.toml").read_text(encoding="utf-8")
    text = text.split("[study]")[0] + textwrap.dedent(
        """\
        [study]
        samples = 60
        seed = 5
        results = ["lecture_total_time", "top_speed_kmh"]

        [study.inputs]
        "transmission.gear_ratios.1" = { dist = "uniform", low = 1.4, high = 2.6 }
        "transmission.gear_ratios.2" = { dist = "uniform", low = 1.2, high = 1.9 }
        """
    )
    path = study_file(tmp_path, text)
    fast = run_study(path)
    assert fast.evaluated.vectorized
    ratios = fast.samples
    broken = ~(ratios[:, 0] > ratios[:, 1])  # by hand: U₂ must exceed U₃
    assert broken.any() and not broken.all()
    assert np.array_equal(fast.evaluated.status == 2, broken)
    assert fast.evaluated.counts["invalid scene"] == int(broken.sum())
    assert any("must decrease" in r for r in fast.evaluated.reasons["invalid scene"])
    monkeypatch.setattr(PROBLEMS["acceleration"].load(), "sweep", None)  # one by one
    slow = run_study(path)
    assert not slow.evaluated.vectorized
    assert np.array_equal(fast.evaluated.status, slow.evaluated.status)
    for key in fast.keys:
        np.testing.assert_allclose(
            fast.evaluated.values[key], slow.evaluated.values[key], rtol=1e-9, equal_nan=True
        )


@pytest.mark.parametrize(("samples", "dims", "seed"), [(1, 1, 0), (7, 3, 5), (4096, 5, 2026)])
def test_the_latin_hypercube_is_scipys_bit_for_bit(samples, dims, seed):
    # drawn in numpy so that a study need not import scipy.stats (0.5 s)
    import warnings

    from scipy.stats import qmc

    from mdcalc.runs.study.sample import latin_hypercube

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        expected = qmc.LatinHypercube(dims, rng=seed).random(samples)
    got = latin_hypercube(samples, dims, seed)
    assert got.shape == expected.shape
    assert np.array_equal(got, expected)
