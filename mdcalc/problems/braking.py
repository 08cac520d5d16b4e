"""``braking``: braking time and distance of a car (seed 000 §7.4, brief §3).

Lecture method (7.48): a constant brake force P_T = k·P_D, no road resistance, no
adhesion limit: t = V0·m/P_T, S = V0²·m/(2·P_T).

Physical model (the reference): the brake force the tyres can pass is limited by
adhesion, F_b = min(F_demand, φ·m·g) (more would lock the wheels); road resistance
ψ·m·g and aerodynamic drag ½·ρ·C_x·A·v² act throughout. The stop has up to three
phases: driver reaction t_r (no brake force), brake build-up t_b (brake force rising
linearly to F_b), full braking. Without drag every phase has a closed form; with
drag the reaction and full-braking phases still do (constant force plus v² drag),
the build-up phase does not, and a tight ODE run is then the reference.
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass, field, replace
from functools import partial
from typing import Any, Literal

from pydantic import Field, model_validator

from mdcalc.core.motion import Phase, constant_force_phase, ramp_phase
from mdcalc.core.ode import IMPORTS as ODE_IMPORTS
from mdcalc.core.units import STANDARD_GRAVITY
from mdcalc.core.xp import of
from mdcalc.domain.tables import ROAD_SURFACES
from mdcalc.domain.vehicle import Drag, SurfaceName, adhesion_of, speed_of
from mdcalc.input.model import CaseBase, CaseModel, exactly_one, with_values
from mdcalc.methods import Method, compare
from mdcalc.output.report import (
    Column,
    MethodQuantity,
    MethodsTable,
    Note,
    Quantities,
    Quantity,
    Report,
    Table,
)

# ------------------------------------------------------------------------ the case


class Vehicle(CaseModel):
    mass: float = Field(gt=0, description="Vehicle mass [kg]")
    initial_speed: float | None = Field(
        default=None, gt=0, description="Speed when braking begins [m/s]"
    )
    initial_speed_kmh: float | None = Field(
        default=None, gt=0, description="Speed when braking begins [km/h]"
    )

    @model_validator(mode="after")
    def _one_speed(self) -> Vehicle:
        exactly_one(
            "vehicle", initial_speed=self.initial_speed, initial_speed_kmh=self.initial_speed_kmh
        )
        return self

    @property
    def speed(self) -> float:
        return speed_of(self.initial_speed, self.initial_speed_kmh)


class Brakes(CaseModel):
    """What the brakes demand; without this section: full braking at the adhesion limit."""

    force: float | None = Field(default=None, gt=0, description="Brake force at the tyres [N]")
    deceleration: float | None = Field(
        default=None, gt=0, description="Demanded deceleration from the brakes [m/s²]"
    )
    traction_force: float | None = Field(
        default=None, gt=0, description="P_D, top-gear traction force (7.35) [N]"
    )
    force_multiple: float | None = Field(
        default=None, gt=0, description="k, brake force as a multiple of P_D (lecture: 10) [-]"
    )

    @model_validator(mode="after")
    def _one_demand(self) -> Brakes:
        lecture = None
        if self.traction_force is not None or self.force_multiple is not None:
            if self.traction_force is None or self.force_multiple is None:
                raise ValueError("traction_force and force_multiple go together (P_T = k·P_D)")
            lecture = self.traction_force * self.force_multiple
        exactly_one(
            "brakes",
            force=self.force,
            deceleration=self.deceleration,
            **{"traction_force with force_multiple": lecture},
        )
        return self

    def demand(self, mass: float) -> float:
        """Brake force the brakes ask of the tyres [N]."""
        if self.force is not None:
            return self.force
        if self.deceleration is not None:
            return mass * self.deceleration
        assert self.traction_force is not None and self.force_multiple is not None
        return self.force_multiple * self.traction_force  # (7.44): P_T = k·P_D


class Road(CaseModel):
    surface: SurfaceName | None = Field(
        default=None, description="Road surface; phi is the low end of its range [-]"
    )
    adhesion: float | None = Field(
        default=None, gt=0, le=2, description="Tyre-road adhesion coefficient phi [-]"
    )
    resistance: float = Field(
        default=0.0, ge=0, lt=1, description="Road resistance coefficient psi, rolling + grade [-]"
    )
    compare_surfaces: bool = Field(
        default=False, description="Add a table of stopping distances over road surfaces [-]"
    )

    @model_validator(mode="after")
    def _one_adhesion(self) -> Road:
        exactly_one("road", surface=self.surface, adhesion=self.adhesion)
        return self

    @property
    def phi(self) -> float:
        return adhesion_of(self.surface, self.adhesion)


class Driver(CaseModel):
    reaction_time: float = Field(default=0.0, ge=0, le=10, description="Driver reaction time [s]")
    build_up_time: float = Field(
        default=0.0, ge=0, le=10, description="Brake build-up time, force rising linearly [s]"
    )


class Case(CaseBase):
    problem: Literal["braking"] = Field(description="Problem name [-]")
    gravity: float = Field(default=STANDARD_GRAVITY, gt=0, description="Gravity g [m/s²]")
    vehicle: Vehicle
    brakes: Brakes | None = None
    road: Road
    drag: Drag | None = None
    driver: Driver | None = None


# ------------------------------------------------------------------------ the scene


@dataclass(frozen=True)
class Scene:
    """The case reduced to SI numbers the methods share."""

    mass: float
    v0: float
    g: float
    phi: float
    psi: float
    demand: float  # brake force asked of the tyres [N]
    brake_force: float  # what adhesion lets through [N]
    drag: float  # k [kg/m]; 0 without drag
    reaction_time: float
    build_up_time: float

    @property
    def road_force(self) -> float:
        return self.psi * self.mass * self.g


def scene_of(case: Case) -> Scene:
    mass, g, phi = case.vehicle.mass, case.gravity, case.road.phi
    adhesion_force = phi * mass * g
    demand = case.brakes.demand(mass) if case.brakes is not None else adhesion_force
    driver = case.driver or Driver()
    return Scene(
        mass=mass,
        v0=case.vehicle.speed,
        g=g,
        phi=phi,
        psi=case.road.resistance,
        demand=demand,
        brake_force=of(demand, adhesion_force).minimum(demand, adhesion_force),
        drag=case.drag.factor if case.drag is not None else 0.0,
        reaction_time=driver.reaction_time,
        build_up_time=driver.build_up_time,
    )


@dataclass(frozen=True)
class Stop:
    reaction: Phase
    build_up: Phase
    braking: Phase

    @property
    def distance(self) -> float:
        return self.reaction.distance + self.build_up.distance + self.braking.distance

    @property
    def time(self) -> float:
        return self.reaction.time + self.build_up.time + self.braking.time

    def values(self) -> dict[str, float]:
        return {"stopping_distance": self.distance, "stopping_time": self.time}


def exact_stop(scene: Scene) -> Stop:
    """Piecewise closed form; exact unless drag acts during a build-up phase."""
    if scene.drag > 0.0 and scene.build_up_time > 0.0:
        raise ValueError("no closed form for the build-up phase with drag")
    return piecewise_stop(scene)


def piecewise_stop(scene: Scene) -> Stop:
    """Reaction, build-up and braking phases by their closed forms; floats, or arrays
    over a sweep's grid (where the caller has ruled out drag during a build-up)."""
    reaction = constant_force_phase(
        scene.v0, scene.road_force, scene.drag, scene.mass, scene.reaction_time
    )
    build_up = ramp_phase(
        reaction.speed, scene.road_force, scene.brake_force, scene.mass, scene.build_up_time
    )
    braking = constant_force_phase(
        build_up.speed, scene.road_force + scene.brake_force, scene.drag, scene.mass, None
    )
    return Stop(reaction, build_up, braking)


def derived(scene: Scene) -> dict[str, Any]:
    """The report's quantities that follow from the scene by a formula, by key; floats,
    or arrays over a sweep's grid."""
    demanded_a = scene.demand / scene.mass
    adhesion_a = scene.phi * scene.g
    lecture = lecture_stop(replace(scene, reaction_time=0.0, build_up_time=0.0))
    return {
        "demanded_deceleration": demanded_a,
        "demanded_deceleration_g": demanded_a / scene.g,
        "lecture_time": lecture["stopping_time"],
        "lecture_distance": lecture["stopping_distance"],
        "adhesion_deceleration": adhesion_a,
        "adhesion_limited_time": scene.v0 / adhesion_a,
        "adhesion_limited_distance": scene.v0**2 / (2.0 * adhesion_a),
        "deceleration": (scene.brake_force + scene.road_force) / scene.mass,
    }


def lecture_stop(scene: Scene) -> dict[str, float]:
    """(7.48) with P_T the demanded force; the textbook V0·t_r + V0·t_b/2 added."""
    braking_time = scene.v0 * scene.mass / scene.demand
    return {
        "stopping_distance": scene.v0 * (scene.reaction_time + 0.5 * scene.build_up_time)
        + 0.5 * scene.v0 * braking_time,
        "stopping_time": scene.reaction_time + 0.5 * scene.build_up_time + braking_time,
    }


def textbook_stop(scene: Scene) -> dict[str, float]:
    """V0·t_r + V0·t_b/2 + V0²/(2a), a from adhesion-limited brakes and road, no drag."""
    a = (scene.brake_force + scene.road_force) / scene.mass
    lead = scene.reaction_time + 0.5 * scene.build_up_time
    return {
        "stopping_distance": scene.v0 * lead + scene.v0**2 / (2.0 * a),
        "stopping_time": lead + scene.v0 / a,
    }


def ode_stop(scene: Scene, rtol: float) -> dict[str, float]:
    """Integrate m·v' = -(F_road + F_brake(t) + k·v²), x' = v phase by phase to v = 0."""
    import numpy as np

    from mdcalc.core.ode import advance, pick_solver

    m, k, base = scene.mass, scene.drag, scene.road_force
    t_r, t_b, f_b = scene.reaction_time, scene.build_up_time, scene.brake_force
    # Upper bound of the stop time: the road and full brake force alone, plus the lead.
    t_bound = t_r + t_b + scene.v0 * m / (base + f_b) * 1.01 + 1.0
    phases = [
        (t_r, lambda t: 0.0),
        (t_r + t_b, lambda t: f_b * (t - t_r) / t_b),
        (t_bound, lambda t: f_b),
    ]
    method = pick_solver(rtol)
    atol = np.array([rtol * scene.v0, rtol * scene.v0 * t_bound]) * 1e-3
    t, y = 0.0, np.array([scene.v0, 0.0])
    for t_end, brake in phases:
        if t_end <= t:
            continue

        def rhs(time: float, state: np.ndarray, brake: Any = brake) -> np.ndarray:
            v = max(state[0], 0.0)
            return np.array([-(base + brake(time) + k * v * v) / m, state[0]])

        segment = advance(
            rhs,
            t,
            y,
            t_end,
            rtol=rtol,
            atol=atol,
            method=method,
            terminal=[(lambda time, state: state[0], -1)],
        )
        t, y = segment.t, segment.y
        if segment.event is not None:
            return {"stopping_distance": float(y[1]), "stopping_time": t}
    raise ArithmeticError("the ODE run did not reach the stop within its time bound")


# ------------------------------------------------------------------------- result


@dataclass
class Result:
    case: Case
    scene: Scene
    stop: dict[str, float]
    phases: Stop | None  # the closed-form phases when the closed form is the reference
    methods: MethodsTable
    surfaces: list[list[Any]] = field(default_factory=list)
    status: Literal["ok", "no-answer"] = "ok"
    message: str | None = None


QUANTITIES = [
    MethodQuantity("stopping_distance", "distance", "m"),
    MethodQuantity("stopping_time", "time", "s"),
]


def solve(case: Case) -> Result:
    scene = scene_of(case)
    has_driver = scene.reaction_time > 0.0 or scene.build_up_time > 0.0
    closed_form_exact = not (scene.drag > 0.0 and scene.build_up_time > 0.0)

    methods = [
        Method(
            "lecture (7.48)",
            lambda: lecture_stop(scene),
            note="k·P_D, no road, no adhesion limit" if case.brakes else "",
        )
    ]
    if has_driver or scene.drag > 0.0:
        methods.append(
            Method(
                "textbook V0·t_r + V0·t_b/2 + V0²/2a",
                lambda: textbook_stop(scene),
                note="no drag" if scene.drag > 0.0 else "",
            )
        )
    if closed_form_exact:
        methods.append(
            Method(
                "exact, piecewise closed form", lambda: exact_stop(scene).values(), reference=True
            )
        )
    if scene.drag > 0.0:
        ladder = partial(ode_stop, scene)  # a function of rtol (--work-precision's rungs)
        methods.append(
            Method(
                "ODE RK45, rtol 1e-3",
                partial(ladder, 1e-3),
                imports=ODE_IMPORTS,
                accuracy=1,
                ladder=ladder,
                rtol=1e-3,
            )
        )
        methods.append(
            Method(
                "ODE RK45, rtol 1e-6",
                partial(ladder, 1e-6),
                imports=ODE_IMPORTS,
                accuracy=2,
                ladder=ladder,
                rtol=1e-6,
            )
        )
        if not closed_form_exact:
            methods.append(
                Method(
                    "ODE DOP853, rtol 1e-10",
                    partial(ladder, 1e-10),
                    imports=ODE_IMPORTS,
                    reference=True,
                    ladder=ladder,
                    rtol=1e-10,
                )
            )
    table = compare("Methods: stopping distance and time", "stop", QUANTITIES, methods)
    reference = next(row for row in table.rows if row.reference)
    stop = {k: float(v) for k, v in reference.values.items() if v is not None}
    return Result(
        case=case,
        scene=scene,
        stop=stop,
        phases=exact_stop(scene) if closed_form_exact else None,
        methods=table,
        surfaces=surface_table(scene) if case.road.compare_surfaces else [],
    )


def surface_table(scene: Scene) -> list[list[Any]]:
    """Stopping distance over road surfaces by the textbook formula (no drag)."""
    rows: list[list[Any]] = []
    for name, phi in ROAD_SURFACES.items():
        distances = []
        for adhesion in (phi.high, phi.low):
            brake_force = min(scene.demand, adhesion * scene.mass * scene.g)
            limited = replace(scene, phi=adhesion, brake_force=brake_force)
            distances.append(textbook_stop(limited)["stopping_distance"])
        locks = scene.demand > phi.low * scene.mass * scene.g
        rows.append([name, phi.low, phi.high, distances[0], distances[1], locks])
    return rows


# ------------------------------------------------------------------------- report


def report(result: Result) -> Report:
    case, scene = result.case, result.scene
    title = case.title or "Braking"
    d = derived(scene)
    lock = scene.demand > scene.phi * scene.mass * scene.g
    road_label = case.road.surface or "given adhesion"

    given = Quantities(
        "Scene",
        [
            Quantity("initial_speed", "Initial speed V0", scene.v0, "m/s"),
            Quantity("initial_speed_kmh", "Initial speed V0", scene.v0 * 3.6, "km/h"),
            Quantity("mass", "Mass m", scene.mass, "kg"),
            Quantity("adhesion", "Adhesion coefficient φ", scene.phi, "", road_label),
        ],
    )
    if scene.psi > 0.0:
        given.items.append(Quantity("road_resistance", "Road resistance ψ", scene.psi, ""))
    if case.drag is not None:
        given.items.append(Quantity("drag_factor", "Drag factor ½·ρ·C_x·A", scene.drag, "kg/m"))

    sections: list[Any] = [given]
    notes: list[Note] = []
    if case.brakes is not None:
        sections.append(
            Quantities(
                "Lecture method (7.48): constant force, no resistance",
                [
                    Quantity("brake_force_demanded", "Brake force demanded P_T", scene.demand, "N"),
                    Quantity(
                        "demanded_deceleration",
                        "Deceleration demanded P_T/m",
                        d["demanded_deceleration"],
                        "m/s²",
                    ),
                    Quantity(
                        "demanded_deceleration_g",
                        "Deceleration demanded",
                        d["demanded_deceleration_g"],
                        "g",
                    ),
                    Quantity("lecture_time", "Braking time t = V0·m/P_T", d["lecture_time"], "s"),
                    Quantity(
                        "lecture_distance",
                        "Braking distance S = V0²·m/(2·P_T)",
                        d["lecture_distance"],
                        "m",
                    ),
                ],
            )
        )
    adhesion_items = [
        Quantity("adhesion_deceleration", "Adhesion limit φ·g", d["adhesion_deceleration"], "m/s²"),
        Quantity(
            "adhesion_limited_time",
            "Time at the adhesion limit V0/(φ·g)",
            d["adhesion_limited_time"],
            "s",
        ),
        Quantity(
            "adhesion_limited_distance",
            "Distance at the adhesion limit V0²/(2·φ·g)",
            d["adhesion_limited_distance"],
            "m",
        ),
    ]
    if case.brakes is not None:
        adhesion_items.insert(
            0,
            Quantity(
                "wheel_lock", "Wheels lock", lock, "", "demand exceeds adhesion" if lock else ""
            ),
        )
        if lock:
            notes.append(Note("warning", _lock_warning(scene)))
    sections.append(Quantities("Adhesion check", adhesion_items))

    stop_items = [
        Quantity("braking_force", "Brake force through the tyres F_b", scene.brake_force, "N"),
        Quantity(
            "deceleration",
            "Deceleration, full braking (no drag)",
            d["deceleration"],
            "m/s²",
        ),
    ]
    if result.phases is not None and (scene.reaction_time > 0 or scene.build_up_time > 0):
        p = result.phases
        stop_items += [
            Quantity(
                "reaction_distance",
                f"Reaction distance, {scene.reaction_time:g} s",
                p.reaction.distance,
                "m",
            ),
            Quantity(
                "build_up_distance",
                f"Build-up distance, {scene.build_up_time:g} s",
                p.build_up.distance,
                "m",
            ),
            Quantity("braking_distance", "Full-braking distance", p.braking.distance, "m"),
        ]
    stop_items += [
        Quantity("stopping_distance", "Stopping distance", result.stop["stopping_distance"], "m"),
        Quantity("stopping_time", "Stopping time", result.stop["stopping_time"], "s"),
    ]
    sections.append(Quantities("Stop (reference method)", stop_items))
    sections.append(result.methods)
    if result.surfaces:
        sections.append(
            Table(
                "Road surfaces (textbook formula, no drag)",
                "surfaces",
                [
                    Column("surface"),
                    Column("φ low"),
                    Column("φ high"),
                    Column("distance at φ high", "m"),
                    Column("distance at φ low", "m"),
                    Column("wheels lock at φ low"),
                ],
                result.surfaces,
            )
        )
    return Report("braking", title, sections, notes, result.status, result.message)


def _lock_warning(scene: Scene) -> str:
    demanded = scene.demand / scene.mass
    limit = scene.phi * scene.g
    lecture_time = scene.v0 * scene.mass / scene.demand
    text = (
        f"the brakes demand {demanded:.4g} m/s² = {demanded / scene.g:.3g}·g, more than "
        f"adhesion allows on this road (φ·g = {limit:.4g} m/s²): the wheels lock and the car "
        f"slides; the braking distance is at least {scene.v0**2 / (2.0 * limit):.3g} m, not "
        f"the {0.5 * scene.v0 * lecture_time:.3g} m in {lecture_time:.3g} s of (7.48)"
    )
    if demanded > 0.9 * scene.g:
        text += "; no road surface gives more than φ = 0.9"
    return text


# ------------------------------------------------------------------------- sweep

#: Keys ``mdcalc sweep`` may vary in the vectorized form, and the scene input each sets.
SWEEP_KEYS = {
    "gravity": "g",
    "vehicle.mass": "mass",
    "vehicle.initial_speed": "v0",
    "vehicle.initial_speed_kmh": "v0_kmh",
    "road.adhesion": "phi",
    "road.resistance": "psi",
    "brakes.force": "force",
    "brakes.deceleration": "deceleration",
    "brakes.traction_force": "traction_force",
    "brakes.force_multiple": "force_multiple",
    "drag.drag_coefficient": "drag_coefficient",
    "drag.frontal_area": "frontal_area",
    "drag.air_density": "air_density",
    "driver.reaction_time": "reaction_time",
    "driver.build_up_time": "build_up_time",
}


def sweep(
    case: Case, grid: dict[str, Any], wanted: Collection[str] | None = None
) -> dict[str, Any] | None:
    """Every numeric result over a grid of scenes at once (numpy): the case with the
    grid's arrays in it goes through the same :func:`scene_of`, :func:`piecewise_stop`
    and :func:`derived` as one scene. None where the sweep needs the ODE (drag during
    a build-up) or varies a key this form does not know."""
    import numpy as np

    if any(key not in SWEEP_KEYS for key in grid):
        return None
    sections = {key.partition(".")[0] for key in grid}
    if "drag" in sections and case.drag is None:
        return None  # a drag section the base case does not have: point by point
    arrays = with_values(
        case, {key: np.asarray(values, dtype=float) for key, values in grid.items()}
    )
    scene = scene_of(arrays)
    shape = np.broadcast_shapes(*(np.shape(value) for value in vars(scene).values()))
    grid_scene: dict[str, Any] = {k: np.broadcast_to(v, shape) for k, v in vars(scene).items()}
    scene = Scene(**grid_scene)
    if np.any((scene.drag > 0.0) & (scene.build_up_time > 0.0)):
        return None  # no closed form for the build-up with drag: point by point (ODE)
    stop = piecewise_stop(scene)
    d = derived(scene)
    # As in the report: a quantity the scene does not show is missing (NaN) there.
    none = np.full(shape, np.nan)
    brakes_only = (lambda values: values) if arrays.brakes is not None else (lambda values: none)
    driver_only = np.where((scene.reaction_time > 0.0) | (scene.build_up_time > 0.0), 1.0, np.nan)
    return {
        "initial_speed": scene.v0,
        "initial_speed_kmh": scene.v0 * 3.6,
        "mass": scene.mass,
        "adhesion": scene.phi,
        "road_resistance": np.where(scene.psi > 0.0, scene.psi, np.nan),
        "drag_factor": scene.drag if arrays.drag is not None else none,
        "brake_force_demanded": brakes_only(scene.demand),
        **{
            key: brakes_only(d[key])
            for key in (
                "demanded_deceleration",
                "demanded_deceleration_g",
                "lecture_time",
                "lecture_distance",
            )
        },
        **{
            key: d[key]
            for key in (
                "adhesion_deceleration",
                "adhesion_limited_time",
                "adhesion_limited_distance",
            )
        },
        "braking_force": scene.brake_force,
        "deceleration": d["deceleration"],
        "reaction_distance": stop.reaction.distance * driver_only,
        "build_up_distance": stop.build_up.distance * driver_only,
        "braking_distance": stop.braking.distance * driver_only,
        "stopping_distance": stop.distance,
        "stopping_time": stop.time,
    }


def template() -> dict[str, Any]:
    return {
        "problem": "braking",
        "title": "Emergency stop from 100 km/h on dry asphalt",
        "vehicle": {"mass": 1500.0, "initial_speed_kmh": 100.0},
        "road": {"surface": "dry-asphalt", "resistance": 0.015},
        "driver": {"reaction_time": 1.0, "build_up_time": 0.2},
    }


def starter_extras() -> dict[str, Any]:
    """Example values ``mdcalc new`` shows commented out beside :func:`template`."""
    return {
        "_source": "illustrative; φ the low end of the surface's range, brief §3",
        "vehicle": {"initial_speed": 27.78},
        "road": {"adhesion": 0.8, "compare_surfaces": True},
        "brakes": {"traction_force": 1644.0, "force_multiple": 10.0,
                   "_or": {"force": 12000.0, "deceleration": 7.0}},
        "drag": {"drag_coefficient": 0.45, "frontal_area": 1.9},
    }  # fmt: skip
