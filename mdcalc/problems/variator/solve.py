"""The solver: the parts the case has, their Methods, and the result."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from mdcalc.core import periodic
from mdcalc.core.units import rpm_to_rad_s
from mdcalc.core.xp import of
from mdcalc.methods import Method, compare
from mdcalc.output.report import MethodQuantity, MethodsTable, Note
from mdcalc.problems.variator.absorber import (
    AbsorberScene,
    absorber_scene,
    chain_amplitudes,
    seed_amplitudes,
)
from mdcalc.problems.variator.case import Absorber, Case, Motor
from mdcalc.problems.variator.drive import (
    CLUTCH,
    CLUTCH_OF_THREE,
    DriveScene,
    ThreeMass,
    _drive_methods,
    drive_values,
    three_mass_values,
)
from mdcalc.problems.variator.motor import motor_models
from mdcalc.problems.variator.transfer import transfer_of


@dataclass
class Result:
    case: Case
    absorber: AbsorberScene | None = None
    absorber_methods: MethodsTable | None = None
    drive: DriveScene | None = None
    two_mass: periodic.Periodic | None = None
    two_mass_methods: MethodsTable | None = None
    three_mass: ThreeMass | None = None
    three_mass_state: periodic.Periodic | None = None
    three_mass_methods: MethodsTable | None = None
    chi_after_kept_damping: float | None = None  # b₁ of the two-mass model kept
    motor_methods: MethodsTable | None = None
    notes: list[Note] = field(default_factory=list)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


AMPLITUDES = [
    MethodQuantity("a1", "|A₁|", "rad"),
    MethodQuantity("a2", "|A₂|", "rad"),
]

MOTOR = [
    MethodQuantity("critical_slip", "S_K", ""),
    MethodQuantity("damping", "b_D", "N·m·s/rad"),
]


def drive_scene(case: Case, with_machine: bool) -> DriveScene:
    assert case.mechanism is not None and case.drive is not None
    d = case.drive
    inertia = d.driven_inertia
    if with_machine and case.antiresonance is not None:
        i = case.antiresonance.ratio
        inertia = inertia + i * i * case.antiresonance.machine_inertia
    psi = d.clutch_loop_area_ratio
    if psi is None and case.clutch is not None:
        psi = case.clutch.loop_area_ratio
    if d.clutch_damping is not None:
        damping = d.clutch_damping
    elif psi is not None:  # (8.44) with the two-mass model's J
        damping = psi / (2.0 * math.pi) * of(inertia, d.stiffness).sqrt(inertia * d.stiffness)
    else:
        damping = 0.0
    return DriveScene(
        rpm_to_rad_s(case.mechanism.input_speed_rpm),
        transfer_of(case.mechanism),
        inertia,
        d.stiffness,
        damping,
        d.load_torque,
    )


def solve(case: Case) -> Result:
    result = Result(case)
    try:
        if case.absorber is not None:
            _solve_absorber(case.absorber, result)
        if case.motor is not None:
            result.motor_methods = _motor_methods(case.motor)
        if case.drive is not None:
            _solve_drive(case, result)
    except (periodic.Unbounded, periodic.Unresolved) as reason:
        result.status, result.message = "no-answer", str(reason)
    return result


def _motor_methods(motor: Motor) -> MethodsTable:
    def method(index: int) -> Method:
        def run() -> dict[str, float]:
            m = motor_models(motor)[2][index]
            return {"critical_slip": m.critical_slip, "damping": m.damping}

        return Method(motor_models(motor)[2][index].name, run, reference=index == 0)

    return compare(
        "Motor as a spring-damper: the seed's forms beside plain Kloss (differences, not errors)",
        "motor",
        MOTOR,
        [method(index) for index in range(3)],
    )


def _solve_absorber(a: Absorber, result: Result) -> None:
    s = absorber_scene(a)
    result.absorber = s
    if s.determinant_is_zero(s.omega):
        low, high = s.resonances()
        raise periodic.Unbounded(
            f"undamped resonance of the two-disk system: ω = {s.omega:.6g} rad/s is one of its "
            f"natural frequencies {low:.6g} and {high:.6g} rad/s (Δ = 0 in (8.38)), the "
            "amplitudes are unbounded; retune the absorber or give it absorber_damping"
        )
    result.absorber_methods = compare(
        "Methods: absorber amplitudes at ω",
        "absorber",
        AMPLITUDES,
        [
            Method(
                "closed form, complex (8.38) with damping",
                lambda: {"a1": abs(s.amplitudes(s.omega)[0]), "a2": abs(s.amplitudes(s.omega)[1])},
                reference=True,
            ),
            Method("(8.38) as printed", lambda: seed_amplitudes(s), note="no damping"),
            Method("linear solve, shared chain core", lambda: chain_amplitudes(s)),
        ],
    )
    if s.tuned and s.bg == 0.0:
        result.absorber_methods.rows[0].note = "tuned: A₁ = 0 exactly"


def _solve_drive(case: Case, result: Result) -> None:
    assert case.drive is not None
    drive = drive_scene(case, with_machine=True)
    result.drive = drive
    system = drive.two_mass()
    exact = periodic.exact_periodic(system)
    result.two_mass = exact
    result.two_mass_methods = compare(
        "Methods: χ of the two-mass model, periodic state",
        "two_mass",
        [MethodQuantity("chi", "χ = q_max/q_c", "")],
        _drive_methods(system, exact, [("chi", CLUTCH, drive.static)], case.drive),
    )
    if case.antiresonance is None:
        return
    base, three = _three_mass(case)
    result.three_mass = three
    system3 = three.system()
    exact3 = periodic.exact_periodic(system3)
    result.three_mass_state = exact3
    observables = [
        ("chi_after", CLUTCH_OF_THREE, base.static),
        ("coupling_factor", three.coupling(), base.load),
    ]
    if _damping_from_loop(case) and base.damping != drive.damping:
        state = periodic.exact_periodic(_kept(base, drive, three).system())
        clutch = periodic.maximum_of(state, CLUTCH_OF_THREE, state.fastest).value
        result.chi_after_kept_damping = clutch / base.static
    result.three_mass_methods = compare(
        "Methods: the three-mass model, periodic state",
        "three_mass",
        [
            MethodQuantity("chi_after", "χ on the clutch", ""),
            MethodQuantity("coupling_factor", "coupling M_max/M_c", ""),
        ],
        _drive_methods(system3, exact3, observables, case.drive),
    )


def _three_mass(case: Case) -> tuple[DriveScene, ThreeMass]:
    """The two-mass model without the machine, and the three-mass design on it."""
    assert case.antiresonance is not None
    ar = case.antiresonance
    # (8.44) with the J the clutch faces: J₂ alone now (J₂ + i²J₃ before); a clutch
    # damping given as b is the same in both
    base = drive_scene(case, with_machine=False)
    # x·x, not x**2: Python's power of a float (libm pow) and numpy's of an array
    # (a product) may round apart by an ulp, which the stiff three-mass model amplifies
    square = ar.ratio * ar.ratio
    j3 = square * ar.machine_inertia
    if ar.coupling_stiffness is not None:
        c2 = square * ar.coupling_stiffness
    else:
        c2 = base.fundamental * base.fundamental * base.inertia * j3 / (base.inertia + j3)
    return base, ThreeMass(base, j3, c2, square * ar.coupling_damping, ar.ratio)


def _damping_from_loop(case: Case) -> bool:
    """b₁ comes from ψ by (8.44), and so differs with the inertia the clutch faces."""
    assert case.drive is not None
    if case.drive.clutch_damping is not None:
        return False
    return case.drive.clutch_loop_area_ratio is not None or (
        case.clutch is not None and case.clutch.loop_area_ratio is not None
    )


def _kept(base: DriveScene, drive: DriveScene, three: ThreeMass) -> ThreeMass:
    """The three-mass design had the clutch kept b₁ of the two-mass model: the other
    reading of (8.44)."""
    kept = DriveScene(
        base.omega, base.transfer, base.inertia, base.stiffness, drive.damping, base.load
    )
    return ThreeMass(kept, three.j3, three.c2, three.b2, three.ratio)


def drive_block(case: Case, size: int, asked: Callable[[str], bool]) -> tuple[dict[str, Any], Any]:
    """The numbers of the two-mass model and of the three-mass design over a block
    of ``size`` scenes (the case's numbers arrays over its rows), of the sections
    ``asked`` for by their keys' prefix; and the rows without a periodic state,
    asked for or not (their scene has no answer: solved alone)."""
    drive = drive_scene(case, with_machine=True)
    two = periodic.exact_block(drive.two_mass(), size)
    declined = two.failure != periodic.SOLVED
    if case.antiresonance is not None:
        base, three = _three_mass(case)
        state = periodic.exact_block(three.system(), size)
        declined = declined | (state.failure != periodic.SOLVED)
        variant = None
        if _damping_from_loop(case):  # where b₁ differs, the other reading of (8.44)
            variant = periodic.exact_block(_kept(base, drive, three).system(), size)
            differs = np.broadcast_to(base.damping != drive.damping, (size,))
            declined = declined | (differs & (variant.failure != periodic.SOLVED))

    def want(*keys: str) -> bool:
        return any(asked(key) for key in keys)

    nothing = np.full(size, np.nan)  # a maximum no asked-for key needs
    values: dict[str, Any] = {}
    machine = case.antiresonance is not None and asked("antiresonance_")
    if not (asked("drive_") or machine):
        return values, declined
    chi = ("antiresonance_chi_", "antiresonance_reduction")
    before = two.maxima(CLUTCH)[0] if want("drive_", *chi) else nothing
    values = drive_values(drive, before)
    if not machine:
        return values, declined
    # the clutch's and the coupling's maxima share the state's grids
    asked_for = [(CLUTCH_OF_THREE, want(*chi)), (three.coupling(), want("antiresonance_coupling_"))]
    found = iter(state.maxima_of([w for w, wanted in asked_for if wanted]))
    clutch, coupling = (next(found)[0] if wanted else nothing for _, wanted in asked_for)
    kept = None
    if variant is not None:
        kept = nothing
        if want("antiresonance_chi_after_kept", "antiresonance_reduction_kept"):
            kept = np.where(differs, variant.maxima(CLUTCH_OF_THREE)[0] / base.static, np.nan)
    return values | three_mass_values(three, before, clutch, coupling, kept), declined
