"""Robust design from Python: the tolerance analysis, and noncirc's Sobol indices against
SALib's on the same samples."""

import numpy as np
import pytest

import noncirc

SALib = pytest.importorskip("SALib")
from SALib.analyze import sobol as salib_sobol  # noqa: E402


def salib_problem(problem):
    """SALib 1.5.1 under pandas 3 takes the names as an array (`pd.unique` refuses lists)."""
    return dict(problem, names=np.array(problem["names"]))


def complete_blocks(y, k):
    """The outputs of the base points whose k + 2 designs the model all took, in SALib's
    layout: noncirc leaves the others out (SALib cannot take NaN)."""
    blocks = y.reshape(-1, k + 2)
    return blocks[np.isfinite(blocks).all(axis=1)].ravel()


def test_salib_on_noncircs_samples_agrees_with_noncirc():
    scene = noncirc.Scene.builtin("paper")
    s = noncirc.sensitivity(scene, base_samples=256, bootstrap=100, threads=2)
    k = s["problem"]["num_vars"]
    assert s["X"].shape == (256 * (k + 2), k)
    names = s["y_names"]
    checked = 0
    for name in s["outputs"]:
        y = complete_blocks(s["Y"][:, names.index(name)], k)
        si = salib_sobol.analyze(salib_problem(s["problem"]), y, calc_second_order=False, num_resamples=100, seed=1)
        ours = s["indices"][name]
        # The same estimators on the same samples (Saltelli 2010's first order, Jansen's
        # total): the same indices.
        np.testing.assert_allclose(ours["S1"], si["S1"], rtol=1e-9, atol=1e-12, err_msg=name)
        np.testing.assert_allclose(ours["ST"], si["ST"], rtol=1e-9, atol=1e-12, err_msg=name)
        checked += 1
    assert checked >= 20


def test_indices_that_cannot_be_read_warn_and_say_how_many_samples_would_do():
    scene = noncirc.Scene.builtin("paper")
    with pytest.warns(RuntimeWarning, match=r"cannot be read at 16 base points\. About (\d+) base points") as w:
        s = noncirc.sensitivity(scene, base_samples=16, bootstrap=50, threads=2)
    assert len([x for x in w if x.category is RuntimeWarning]) == 1
    assert w[0].filename == __file__  # at the user's call, not inside the package
    needed = s["base_samples_needed"]
    assert needed >= 128 and needed & (needed - 1) == 0
    assert f"--base-samples {needed}" in str(w[0].message)
    for name in s["outputs"]:
        kinds = {u["kind"] for u in s["unreliable"][name]}
        assert "wide_interval" in kinds, (name, kinds)
    # At the default 1024 the objectives' indices read to ±0.1, without a word for them.
    s = noncirc.sensitivity(scene, bootstrap=50, threads=2)
    objectives = ["interference", "picking_angle", "pushing_angle", "angle_difference", "seedling_push",
                  "ground_clearance", "trajectory_height", "module", "picking_admissible"]
    assert s["outputs"][: len(objectives)] == objectives
    for name in objectives:
        assert s["unreliable"][name] == [], name


def test_salib_run_on_evaluate_batch_agrees_too():
    # SALib's own samples through evaluate_batch (docs/robustness.md shows this).
    from SALib.sample import sobol as salib_sample

    scene = noncirc.Scene.builtin("paper")
    s = noncirc.sensitivity(scene, base_samples=512, bootstrap=50)
    problem = salib_problem(s["problem"])
    x = salib_sample.sample(problem, 512, calc_second_order=False, seed=3)
    batch = noncirc.evaluate_batch(scene, x, threads=2)
    y = complete_blocks(batch.value("picking_angle"), problem["num_vars"])
    si = salib_sobol.analyze(problem, y, calc_second_order=False, seed=3)
    ours = s["indices"]["picking_angle"]
    # Two estimates from independent samples: within their intervals.
    assert np.all(np.abs(ours["ST"] - si["ST"]) <= ours["ST_conf"] + si["ST_conf"] + 0.02)


def test_robustness_reports_probabilities_and_margins():
    scene = noncirc.Scene.builtin("paper")
    r = noncirc.robustness(scene, samples=256)
    assert r["samples"] == 256
    assert r["margins"].shape == (len(r["objectives"]), 256)
    for o, row in zip(r["objectives"], r["margins"]):
        assert o["probability"] == pytest.approx(np.mean(row >= 0))
    # The paper's module misses its bound: no machine meets every objective.
    assert r["probability_all"] == 0.0
    with pytest.raises(noncirc.ParameterError, match="tolerances.samples"):
        noncirc.robustness(scene, samples=0)
