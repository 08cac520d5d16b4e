"""The report: the sections a mount scene needs."""

from __future__ import annotations

import cmath
import math
from typing import Any

from mdcalc.output.report import Note, Quantities, Quantity, Report
from mdcalc.problems.mount.scene import (
    QUASI_STATIC_FACTOR,
    RAD_S_TO_RPM,
    Scene,
    isolation_numbers,
    response_numbers,
    scene_numbers,
    transmission_numbers,
)
from mdcalc.problems.mount.solve import Result


def report(result: Result) -> Report:
    case, s = result.case, result.scene
    title = case.title or "Engine on elastic mounts"
    n = scene_numbers(s)
    beta, ratio = n["natural_frequency"], n["frequency_ratio"]
    sections: list[Any] = [
        Quantities(
            "Scene",
            [
                Quantity("engine_mass", "Engine mass M", n["engine_mass"], "kg"),
                Quantity("piston_mass", "Piston mass m", n["piston_mass"], "kg"),
                Quantity("crank_radius", "Crank radius r", n["crank_radius"], "m"),
                Quantity("rod_ratio", "λ = r/l", n["rod_ratio"], ""),
                Quantity("crank_speed", "Crank speed ω", n["crank_speed"], "rad/s"),
                Quantity("crank_speed_rpm", "Crank speed", n["crank_speed_rpm"], "rpm"),
                Quantity("stiffness", "Mount stiffness c", n["stiffness"], "N/m"),
                Quantity(
                    "static_deflection",
                    "Static deflection f = M·g/c",
                    n["static_deflection"],
                    "m",
                ),
            ],
        ),
        Quantities(
            "Natural frequency and resonances",
            [
                Quantity("natural_frequency", "β = √(c/M) = √(g/f)", beta, "rad/s"),
                Quantity("natural_frequency_hz", "β/2π", n["natural_frequency_hz"], "Hz"),
                Quantity(
                    "resonant_speed_1",
                    "Resonance of the 1st harmonic, ω = β",
                    n["resonant_speed_1"],
                    "rad/s",
                    f"{beta * RAD_S_TO_RPM:.5g} rpm",
                ),
                Quantity(
                    "resonant_speed_2",
                    "Resonance of the 2nd harmonic, ω = β/2",
                    n["resonant_speed_2"],
                    "rad/s",
                    f"{beta / 2.0 * RAD_S_TO_RPM:.5g} rpm; (7.74) prints 2·β = {2 * beta:.4g}",
                ),
                Quantity("frequency_ratio", "ω/β", ratio, ""),
            ],
        ),
    ]
    notes: list[Note] = []
    if result.status != "ok":
        return Report("mount", title, sections, notes, result.status, result.message)

    first, second = s.response(1), s.response(2)
    h = response_numbers(s)
    harmonics = [
        Quantity("force_1", "1st harmonic force m·r·ω²", h["force_1"], "N"),
        Quantity("force_2", "2nd harmonic force λ·m·r·ω²", h["force_2"], "N"),
        Quantity(
            "amplitude_1", "|A₁| = m·r·ω²/|c - M·ω²|", h["amplitude_1"], "m", _phase_note(first)
        ),
        Quantity(
            "amplitude_2",
            "|A₂| = λ·m·r·ω²/|c - 4·M·ω²|",
            h["amplitude_2"],
            "m",
            _phase_note(second),
        ),
        Quantity(
            "peak_displacement",
            "Peak |x| over a revolution",
            result.peak[0],
            "m",
            f"{result.peak[0] * 1e3:.4g} mm at crank angle "
            f"{math.degrees(result.peak[1]) % 360:.1f}°",
        ),
    ]
    sections.append(Quantities("Forced vibration (steady state)", harmonics))

    mu = h["dynamic_factor"]
    mu_label = "μ = 1/(1 - ω²·M/c)" if s.zeta == 0.0 else "μ = |A₁|/f_st, damped"
    quasi = abs(mu) <= QUASI_STATIC_FACTOR and ratio < 1.0
    sections.append(
        Quantities(
            "Dynamic factor (7.78) and the quasi-static rule",
            [
                Quantity("dynamic_factor", mu_label, mu, ""),
                Quantity(
                    "quasi_static_ratio",
                    f"μ ≤ {QUASI_STATIC_FACTOR:g} while ω/β ≤ √(1 - 1/1.05)",
                    h["quasi_static_ratio"],
                    "",
                    "the lecture rounds to 0.218",
                ),
                Quantity("quasi_static_speed", "that is ω ≤", h["quasi_static_speed"], "rad/s"),
                Quantity(
                    "quasi_static_period_ratio",
                    "or forcing period over free period ≥",
                    h["quasi_static_period_ratio"],
                    "",
                    "the lecture prints 4.59",
                ),
                Quantity("quasi_static", "Load may be taken as static", quasi, ""),
            ],
        )
    )
    if case.mounts.damping_ratio is not None:
        sections.append(_transmission_section(result))
    if case.isolation is not None:
        sections.append(_isolation_section(s, case.isolation.transmissibility))
    assert result.methods is not None
    sections.append(result.methods)
    if 0.7 < ratio < 1.4 or 0.35 < ratio < 0.7:
        notes.append(
            Note("warning", f"ω/β = {ratio:.3g}: the crank runs near a resonance of the mounts")
        )
    return Report("mount", title, sections, notes)


def _phase_note(amplitude: complex) -> str:
    lag = -math.degrees(cmath.phase(amplitude))
    return f"{abs(amplitude) * 1e3:.4g} mm; lags the force by {lag:.4g}°"


def _transmission_section(result: Result) -> Quantities:
    t = transmission_numbers(result.scene)
    items = [
        Quantity("damping_ratio", "Damping ratio ζ", t["damping_ratio"], ""),
        Quantity("damping_coefficient", "c_d = 2·ζ·√(c·M)", t["damping_coefficient"], "N·s/m"),
    ]
    for order in (1, 2):
        items.append(
            Quantity(
                f"transmissibility_{order}",
                f"Transmissibility, harmonic {order}",
                t[f"transmissibility_{order}"],
                "",
            )
        )
        items.append(
            Quantity(
                f"transmitted_force_{order}",
                f"Force on the frame, harmonic {order}",
                t[f"transmitted_force_{order}"],
                "N",
            )
        )
    items.append(
        Quantity(
            "transmitted_force_peak",
            "Peak force on the frame over a revolution",
            result.force_peak[0],
            "N",
            "dynamic part, on top of the weight",
        )
    )
    return Quantities("Mount damping and force transmission", items)


def _isolation_section(s: Scene, target: float) -> Quantities:
    i = isolation_numbers(s, target)
    return Quantities(
        f"Isolation target (first harmonic, ζ = {s.zeta:g} kept)",
        [
            Quantity("target_transmissibility", "Target transmissibility", target, ""),
            Quantity(
                "required_stiffness", "Mount stiffness needed c", i["required_stiffness"], "N/m"
            ),
            Quantity(
                "required_static_deflection",
                "Static deflection with it",
                i["required_static_deflection"],
                "m",
            ),
            Quantity(
                "required_natural_frequency",
                "Natural frequency with it",
                i["required_natural_frequency"],
                "rad/s",
            ),
        ],
    )
