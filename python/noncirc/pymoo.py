"""A vectorised pymoo `Problem` made from a scene, so any pymoo algorithm can search it.

The objectives' normalised violations, then the scene's search constraints'
(`search.constraints`), are pymoo inequality constraints (`G <= 0` is met; pymoo sums
them the same way noncirc does), and the scene's search goals are `F` as
noncirc's own searches rank them: all minimised, a maximised goal negated, an objective's
margin divided by its scale. `scene.goal_names()` names the quantities, and
`SceneProblem.goal_values(res.X)` gives them in their units.

pymoo's NSGA-II seldom reaches the feasible region of a transplanting mechanism from random
starts (best CV 0.10 after 100 000 evaluations on the default space). `feasible_start`
gives it designs to start from, and `summary` says how a run ended.
"""

from __future__ import annotations

import warnings

import numpy as np
from pymoo.core.problem import Problem

from ._noncirc import Scene, evaluate_batch, optimise


class SceneProblem(Problem):
    """pymoo problem over `scene.free_parameters()`; every batch runs in noncirc's core."""

    def __init__(self, scene: Scene, *, samples_per_turn: int | None = None, threads: int | None = None):
        params = scene.free_parameters()
        self.scene = scene
        self.names = [p[0] for p in params]
        self.samples_per_turn = samples_per_turn
        self.threads = threads
        super().__init__(
            n_var=len(params),
            n_obj=len(scene.goal_names()),
            n_ieq_constr=len(scene.objective_names()) + len(scene.constraint_names()),
            xl=np.array([p[1] for p in params]),
            xu=np.array([p[2] for p in params]),
        )

    def _evaluate(self, x, out, *args, **kwargs):
        result = evaluate_batch(
            self.scene,
            np.ascontiguousarray(x, dtype=np.float64),
            samples_per_turn=self.samples_per_turn,
            threads=self.threads,
            measures=[],  # only the goals and constraints: the fastest batch
        )
        out["F"] = result["goals"]
        out["G"] = np.hstack([result["normalised_violations"], result["constraint_normalised_violations"]])

    def goal_values(self, x) -> np.ndarray:
        """The goals of designs `x` (one row per design: pymoo's `res.X`, `res.opt.get("X")`)
        as the quantities they are, in their units, one column per `scene.goal_names()`
        (`module_mm`, `picking_tip_speed_m_s`, …). `F` holds their ranked form (a maximised
        goal negated, an objective's margin over its scale), which is what pymoo compares
        but not what a reader wants; the designs are evaluated again, at the problem's
        resolution, so the values are `evaluate_batch`'s own."""
        x = np.ascontiguousarray(np.atleast_2d(x), dtype=np.float64)
        result = evaluate_batch(
            self.scene, x, samples_per_turn=self.samples_per_turn, threads=self.threads, measures=[]
        )
        return np.asarray(result["goal_values"])


def feasible_start(
    scene: Scene, *, seed: int = 1, budget: int | None = None, threads: int | None = None
) -> np.ndarray:
    """Designs to start a pymoo algorithm from (`sampling=`), one row per design in
    `scene.free_parameters()` order: the confirmed Pareto set of noncirc's own NSGA-II on
    the scene's goals, whose feasibility phase (differential-evolution moves while no
    member is feasible) reaches the feasible region from random starts. Warns (a
    `RuntimeWarning`) when that run found no feasible design; its best design is returned.
    """
    run = optimise(scene, algorithm="nsga2", seed=seed, budget=budget, threads=threads)
    names = [p[0] for p in scene.free_parameters()]
    return np.array([[d["parameters"][n] for n in names] for d in run["pareto"]], dtype=np.float64)


def summary(res) -> str:
    """How a pymoo run on a `SceneProblem` ended: the number of feasible non-dominated
    designs, or, when none is feasible, the least summed violation and a `RuntimeWarning`
    saying so."""
    pop = res.pop if res.opt is None else res.opt
    cv = np.maximum(pop.get("G"), 0.0).sum(axis=1)
    feasible = int((cv <= 0.0).sum())
    if feasible == 0:
        message = (
            f"no feasible design: the least summed normalised violation is {cv.min():.4g} "
            "(start from noncirc.pymoo.feasible_start(scene), or raise the budget)"
        )
        warnings.warn(message, RuntimeWarning, stacklevel=2)
        return message
    return f"{feasible} feasible non-dominated designs"
