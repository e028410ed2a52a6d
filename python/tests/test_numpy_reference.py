"""The NumPy reference implementation computes the same numbers as noncirc."""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parents[1] / "benchmarks"))
import noncirc  # noqa: E402
from numpy_model import PAPER, evaluate  # noqa: E402


def test_numpy_model_agrees_with_noncirc_on_the_paper_design_and_random_ones():
    scene = noncirc.Scene.builtin("paper-search")
    params = scene.free_parameters()
    names = [p[0] for p in params]
    lo, hi = np.array([p[1] for p in params]), np.array([p[2] for p in params])
    paper = np.array([[*PAPER["radii"], 86, -29, 145, 65, -53]], dtype=float)
    x = np.vstack([paper, lo + np.random.default_rng(3).random((30, len(params))) * (hi - lo)])
    ref = evaluate(x, names, PAPER, samples=720)
    core = noncirc.evaluate_batch(scene, x, samples_per_turn=720, closure_rel_tol=1e-3)
    names_core = core.objective_names
    checked = 0
    for i in np.flatnonzero(core.valid):
        v = dict(zip(names_core, core.values[i]))
        # Same closure and trajectory samples; the NumPy model takes events and extremes at
        # the nearest of 720 samples where noncirc refines them, hence these tolerances.
        tol = {"trajectory_height": 0.5, "ground_clearance": 0.5, "interference": 0.5, "picking_angle": 2.0,
               "pushing_angle": 2.0, "angle_difference": 3.0}
        for key, t in tol.items():
            assert abs(ref[key][i] - v[key]) < t, (i, key, ref[key][i], v[key])
        assert abs(ref["module"][i] - v["module"]) < 0.02 * max(v["module"], 0.05), (i, ref["module"][i], v["module"])
        checked += 1
    assert checked >= 15
    one = noncirc.evaluate(scene, samples_per_turn=720)
    assert abs(ref["centre_distance_mm"][0] - one.centre_distance_mm) < 1e-9
    assert np.abs(ref["trajectory"][0] - one.trajectory).max() < 1e-3
