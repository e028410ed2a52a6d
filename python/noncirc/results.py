"""Typed results of `evaluate`, `evaluate_batch` and `optimise`: attributes with units in
their names or beside them, `to_dict()` for plain data and `to_pandas()` for a table
(pandas is optional: it is imported only there).

Column and attribute names end in their unit (`centre_distance_mm`, `picking_angle_deg`,
`picking_tip_speed_m_s`); `_m_s` is metres per second.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

if TYPE_CHECKING:
    import pandas

    from ._noncirc import Scene


def with_unit(name: str, unit: str) -> str:
    """`name` ending in `unit` once: ("module", "mm") -> "module_mm",
    ("picking_tip_speed_m_s", "m/s") -> itself."""
    token = unit.replace("/", "_")
    if not token or name.endswith("_" + token):
        return name
    return f"{name}_{token}"


def _pandas() -> Any:
    try:
        import pandas
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pandas


def _plain(value: Any) -> Any:
    """`value` with arrays as lists, for `to_dict()` (JSON-ready)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    return value


def _number(value: Optional[float], missing: float) -> float:
    """A number from JSON, where NaN and infinities arrive as null: `missing` then."""
    return missing if value is None else value


@dataclass(frozen=True)
class Objective:
    """One agronomic objective of a design: its value, bounds and how far it is from them,
    all in `unit` (mm or deg)."""

    name: str
    value: float
    unit: str
    lower: Optional[float]
    """Lower bound, or None."""
    upper: Optional[float]
    """Upper bound, or None."""
    violation: float
    """How far outside the bounds (0 when met), in `unit`."""
    margin: float
    """How far inside the nearer bound (negative when missed), in `unit`."""

    @property
    def met(self) -> bool:
        return self.violation == 0.0


@dataclass(frozen=True)
class Quantity:
    """A number with its unit."""

    value: float
    unit: str


@dataclass(frozen=True)
class Evaluation:
    """One design evaluated: what `noncirc evaluate --format json` prints, and the arrays
    to draw it. Arrays are per carrier sample (`samples_per_turn` of them) or per point
    of a pitch curve, in mm and degrees; those of a three-arm mechanism are None for a
    moving-box scene."""

    samples_per_turn: int
    feasible: bool
    """Whether every objective and search constraint is met."""
    total_violation: float
    """Sum of the objectives' and the constraints' violations, each in its own unit."""
    centre_distance_mm: float
    objectives: dict[str, Objective]
    """By name, in the paper's order."""
    constraints: dict[str, ConstraintReading]
    """The scene's search constraints (`search.constraints`), keyed as written."""
    events: Optional[dict[str, Any]]
    """Picking and planting: carrier angles, attitudes (deg), the picking window, the tip
    speed (m/s), branch gaps (mm) and the picking check; None without a three-arm train."""
    sections: Optional[dict[str, dict[str, Any]]]
    """The trajectory's sections by name: carrier span, length and heights."""
    measures: dict[str, Quantity]
    """Every measure this design has (`noncirc.measures()` lists them)."""
    carrier_deg: Optional[np.ndarray]
    """(n,) carrier angle of each sample."""
    trajectory: Optional[np.ndarray]
    """(n, 2) arm I's tip (x, y), mm."""
    planet_centres: Optional[np.ndarray]
    """(n, 2) arm I's planet centre (x, y), mm."""
    ratio: Optional[np.ndarray]
    """(n,) speed ratio of the sun–intermediate pair."""
    attitude_deg: Optional[np.ndarray]
    """(n,) arm I's pusher attitude."""
    driver_curve: Optional[np.ndarray]
    """(p, 2) driver pitch curve, mm (to a 1 µm chord)."""
    driven_curve: Optional[np.ndarray]
    """(p, 2) driven pitch curve, mm."""
    second_driver_curve: Optional[np.ndarray]
    """(p, 2) the train with two pairs: the intermediate's layer B, mm (None otherwise)."""
    second_driven_curve: Optional[np.ndarray]
    """(p, 2) the train with two pairs: the planet's pitch curve, mm (None otherwise)."""
    report: dict[str, Any]
    """Exactly `noncirc evaluate --format json`, as nested dicts."""

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> Evaluation:
        objectives = {name: Objective(name=name, **o) for name, o in raw["objectives"].items()}
        measures = {name: Quantity(**m) for name, m in raw["measures"].items()}
        constraints = {text: ConstraintReading(constraint=text, **c) for text, c in raw["constraints"].items()}
        arrays = [
            "carrier_deg",
            "trajectory",
            "planet_centres",
            "ratio",
            "attitude_deg",
            "driver_curve",
            "driven_curve",
            "second_driver_curve",
            "second_driven_curve",
        ]
        return Evaluation(
            samples_per_turn=raw["samples_per_turn"],
            feasible=raw["feasible"],
            total_violation=raw["total_violation"],
            centre_distance_mm=raw["centre_distance_mm"],
            objectives=objectives,
            constraints=constraints,
            events=raw.get("events"),
            sections=raw.get("sections"),
            measures=measures,
            report=raw["report"],
            **{k: raw.get(k) for k in arrays},
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain data (lists, not arrays): JSON-ready."""
        return _plain(self)

    def to_pandas(self) -> pandas.DataFrame:
        """The objectives as a table: one row each, indexed by name, with columns value,
        unit, lower, upper, violation, margin and met."""
        pd = _pandas()
        rows = [dataclasses.asdict(o) | {"met": o.met} for o in self.objectives.values()]
        return pd.DataFrame(rows).set_index("name")

    def samples_to_pandas(self) -> pandas.DataFrame:
        """Per carrier sample: carrier_deg, tip_x_mm, tip_y_mm, planet_x_mm, planet_y_mm,
        ratio and attitude_deg. A ValueError for a scene without a three-arm train."""
        if self.carrier_deg is None:
            raise ValueError("this scene has no three-arm mechanism: it has no samples to tabulate")
        pd = _pandas()
        return pd.DataFrame(
            {
                "carrier_deg": self.carrier_deg,
                "tip_x_mm": self.trajectory[:, 0],
                "tip_y_mm": self.trajectory[:, 1],
                "planet_x_mm": self.planet_centres[:, 0],
                "planet_y_mm": self.planet_centres[:, 1],
                "ratio": self.ratio,
                "attitude_deg": self.attitude_deg,
            }
        )


@dataclass(frozen=True)
class Batch:
    """A batch of designs evaluated: one row per design of `x`, in its order. A design
    the model refuses has `valid` False, its reason in `errors` and NaN values."""

    parameter_names: list[str]
    """The columns of `x`: the scene's free parameters (their names end in their unit)."""
    x: np.ndarray
    """(n, d) the designs, as float64."""
    objective_names: list[str]
    objective_units: list[str]
    values: np.ndarray
    """(n, k) each objective's value, in its unit."""
    violations: np.ndarray
    """(n, k) how far outside its bounds, in its unit (0 when met)."""
    normalised_violations: np.ndarray
    """(n, k) violations divided by each objective's scale (docs/search.md)."""
    constraint_names: list[str]
    """The scene's search constraints as written (`picking_height_mm <= -90`)."""
    constraint_values: np.ndarray
    """(n, c) each constrained measure's value, in its unit (NaN where a design has none)."""
    constraint_normalised_violations: np.ndarray
    """(n, c) how far past its bound, over the constraint's scale (a tenth of the bound, at
    least 1, in the measure's unit; 0 when met)."""
    cv: np.ndarray
    """(n,) the sum of both normalised violations: 0 for a feasible design."""
    goal_names: list[str]
    """The search goals as the quantities they are, named with their units (`module_mm`)."""
    goal_maximised: list[bool]
    """Whether the search makes each goal larger."""
    goal_values: np.ndarray
    """(n, g) the goals' quantities in their units; NaN for a refused design."""
    goals: np.ndarray
    """(n, g) the goals as a search ranks them, all minimised (a maximised goal negated,
    an objective's margin normalised): what pymoo's `F` is."""
    measure_names: list[str]
    measure_units: list[str]
    measures: np.ndarray
    """(n, m) the events, shape and sections measures asked for; NaN where a design has
    none (a refused design, a branch gap that does not exist)."""
    valid: np.ndarray
    """(n,) False where the model refused the design."""
    errors: list[Optional[str]]
    """None, or why the model refused the design."""
    samples_per_turn: int
    trajectories: Optional[np.ndarray] = None
    """(n, samples_per_turn, 2) with `evaluate_batch(..., trajectories=True)`: each design's
    tip path of arm I over one carrier turn from carrier angle 0, in mm in the carrier's
    frame (x horizontal, y up; `evaluate`'s `trajectory`); NaN rows for a refused design.
    None when not asked for."""

    @staticmethod
    def _from_raw(raw: dict[str, Any], parameter_names: list[str], x: np.ndarray) -> Batch:
        fields = {f.name for f in dataclasses.fields(Batch)} - {"parameter_names", "x"}
        # `trajectories` is there only when asked for (its default: None).
        return Batch(parameter_names=parameter_names, x=x, **{k: raw[k] for k in fields if k in raw})

    @property
    def feasible(self) -> np.ndarray:
        """(n,) True where the design is valid and meets every objective and constraint."""
        return self.valid & (self.cv == 0)

    def value(self, name: str) -> np.ndarray:
        """(n,) one objective's or measure's column by name."""
        if name in self.objective_names:
            return self.values[:, self.objective_names.index(name)]
        if name in self.measure_names:
            return self.measures[:, self.measure_names.index(name)]
        known = ", ".join(self.objective_names + self.measure_names)
        raise KeyError(f"{name!r} is neither an objective nor a measure of this batch: {known}")

    def to_dict(self) -> dict[str, Any]:
        """Plain data (lists, not arrays): JSON-ready."""
        return _plain(self)

    def to_pandas(self) -> pandas.DataFrame:
        """One row per design. Columns: the parameters, the objectives' values (named with
        their unit: `picking_angle_deg`), the measures, the constrained measures (named by
        their constraints: `picking_height_mm <= -90`), `cv`, the goals' quantities (named
        with their units: `module_mm`), `valid` and `error`."""
        pd = _pandas()
        columns: dict[str, Any] = {n: self.x[:, j] for j, n in enumerate(self.parameter_names)}
        for j, (n, u) in enumerate(zip(self.objective_names, self.objective_units)):
            columns[with_unit(n, u)] = self.values[:, j]
        for j, (n, u) in enumerate(zip(self.measure_names, self.measure_units)):
            columns[with_unit(n, u)] = self.measures[:, j]
        for j, n in enumerate(self.constraint_names):
            columns[n] = self.constraint_values[:, j]
        columns["cv"] = self.cv
        for j, n in enumerate(self.goal_names):
            columns[n] = self.goal_values[:, j]
        columns["valid"] = self.valid
        columns["error"] = self.errors
        return pd.DataFrame(columns)


@dataclass(frozen=True)
class Goal:
    """A search goal as the quantity it is, and the reported design's value of it."""

    name: str
    """Named with its unit: `module_mm`, `picking_tip_speed_m_s`."""
    unit: str
    maximised: bool
    """Whether the search made it larger."""
    value: Optional[float]
    """The reported design's value, in `unit`."""


@dataclass(frozen=True)
class ConstraintReading:
    """A search constraint (`search.constraints`) and a design's reading of it."""

    constraint: str
    """As written: `picking_height_mm <= -90`."""
    measure: str
    value: float
    """The measure's value, in `unit` (NaN where the design has none)."""
    unit: str
    bound: float
    at_most: bool
    """True for `<=` (the measure at most `bound`), False for `>=`."""
    violation: float
    """How far past the bound, in `unit`: 0 when met (infinite without a value)."""
    margin: float
    """How far inside the bound, in `unit`: negative when missed."""

    @property
    def met(self) -> bool:
        return self.violation == 0.0


@dataclass(frozen=True)
class Design:
    """One design of a confirmed Pareto set."""

    parameters: dict[str, float]
    """The free parameters' values, in the scene's order."""
    goals: dict[str, float]
    """The goals' quantities in their units, by name (`SearchResult.goals`)."""
    cv: float
    """Its violation sum at the confirming resolution: 0 when feasible."""


@dataclass(frozen=True)
class SearchResult:
    """A search's outcome: the design it reports, confirmed at the scene's resolution, and
    its confirmed Pareto set (one design for a single goal)."""

    scene: str
    algorithm: str
    seed: int
    threads: int
    feasible: bool
    """Whether the reported design meets every objective and search constraint at the
    scene's resolution."""
    best: dict[str, float]
    """The reported design's free parameters, in the scene's order."""
    objectives: dict[str, float]
    """Its objectives' values, each in its unit (`Scene.objective_names()` order)."""
    violations: dict[str, float]
    """Its objectives' violations, each in its unit."""
    constraints: list[ConstraintReading]
    """Its search constraints (`search.constraints`), in the scene's order."""
    evaluations: int
    confirmations: int
    first_feasible_evaluations: Optional[int]
    seconds: float
    seconds_to_first_feasible: Optional[float]
    screening_samples_per_turn: int
    confirming_samples_per_turn: int
    stopped_early: bool
    """Whether the progress callback stopped it before its budget."""
    goals: list[Goal]
    """The goals: quantities, units, directions and the reported design's values."""
    pareto: list[Design]
    best_scene: Optional[Scene]
    """The scene with the reported design set: evaluate it, save it, search from it."""

    @staticmethod
    def _from_raw(raw: dict[str, Any], parameter_names: list[str], objective_names: list[str]) -> SearchResult:
        def ordered(values: dict[str, float], names: list[str]) -> dict[str, float]:
            return {n: values[n] for n in names if n in values}

        fields = {f.name for f in dataclasses.fields(SearchResult)}
        plain = {k: v for k, v in raw.items() if k in fields}
        plain["best"] = ordered(raw["best"], parameter_names)
        plain["objectives"] = ordered(raw["objectives"], objective_names)
        plain["violations"] = ordered(raw["violations"], objective_names)
        goals = [Goal(**g) for g in raw["goals"]]
        plain["goals"] = goals
        plain["pareto"] = [
            Design(parameters=ordered(d["parameters"], parameter_names), goals={g.name: v for g, v in zip(goals, d["goal_values"])}, cv=d["cv"])
            for d in raw["pareto"]
        ]
        plain["constraints"] = [
            ConstraintReading(
                constraint=c["label"],
                measure=c["name"],
                value=_number(c["value"], float("nan")),
                unit=c["unit"],
                bound=c["upper"] if c["upper"] is not None else c["lower"],
                at_most=c["upper"] is not None,
                violation=_number(c["violation"], float("inf")),
                margin=_number(c["margin"], float("nan")),
            )
            for c in raw["constraints"]
        ]
        plain["best_scene"] = raw.get("best_scene")
        return SearchResult(**plain)

    @property
    def missed(self) -> list[str]:
        """The objectives the reported design misses, in the paper's order, then the search
        constraints it misses, as written."""
        return [n for n, v in self.violations.items() if v > 0] + [
            c.constraint for c in self.constraints if not c.met
        ]

    def to_dict(self) -> dict[str, Any]:
        """Plain data (the best scene as its TOML text): JSON-ready."""
        d = _plain({f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name != "best_scene"})
        d["best_scene"] = None if self.best_scene is None else self.best_scene.to_toml()
        return d

    def to_pandas(self) -> pandas.DataFrame:
        """The confirmed Pareto set, one row per design: its parameters, its goals'
        quantities (named with their units: `module_mm`) and `cv`."""
        pd = _pandas()
        rows = []
        for d in self.pareto:
            row: dict[str, float] = dict(d.parameters)
            row.update(d.goals)
            row["cv"] = d.cv
            rows.append(row)
        return pd.DataFrame(rows)


@dataclass(frozen=True)
class FitMeasure:
    """One measure of a fit: its value in `unit` (mm or deg) and, where it counts, the
    tolerance it is held to."""

    name: str
    value: float
    unit: str
    tolerance: Optional[float]
    """The tolerance, in `unit`; None for a measure that is reported only (the RMS
    distance, a pose that does not count)."""
    met: Optional[bool]


def _point(v: Any) -> tuple[float, float]:
    """A point of a summary (`{"x", "y"}` or `[x, y]`), mm."""
    return (float(v["x"]), float(v["y"])) if isinstance(v, dict) else (float(v[0]), float(v[1]))

@dataclass(frozen=True)
class PoseFit:
    """Where a key pose was read on the fitted design's path, and its errors."""

    name: str
    carrier_deg: float
    """Carrier angle of arm I where the pose was read."""
    tip_mm: tuple[float, float]
    attitude_deg: float
    """The arm's attitude there: the pusher's dip below the horizontal."""
    position_error_mm: float
    attitude_error_deg: Optional[float]
    """Attitude minus the pose's, if it names one."""
    carrier_error_deg: Optional[float]
    """Carrier angle minus the pose's (wrapped to ±180°), if it names one."""
    counts: bool
    met: bool


@dataclass(frozen=True)
class FitResult:
    """A fit's outcome: the fitted design (`scene`), its fit measures with their
    tolerances, its objectives, its free parameters, and how the search and the
    refinement ran."""

    met: bool
    """Every objective met and every counting part of the target within its tolerance."""
    feasible: bool
    """Every objective met."""
    measures: dict[str, FitMeasure]
    """`path_hausdorff_mm`, `path_rms_mm`, then `poseK_position_mm`,
    `poseK_attitude_deg`, `poseK_carrier_deg` for each pose K (those it names)."""
    poses: list[PoseFit]
    path_hausdorff_mm: float
    path_rms_mm: float
    hausdorff_at_mm: tuple[float, float]
    """The point (of either path) farthest from the other."""
    cost: float
    """Half the squared norm of the residuals, each over its tolerance."""
    objectives: dict[str, Quantity]
    """The fitted design's objectives, each with its unit."""
    violations: dict[str, float]
    design: dict[str, float]
    """The fitted design's free parameters, in the scene's order."""
    evaluations: int
    """Designs the search evaluated."""
    local_evaluations: int
    """Designs the refinement evaluated."""
    seconds: float
    """The search's time (the refinement's is a fraction of it)."""
    algorithm: str
    seed: int
    threads: int
    stopped_early: bool
    refined: bool
    """Whether the refinement's design is the one reported (it stayed feasible and fitted
    better than the search's)."""
    scene: Optional[Scene]
    """The scene with the fitted design set (its target inline)."""

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> FitResult:
        fit = raw.get("fit") or {}
        run = raw["run"]
        local = run.get("local") or {}

        return FitResult(
            met=raw["met"],
            feasible=raw["feasible"],
            measures={m["name"]: FitMeasure(**m) for m in raw["measures"]},
            poses=[
                PoseFit(
                    name=p["name"],
                    carrier_deg=p["carrier_deg"],
                    tip_mm=_point(p["tip_mm"]),
                    attitude_deg=p["attitude_deg"],
                    position_error_mm=p["position_error_mm"],
                    attitude_error_deg=p["attitude_error_deg"],
                    carrier_error_deg=p["carrier_error_deg"],
                    counts=p["counts"],
                    met=p["met"],
                )
                for p in fit.get("poses", [])
            ],
            path_hausdorff_mm=fit.get("path_hausdorff_mm", float("nan")),
            path_rms_mm=fit.get("path_rms_mm", float("nan")),
            hausdorff_at_mm=_point(fit["hausdorff_at_mm"]) if fit else (float("nan"), float("nan")),
            cost=fit.get("cost", float("nan")),
            objectives={o["name"]: Quantity(o["value"], o["unit"]) for o in raw["objectives"]},
            violations={o["name"]: o["violation"] for o in raw["objectives"]},
            design={d["name"]: d["value"] for d in raw["design"]},
            evaluations=run["evaluations"],
            local_evaluations=local.get("evaluations", 0),
            seconds=run["seconds"],
            algorithm=run["algorithm"],
            seed=run["seed"],
            threads=run["threads"],
            stopped_early=run["stopped_early"],
            refined=run["refined"],
            scene=raw.get("best_scene"),
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain data (the scene as its TOML text): JSON-ready."""
        d = _plain({f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name != "scene"})
        d["scene"] = None if self.scene is None else self.scene.to_toml()
        return d

    def to_pandas(self) -> pandas.DataFrame:
        """The fit measures, one row each: name, value, unit, tolerance, met."""
        pd = _pandas()
        return pd.DataFrame([dataclasses.asdict(m) for m in self.measures.values()])


@dataclass(frozen=True)
class Place:
    """Where on the target an inversion's condition fails."""

    path_mm: tuple[float, float]
    """The arc, in mm of arc length from the target's first point as the tip runs it."""
    carrier_deg: Optional[tuple[float, float]]
    """The carrier angles there (a pitch curve's concave arc), if known."""
    point_mm: tuple[float, float]
    """The worst point, mm."""


@dataclass(frozen=True)
class Condition:
    """One condition of the inversion (docs/inverse.md §6)."""

    name: str
    """`pusher_within_arm`, `carrier_advances`, `carrier_turns_once`, `arm_turns_back`,
    `ratio_positive`, `<gear>_convex`, `evaluates`, `path_within_tolerance`, `pose:<name>`
    or `objective:<name>`."""
    holds: bool
    blocks: bool
    """Whether failing it leaves no design that can be made as it is."""
    value: float
    bound: float
    unit: str
    meaning: str
    places: list[Place]


@dataclass(frozen=True)
class InverseResult:
    """The train with two pairs inverted from a target: the geometry the path fixes, the
    forward check, every condition, and the design (`scene`, with both pitch curves as
    tables) when one was built."""

    met: bool
    """Every condition holds and every objective is met."""
    built: bool
    branch: str
    """The elbow's branch from the path's farthest point to its nearest."""
    reversed: bool
    """Whether the target was read backwards to run in the carrier's sense."""
    arm_length_mm: float
    planet_radius_mm: float
    centre_distances_mm: tuple[float, float]
    split: float
    """The first pair's share λ of the overall ratio (0: circular, 1: all of it)."""
    half_weight_harmonic: float
    """The half-weight harmonic of the target's smoothed Fourier series."""
    smoothing_mm: float
    """Largest distance of the target's Fourier series from its points."""
    shaping_mm: float
    """Largest move of the tip by the ratio's shaping for buildable curves (0: not shaped)."""
    pusher_offset_mm: Optional[float]
    """The pusher offset H1 (mm) chosen for the poses' attitudes (None: the scene's kept)."""
    path_hausdorff_mm: Optional[float]
    """The design's path against the target (None: no design)."""
    path_rms_mm: Optional[float]
    conditions: list[Condition]
    scene: Optional[Scene]

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> InverseResult:
        conditions = [
            Condition(
                name=c["name"],
                holds=c["holds"],
                blocks=c["blocks"],
                value=c["value"],
                bound=c["bound"],
                unit=c["unit"],
                meaning=c["meaning"],
                places=[
                    Place(
                        path_mm=(p["path_mm"][0], p["path_mm"][1]),
                        carrier_deg=None if p.get("carrier_deg") is None else tuple(p["carrier_deg"]),
                        point_mm=_point(p["point_mm"]),
                    )
                    for p in c["places"]
                ],
            )
            for c in raw["conditions"]
        ]
        return InverseResult(
            met=raw["met"],
            built=raw["built"],
            branch=raw["branch"],
            reversed=raw["reversed"],
            arm_length_mm=raw["arm_length_mm"],
            planet_radius_mm=raw["planet_radius_mm"],
            centre_distances_mm=tuple(raw["centre_distances_mm"]),
            split=raw["split"],
            half_weight_harmonic=raw["half_weight_harmonic"],
            smoothing_mm=raw["smoothing_mm"],
            shaping_mm=raw["shaping_mm"],
            pusher_offset_mm=raw.get("pusher_offset_mm"),
            path_hausdorff_mm=raw.get("path_hausdorff_mm"),
            path_rms_mm=raw.get("path_rms_mm"),
            conditions=conditions,
            scene=raw.get("scene"),
        )

    def failures(self) -> list[Condition]:
        """The conditions that fail."""
        return [c for c in self.conditions if not c.holds]

    def to_dict(self) -> dict[str, Any]:
        """Plain data (the scene as its TOML text): JSON-ready."""
        d = _plain({f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name != "scene"})
        d["scene"] = None if self.scene is None else self.scene.to_toml()
        return d

    def to_pandas(self) -> pandas.DataFrame:
        """The conditions, one row each: name, holds, blocks, value, bound, unit, and how
        many places it fails at."""
        pd = _pandas()
        return pd.DataFrame(
            [
                {
                    "name": c.name,
                    "holds": c.holds,
                    "blocks": c.blocks,
                    "value": c.value,
                    "bound": c.bound,
                    "unit": c.unit,
                    "places": len(c.places),
                }
                for c in self.conditions
            ]
        )


@dataclass(frozen=True)
class Change:
    """A free parameter's change in a repair."""

    name: str
    symbol: str
    """The papers' symbol (r1 … r12, Φ0, β0, S, H1, γ0), if it has one."""
    before: float
    after: float
    delta: float
    """`after − before`, in the parameter's unit."""
    delta_percent_of_box: float
    """The change as a percentage of the parameter's search interval."""


@dataclass(frozen=True)
class EventShift:
    """Where a repair moved the picking or planting instant."""

    name: str
    position_mm: float
    """Distance between the tips before and after, mm."""
    attitude_deg: float
    """Attitude after minus before, deg."""
    carrier_deg: float
    """Carrier angle after minus before, wrapped to ±180°, deg."""


@dataclass(frozen=True)
class RepairResult:
    """A repair's outcome (docs/inverse.md §5): the given and the repaired design's
    objectives, every change, how far the tip path moved, and the teeth's verdict."""

    repaired: bool
    """Every objective met and the teeth cut and mesh."""
    before: dict[str, Quantity]
    """The given design's objectives."""
    after: dict[str, Quantity]
    """The repaired design's (empty when no design evaluated)."""
    violations_before: dict[str, float]
    violations_after: dict[str, float]
    changes: list[Change]
    """The free parameters' changes, largest (in % of the box) first."""
    path_hausdorff_mm: Optional[float]
    """Hausdorff distance of the repaired tip path from the given one (None: no design)."""
    path_rms_mm: Optional[float]
    events: list[EventShift]
    teeth_failures: Optional[list[str]]
    """The repaired teeth's failed checks (empty: they cut and mesh; None: not cut, as the
    design misses an objective)."""
    teeth_set: list[str]
    """Teeth settings changed so that they cut, as `--set` assignments."""
    evaluations: int
    """Designs searched over every box."""
    seed: int
    threads: int
    scene: Optional[Scene]
    """The given scene with the repaired design (and teeth settings)."""

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> RepairResult:
        run = raw["run"]
        return RepairResult(
            repaired=raw["repaired"],
            before={o["name"]: Quantity(o["value"], o["unit"]) for o in raw["before"]},
            after={o["name"]: Quantity(o["value"], o["unit"]) for o in raw["after"]},
            violations_before={o["name"]: o["violation"] for o in raw["before"]},
            violations_after={o["name"]: o["violation"] for o in raw["after"]},
            changes=[Change(**c) for c in raw["changes"]],
            path_hausdorff_mm=raw.get("path_hausdorff_mm"),
            path_rms_mm=raw.get("path_rms_mm"),
            events=[EventShift(**e) for e in raw["events"]],
            teeth_failures=raw.get("teeth_failures"),
            teeth_set=raw["teeth_set"],
            evaluations=sum(st["evaluations"] for st in raw["stages"]),
            seed=run["seed"],
            threads=run["threads"],
            scene=raw.get("repaired_scene"),
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain data (the scene as its TOML text): JSON-ready."""
        d = _plain({f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name != "scene"})
        d["scene"] = None if self.scene is None else self.scene.to_toml()
        return d

    def to_pandas(self) -> pandas.DataFrame:
        """The changes, one row each: name, symbol, before, after, delta,
        delta_percent_of_box."""
        pd = _pandas()
        return pd.DataFrame([dataclasses.asdict(c) for c in self.changes])


@dataclass(frozen=True)
class Body:
    """A rigid body of one arm set in its own frame (its axle at the origin)."""

    mass_kg: float
    #: Centre of mass (mm), in the body's own frame.
    centroid_mm: tuple[float, float]
    #: Moment of inertia about the centre of mass, normal to the plane (kg·m²).
    inertia_kg_m2: float

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> Body:
        return Body(raw["mass_kg"], tuple(raw["centroid_mm"]), raw["inertia_kg_m2"])


@dataclass(frozen=True)
class GearStrength:
    """One gear's tooth stresses over the carrier turn and their worst (docs/dynamics.md,
    "Tooth strength"): ISO 6336-3 method B on each cut tooth, Hertz at the pitch point."""

    #: `sun`, `intermediate`, `layer B` or `planet`.
    name: str
    teeth: int
    module_mm: float
    #: Root stress of the tooth in mesh at each carrier angle (MPa).
    bending_mpa: np.ndarray
    #: Contact stress of the flank in mesh at each carrier angle (MPa).
    contact_mpa: np.ndarray
    #: The largest root stress (MPa), its tooth (index from the tooth at ψ = 0), carrier
    #: angle (°), and the bending safety factor σFE/σF.
    bending_peak_mpa: float
    bending_worst_tooth: int
    bending_peak_carrier_deg: float
    bending_safety: float
    #: The largest contact stress (MPa), its tooth, carrier angle (°), and σHlim/σH.
    contact_peak_mpa: float
    contact_worst_tooth: int
    contact_peak_carrier_deg: float
    contact_safety: float
    #: The worst tooth's root geometry: root_chord_mm (sFn), lever_mm (hFe),
    #: fillet_radius_mm (ρF), load_angle_deg (αFen), form_factor (YF),
    #: stress_correction (YS), stress_per_newton (MPa/N on 1 mm of face), loaded flank.
    worst_form: dict[str, Any]
    #: The least and largest form factor YF over the gear's teeth.
    form_factor_range: tuple[float, float]

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> GearStrength:
        return GearStrength(
            **{
                **raw,
                "bending_mpa": np.asarray(raw["bending_mpa"], dtype=float),
                "contact_mpa": np.asarray(raw["contact_mpa"], dtype=float),
                "form_factor_range": tuple(raw["form_factor_range"]),
            }
        )


@dataclass(frozen=True)
class Strength:
    """The train's tooth strength at working speed, of the scene's material."""

    material: str
    face_width_mm: float
    #: Application factor KA on the mesh forces.
    application_factor: float
    #: σFE and σHlim (MPa).
    bending_limit_mpa: float
    contact_limit_mpa: float
    gears: list[GearStrength]
    #: The least safety factors over the gears.
    bending_safety_min: float
    contact_safety_min: float

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> Strength:
        return Strength(**{**raw, "gears": [GearStrength._from_raw(g) for g in raw["gears"]]})

    def to_pandas(self) -> pandas.DataFrame:
        """One row per gear: its worst stresses, where, and its safety factors."""
        rows = []
        for g in self.gears:
            row = {k: v for k, v in dataclasses.asdict(g).items() if k not in ("bending_mpa", "contact_mpa", "worst_form")}
            row["form_factor_least"], row["form_factor_largest"] = row.pop("form_factor_range")
            rows.append(row)
        return _pandas().DataFrame(rows)


@dataclass(frozen=True)
class SpeedFluctuation:
    """The carrier's speed over the turn when the drive's torque is constant (its mean)
    and a flywheel sits on the carrier's axis (docs/dynamics.md, "Speed fluctuation and
    the flywheel")."""

    #: The constant drive torque (N·m).
    drive_torque_nm: float
    #: The carrier's own moment of inertia and the flywheel's (kg·m²).
    carrier_inertia_kg_m2: float
    flywheel_inertia_kg_m2: float
    #: The carrier's speed at each of `Dynamics.carrier_deg` (rad/s); its mean over time is
    #: the working speed.
    carrier_speed_rad_s: np.ndarray
    #: (ω_max − ω_min)/ω_mean.
    coefficient: float

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> SpeedFluctuation:
        return SpeedFluctuation(
            drive_torque_nm=raw["drive_torque_nm"],
            carrier_inertia_kg_m2=raw["carrier_inertia_kg_m2"],
            flywheel_inertia_kg_m2=raw["flywheel_inertia_kg_m2"],
            carrier_speed_rad_s=np.asarray(raw["carrier_speed_rad_s"], dtype=float),
            coefficient=raw["coefficient"],
        )


@dataclass(frozen=True)
class Dynamics:
    """The train at its working speed over one carrier turn (`noncirc dynamics`,
    docs/dynamics.md). Arrays run over `carrier_deg`; vectors are (angles, 2) arrays of
    (x, y) in the ground frame, y up. Torques are positive where the drive delivers power."""

    carrier_speed_rad_s: float
    arms: int
    pressure_angle_deg: float
    intermediate: Body
    planet: Body
    arm: Body
    planet_with_arm: Body
    carrier_deg: np.ndarray
    #: Input torque of all arm sets (N·m): Newton–Euler, and the energy balance.
    input_torque_nm: np.ndarray
    input_torque_energy_nm: np.ndarray
    #: Arm set I: the meshes' moments on the intermediate about O2 and on the planet about O3 (N·m).
    intermediate_moment_nm: np.ndarray
    planet_moment_nm: np.ndarray
    #: Arm set I: normal forces along the lines of action, sun–intermediate and
    #: intermediate–planet (N).
    mesh_force_sun_intermediate_n: np.ndarray
    mesh_force_intermediate_planet_n: np.ndarray
    #: Arm set I: the carrier's force on the intermediate's and the planet's axle (N).
    intermediate_axle_n: np.ndarray
    planet_axle_n: np.ndarray
    #: All arm sets: the load on the sun shaft and on the carrier bearing (N).
    sun_shaft_n: np.ndarray
    carrier_bearing_n: np.ndarray
    #: All arm sets: the shaking force (N) and moment about the carrier axis (N·m).
    shaking_force_n: np.ndarray
    shaking_moment_nm: np.ndarray
    #: All arm sets: the moving bodies' kinetic energy over ½ω² (kg·m²), and the torque
    #: gravity and the tip's loads need whatever the speed (N·m).
    reduced_inertia_kg_m2: np.ndarray
    load_torque_nm: np.ndarray
    #: The carrier's speed with a constant drive torque and the scene's flywheel; the least
    #: flywheel (kg·m²) that holds its fluctuation to `speed_fluctuation_allowed`.
    speed: SpeedFluctuation
    flywheel_needed_kg_m2: float
    speed_fluctuation_allowed: float
    #: The cycle's extremes, as `noncirc dynamics` prints them (units in the names).
    summary: dict[str, Any]
    #: The teeth's stresses and safety factors; None when the teeth cannot be cut
    #: (`strength_unavailable` says why).
    strength: Optional[Strength]
    strength_unavailable: Optional[str]
    #: Everything the CLI's JSON holds (the joints' motion too).
    report: dict[str, Any]

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> Dynamics:
        a = lambda key: np.asarray(raw[key], dtype=float)  # noqa: E731
        return Dynamics(
            carrier_speed_rad_s=raw["carrier_speed_rad_s"],
            arms=raw["arms"],
            pressure_angle_deg=raw["pressure_angle_deg"],
            intermediate=Body._from_raw(raw["intermediate"]),
            planet=Body._from_raw(raw["planet"]),
            arm=Body._from_raw(raw["arm"]),
            planet_with_arm=Body._from_raw(raw["planet_with_arm"]),
            carrier_deg=a("carrier_deg"),
            input_torque_nm=a("input_torque_nm"),
            input_torque_energy_nm=a("input_torque_energy_nm"),
            intermediate_moment_nm=a("intermediate_moment_nm"),
            planet_moment_nm=a("planet_moment_nm"),
            mesh_force_sun_intermediate_n=np.asarray(raw["mesh_force_n"][0], dtype=float),
            mesh_force_intermediate_planet_n=np.asarray(raw["mesh_force_n"][1], dtype=float),
            intermediate_axle_n=a("intermediate_axle_n"),
            planet_axle_n=a("planet_axle_n"),
            sun_shaft_n=a("sun_shaft_n"),
            carrier_bearing_n=a("carrier_bearing_n"),
            shaking_force_n=a("shaking_force_n"),
            shaking_moment_nm=a("shaking_moment_nm"),
            reduced_inertia_kg_m2=a("reduced_inertia_kg_m2"),
            load_torque_nm=a("load_torque_nm"),
            speed=SpeedFluctuation._from_raw(raw["speed"]),
            flywheel_needed_kg_m2=raw["flywheel_needed_kg_m2"],
            speed_fluctuation_allowed=raw["speed_fluctuation_allowed"],
            summary=raw["summary"],
            strength=None if raw["strength"] is None else Strength._from_raw(raw["strength"]),
            strength_unavailable=raw.get("strength_unavailable"),
            report=raw,
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain data (lists, not arrays)."""
        return {f.name: _plain(getattr(self, f.name)) for f in dataclasses.fields(self) if f.name != "report"}

    def to_pandas(self) -> pandas.DataFrame:
        """One row per carrier angle; a vector's components as `<name>_x_n` and `<name>_y_n`;
        the carrier's speed with a constant drive torque as `carrier_speed_constant_drive_rad_s`."""
        columns: dict[str, Any] = {"carrier_deg": self.carrier_deg}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if f.name == "carrier_deg" or not isinstance(value, np.ndarray):
                continue
            if value.ndim == 2:
                stem = f.name.removesuffix("_n")
                columns[f"{stem}_x_n"] = value[:, 0]
                columns[f"{stem}_y_n"] = value[:, 1]
            else:
                columns[f.name] = value
        columns["carrier_speed_constant_drive_rad_s"] = self.speed.carrier_speed_rad_s
        return _pandas().DataFrame(columns)


@dataclass(frozen=True)
class CadPart:
    """A part of `noncirc.cad`'s solids: its profile extruded by its thickness (mm)."""

    name: str
    thickness_mm: float
    #: The profile's area (mm²), exactly from its lines and arcs.
    area_mm2: float
    volume_mm3: float


@dataclass(frozen=True)
class CadInstance:
    """A placed copy of a part: its frame's origin (mm) and turn about z (degrees)."""

    name: str
    part: str
    at_mm: tuple[float, float, float]
    angle_deg: float


@dataclass(frozen=True)
class CadResult:
    """What `noncirc.cad` wrote (docs/cad.md): the files, and the teeth's failed checks
    (where there are any, nothing is written unless `force`)."""

    paths: list[Path]
    failures: list[str]
    #: Degrees; None for a gear pair (or where nothing was written).
    carrier_deg: Optional[float]
    parts: list[CadPart]
    instances: list[CadInstance]

    @staticmethod
    def _from_raw(raw: dict[str, Any]) -> CadResult:
        m = raw["manifest"] or {"carrier_deg": None, "parts": [], "instances": []}
        parts = [CadPart(p["name"], p["thickness_mm"], p["area_mm2"], p["volume_mm3"]) for p in m["parts"]]
        return CadResult(
            paths=[Path(p) for p in raw["paths"]],
            failures=list(raw["failures"]),
            carrier_deg=m["carrier_deg"],
            parts=parts,
            instances=[
                CadInstance(i["name"], parts[i["part"]].name, tuple(i["at_mm"]), i["angle_deg"]) for i in m["instances"]
            ],
        )
