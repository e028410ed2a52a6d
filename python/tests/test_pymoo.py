"""Any pymoo algorithm can search a noncirc scene through the vectorised adapter."""

import numpy as np
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.optimize import minimize

import pytest

from noncirc import Scene, evaluate_batch
from noncirc.pymoo import SceneProblem, feasible_start, summary


def test_adapter_shapes_and_constraints_match_the_core():
    scene = Scene.builtin("paper-search")
    problem = SceneProblem(scene)
    assert problem.n_var == 17 and problem.n_obj == 1 and problem.n_ieq_constr == 9
    x = problem.xl + np.random.default_rng(0).random((5, 17)) * (problem.xu - problem.xl)
    out = problem.evaluate(x, return_as_dictionary=True)
    core = evaluate_batch(scene, x)
    assert np.array_equal(out["G"], core.normalised_violations)
    assert np.array_equal(out["F"], core.goals)


def test_pymoo_nsga2_runs_on_the_default_scene():
    scene = Scene.builtin("paper-search").with_set("search.goals", '["module", "picking_tip_speed"]')
    problem = SceneProblem(scene)
    res = minimize(problem, NSGA2(pop_size=40), ("n_gen", 15), seed=1, verbose=False)
    assert res.algorithm.evaluator.n_eval >= 600
    pop = res.pop.get("G")
    # The population's summed violation fell from the random start.
    assert pop.shape == (40, len(scene.objective_names()))
    cv = np.maximum(pop, 0).sum(axis=1)
    first = np.maximum(problem.evaluate(problem.xl + 0.5 * (problem.xu - problem.xl)[None, :], return_as_dictionary=True)["G"], 0).sum()
    assert cv.min() < max(first, 1.0)


def test_the_documented_example_returns_a_feasible_front_of_at_least_20_designs():
    # docs/python.md, "pymoo", as written there.
    scene = Scene.builtin("paper-search").with_set("search.goals", '["module", "picking_tip_speed"]')
    start = feasible_start(scene, seed=1)
    res = minimize(SceneProblem(scene), NSGA2(pop_size=40, sampling=start), ("n_gen", 50), seed=1)
    assert summary(res).endswith("feasible non-dominated designs")
    g = res.opt.get("G")
    feasible = (np.maximum(g, 0).sum(axis=1) <= 0).sum()
    assert feasible >= 20, f"{feasible} feasible designs in the final front"
    # Non-dominated among themselves (pymoo's opt is its first front).
    f = res.opt.get("F")
    dominated = [any(np.all(f[j] <= f[i]) and np.any(f[j] < f[i]) for j in range(len(f))) for i in range(len(f))]
    assert not any(dominated)
    # The front in the goals' units: the module in mm (maximised: F falls as it grows,
    # every feasible design at or above the 2.5 mm bound), the tip speed in m/s (F itself).
    problem = SceneProblem(scene)
    values = problem.goal_values(res.opt.get("X"))
    assert values.shape == (len(f), 2)
    assert np.all(values[:, 0] >= 2.5)
    assert np.array_equal(np.argsort(f[:, 0]), np.argsort(-values[:, 0]))
    assert np.array_equal(values[:, 1], f[:, 1])


def test_a_run_that_ends_infeasible_says_so():
    scene = Scene.builtin("paper-search").with_set("search.goals", '["module", "picking_tip_speed"]')
    res = minimize(SceneProblem(scene), NSGA2(pop_size=8), ("n_gen", 2), seed=1, verbose=False)
    with pytest.warns(RuntimeWarning, match="no feasible design"):
        message = summary(res)
    assert message.startswith("no feasible design")


def test_search_constraints_are_pymoo_constraints_after_the_objectives():
    # A bound on any measure: one more column of G, the constraint's normalised violation,
    # read from the batch's constrained measure (picking height ≤ −95 mm; scale 9.5 mm).
    scene = Scene.builtin("paper-search").with_set("search.constraints", '["picking_height_mm <= -95"]')
    assert scene.constraint_names() == ["picking_height_mm <= -95"]
    problem = SceneProblem(scene)
    assert problem.n_ieq_constr == 10
    x = problem.xl + np.random.default_rng(3).random((40, 17)) * (problem.xu - problem.xl)
    out = problem.evaluate(x, return_as_dictionary=True)
    core = evaluate_batch(scene, x, measures=["picking_height_mm"])
    valid = core.valid
    assert valid.sum() >= 20
    height = core.value("picking_height_mm")
    np.testing.assert_array_equal(core.constraint_values[valid, 0], height[valid])
    expected = np.maximum(height + 95.0, 0.0) / 9.5
    np.testing.assert_allclose(out["G"][valid, 9], expected[valid], rtol=0, atol=1e-12)
    assert (out["G"][valid, 9] > 0).any() and (out["G"][valid, 9] == 0).any(), "both sides of the bound are sampled"
    np.testing.assert_allclose(core.cv[valid], np.maximum(out["G"][valid], 0).sum(axis=1), rtol=1e-12)
    assert np.array_equal(core.feasible, valid & (np.maximum(out["G"], 0).sum(axis=1) == 0))
