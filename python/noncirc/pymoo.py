"""A vectorised pymoo `Problem` made from a scene, so any pymoo algorithm can search it.

The objectives' normalised violations are pymoo inequality constraints (`G <= 0` is met;
pymoo sums them the same way noncirc does), and the scene's search goals are `F`.
"""

from __future__ import annotations

import numpy as np
from pymoo.core.problem import Problem

from ._noncirc import Scene, evaluate_batch


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
            n_ieq_constr=len(scene.objective_names()),
            xl=np.array([p[1] for p in params]),
            xu=np.array([p[2] for p in params]),
        )

    def _evaluate(self, x, out, *args, **kwargs):
        result = evaluate_batch(
            self.scene,
            np.ascontiguousarray(x, dtype=np.float64),
            samples_per_turn=self.samples_per_turn,
            threads=self.threads,
        )
        out["F"] = result["goals"]
        out["G"] = result["normalised_violations"]
