"""Tables of coefficients: data, not code paths. Each entry names its source."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Range:
    low: float
    high: float
    source: str

    @property
    def middle(self) -> float:
        return 0.5 * (self.low + self.high)


#: Tyre-road adhesion coefficient phi [-] by road surface. The lecture (seed 000
#: §7.4) gives dry asphalt 0.7-0.9 and ice 0.01-0.03; the rest are the usual
#: handbook ranges for passenger-car tyres.
ROAD_SURFACES: dict[str, Range] = {
    "dry-asphalt": Range(0.7, 0.9, "seed 000 §7.4"),
    "wet-asphalt": Range(0.35, 0.45, "handbook range"),
    "gravel": Range(0.6, 0.7, "handbook range"),
    "dry-dirt": Range(0.5, 0.6, "handbook range"),
    "wet-dirt": Range(0.2, 0.4, "handbook range"),
    "packed-snow": Range(0.2, 0.3, "handbook range"),
    "icy-road": Range(0.08, 0.15, "handbook range"),
    "ice": Range(0.01, 0.03, "seed 000 §7.4 (wet glaze ice)"),
}

#: Allowable load acceleration at start [m/s^2] by machine type (seed 000, after (7.32)).
HOIST_ACCELERATION: dict[str, Range] = {
    "crane": Range(0.1, 0.8, "seed 000 §7.2"),
    "lift": Range(1.5, 2.0, "seed 000 §7.2"),
}

#: Braking safety factor K_t usually chosen by duty class (brief §1).
BRAKE_SAFETY_FACTOR = Range(1.5, 2.5, "PROBLEMS.md §1, (7.27)")
