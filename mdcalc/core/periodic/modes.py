"""The modes of a block of systems M·x'' + C·x' + K·x = …, one per row: of one or
two coordinates the roots of det(λ²M + λC + K) in closed form, polished by Newton
steps, and their eigenvectors (x, λx); of more, numpy's eig of the first-order
matrix."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

#: Newton steps at most that polish an eigenvalue of one or two coordinates.
NEWTON_STEPS = 6
#: Two eigenvalues polished from the closed form's starts closer than this (relative
#: to the larger) may be one root reached twice: the row's starts are eigvals'.
SAME_ROOT = 1e-9
#: An eigenvalue whose determinant's rounding leaves it uncertain by more than this
#: (relative) is not resolved: its row has no answer (the modes spread too far, or
#: K is all but singular), unless its eigenvalues meet.
RESOLVED = 1e-8


def _modes(
    first: np.ndarray | Callable[[Any], np.ndarray],
    mass: np.ndarray,
    damping: np.ndarray,
    stiffness: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None, np.ndarray]:
    """Eigenvalues and unit eigenvectors of each row's first-order matrix A, complex
    throughout; whether each row's eigenvalues are sure; the eigenvectors' inverse
    V⁻¹ where it comes with them (None: numpy's eig); and the eigenvalues' least
    distance apart relative to their size (:func:`_closest`).

    A system of one or two coordinates takes its eigenvalues as the roots of
    det(λ²M + λC + K), a quadratic or a quartic: from its closed form
    (:func:`_roots`), polished by Newton steps (:func:`_newton`); a row whose
    starts do not all settle, or two of which settle on one root, starts again
    from numpy's eigvals of A. (The closed form settled every row of 3000 random
    two-mass drives whose stiffnesses span 10³–10¹², and has the slow pair of two
    overdamped masses 10¹⁴ below the fast one to 1e-14, where eigvals is over 1 %
    off. On 4096 rows of vk_variator.toml's three-mass state it and its Newton step
    take 3.9 ms, eigvals 8.2 ms and its steps 3.0.) Each eigenvector is (x, λx),
    x the null vector of λ²M + λC + K: of one coordinate 1, of two a row of that
    2×2 turned a right angle, the one that leaves the other row the least residual
    against its terms; conjugate eigenvalues get conjugate vectors, bit for bit.
    V⁻¹'s rows are the left eigenvectors (w(λM + C), wM) over w(2λM + C)x, w the
    left null vector (:func:`_vectors`: a few products a row, where numpy's batched
    inverse of 4×4 matrices took 2.4 ms a 4096-row block). Sure: a Newton step has
    come under 1e-8 of each eigenvalue, and the determinant's rounding leaves each
    within :data:`RESOLVED` of itself (:func:`_uncertainty`); numpy's eig: always.

    ``first``: each row's first-order matrix A, or a function that gives those of
    the rows it is given (a row whose closed form settles needs none)."""
    n = mass.shape[-1]

    def matrices(rows: Any) -> np.ndarray:
        return first[rows] if isinstance(first, np.ndarray) else first(rows)

    if n > 2:
        eigenvalues, vectors = np.linalg.eig(matrices(slice(None)))
        sure = np.ones(len(mass), bool)
        eigenvalues = eigenvalues.astype(complex)
        return eigenvalues, vectors.astype(complex), sure, None, _closest(eigenvalues)
    m = [[mass[:, i, j, None] for j in range(n)] for i in range(n)]
    c = [[damping[:, i, j, None] for j in range(n)] for i in range(n)]
    k = [[stiffness[:, i, j, None] for j in range(n)] for i in range(n)]
    starts = _roots(m, c, k)
    if _paired(starts):  # (the steps from conjugate starts are conjugate, bit for bit)
        lam, close = _newton(starts[:, ::2], m, c, k)
        lam, close = _unfold(lam, -1), np.repeat(close, 2, axis=-1)
    else:
        lam, close = _newton(starts, m, c, k)
    sure = np.all(close, axis=-1)
    closest = _closest(lam)
    again = np.flatnonzero(~sure | (closest <= SAME_ROOT))
    if again.size:
        part = [[[x[again] for x in row] for row in matrix] for matrix in (m, c, k)]
        lam[again], close = _newton(np.linalg.eigvals(matrices(again)).astype(complex), *part)
        sure[again] = np.all(close, axis=-1)
        closest[again] = _closest(lam[again])
    # a pair whose Newton steps crossed the axis: the upper one first again (each
    # pair once: a pair repeated, p p̄ p p̄, keeps its order)
    for i, pair in enumerate(_pairs(lam)):
        flip = pair & (lam[:, i].imag < 0.0)
        lam[flip, i : i + 2] = lam[flip, i : i + 2][:, ::-1]
    # every row's modes in conjugate pairs (an underdamped block): what follows is
    # taken for the first of each pair, and the partner's is its conjugate (each
    # product, quotient and size below gives the conjugate's the conjugate result,
    # bit for bit but for the sign of a zero part: a real times a complex number
    # is a complex product, whose 0·imaginary part keeps its sign)
    paired = _paired(lam)
    at = lam[:, ::2] if paired else lam
    with np.errstate(all="ignore"):  # (a zero pencil, two modes alike: they meet)
        q = _pencil(at, m, c, k)
        terms = _terms(at, m, c, k)
        sure &= np.all(_uncertainty(at, q, terms, m, c) <= RESOLVED * np.abs(at), axis=-1)
        vectors, inverse = _vectors(at, q, terms, m, c, k)
    if paired:
        vectors, inverse = _unfold(vectors, -1), _unfold(inverse, 1)
    return lam, vectors, sure, inverse, closest


def _pairs(lam: np.ndarray) -> list[np.ndarray]:
    """For each mode i but the last, the rows where it and mode i + 1 are a conjugate
    pair (not real; each mode in one pair at most, the first it can be in)."""
    pairs, taken = [], np.zeros(len(lam), dtype=bool)
    for i in range(lam.shape[-1] - 1):
        taken = ~taken & (lam[:, i + 1] == np.conj(lam[:, i])) & (lam[:, i].imag != 0.0)
        pairs.append(taken)
    return pairs


def _paired(lam: np.ndarray, none_real: bool = False) -> bool:
    """Whether every row's modes are conjugate pairs, side by side (and, with
    ``none_real``, none of them real)."""
    if lam.shape[-1] % 2:
        return False
    paired = bool(np.all(lam[:, 1::2] == np.conj(lam[:, ::2])))
    return paired and (not none_real or bool(np.all(lam[:, ::2].imag != 0.0)))


def _unfold(half: np.ndarray, axis: int) -> np.ndarray:
    """The first of each conjugate pair along ``axis``, and its partner beside it."""
    shape = list(half.shape)
    shape[axis] *= 2
    both = np.empty(shape, dtype=complex)
    first, second = [slice(None)] * half.ndim, [slice(None)] * half.ndim
    first[axis], second[axis] = slice(0, None, 2), slice(1, None, 2)
    both[tuple(first)], both[tuple(second)] = half, np.conj(half)
    return both


def _closest(eigenvalues: np.ndarray) -> np.ndarray:
    """The least distance between two eigenvalues of each row, relative to the
    larger of the two (1 where a row has one)."""
    first, second = np.triu_indices(eigenvalues.shape[-1], 1)  # each pair once
    lam, other = eigenvalues[:, first], eigenvalues[:, second]
    with np.errstate(all="ignore"):
        ratio = np.abs(lam - other) / np.maximum(np.abs(lam), np.abs(other))
    return np.min(np.where(np.isnan(ratio), 0.0, ratio), axis=-1, initial=1.0)


Entries = list[list[np.ndarray]]  # a 2×2 (or 1×1) matrix by its entries, (m, 1) each


def _roots(m: Entries, c: Entries, k: Entries) -> np.ndarray:
    """The roots of det(λ²M + λC + K) of each row, (m, 2n) complex: a conjugate pair
    side by side (the one above the axis first), conjugate bit for bit. The
    quadratic of one coordinate by its stable form; the quartic of two as two real
    quadratics, by Ferrari's resolvent cubic (its largest real root) in λ scaled by
    the roots' geometric mean. NaN where a number is not finite, or K of two
    coordinates is singular; a zero root where K of one is zero."""
    if len(m) == 1:
        p, q = c[0][0] / m[0][0], k[0][0] / m[0][0]
        return _quadratic_roots(p[:, 0], q[:, 0])
    with np.errstate(all="ignore"):
        a4 = m[0][0] * m[1][1] - m[0][1] * m[1][0]
        a3 = m[0][0] * c[1][1] + c[0][0] * m[1][1] - m[0][1] * c[1][0] - c[0][1] * m[1][0]
        a2 = (m[0][0] * k[1][1] + c[0][0] * c[1][1] + k[0][0] * m[1][1]
              - m[0][1] * k[1][0] - c[0][1] * c[1][0] - k[0][1] * m[1][0])  # fmt: skip
        a1 = c[0][0] * k[1][1] + k[0][0] * c[1][1] - c[0][1] * k[1][0] - k[0][1] * c[1][0]
        a0 = k[0][0] * k[1][1] - k[0][1] * k[1][0]
        scale = np.sqrt(np.sqrt(np.abs(a0 / a4)))[:, 0]
        b = (a3 / a4)[:, 0] / scale
        c2 = (a2 / a4)[:, 0] / scale**2
        d = (a1 / a4)[:, 0] / scale**3
        e = (a0 / a4)[:, 0] / scale**4
        # x⁴ + bx³ + c₂x² + dx + e = (x² + bx/2 + y/2)² - (αx + β)² where y is a root
        # of y³ - c₂y² + (bd - 4e)y - (b²e - 4c₂e + d²) = 0 that makes α² ≥ 0
        y = _largest_real_root(-c2, b * d - 4.0 * e, -(b * b * e - 4.0 * c2 * e + d * d))
        alpha = np.sqrt(np.maximum(0.25 * b * b - c2 + y, 0.0))
        beta = np.where(
            alpha > 0.0,
            (0.5 * b * y - d) / (2.0 * alpha),
            np.sqrt(np.maximum(0.25 * y * y - e, 0.0)),
        )
        # the factor with the larger roots keeps its digits; the other loses them to
        # the cancellation the first has not: it is taken from the quartic's last
        # two coefficients by the first (q₁q₂ = e, p₁q₂ + p₂q₁ = d)
        p1, q1 = 0.5 * b - alpha, 0.5 * y - beta
        p2, q2 = 0.5 * b + alpha, 0.5 * y + beta
        swap = np.abs(q1) > np.abs(q2)
        p1, p2 = np.where(swap, p2, p1), np.where(swap, p1, p2)
        q1, q2 = np.where(swap, q2, q1), np.where(swap, q1, q2)
        q1 = e / q2
        p1 = (d - p2 * q1) / q2
        low, high = _quadratic_roots(p1, q1), _quadratic_roots(p2, q2)
        return np.concatenate([low, high], axis=-1) * scale[:, None]


def _quadratic_roots(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """The roots of x² + px + q, (m, 2): a conjugate pair (+ first) where they are
    complex, else the larger by -(p/2 ± √·) and the other by q over it."""
    with np.errstate(all="ignore"):
        half = 0.5 * p
        disc = half * half - q
        root = np.sqrt(np.abs(disc))
        larger = -(half + np.copysign(root, half))
        real = np.stack([larger, q / larger], axis=-1).astype(complex)
        pair = np.stack([-half + 1j * root, -half - 1j * root], axis=-1)
        return np.where((disc < 0.0)[:, None], pair, real)


def _largest_real_root(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The largest real root of y³ + ay² + by + c (one real root: Cardano's, without
    its cancellation; three: the trigonometric form's largest), then two Newton
    steps."""
    with np.errstate(all="ignore"):
        shift = a / 3.0
        p = b - a * shift
        q = c - shift * (b - 2.0 * shift * shift)  # 2a³/27 - ab/3 + c
        disc = 0.25 * q * q + p * p * p / 27.0
        u = np.cbrt(-0.5 * q - np.copysign(np.sqrt(np.maximum(disc, 0.0)), q))
        one = u - p / (3.0 * np.where(u == 0.0, 1.0, u))
        radius = np.sqrt(np.maximum(-p / 3.0, 0.0))
        cosine = np.clip(-0.5 * q / np.where(radius == 0.0, 1.0, radius**3), -1.0, 1.0)
        three = 2.0 * radius * np.cos(np.arccos(cosine) / 3.0)
        y = np.where(disc > 0.0, one, three) - shift
        for _ in range(2):
            value = ((y + a) * y + b) * y + c
            slope = (3.0 * y + 2.0 * a) * y + b
            step = value / slope
            y = np.where(np.isfinite(step), y - step, y)
        return y


def _pencil(lam: np.ndarray, m: Entries, c: Entries, k: Entries) -> Entries:
    """The entries of λ²M + λC + K at each eigenvalue."""
    square, size = lam * lam, range(len(m))
    return [[square * m[i][j] + lam * c[i][j] + k[i][j] for j in size] for i in size]


def _determinant(
    lam: np.ndarray, q: Entries, m: Entries, c: Entries
) -> tuple[np.ndarray, np.ndarray]:
    """det(λ²M + λC + K) from its entries ``q`` at λ, and its slope in λ (the
    entries' own slope 2λM + C)."""
    double, size = 2.0 * lam, range(len(m))
    dq = [[double * m[i][j] + c[i][j] for j in size] for i in size]
    if len(m) == 1:
        return q[0][0], dq[0][0]
    det = q[0][0] * q[1][1] - q[0][1] * q[1][0]
    slope = dq[0][0] * q[1][1] + q[0][0] * dq[1][1] - dq[0][1] * q[1][0]
    return det, slope - q[0][1] * dq[1][0]


def _newton(lam: np.ndarray, m: Entries, c: Entries, k: Entries) -> tuple[np.ndarray, np.ndarray]:
    """Newton steps on det(λ²M + λC + K) from each start, and whether a step has come
    under 1e-8 of each eigenvalue.

    eigvals has each λ to about ε·‖A‖, so a slow mode of a stiff system only to
    ε·|λ_fast/λ_slow| of itself (the closed form has most to a few ε); a step
    squares that (the determinant of at most 2×2 carries rounding of its terms'
    size only). Up to NEWTON_STEPS, each taken only where it is under 1 % of λ; an
    eigenvalue stops once its step is under 1e-14 of it (its own steps, whatever
    the block holds: a row alone gets the same digits; after the first step only
    the rows still going are stepped). From eigvals, |λ_fast/λ_slow| up to about
    10¹² keeps the slow mode to its rounding (a review: 6.7·10⁻¹² at 10¹³); beyond
    10¹³ or so eigvals' own first error is over 1 %: the row is not sure."""
    lam = lam.copy()
    close = np.zeros(lam.shape, dtype=bool)  # a step has been under 1e-8 of λ
    going = np.ones(lam.shape, dtype=bool)
    rows = np.arange(len(lam))  # the rows with an eigenvalue going (after a step: few)
    at, entries = lam, [m, c, k]
    for step_number in range(NEWTON_STEPS):
        if step_number:
            rows = rows[np.any(going, axis=-1)]
            if not rows.size:
                break
            at, going = lam[rows], going[np.any(going, axis=-1)]
            entries = [[[x[rows] for x in row] for row in matrix] for matrix in (m, c, k)]
        q = _pencil(at, *entries)
        det, slope = _determinant(at, q, *entries[:2])
        with np.errstate(all="ignore"):
            step = det / slope
            size = np.abs(step) / np.abs(at)
        taken = going & np.isfinite(step) & (size <= 1e-2)
        lam[rows] = np.where(taken, at - step, at)
        close[rows] |= taken & (size <= 1e-8)
        going = taken & (size > 1e-14)
    return lam, close


def _terms(lam: np.ndarray, m: Entries, c: Entries, k: Entries) -> Entries:
    """|λ|²|M| + |λ||C| + |K| entry by entry: what the pencil's entries round of."""
    at = np.abs(lam)
    size, n = at * at, range(len(m))
    return [[size * np.abs(m[i][j]) + at * np.abs(c[i][j]) + np.abs(k[i][j]) for j in n] for i in n]


def _uncertainty(lam: np.ndarray, q: Entries, terms: Entries, m: Entries, c: Entries) -> np.ndarray:
    """How far each eigenvalue may lie from the root of det(λ²M + λC + K) for the
    rounding of that determinant alone: 4ε times the terms it rounds of (each
    product of its entries' terms by the other entry's size) over its slope. A
    slow mode of an all but singular K (the determinant a small difference of
    large products) is uncertain far beyond its own size; one of widely spread
    modes is not. A bound, not an estimate: on a review's rows it was 54–86 times
    the eigenvalue's true error (median; 2.5–1000 times in all), so that some
    scenes it refuses would have had 8 digits; taken as the rounding's typical
    size (ε times the root of the squares) it let through, among 360 such rows,
    33 whose maxima were more than 1e-8 off, up to 17 %."""
    slope = _determinant(lam, q, m, c)[1]
    if len(m) == 1:
        noise = terms[0][0]
    else:
        noise = terms[0][0] * np.abs(q[1][1]) + np.abs(q[0][0]) * terms[1][1]
        noise = noise + terms[0][1] * np.abs(q[1][0]) + np.abs(q[0][1]) * terms[1][0]
    return 4.0 * np.finfo(float).eps * noise / np.abs(slope)


def _vectors(
    lam: np.ndarray, q: Entries, terms: Entries, m: Entries, c: Entries, k: Entries
) -> tuple[np.ndarray, np.ndarray]:
    """The unit eigenvectors (x, λx) as columns, (m, 2n, 2n): x over its norm
    times √(1 + |λ|²), and λ times that (``q``: the pencil's entries at λ,
    ``terms``: :func:`_terms`); and their inverse, whose row for λ is the left
    eigenvector (w(λM + C), wM) over w(2λM + C)x, w the left null vector of the
    pencil (wA = λw for w's row of A's first-order form, and its product with
    (x, λx) is w(2λM + C)x)."""
    rows, modes = lam.shape
    n = len(q)
    if n == 1:
        x = [np.ones(lam.shape, dtype=complex)]
        w = x
    else:
        # Either row turned a right angle is a null vector; the other row's residual
        # is |det| for both. The one chosen makes that residual the least against
        # the other row's terms (|λ|²|M| + |λ||C| + |K|, what its rounding is of):
        # the larger row outright can be mostly the rounding of λ² + k₁. The left
        # null vector the same way, by columns.
        first_row = terms[1][0] * np.abs(q[0][1]) + terms[1][1] * np.abs(q[0][0])
        second_row = terms[0][0] * np.abs(q[1][1]) + terms[0][1] * np.abs(q[1][0])
        top = first_row >= second_row
        x = [np.where(top, q[0][1], q[1][1]), -np.where(top, q[0][0], q[1][0])]
        first_column = terms[0][1] * np.abs(q[1][0]) + terms[1][1] * np.abs(q[0][0])
        second_column = terms[0][0] * np.abs(q[1][1]) + terms[1][0] * np.abs(q[0][1])
        left = first_column >= second_column
        w = [np.where(left, q[1][0], q[1][1]), -np.where(left, q[0][0], q[0][1])]
    length = sum(part.real * part.real + part.imag * part.imag for part in x)
    length = np.sqrt(length * (1.0 + (lam.real * lam.real + lam.imag * lam.imag)))
    vectors = np.empty((rows, 2 * n, modes), dtype=complex)
    for i, part in enumerate(x):
        vectors[:, i] = part / length
        vectors[:, n + i] = lam * vectors[:, i]
    wm = [sum(w[i] * m[i][j] for i in range(n)) for j in range(n)]  # wM
    wc = [sum(w[i] * c[i][j] for i in range(n)) for j in range(n)]  # wC
    across = sum((2.0 * lam * wm[j] + wc[j]) * x[j] for j in range(n))  # w(2λM + C)x
    scale = length / across
    inverse = np.empty((rows, modes, 2 * n), dtype=complex)
    for j in range(n):
        # w(λM + C) = -wK/λ: of the two, the one that cancels the less (λwM + wC of
        # a fast overdamped mode, λ ≈ -c/m, is a small difference of large terms)
        direct = lam * wm[j] + wc[j]
        wk = sum(w[i] * k[i][j] for i in range(n))
        via_k = -wk / lam
        kept_direct = np.abs(direct) * sum(np.abs(w[i]) * np.abs(k[i][j]) for i in range(n))
        kept_k = np.abs(wk) * (np.abs(lam) * np.abs(wm[j]) + np.abs(wc[j]))
        inverse[:, :, j] = np.where(kept_direct >= kept_k, direct, via_k) * scale
        inverse[:, :, n + j] = wm[j] * scale
    return vectors, inverse
