"""The exact piecewise solution of the rope model: the rope history (smooth pieces
between lift-off, slack and touch-down), its peak; what ``--plot`` draws and what
checks the Methods' rope rows."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from mdcalc.problems.hoist.rope import RopeScene

#: Smooth pieces of the exact rope solution before it gives up (a chattering rope).
MAX_ROPE_PIECES = 10_000


@dataclass(frozen=True)
class RopePiece:
    """One smooth piece of the exact two-mass solution from ``t0`` to ``t1``: the rope
    taut or slack, the load on the ground or in the air, the drive force ``drive``
    constant. The state at ``t0``: rope stretch u = x1 - y - s and its rate, load
    height y and speed."""

    t0: float
    t1: float
    taut: bool
    grounded: bool
    drive: float  # D [N]
    u: float  # [m]
    du: float  # [m/s]
    y: float  # [m]
    vy: float  # [m/s]


@dataclass(frozen=True)
class RopeHistory:
    """The exact solution of :func:`rope_ode`'s model over the same horizon, piece by
    piece, with its events: (time, what) for "taut", "slack", "lift-off",
    "touch-down" and "start ends"."""

    pieces: list[RopePiece]
    events: list[tuple[float, str]]
    horizon: float
    complete: bool  # False: stopped at MAX_ROPE_PIECES


def _frequency(r: RopeScene, p: RopePiece) -> float:
    """Of a taut piece: β1 = √(c/m1) with the load on the ground, β in the air."""
    return math.sqrt(r.c / r.m1) if p.grounded else r.beta


def _centre(r: RopeScene, p: RopePiece) -> float:
    """Stretch about which a taut piece swings: c·u = D on the ground, and in the
    air c·u = (D·m2 + G·m1)/(m1 + m2) (G + m2·a during the start, G after it)."""
    if p.grounded:
        return p.drive / r.c
    return (p.drive * r.m2 + r.weight * r.m1) / ((r.m1 + r.m2) * r.c)


def _stretch_acceleration(r: RopeScene, p: RopePiece) -> float:
    """u'' of a slack piece: the drive accelerates at D/m1, a flying load falls at g."""
    return p.drive / r.m1 + (0.0 if p.grounded else r.weight / r.m2)


def _stretch(r: RopeScene, p: RopePiece, tau: Any) -> tuple[Any, Any]:
    """u and u' at ``tau`` after the piece's start (float or numpy array)."""
    import numpy as np

    if not p.taut:
        acc = _stretch_acceleration(r, p)
        return p.u + p.du * tau + 0.5 * acc * tau * tau, p.du + acc * tau
    w, centre = _frequency(r, p), _centre(r, p)
    x = w * tau
    a, b = p.u - centre, p.du / w
    return centre + a * np.cos(x) + b * np.sin(x), w * (b * np.cos(x) - a * np.sin(x))


def _load(r: RopeScene, p: RopePiece, tau: Any) -> tuple[Any, Any]:
    """Load height y and speed at ``tau`` after the piece's start. In a taut piece
    y'' = (c·u - G)/m2, integrated with P(x) = x²/2 - (1 - cos x) and
    Q(x) = x - sin x, which keep their accuracy at small x (no cancellation at
    lift-off, where c·u = G)."""
    import numpy as np

    if p.grounded:
        return 0.0 * tau, 0.0 * tau
    g = r.weight / r.m2
    if not p.taut:
        return p.y + p.vy * tau - 0.5 * g * tau * tau, p.vy - g * tau
    w, centre = _frequency(r, p), _centre(r, p)
    x = np.asarray(w * tau, dtype=float)
    small = np.abs(x) < 1e-2
    x2 = x * x
    p_x = np.where(small, x2 * x2 * (1 / 24 - x2 / 720), 0.5 * x2 - (1.0 - np.cos(x)))
    q_x = np.where(small, x * x2 * (1 / 6 - x2 / 120), x - np.sin(x))
    k = r.c / r.m2
    excess = (r.c * p.u - r.weight) / r.m2  # y'' at the piece's start
    a, b = p.u - centre, p.du / w
    y = p.y + p.vy * tau + 0.5 * excess * tau * tau + k * (b * q_x - a * p_x) / (w * w)
    vy = p.vy + excess * tau + k * (b * (1.0 - np.cos(x)) - a * q_x) / w
    return y, vy


def _sine_crossing(r: RopeScene, p: RopePiece, level: float, rising: bool) -> float:
    """First time after a taut piece's start at which u crosses ``level``."""
    w, centre = _frequency(r, p), _centre(r, p)
    a, b = p.u - centre, p.du / w
    amplitude = math.hypot(a, b)
    if amplitude == 0.0:
        return math.inf
    q = (level - centre) / amplitude
    if not -1.0 < q < 1.0:
        return math.inf  # never reached, or only touched
    # u = centre + amplitude·cos(x - φ); rising where sin(x - φ) < 0
    phi = math.atan2(b, a)
    angle = (phi + (-1.0 if rising else 1.0) * math.acos(q)) % (2.0 * math.pi)
    if angle < 1e-9:
        angle += 2.0 * math.pi  # the crossing the piece starts at
    return angle / w


def _quadratic_crossing(p0: float, p1: float, p2: float, rising: bool) -> float:
    """First τ > 0 at which p0 + p1·τ + p2·τ²/2 crosses 0 going up (or down)."""
    roots: list[float] = []
    if p2 == 0.0:
        if p1 != 0.0:
            roots = [-p0 / p1]
    else:
        disc = p1 * p1 - 2.0 * p2 * p0
        if disc < 0.0:
            return math.inf
        q = -0.5 * (p1 + math.copysign(math.sqrt(disc), p1))
        roots = [q / (0.5 * p2), p0 / q] if q != 0.0 else [0.0]
    for root in sorted(roots):
        slope = p1 + p2 * root
        if root > 0.0 and slope != 0.0 and (slope > 0.0) == rising:
            return root
    return math.inf


def _touch_down(r: RopeScene, p: RopePiece, span: float) -> float:
    """First time in (0, span] at which a taut piece's load comes down to the ground.
    y is a trend y0 + v·τ + y''·τ²/2 plus a swing of at most ``reach``: only where the
    trend is below ``reach`` can y reach 0; there it is sampled at 32 points a period,
    and the first sign change bisected."""
    import numpy as np

    w, centre = _frequency(r, p), _centre(r, p)
    k = r.c / (r.m2 * w * w)
    a, b = p.u - centre, p.du / w
    # y = trend(τ) + k·[a·(1 - cos x) - b·sin x] >= trend(τ) - k·(hypot(a, b) - a)
    reach = k * (math.hypot(a, b) - a)
    slope = p.vy + k * w * b
    curvature = (r.c * centre - r.weight) / r.m2
    start, stop = 0.0, span
    if curvature > 0.0:  # the trend is below reach between two roots at most
        disc = slope * slope - 2.0 * curvature * (p.y - reach)
        if disc < 0.0:
            return math.inf
        root = math.sqrt(disc)
        start = max(0.0, (-slope - root) / curvature)
        stop = min(span, (-slope + root) / curvature)
    step = 2.0 * math.pi / w / 32.0
    while start < stop:
        count = min(4096, math.ceil((stop - start) / step))
        tau = np.minimum(start + step * np.arange(1, count + 1), stop)
        heights, _ = _load(r, p, tau)
        below = np.nonzero(heights < 0.0)[0]
        if below.size:
            j = int(below[0])
            lo, hi = (start if j == 0 else float(tau[j - 1])), float(tau[j])
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                if float(_load(r, p, mid)[0]) < 0.0:
                    hi = mid
                else:
                    lo = mid
            return hi
        start = float(tau[-1])
    return math.inf


def rope_history(r: RopeScene, hanging: bool) -> RopeHistory:
    """The exact piecewise solution of :func:`rope_ode`'s two-mass model: in each
    smooth piece the stretch is a sine about its centre (taut rope) or a parabola
    (slack), and the events (rope taut or slack, lift-off, touch-down, the end of
    the start) have closed forms -- a touch-down of a load on a taut rope is
    bisected. The horizon is :func:`rope_ode`'s: the start, then two periods after
    the start or after the last lift-off, whichever is later."""
    t_p, period = r.start_time, 2.0 * math.pi / r.beta
    drive = r.drive_force if t_p > 0.0 else r.weight
    if hanging:
        p = RopePiece(0.0, 0.0, True, False, drive, r.weight / r.c, 0.0, 0.0, 0.0)
        t_lift = 0.0
    else:
        p = RopePiece(0.0, 0.0, r.slack == 0.0, True, drive, -r.slack, 0.0, 0.0, 0.0)
        t_lift = math.inf
    pieces: list[RopePiece] = []
    events: list[tuple[float, str]] = []
    t = 0.0
    while len(pieces) < MAX_ROPE_PIECES:
        if t < t_p:
            limit = t_p
        elif p.grounded:
            limit = math.inf
        else:
            limit = max(t_p, t_lift) + 2.0 * period
            if t >= limit:
                return RopeHistory(pieces, events, t, True)
        found: list[tuple[float, str]] = []
        if p.taut:
            found.append((_sine_crossing(r, p, 0.0, rising=False), "slack"))
            if p.grounded:
                found.append((_sine_crossing(r, p, r.weight / r.c, rising=True), "lift-off"))
        else:
            acc = _stretch_acceleration(r, p)
            found.append((_quadratic_crossing(p.u, p.du, acc, rising=True), "taut"))
        if not hanging and not p.grounded:
            span = min(limit, *(f[0] + t for f in found)) - t
            if p.taut:
                found.append((_touch_down(r, p, span), "touch-down"))
            else:
                g = r.weight / r.m2
                found.append((_quadratic_crossing(p.y, p.vy, -g, rising=False), "touch-down"))
        tau, what = min(found)
        if t + tau >= limit:
            tau, what = limit - t, "start ends" if limit == t_p else "horizon"
        if not math.isfinite(tau):
            break  # nothing more happens (not reached: D >= G keeps it moving)
        u, du = (float(v) for v in _stretch(r, p, tau))
        y, vy = (float(v) for v in _load(r, p, tau))
        pieces.append(RopePiece(t, t + tau, p.taut, p.grounded, p.drive, p.u, p.du, p.y, p.vy))
        t = t_p if what == "start ends" else t + tau
        taut, grounded, drive = p.taut, p.grounded, p.drive
        if what == "start ends":
            drive = r.weight
        elif what == "slack":
            taut, u = False, 0.0
        elif what == "taut":
            taut, u = True, 0.0
        elif what == "lift-off":
            grounded, u, t_lift = False, r.weight / r.c, t
        elif what == "touch-down":  # the load stops on the ground; the drive goes on
            grounded, du, y, vy = True, du + vy, 0.0, 0.0
        if what != "horizon":
            events.append((t, what))
        p = RopePiece(t, t, taut, grounded, drive, u, du, y, vy)
    return RopeHistory(pieces, events, t, False)


def _piece_peak(r: RopeScene, p: RopePiece) -> tuple[float, float]:
    """(time, rope force) of the first maximum of the force over a piece."""
    if not p.taut:
        return p.t0, 0.0
    span = p.t1 - p.t0
    w, centre = _frequency(r, p), _centre(r, p)
    a, b = p.u - centre, p.du / w
    crest = (math.atan2(b, a) % (2.0 * math.pi)) / w  # first τ where u = centre + amplitude
    candidates = [0.0, span] + ([crest] if crest <= span else [])
    forces = [r.c * float(_stretch(r, p, tau)[0]) for tau in candidates]
    best = max(range(len(candidates)), key=lambda j: (forces[j], -candidates[j]))
    return p.t0 + candidates[best], forces[best]


def rope_peak(history: RopeHistory, r: RopeScene) -> tuple[float, float]:
    """(time, force) of the largest rope force over the horizon, its first occurrence
    (during a long start the same crest comes back every period)."""
    peaks = [_piece_peak(r, p) for p in history.pieces]
    top = max(f for _, f in peaks)
    return next((t, f) for t, f in peaks if f >= top * (1.0 - 1e-12))
