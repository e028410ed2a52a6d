"""The package's calls: the compiled extension's, returning typed results
(`noncirc.results`) instead of its plain dicts."""

from __future__ import annotations

import os
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _noncirc
from ._noncirc import Scene
from .progress import ProgressBar, interactive
from .results import Batch, CadResult, Dynamics, Evaluation, FitResult, InverseResult, RepairResult, SearchResult

Progress = Union[bool, Callable[[dict[str, Any]], Optional[bool]], None]


def evaluate(scene: Scene, *, samples_per_turn: Optional[int] = None, closure_rel_tol: Optional[float] = None) -> Evaluation:
    """One design: its objectives, events, sections and measures, the arrays to draw it,
    and `report`, exactly what `noncirc evaluate --format json` prints. Raises
    `ParameterError` for a bad setting and `ModelError` for a design the model cannot
    build."""
    return Evaluation._from_raw(_noncirc.evaluate(scene, samples_per_turn=samples_per_turn, closure_rel_tol=closure_rel_tol))


def dynamics(scene: Scene) -> Dynamics:
    """The scene's train at its working speed (`noncirc dynamics`, docs/dynamics.md): the
    input torque, mesh forces, axle loads and shaking over a carrier turn, from the scene's
    `[dynamics]` bodies and loads. Raises `ParameterError` for a bad value (naming the
    field) and `ModelError` for a design the model cannot build."""
    return Dynamics._from_raw(_noncirc.dynamics(scene))


def cad(
    scene: Scene,
    out: Union[str, os.PathLike],
    *,
    carrier_deg: float = 0.0,
    formats: Sequence[str] = ("step", "stl"),
    tolerance_mm: float = 1e-3,
    force: bool = False,
) -> CadResult:
    """The solids of the scene's gears and train written into `out` (`noncirc cad`,
    docs/cad.md): STEP AP214 (the assembly and each part) and STL (each part), with the
    scene's `[cad]` dimensions, assembled at `carrier_deg`. Teeth that fail a check are
    reported in `failures` and not written unless `force`. Raises `ParameterError` for a
    dimension that does not fit (naming the field; nothing is written) and `ModelError`
    for teeth that cannot be cut."""
    raw = _noncirc.cad(
        scene, os.fspath(out), carrier_deg=carrier_deg, formats=list(formats), tolerance_mm=tolerance_mm, force=force
    )
    return CadResult._from_raw(raw)


def evaluate_batch(
    scene: Scene,
    x: npt.ArrayLike,
    *,
    samples_per_turn: Optional[int] = None,
    closure_rel_tol: Optional[float] = None,
    threads: Optional[int] = None,
    measures: Union[None, str, Sequence[str]] = None,
    progress: Optional[Callable[[dict[str, Any]], Any]] = None,
    trajectories: bool = False,
) -> Batch:
    """An (n, d) batch of designs (columns: `scene.free_parameters()`), in parallel with
    the GIL released; Ctrl-C stops it within one piece of 4 096 rows (about 0.1 s). `x`
    is anything `np.asarray(x, dtype=float64)` accepts. `measures` are returned besides
    the objectives (`noncirc.measures()` lists them): by default those read from the
    evaluation at no cost (carrier angles, picking window, tip speed, branch gaps,
    heights); `"all"` adds the trajectory's sections and loop, which double a design's
    time, the gearbox's overlap `gear_overlap_mm`, which costs several designs' time, and
    the dynamics at working speed (`input_torque_peak_nm` …, docs/dynamics.md), about ten
    designs' time; the teeth's safety factors (`bending_safety`, `contact_safety`) only by
    name, as they cut the teeth (tenths of a second a design); a list names them; `[]`
    returns none. `trajectories=True` returns each design's tip path too, as
    `Batch.trajectories` (n, samples_per_turn, 2) in mm (16 bytes a point: at most 2 GB,
    refused above). `progress(info)` is called after every piece (info: `evaluations` done
    so far, `total`)."""
    names = measures if measures is None or isinstance(measures, str) else list(measures)
    raw = _noncirc.evaluate_batch(
        scene,
        x,
        samples_per_turn=samples_per_turn,
        closure_rel_tol=closure_rel_tol,
        threads=threads,
        measures=names,
        progress=progress,
        trajectories=trajectories,
    )
    parameter_names = [p[0] for p in scene.free_parameters()]
    return Batch._from_raw(raw, parameter_names, np.asarray(x, dtype=np.float64))


def _with_progress(progress: Progress, run: Callable[[Any], dict[str, Any]]) -> dict[str, Any]:
    """`run(callback)` with the progress a search was asked for: a bar on stderr (True, or
    None when a person is watching), the caller's callable, or nothing."""
    bar = ProgressBar() if progress is True or (progress is None and interactive()) else None
    callback = bar if bar is not None else (progress if callable(progress) else None)
    try:
        return run(callback)
    finally:
        if bar is not None:
            bar.close()


def optimise(
    scene: Optional[Scene] = None,
    *,
    algorithm: Optional[str] = None,
    seed: Optional[int] = None,
    budget: Optional[int] = None,
    population: Optional[int] = None,
    threads: Optional[int] = None,
    screening_samples_per_turn: Optional[int] = None,
    progress: Progress = None,
    checkpoint: Optional[Union[str, os.PathLike[str]]] = None,
    checkpoint_every: float = 10.0,
    resume: Optional[Union[str, os.PathLike[str]]] = None,
) -> SearchResult:
    """A search of the scene's free parameters; the keywords override its `[search]`
    settings. Returns the reported design, confirmed at the scene's resolution, and the
    confirmed Pareto set; warns (RuntimeWarning) when no design meets every objective.

    `progress`: a callable `progress(info)` after every generation (info: generation,
    evaluations, budget, best_violation, feasible; return False to stop), True for a
    progress bar on stderr, False for nothing; by default a bar when a person is watching
    (a terminal or a notebook) and nothing otherwise; it is called from the search's
    thread. Ctrl-C stops the search within about 20 ms (the generation in flight is
    dropped whole) and raises KeyboardInterrupt. `checkpoint` writes the state every
    `checkpoint_every` seconds and at the end; `resume` continues one (its scene and
    settings; `budget` may be raised)."""
    raw = _with_progress(
        progress,
        lambda callback: _noncirc.optimise(
            scene,
            algorithm=algorithm,
            seed=seed,
            budget=budget,
            population=population,
            threads=threads,
            screening_samples_per_turn=screening_samples_per_turn,
            progress=callback,
            checkpoint=checkpoint,
            checkpoint_every=checkpoint_every,
            resume=resume,
        ),
    )
    return SearchResult._from_raw(raw, raw["parameter_names"], raw["objective_names"])


def fit(
    scene: Optional[Scene] = None,
    *,
    target: Optional[Union[str, os.PathLike[str]]] = None,
    tolerance_mm: Optional[float] = None,
    algorithm: Optional[str] = None,
    seed: Optional[int] = None,
    budget: Optional[int] = None,
    population: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Progress = None,
    checkpoint: Optional[Union[str, os.PathLike[str]]] = None,
    checkpoint_every: float = 10.0,
    resume: Optional[Union[str, os.PathLike[str]]] = None,
) -> FitResult:
    """The design of the scene's search box whose tip path and key poses come nearest a
    target while it meets every objective (docs/inverse.md): the scene's search with the
    goal `fit`, then Levenberg–Marquardt from its best design. `target` is a file, a CSV of
    `x_mm,y_mm` points (machine frame, in the order of motion) or a TOML file with a
    `[target]` table, replacing the scene's own; `tolerance_mm` sets the path's tolerance.
    A bad target raises `ParameterError` naming the field and the value (an open path, too
    few points, NaN, a crossing, a point out of the arm's reach).

    `progress`, Ctrl-C, `checkpoint` and `resume` work as for `optimise`; the same seed
    gives the same design whatever `threads`."""
    raw = _with_progress(
        progress,
        lambda callback: _noncirc.fit(
            scene,
            target=target,
            tolerance_mm=tolerance_mm,
            algorithm=algorithm,
            seed=seed,
            budget=budget,
            population=population,
            threads=threads,
            progress=callback,
            checkpoint=checkpoint,
            checkpoint_every=checkpoint_every,
            resume=resume,
        ),
    )
    return FitResult._from_raw(raw)


def inverse(
    scene: Optional[Scene] = None,
    *,
    target: Optional[Union[str, os.PathLike[str]]] = None,
    split: Union[str, float] = "equal",
    centre_ratio: Optional[float] = None,
    branch: Optional[str] = None,
    samples_per_turn: int = 720,
) -> InverseResult:
    """The train with two pairs from a target tip path (docs/inverse.md §6), as
    `noncirc inverse`: the path fixes the arm length and the planet circle, the carrier
    angle and the arm's direction along it give the overall ratio, and `split` shares it
    between the pairs ("equal", "first-circular", "second-circular" or the first pair's
    share λ from 0 to 1); both pitch curves are built by closure. `scene` gives the train
    (γ0, Φ0, H1, sense, arms; default the paper's), `target` a CSV or TOML file (default
    the scene's own `[target]`), `centre_ratio` a_B/a_A (default the scene's). Failing
    conditions are in the result, with their places; bad input raises `ParameterError`."""
    raw = _noncirc.inverse(
        scene,
        target=target,
        split=str(split),
        centre_ratio=centre_ratio,
        branch=branch,
        samples_per_turn=samples_per_turn,
    )
    return InverseResult._from_raw(raw)


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
    progress: Progress = None,
) -> RepairResult:
    """The design nearest the scene's that meets every objective and whose teeth cut and
    mesh (docs/inverse.md §5), as `noncirc repair`: a fit to the design's own tip path and
    picking and planting poses, each free parameter pulled towards its value (a change of
    `design_scale` of its interval costs as much as the path off by `path_tolerance_mm`),
    in boxes about the design within the scene's search box. `progress` and Ctrl-C work as
    for `optimise`; the same seed gives the same design whatever `threads`."""
    raw = _with_progress(
        progress,
        lambda callback: _noncirc.repair(
            scene,
            path_tolerance_mm=path_tolerance_mm,
            design_scale=design_scale,
            algorithm=algorithm,
            seed=seed,
            budget=budget,
            population=population,
            threads=threads,
            progress=callback,
        ),
    )
    return RepairResult._from_raw(raw)
