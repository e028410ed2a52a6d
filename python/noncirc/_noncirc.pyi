"""Type stubs of the compiled extension. Its functions return plain dicts; the package's
own `noncirc.evaluate`, `evaluate_batch` and `optimise` (noncirc/api.py) wrap them into
the typed results of noncirc/results.py."""

import os
from typing import Any, Callable, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

class NoncircError(ValueError):
    """A noncirc input or model error; the message names the bad value. Its subclasses
    say which kind."""

class SceneError(NoncircError):
    """A scene's text, or an edit of it, that cannot be read: its syntax, a value of the
    wrong kind, an unknown built-in; the message names the file and line or the call."""

class ParameterError(NoncircError):
    """A value the model refuses for a setting or a parameter: out of its range, not
    finite, a list entry that cannot stand there."""

class ModelError(NoncircError):
    """A design the model cannot build: a pitch curve that is not positive or not
    star-shaped, a closure the resolution does not resolve, teeth that cannot be cut."""

class UnknownNameError(NoncircError):
    """A scene key, parameter, measure or goal noncirc does not know; the message lists
    the nearest names it does know."""

class InternalError(RuntimeError):
    """A failure inside noncirc, not in what it was given (a value it cannot serialise, a
    lock poisoned by an earlier panic): a bug, to be reported with the call that raised it."""

class Scene:
    """A scene: what is designed and asked, and at which resolution. Immutable; pickles."""

    @staticmethod
    def from_file(path: str) -> Scene: ...
    @staticmethod
    def from_string(text: str, origin: str = "<string>") -> Scene: ...
    @staticmethod
    def from_json(text: str) -> Scene: ...
    @staticmethod
    def builtin(name: str) -> Scene: ...
    @staticmethod
    def builtins() -> list[str]: ...
    def with_set(self, key: str, value: float | int | bool | str | list[Any] | dict[str, Any]) -> Scene:
        """A copy with `key` set to `value` as the scene file holds it (a str is read as
        TOML text if it is TOML, else as the string). Raises `UnknownNameError` for an unknown
        key, `TypeError` for a value of another type, `NoncircError` for a bad value."""
    def get(self, key: str) -> Any:
        """The value at `key` ("train.phi0_deg", "gear.curve.radii_mm[3]", "bounds")."""
    def with_values(self, names: list[str], row: Any) -> Scene:
        """A copy with the numeric parameters `names` set to `row` (fast: no text)."""
    def free_values(self) -> dict[str, float]:
        """The free parameters' current values, in `free_parameters()` order."""
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def to_toml(self) -> str: ...
    def to_json(self) -> str: ...
    @property
    def name(self) -> str: ...
    def free_parameters(self) -> list[tuple[str, float, float]]:
        """The search space `(name, lower, upper)`: the columns of `evaluate_batch`'s x."""
    def goal_names(self) -> list[str]: ...
    def objective_names(self) -> list[str]: ...
    def constraint_names(self) -> list[str]:
        """The search constraints (`search.constraints`) as written: `picking_height_mm <= -90`."""

def evaluate(
    scene: Scene, *, samples_per_turn: Optional[int] = None, closure_rel_tol: Optional[float] = None
) -> dict[str, Any]:
    """One design: objectives (dict), events with the picking check, the trajectory's
    sections, every measure (``{name: {"value", "unit"}}``), trajectory and pitch curves
    (arrays, mm), the pair's speed ratio and arm I's attitude per carrier sample
    (``ratio``, ``attitude_deg``), and ``report``: everything ``noncirc evaluate --format
    json`` prints, as the same nested dict."""

def measures() -> dict[str, tuple[str, str]]:
    """Every measure by name: ``(unit, description)``; goals take ``min:NAME``/``max:NAME``."""

def evaluate_batch(
    scene: Scene,
    x: npt.ArrayLike,
    *,
    samples_per_turn: Optional[int] = None,
    closure_rel_tol: Optional[float] = None,
    threads: Optional[int] = None,
    measures: Union[None, str, list[str]] = None,
    progress: Optional[Callable[[dict[str, Any]], Any]] = None,
    trajectories: bool = False,
) -> dict[str, Any]:
    """An (n, d) batch in parallel, GIL released: values, violations, the constraints'
    values and normalised violations, cv, goals, valid,
    errors and the measures (those read at no cost by default, "all", a list, `[]` for
    none); with `trajectories`, the tip paths (n, samples_per_turn, 2) in mm. `x` is
    anything `np.asarray(x, dtype=float64)` accepts; another shape is an error naming it.
    `progress(info)` after every piece of rows (evaluations, total)."""

def optimise(
    scene: Optional[Scene] = None,
    *,
    algorithm: Optional[str] = None,
    seed: Optional[int] = None,
    budget: Optional[int] = None,
    population: Optional[int] = None,
    threads: Optional[int] = None,
    screening_samples_per_turn: Optional[int] = None,
    progress: Optional[Callable[[dict[str, Any]], Optional[bool]]] = None,
    checkpoint: Optional[str | os.PathLike[str]] = None,
    checkpoint_every: float = 10.0,
    resume: Optional[str | os.PathLike[str]] = None,
) -> dict[str, Any]:
    """A search: summary (feasible, best, violations, evaluations, stopped_early, ...),
    parameter, goal and objective names, pareto, best_scene. `progress(info)` after every generation (info: generation,
    evaluations, budget, best_violation, feasible; return False to stop), called from the
    search's thread. Ctrl-C stops at once (the generation in flight is dropped) and raises
    KeyboardInterrupt. `checkpoint` writes the
    state every `checkpoint_every` s and at the end; `resume` continues one (its scene and
    settings; `budget` may be raised)."""

def fit(
    scene: Optional[Scene] = None,
    *,
    target: Optional[str | os.PathLike[str]] = None,
    tolerance_mm: Optional[float] = None,
    algorithm: Optional[str] = None,
    seed: Optional[int] = None,
    budget: Optional[int] = None,
    population: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Optional[Callable[[dict[str, Any]], Optional[bool]]] = None,
    checkpoint: Optional[str | os.PathLike[str]] = None,
    checkpoint_every: float = 10.0,
    resume: Optional[str | os.PathLike[str]] = None,
) -> dict[str, Any]:
    """A fit to a target (`noncirc fit --format json`'s summary: met, feasible, measures,
    fit, objectives, design, run) and best_scene. `target` is a CSV or TOML file replacing
    the scene's `[target]`."""

def inverse(
    scene: Optional[Scene] = None,
    *,
    target: Optional[str | os.PathLike[str]] = None,
    split: str = "equal",
    centre_ratio: Optional[float] = None,
    branch: Optional[str] = None,
    samples_per_turn: int = 720,
) -> dict[str, Any]:
    """The inversion for the train with two pairs (`noncirc inverse --format json`'s
    summary: met, built, geometry, conditions) and `scene` when a design was built."""

def repair(
    scene: Scene,
    *,
    path_tolerance_mm: float = 1.0,
    design_scale: float = 0.1,
    algorithm: Optional[str] = None,
    seed: Optional[int] = None,
    budget: Optional[int] = None,
    population: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Optional[Callable[[dict[str, Any]], Optional[bool]]] = None,
) -> dict[str, Any]:
    """A repair (`noncirc repair --format json`'s summary: repaired, before, after,
    changes, path distances, events, teeth, stages, run) and repaired_scene."""

def emigrants(checkpoint: str | os.PathLike[str], count: int) -> str:
    """The `count` best members of the search in a checkpoint file, as JSON text, for
    another island of the same search (`noncirc.dask.islands`)."""

def immigrate(checkpoint: str | os.PathLike[str], migrants: str) -> None:
    """Takes `migrants` (the text of `emigrants` from another island of the same search)
    into the checkpoint's search in place of its worst members; refuses another scene's."""

def dynamics(scene: Scene) -> dict[str, Any]:
    """The train at its working speed (`noncirc dynamics --format json`), as a dict; see
    `noncirc.dynamics` for the typed result."""

def robustness(
    scene: Scene, *, samples: Optional[int] = None, seed: Optional[int] = None, worst_case: bool = True
) -> dict[str, Any]:
    """A tolerance analysis of the scene's design under its `[tolerances]` (`noncirc
    robustness`): `probability_all`, `objectives` (each one's probability, margin
    quantiles, worst case), branch switches, `convergence`, as the CLI's JSON; `margins`
    an (objectives, samples) array of every sample's margin (NaN where refused)."""

def cad(
    scene: Scene,
    out: str,
    *,
    carrier_deg: float = 0.0,
    formats: list[str] = ...,
    tolerance_mm: float = 1e-3,
    force: bool = False,
) -> dict[str, Any]:
    """The solids written into `out` (`noncirc cad`): `paths`, `failures`, `manifest`; see
    `noncirc.cad` for the typed result."""

def sensitivity(
    scene: Scene,
    *,
    base_samples: int = 1024,
    bootstrap: int = 100,
    box_scale: float = 0.25,
    threads: Optional[int] = None,
) -> dict[str, Any]:
    """First-order and total Sobol indices of every output over the scene's search box
    scaled by `box_scale` about the design (`noncirc sensitivity`), in SALib's layout:
    `problem`, `X` and `Y` in SALib's sample order (`calc_second_order=False`), `outputs`,
    `indices[name]` with `S1`, `S1_conf`, `ST`, `ST_conf`, and those as (outputs, k)
    arrays. First order by Saltelli (2010), total by Jansen: SALib's estimators, the same
    numbers on the same samples. `unreliable[name]` lists why an output's indices cannot
    be read at `base_samples` (dicts with `kind`), `base_samples_needed` how many base
    points would read every index to ±0.1; a `RuntimeWarning` says both."""
