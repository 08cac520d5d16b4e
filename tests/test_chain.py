"""Independent tests of :mod:`mdcalc.core.chain` (free-free torsional chains).

Every expected value is computed here, independently of the module under test:

* eigenvalues from numpy's symmetric eigensolver applied to J^-1/2·K·J^-1/2 (the
  generalized problem K·θ = λ·J·θ), and for three masses from the closed-form
  characteristic quadratic (seed 002 / brief §6) evaluated with ``decimal`` at 50
  digits;
* mode shapes checked by the residual of K·θ = λ·J·θ and by J-orthogonality;
* the step response against the exact solution of the moment ODE M'' + A·M = f,
  M(0) = M'(0) = 0, obtained with scipy's matrix exponential of the first-order
  system, and against the three-mass amplitudes solved by hand from M(0) = 0 with the
  seed's (8) ratio g = J₂(β₁₂² - β²)/c₁₂;
* maxima of cosine sums against a dense grid refined by scipy's bounded scalar search;
* the harmonic response of a two-mass chain against its closed-form twist amplitude.

The matrices K, J, A and f are built in this file from the chain data; the module's
own matrix helpers are only compared against them.
"""

from __future__ import annotations

import math
from decimal import Decimal, localcontext

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import minimize_scalar

from mdcalc.core.chain import (
    Chain,
    harmonic_response,
    moment_equations,
    natural_modes,
    static_moments,
    suddenly_applied,
)
from mdcalc.core.cosine_sums import cosine_sum_maximum

# Seed 002 (Osipova) hoist at H = 1025 m, reduced to the drum axis.
SEED_J = (479.15e3, 27.97e3, 156.86e3)  # kg·m²
SEED_C = (18609.2e3, 893.45e3)  # N·m/rad

# ----------------------------------------------------------------------------- helpers


def hand_matrices(inertias, stiffnesses) -> tuple[np.ndarray, np.ndarray]:
    """K (tridiagonal, free-free) and J = diag(J) written out entry by entry."""
    n = len(inertias)
    k = np.zeros((n, n))
    for i, c in enumerate(stiffnesses):
        k[i, i] += c
        k[i + 1, i + 1] += c
        k[i, i + 1] -= c
        k[i + 1, i] -= c
    return k, np.diag(np.array(inertias, dtype=float))


def numpy_elastic_eigenvalues(inertias, stiffnesses) -> np.ndarray:
    """λ of K·θ = λ·J·θ via the symmetric J^-1/2·K·J^-1/2, rigid zero dropped."""
    k, j = hand_matrices(inertias, stiffnesses)
    s = 1.0 / np.sqrt(np.diag(j))
    values = np.linalg.eigvalsh(s[:, None] * k * s[None, :])
    return np.sort(values)[1:]


def decimal_quadratic(j1, j2, j3, c12, c23) -> tuple[Decimal, Decimal]:
    """β² roots of λ² - λ·[c₁₂(1/J₁+1/J₂) + c₂₃(1/J₂+1/J₃)] + c₁₂c₂₃ΣJ/(J₁J₂J₃) = 0
    at 50 digits; the small root as 2P/(S + √(S²-4P)) (no cancellation)."""
    with localcontext() as ctx:
        ctx.prec = 50
        j1, j2, j3, c12, c23 = (Decimal(repr(float(v))) for v in (j1, j2, j3, c12, c23))
        s = c12 * (1 / j1 + 1 / j2) + c23 * (1 / j2 + 1 / j3)
        p = c12 * c23 * (j1 + j2 + j3) / (j1 * j2 * j3)
        root = (s * s - 4 * p).sqrt()
        return 2 * p / (s + root), (s + root) / 2


def rel_err(value: float, exact: Decimal) -> float:
    with localcontext() as ctx:
        ctx.prec = 50
        return float(abs((Decimal(repr(float(value))) - exact) / exact))


def brute_max(constant, amplitudes, frequencies, start, end) -> tuple[float, float]:
    """max of constant + Σ b·cos(w·t) on [start, end]: a grid of 200 points per period
    of the fastest term, every grid local maximum within the grid error of the best
    refined by a bounded scalar search, and both ends."""
    b = np.asarray(amplitudes, dtype=float)
    w = np.asarray(frequencies, dtype=float)

    def f(t):
        return constant + np.cos(np.multiply.outer(np.atleast_1d(t), w)) @ b

    n = max(20001, int(math.ceil((end - start) * w.max() / (2 * math.pi) * 200)) + 1)
    t = np.linspace(start, end, n)
    v = f(t)
    h = t[1] - t[0]
    slack = float(np.sum(np.abs(b) * w * w)) * h * h  # twice the grid error bound
    peaks = [
        i
        for i in range(1, n - 1)
        if v[i] >= v[i - 1] and v[i] >= v[i + 1] and v[i] >= v.max() - slack
    ]
    best_value, best_time = float(v[0]), start
    if v[-1] > best_value:
        best_value, best_time = float(v[-1]), end
    for i in peaks:
        found = minimize_scalar(
            lambda x: -float(f(x)[0]),
            bounds=(t[i - 1], t[i + 1]),
            method="bounded",
            options={"xatol": 1e-14},
        )
        if -found.fun > best_value:
            best_value, best_time = float(-found.fun), float(found.x)
    return best_value, best_time


def random_chain(rng: np.random.Generator, n: int) -> Chain:
    return Chain(
        tuple(float(x) for x in rng.uniform(0.5, 5.0, n)),
        tuple(float(x) for x in rng.uniform(1.0, 10.0, n - 1)),
    )


EXTREME_THREE_MASS = {
    "seed": (*SEED_J, *SEED_C),
    "stiff chord c12 = 1e9 c23": (*SEED_J, 1e9 * SEED_C[1], SEED_C[1]),
    "stiff rope c23 = 1e9 c12": (*SEED_J, SEED_C[0], 1e9 * SEED_C[0]),
    "tiny sheave J2 = 1e-12 J1": (SEED_J[0], 1e-12 * SEED_J[0], SEED_J[2], *SEED_C),
    "tiny drum J1 = 1e-12": (1e-12, 1.0, 1.0, 1.0, 1.0),
    "tiny cage J3 = 1e-12": (1.0, 1.0, 1e-12, 1.0, 1.0),
    "tiny sheave and stiff chord": (1.0, 1e-12, 1.0, 1e9, 1.0),
}

# ------------------------------------------------------------------ natural modes


@pytest.mark.parametrize("n", [4, 5])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_eigenvalues_match_numpy_generalized_problem(n: int, seed: int) -> None:
    chain = random_chain(np.random.default_rng(seed), n)
    modes = natural_modes(chain)
    expected = numpy_elastic_eigenvalues(chain.inertias, chain.stiffnesses)  # numpy eigvalsh
    assert len(modes.eigenvalues) == n - 1
    assert np.allclose(modes.eigenvalues, expected, rtol=1e-11, atol=0.0)
    assert modes.frequencies == pytest.approx(np.sqrt(expected), rel=1e-11)
    # the module's K and J are the hand-written ones
    k, j = hand_matrices(chain.inertias, chain.stiffnesses)
    assert np.array_equal(chain.stiffness_matrix(), k)
    assert np.array_equal(chain.mass_matrix(), j)


@pytest.mark.parametrize("data", EXTREME_THREE_MASS.values(), ids=EXTREME_THREE_MASS.keys())
def test_three_mass_eigenvalues_match_decimal_quadratic(data) -> None:
    j1, j2, j3, c12, c23 = data
    modes = natural_modes(Chain((j1, j2, j3), (c12, c23)))
    slow, fast = decimal_quadratic(*data)  # 50-digit characteristic quadratic
    assert rel_err(modes.eigenvalues[0], slow) < 1e-13
    assert rel_err(modes.eigenvalues[1], fast) < 1e-13


def test_partial_eigenvalues_hand_formula() -> None:
    j1, j2, j3 = SEED_J
    c12, c23 = SEED_C
    beta12_sq, beta23_sq = Chain(SEED_J, SEED_C).partial_eigenvalues()
    assert beta12_sq == pytest.approx(c12 * (1 / j1 + 1 / j2), rel=1e-14)  # brief §6
    assert beta23_sq == pytest.approx(c23 * (1 / j2 + 1 / j3), rel=1e-14)  # brief §6


def _mode_cases() -> list[Chain]:
    rng = np.random.default_rng(7)
    chains = [random_chain(rng, 4), random_chain(rng, 5)]
    chains += [Chain(d[:3], d[3:]) for d in EXTREME_THREE_MASS.values()]
    return chains


@pytest.mark.parametrize("chain", _mode_cases())
def test_mode_shapes_solve_eigenproblem_and_are_orthogonal(chain: Chain) -> None:
    modes = natural_modes(chain)
    k, j = hand_matrices(chain.inertias, chain.stiffnesses)
    jd = np.diag(j)
    for col, lam in enumerate(modes.eigenvalues):
        theta = modes.shapes[:, col]
        assert np.max(np.abs(theta)) == pytest.approx(1.0, rel=1e-15)  # normalised
        # K·θ = λ·J·θ, each row scaled by the size of its terms
        residual = k @ theta - lam * jd * theta
        scale = np.abs(k) @ np.abs(theta) + lam * jd * np.abs(theta)
        assert np.max(np.abs(residual) / scale) < 1e-12
        # J-orthogonal to the rigid mode (1, 1, ..., 1): Σ Jθ = 0
        assert abs(jd @ theta) <= 1e-12 * (jd @ np.abs(theta))
        # spring moments: c_k(θ_k - θ_k+1) (cancels in a stiff spring: absolute
        # tolerance in units of c_k·max|θ|) and the inertia torques left of the spring
        spring = modes.moments[:, col]
        twist = theta[:-1] - theta[1:]
        c = np.array(chain.stiffnesses)
        assert np.all(np.abs(spring - c * twist) <= 1e-12 * c + 1e-12 * np.abs(spring))
        left = lam * np.cumsum(jd * theta)[:-1]
        assert np.allclose(spring, left, rtol=1e-10, atol=1e-12 * np.max(np.abs(spring)))
        # and J-orthogonal to the other elastic modes
        for other in range(col + 1, len(modes.eigenvalues)):
            phi = modes.shapes[:, other]
            assert abs(theta @ (jd * phi)) <= 1e-10 * (np.abs(theta) @ (jd * np.abs(phi)))


# ------------------------------------------------------------------ static moments


def test_static_moments_three_mass_hand_formula() -> None:
    j1, j2, j3 = SEED_J
    m1, w = 1.0e6, 5.0e5
    (r12, r23), accel = static_moments(Chain(SEED_J, SEED_C), (m1, 0.0, -w))
    total = j1 + j2 + j3
    assert accel == pytest.approx((m1 - w) / total, rel=1e-14)  # ε = (M₁ - W)/ΣJ
    assert r12 == pytest.approx((m1 * (j2 + j3) + w * j1) / total, rel=1e-14)  # brief R₁₂
    assert r23 == pytest.approx((m1 * j3 + w * (j1 + j2)) / total, rel=1e-14)  # brief R₂₃


def test_static_moments_five_mass_by_free_body() -> None:
    # Free body of masses k+1..n: the spring k pulls them with R_k, the torques on them
    # and R_k accelerate them at ε: R_k = Σ_{i>k}(J_i ε - M_i).
    chain = random_chain(np.random.default_rng(11), 5)
    torques = (3.0, -1.0, 0.5, 2.0, -4.5)
    static, accel = static_moments(chain, torques)
    eps = sum(torques) / sum(chain.inertias)
    assert accel == pytest.approx(eps, rel=1e-14)
    for k in range(4):
        right = sum(chain.inertias[i] * eps - torques[i] for i in range(k + 1, 5))
        assert static[k] == pytest.approx(right, rel=1e-12, abs=1e-12)


# ------------------------------------------------------------------ step response


def hand_moment_ode(chain: Chain, torques) -> tuple[np.ndarray, np.ndarray]:
    """A and f of M'' = -A·M + f for M_k = c_k(φ_k - φ_k+1), from J·φ'' = -K·φ + M:
    M_k'' = c_k(φ_k'' - φ_k+1''), φ_i'' = (M_i + M_(i-1 spring) - M_(i spring))/J_i."""
    j, c = chain.inertias, chain.stiffnesses
    n = len(j)
    a = np.zeros((n - 1, n - 1))
    f = np.zeros(n - 1)
    for k in range(n - 1):
        # φ_k'' = (Mext_k + M_{k-1} - M_k)/J_k ; φ_{k+1}'' = (Mext_{k+1} + M_k - M_{k+1})/J_{k+1}
        a[k, k] = c[k] * (1 / j[k] + 1 / j[k + 1])
        if k > 0:
            a[k, k - 1] = -c[k] / j[k]
        if k + 1 < n - 1:
            a[k, k + 1] = -c[k] / j[k + 1]
        f[k] = c[k] * (torques[k] / j[k] - torques[k + 1] / j[k + 1])
    return a, f


def exact_moments(a: np.ndarray, f: np.ndarray, times) -> np.ndarray:
    """M(t) from M'' = -A·M + f, M(0) = M'(0) = 0: exp of the augmented first-order
    system z = (M, M', 1), z' = [[0, I, 0], [-A, 0, f], [0, 0, 0]]·z (scipy expm)."""
    m = len(f)
    big = np.zeros((2 * m + 1, 2 * m + 1))
    big[:m, m : 2 * m] = np.eye(m)
    big[m : 2 * m, :m] = -a
    big[m : 2 * m, 2 * m] = f
    z0 = np.zeros(2 * m + 1)
    z0[-1] = 1.0
    return np.array([(expm(big * t) @ z0)[:m] for t in times]).T


STEP_CASES = {
    "seed M1 = 2W": (Chain(SEED_J, SEED_C), (1.0e6, 0.0, -5.0e5)),
    "random 4 masses": (random_chain(np.random.default_rng(5), 4), (2.0, -1.0, 0.0, 0.5)),
    "random 5 masses": (random_chain(np.random.default_rng(6), 5), (1.0, 0.0, 0.0, 0.0, -3.0)),
}


@pytest.mark.parametrize("chain,torques", STEP_CASES.values(), ids=STEP_CASES.keys())
def test_step_response_solves_moment_ode_from_rest(chain: Chain, torques) -> None:
    modes = natural_modes(chain)
    response = suddenly_applied(chain, torques, modes)
    a, f = hand_moment_ode(chain, torques)
    a_prog, f_prog = moment_equations(chain, torques)
    assert np.allclose(a_prog, a, rtol=1e-14, atol=0.0)
    assert np.allclose(f_prog, f, rtol=1e-14, atol=1e-14 * np.max(np.abs(f)))
    static = np.array(response.static)
    scale = np.max(np.abs(static)) + np.max(np.abs(response.amplitudes))
    # R = A⁻¹f (the constant particular solution)
    assert np.allclose(static, np.linalg.solve(a, f), rtol=1e-10, atol=1e-12 * scale)
    # M(0) = 0 (ropes unloaded)
    assert np.max(np.abs(response.moments(np.array([0.0])))) <= 1e-12 * scale
    # M(t) against the matrix exponential of the ODE at assorted times
    period = 2 * math.pi / response.frequencies[0]
    times = np.linspace(0.0, 3.0 * period, 37)[1:]
    assert np.max(np.abs(response.moments(times) - exact_moments(a, f, times))) <= 1e-9 * scale
    # M'' + A·M = f by central differences of the module's M(t)
    h = 1e-3 / response.frequencies[-1]
    t = times[:, None] + np.array([-h, 0.0, h])[None, :]
    m = response.moments(t.ravel()).reshape(len(static), len(times), 3)
    second = (m[:, :, 0] - 2 * m[:, :, 1] + m[:, :, 2]) / (h * h)
    lhs = second + a @ m[:, :, 1]
    size = np.max(np.abs(a)) * scale
    assert np.max(np.abs(lhs - f[:, None])) <= 1e-5 * size


def test_seed_step_amplitudes_by_hand_and_supremum() -> None:
    # Seed (8): M₂₃ terms are g·B with g = J₂(β₁₂² - β²)/c₁₂; B from M₁₂(0) = 0,
    # M₂₃(0) = 0: B₁ + B₂ = -R₁₂, g₁B₁ + g₂B₂ = -R₂₃ (50-digit decimals).
    j1, j2, j3 = SEED_J
    c12, c23 = SEED_C
    m1, w = 1.0e6, 5.0e5
    chain = Chain(SEED_J, SEED_C)
    response = suddenly_applied(chain, (m1, 0.0, -w), natural_modes(chain))
    with localcontext() as ctx:
        ctx.prec = 50
        lam = decimal_quadratic(j1, j2, j3, c12, c23)
        dj1, dj2, dj3, dc12, dm1, dw = (Decimal(repr(v)) for v in (j1, j2, j3, c12, m1, w))
        total = dj1 + dj2 + dj3
        r12 = (dm1 * (dj2 + dj3) + dw * dj1) / total
        r23 = (dm1 * dj3 + dw * (dj1 + dj2)) / total
        beta12_sq = dc12 * (1 / dj1 + 1 / dj2)
        g = [dj2 * (beta12_sq - v) / dc12 for v in lam]
        b2 = (-r23 + g[0] * r12) / (g[1] - g[0])
        b1 = -r12 - b2
        expected = [[float(b1), float(b2)], [float(g[0] * b1), float(g[1] * b2)]]
        sup = [float(r12 + abs(b1) + abs(b2)), float(r23 + abs(g[0] * b1) + abs(g[1] * b2))]
    assert np.allclose(response.amplitudes, expected, rtol=1e-11, atol=0.0)
    assert response.supremum(0) == pytest.approx(sup[0], rel=1e-13)  # R + Σ|B|
    assert response.supremum(1) == pytest.approx(sup[1], rel=1e-13)
    # brief §6: μ₁₂ sup = 2.0000, μ₂₃ sup = 2.0070
    assert response.supremum(0) / response.static[0] == pytest.approx(2.0000, abs=5e-5)
    assert response.supremum(1) / response.static[1] == pytest.approx(2.0070, abs=5e-5)


def test_supremum_is_approached_and_never_exceeded() -> None:
    # Over a long window the largest sampled M(t) stays below R + Σ|B| and comes
    # close to it (β₂/β₁ of the seed is irrational, so phases line up again).
    chain = Chain(SEED_J, SEED_C)
    response = suddenly_applied(chain, (1.0e6, 0.0, -5.0e5), natural_modes(chain))
    times = np.linspace(0.0, 400.0, 400_001)
    moments = response.moments(times)
    for k in range(2):
        sup = response.static[k] + float(np.sum(np.abs(response.amplitudes[k])))  # R + Σ|B|
        assert response.supremum(k) == pytest.approx(sup, rel=1e-15)
        assert np.max(moments[k]) <= sup * (1 + 1e-14)
        assert np.max(moments[k]) >= sup - 1e-3 * response.static[k]


# ------------------------------------------------------------ maxima of cosine sums


@pytest.mark.parametrize("seed", range(12))
def test_cosine_sum_maximum_matches_brute_force(seed: int) -> None:
    rng = np.random.default_rng(100 + seed)
    terms = int(rng.integers(1, 5))
    b = rng.uniform(-1.0, 1.0, terms)
    w = rng.uniform(0.3, 40.0, terms)
    constant = float(rng.uniform(-1.0, 1.0))
    start = float(rng.uniform(0.0, 3.0))
    end = start + float(rng.uniform(0.1, 10.0))
    found = cosine_sum_maximum(constant, b.tolist(), w.tolist(), start, end)
    expected, _ = brute_max(constant, b, w, start, end)  # grid + bounded refinement
    assert not found.bound
    assert found.value == pytest.approx(expected, abs=1e-12 * (1 + np.sum(np.abs(b))))
    assert start <= found.time <= end
    at_time = constant + float(np.cos(w * found.time) @ b)
    assert found.value == pytest.approx(at_time, abs=1e-14 * (1 + np.sum(np.abs(b))))


@pytest.mark.parametrize("b", [-0.7, 0.7])
def test_cosine_sum_maximum_single_cosine_known(b: float) -> None:
    # constant + b·cos(ωt) over one period: max constant + |b|, at t = π/ω for b < 0
    # and at an end (t = 0 or 2π/ω) for b > 0.
    omega, constant = 3.7, 1.0
    found = cosine_sum_maximum(constant, [b], [omega], 0.0, 2 * math.pi / omega)
    assert found.value == pytest.approx(constant + abs(b), abs=1e-15)
    if b < 0:
        assert found.time == pytest.approx(math.pi / omega, abs=1e-7)
    else:
        assert min(found.time, 2 * math.pi / omega - found.time) < 1e-7
    # a window that stops before the peak: the maximum is at its end
    end = 0.5 * math.pi / omega * 1.3
    part = cosine_sum_maximum(constant, [-abs(b)], [omega], 0.0, end)
    assert part.value == pytest.approx(constant - abs(b) * math.cos(omega * end), abs=1e-15)
    assert part.time == pytest.approx(end, abs=1e-12)


def test_cosine_sum_maximum_bound_for_unresolved_fast_mode() -> None:
    # With a small budget the 1000 rad/s mode cannot be sampled: it is added at its
    # amplitude and the result is an upper bound, high by at most ``error``.
    constant, b, w = 1.0, [-1.0, 0.3], [1.0, 1000.0]
    end = 2 * math.pi
    found = cosine_sum_maximum(constant, b, w, 0.0, end, budget=1000)
    truth, _ = brute_max(constant, b, w, 0.0, end)  # grid + refinement
    assert found.bound
    assert found.value >= truth - 1e-12
    assert found.value <= truth + found.error + 1e-12
    # slow part max (1 + 1 at t = π) plus the fast amplitude 0.3
    assert found.value == pytest.approx(2.3, abs=1e-12)


# -------------------------------------------------------------- harmonic response


def two_mass_twist(j1, j2, c, alpha, omega, torque) -> complex:
    """Twist q = X₁ - X₂ of two masses with a spring c and a damper α across it, under
    M·e^(iωt) on mass 1: subtracting J₂X₂'' = c·q + α·q' from J₁X₁'' = M - c·q - α·q'
    gives q'' + p·q' + β²q = M/J₁ with β² = c(1/J₁ + 1/J₂), p = α(1/J₁ + 1/J₂), hence
    Q = (M/J₁)/(β² - ω² + i·p·ω)."""
    inv = 1 / j1 + 1 / j2
    return (torque / j1) / complex(c * inv - omega * omega, alpha * inv * omega)


@pytest.mark.parametrize("omega", [5.0, 20.0, math.sqrt(500.0), 40.0])
def test_harmonic_response_two_mass_closed_form(omega: float) -> None:
    j1, j2, c, alpha, torque = 2.0, 3.0, 600.0, 1.5, 10.0  # β² = 500 1/s²
    angles, springs = harmonic_response(
        Chain((j1, j2), (c,)), omega, [torque, 0.0], spring_damping=[alpha]
    )
    q = two_mass_twist(j1, j2, c, alpha, omega, torque)
    # rigid part: (J₁+J₂)·(-ω²)·X_c = M (the damper is internal)
    xc = -torque / ((j1 + j2) * omega * omega)
    x1, x2 = xc + j2 / (j1 + j2) * q, xc - j1 / (j1 + j2) * q
    assert abs(angles[0] - x1) <= 1e-12 * abs(x1)
    assert abs(angles[1] - x2) <= 1e-12 * max(abs(x2), abs(x1))
    moment = complex(c, omega * alpha) * q  # spring + damper moment
    assert abs(springs[0] - moment) <= 1e-12 * abs(moment)
    if omega == math.sqrt(500.0):  # at resonance |Q| = (M/J₁)/(p·ω)
        assert abs(q) == pytest.approx(torque / j1 / (alpha * (1 / j1 + 1 / j2) * omega))


def test_harmonic_response_ground_damping_by_cramer() -> None:
    # [[c - ω²J₁ + iωg₁, -c], [-c, c - ω²J₂ + iωg₂]]·X = (M₁, M₂) by Cramer's rule.
    j1, j2, c, g1, g2, omega = 2.0, 3.0, 600.0, 4.0, 0.5, 17.0
    m1, m2 = 10.0 + 2.0j, -3.0
    d11 = complex(c - omega**2 * j1, omega * g1)
    d22 = complex(c - omega**2 * j2, omega * g2)
    det = d11 * d22 - c * c
    x1 = (m1 * d22 + c * m2) / det
    x2 = (d11 * m2 + c * m1) / det
    angles, springs = harmonic_response(
        Chain((j1, j2), (c,)), omega, [m1, m2], absolute_damping=[g1, g2]
    )
    assert abs(angles[0] - x1) <= 1e-12 * abs(x1)
    assert abs(angles[1] - x2) <= 1e-12 * abs(x2)
    assert abs(springs[0] - c * (x1 - x2)) <= 1e-12 * abs(c * (x1 - x2))


def test_harmonic_response_undamped_resonance_raises() -> None:
    # two masses: β = √(c(1/J₁ + 1/J₂)) = √500
    with pytest.raises(ArithmeticError):
        harmonic_response(Chain((2.0, 3.0), (600.0,)), math.sqrt(500.0), [10.0, 0.0])
    # the seed chain at each natural frequency from the 50-digit quadratic
    for lam in decimal_quadratic(*SEED_J, *SEED_C):
        with pytest.raises(ArithmeticError):
            harmonic_response(Chain(SEED_J, SEED_C), float(lam.sqrt()), [1.0e6, 0.0, -5.0e5])
    # ω = 0 is the rigid-body "resonance" of a free-free chain
    with pytest.raises(ArithmeticError):
        harmonic_response(Chain((2.0, 3.0), (600.0,)), 0.0, [10.0, 0.0])
    # away from resonance the undamped response is real and finite
    angles, _ = harmonic_response(Chain((2.0, 3.0), (600.0,)), 10.0, [10.0, 0.0])
    assert np.all(np.isfinite(angles)) and np.all(angles.imag == 0.0)


def test_chain_rejects_bad_data() -> None:
    with pytest.raises(ValueError):
        Chain((1.0,), ())
    with pytest.raises(ValueError):
        Chain((1.0, 2.0), (1.0, 2.0))
    with pytest.raises(ValueError):
        Chain((1.0, -2.0), (1.0,))
    with pytest.raises(ValueError):
        Chain((1.0, 2.0), (0.0,))


def test_each_polished_eigenvalue_is_a_root_of_holzers_residual_to_the_last_bit() -> None:
    # the residual is exactly zero there or changes sign to a neighbouring float:
    # found by review, a 4-ulp bracket whose end hit an exact zero ended 8 ulps off
    # on the far side (mode 2 of this chain); and 2000 random chains of 2-10 masses
    from mdcalc.core.chain import block_modes, holzer_residual

    j = [42.13607778008808, 129.74795844161537, 33.075995475757914, 76.57893797412996]
    j += [0.0004900448059235861, 0.00017514124392257758]
    c = [4345934.236916144, 27309.23279877775, 2724.392322655329, 617882.8384036173]
    c += [0.12140530042548392]
    chains = [(np.array([j]), np.array([c]))]
    rng = np.random.default_rng(12)
    for n in range(2, 11):
        chains.append((10 ** rng.uniform(-4, 4, (250, n)), 10 ** rng.uniform(-1, 7, (250, n - 1))))
    for jj, cc in chains:
        lam = block_modes(jj, cc).eigenvalues

        def residual(value: np.ndarray, jj=jj, cc=cc) -> np.ndarray:
            return holzer_residual(jj, cc, value) / value

        here = residual(lam)
        up, down = residual(np.nextafter(lam, np.inf)), residual(np.nextafter(lam, -np.inf))
        root = (here == 0.0) | (np.sign(up) != np.sign(here)) | (np.sign(down) != np.sign(here))
        assert root.all(), (np.argwhere(~root)[:3], lam[~root][:3])
