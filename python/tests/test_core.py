"""The Python API over the Rust core: scenes, evaluation, batches, errors, search."""

import pickle
import threading
import time

import numpy as np
import pytest

import noncirc
from noncirc import NoncircError, Scene, evaluate, evaluate_batch, optimise
from cli_binary import NONCIRC_BIN


def test_scenes_load_from_builtin_string_file_and_json(tmp_path):
    assert "paper" in Scene.builtins() and "paper-search" in Scene.builtins()
    paper = Scene.builtin("paper")
    path = tmp_path / "paper.toml"
    path.write_text(paper.to_toml())
    for s in [Scene.from_file(str(path)), Scene.from_string(paper.to_toml()), Scene.from_json(paper.to_json())]:
        assert s.to_json() == paper.to_json()
    assert pickle.loads(pickle.dumps(paper)).to_json() == paper.to_json()


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_a_seed_anywhere_in_u64_survives_the_search_and_the_scene_files():
    for seed in [0, 2**63 - 1, 2**63, 2**64 - 1]:
        result = optimise(Scene.builtin("paper-search"), seed=seed, budget=200, threads=1, progress=False)
        assert result.seed == seed
        text = result.best_scene.to_toml()
        again = Scene.from_string(text)
        assert again.to_json() == result.best_scene.to_json()
        assert Scene.builtin("paper").with_set("tolerances.seed", seed).to_toml()
    with pytest.raises(NoncircError, match="whole number"):
        Scene.builtin("paper").with_set("search.seed", 2**64)


def test_bad_scenes_raise_value_errors_naming_the_place():
    assert issubclass(NoncircError, ValueError)
    with pytest.raises(NoncircError, match=r"bad\.toml.*line 2.*samples_per_turn"):
        Scene.from_string("[resolution]\nsamples_per_turn = 'many'\n", "bad.toml")
    with pytest.raises(NoncircError, match="unknown"):
        Scene.builtin("nope")
    with pytest.raises(FileNotFoundError, match="no such scene file"):
        Scene.from_file("/nonexistent/scene.toml")
    with pytest.raises(NoncircError, match="unknown key"):
        Scene.builtin("paper").with_set("train.nope", "1")
    with pytest.raises(NoncircError, match="arm_half_width_mm"):
        evaluate(Scene.builtin("paper").with_set("agronomy.arm_half_width_mm", "-3"))


def test_evaluate_matches_the_pinned_paper_design():
    r = evaluate(Scene.builtin("paper"), samples_per_turn=360)
    assert r.samples_per_turn == 360
    assert abs(r.centre_distance_mm - 85.01753) < 1e-4
    o = r.objectives
    assert abs(o["picking_angle"].value - 0.2970) < 1e-3 and o["picking_angle"].unit == "deg"
    assert abs(o["pushing_angle"].value - 53.9909) < 1e-3
    # The picking instant is one a machine can have (the same pins as tests/picking.rs).
    assert abs(o["picking_admissible"].value - 51.9908) < 1e-3
    assert o["picking_admissible"].violation == 0.0 and o["picking_admissible"].met
    ev = r.events
    assert ev["picking_refused"] is None and ev["picking_branch_gap_mm"] > 100.0
    m = r.measures
    assert m["picking_carrier_deg"].unit == "deg"
    assert abs(m["picking_carrier_deg"].value - 71.879) < 1e-2
    assert abs(m["planting_carrier_deg"].value - 157.179) < 1e-2
    assert o["module"].violation > 2.0 and not o["module"].met and o["trajectory_height"].violation == 0.0
    assert r.trajectory.shape == (360, 2) and r.trajectory.dtype == np.float64
    # The pitch curves to a 1 µm chord tolerance (more points than the evaluation's).
    n = r.driver_curve.shape[0]
    assert n > 360 and r.driven_curve.shape == (n, 2)
    # The driven curve closes the pair: radii add up to one centre distance point by point
    # (re-closed by the export's quadrature, within the evaluation's closure error).
    radii = np.hypot(*r.driver_curve.T) + np.hypot(*r.driven_curve.T)
    assert np.allclose(radii, radii[0], atol=1e-9)
    assert abs(radii[0] - r.centre_distance_mm) < 1e-4


def paper_batch(n, seed=0):
    scene = Scene.builtin("paper-search")
    params = scene.free_parameters()
    rng = np.random.default_rng(seed)
    lo = np.array([p[1] for p in params])
    hi = np.array([p[2] for p in params])
    return scene, lo + rng.random((n, len(params))) * (hi - lo)


def test_batch_rows_equal_single_evaluations():
    scene, x = paper_batch(40)
    r = evaluate_batch(scene, x, measures="all")
    k = len(scene.objective_names())
    assert r.values.shape == (40, k) and r.cv.shape == (40,) and r.goals.shape == (40, 1)
    assert r.measures.shape == (40, len(r.measure_names)) and r.x.shape == (40, 17)
    names = [p[0] for p in scene.free_parameters()]
    assert r.parameter_names == names
    for i in range(0, 40, 7):
        if not r.valid[i]:
            assert r.errors[i]
            continue
        s = scene
        for name, v in zip(names, x[i]):
            s = s.with_set(name, repr(float(v)))
        single = evaluate(s)
        for j, name in enumerate(r.objective_names):
            assert r.values[i, j] == pytest.approx(single.objectives[name].value, rel=1e-12, abs=1e-12)
        # The events and trajectory measures, as one design's evaluation gives them.
        for name in r.measure_names:
            if name in single.measures:
                assert r.value(name)[i] == pytest.approx(single.measures[name].value, rel=1e-12, abs=1e-12)
            else:
                assert np.isnan(r.value(name)[i])


def test_batch_trajectories_are_each_designs_tip_path():
    scene, x = paper_batch(30, seed=4)
    x[2, 0] = -5.0  # refused: a NaN path
    r = evaluate_batch(scene, x, trajectories=True, samples_per_turn=90)
    assert r.trajectories.shape == (30, 90, 2) and r.trajectories.dtype == np.float64
    assert not r.valid[2] and np.isnan(r.trajectories[2]).all()
    names = [p[0] for p in scene.free_parameters()]
    checked = 0
    for i in np.flatnonzero(r.valid)[:5]:
        s = scene.with_set("resolution.samples_per_turn", "90")
        for name, v in zip(names, x[i]):
            s = s.with_set(name, repr(float(v)))
        np.testing.assert_array_equal(r.trajectories[i], evaluate(s).trajectory)
        checked += 1
    assert checked == 5
    assert np.isfinite(r.trajectories[r.valid]).all()
    # Not asked: None, and no memory spent.
    assert evaluate_batch(scene, x[:3]).trajectories is None
    # More than 2 GB of paths is refused before any design is evaluated, naming the flag.
    with pytest.raises(NoncircError, match=r"trajectories=True for 1100000 designs .* 2\.1 GB"):
        evaluate_batch(scene, np.zeros((1_100_000, 17)), trajectories=True)


@pytest.mark.parametrize(
    "bad, message",
    [
        (np.zeros((3, 5)), "columns"),
        (np.zeros(17), r"2-D, of shape \(n, 17\).*got shape \(17,\)"),
        (np.zeros((3, 17, 1)), r"got shape \(3, 17, 1\)"),
        (np.full((2, 17), np.nan), "not finite"),
    ],
)
def test_bad_batches_raise_value_errors(bad, message):
    scene = Scene.builtin("paper-search")
    with pytest.raises(NoncircError, match=message):
        evaluate_batch(scene, bad)


def test_invalid_designs_are_flagged_not_nan_silently():
    scene, x = paper_batch(4)
    x[1, 0] = -5.0  # a negative control radius
    r = evaluate_batch(scene, x)
    assert not r.valid[1] and "radius" in r.errors[1] and not r.feasible[1]
    assert r.cv[1] == 1e5 and np.isfinite(r.cv).all() and np.isnan(r.measures[1]).all()


def test_two_python_threads_run_batches_concurrently():
    """With the GIL released, two calls from two Python threads overlap in time."""
    scene, x = paper_batch(2000, seed=1)
    spans = {}

    def run(name):
        start = time.perf_counter()
        evaluate_batch(scene, x, threads=1)
        spans[name] = (start, time.perf_counter())

    threads = [threading.Thread(target=run, args=(name,)) for name in ("a", "b")]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    (a0, a1), (b0, b1) = spans["a"], spans["b"]
    overlap = min(a1, b1) - max(a0, b0)
    # Holding the GIL would serialise the calls: no overlap at all.
    assert overlap > 0.5 * min(a1 - a0, b1 - b0), f"calls overlapped {overlap:.3f}s of {spans}"


def test_optimise_finds_a_feasible_design_reproducibly():
    scene = Scene.builtin("paper-search")
    a = optimise(scene, algorithm="de", seed=3, budget=30000)
    b = optimise(scene, algorithm="de", seed=3, budget=30000, threads=1)
    assert a.best == b.best and a.evaluations == b.evaluations
    # In the scene's order, not alphabetical.
    assert list(a.best) == [p[0] for p in scene.free_parameters()]
    assert list(a.objectives) == scene.objective_names()
    if a.feasible:
        again = evaluate(a.best_scene)
        assert again.feasible and not a.missed


def test_keyword_knobs_are_validated():
    with pytest.raises(NoncircError, match="samples_per_turn"):
        evaluate(Scene.builtin("paper"), samples_per_turn=7)
    with pytest.raises(NoncircError, match="algorithm"):
        optimise(Scene.builtin("paper-search"), algorithm="simplex", budget=10)
    # Resource limits are typed errors, never a PanicException or a thread storm.
    with pytest.raises(NoncircError, match="search.population"):
        optimise(Scene.builtin("paper-search"), population=2**63 - 1, budget=10)
    with pytest.raises(NoncircError, match="threads"):
        optimise(Scene.builtin("paper-search"), threads=2**63, budget=10)
    with pytest.raises(NoncircError, match="threads"):
        evaluate_batch(Scene.builtin("paper-search"), np.zeros((1, 17)), threads=2**63)
    # A NaN bound is refused when the scene is read, not counted as met.
    with pytest.raises(NoncircError, match="bounds.module_min_mm"):
        Scene.builtin("paper").with_set("bounds.module_min_mm", "nan")
    assert noncirc.__version__


def test_unknown_names_are_typed_errors_with_suggestions():
    import pytest

    from noncirc import NoncircError, UnknownNameError

    scene = Scene.builtin("paper-search")
    with pytest.raises(UnknownNameError, match="train.gamma0_deg"):
        scene.with_set("train.gama0_deg", "-50")
    # Any number of the scene is a free parameter, by the same path as --set.
    free = scene.with_set("search.free", '[{name = "bounds.module_min_mm", lower = 1, upper = 3}]')
    assert free.free_parameters() == [("bounds.module_min_mm", 1.0, 3.0)]
    # An unknown free parameter fails when it is set, naming the nearest.
    with pytest.raises(UnknownNameError, match="bounds.module_min_mm"):
        scene.with_set("search.free", '[{name = "bounds.modul_min_mm", lower = 1, upper = 3}]')
    assert issubclass(UnknownNameError, NoncircError)


def test_x_is_anything_numpy_reads_as_float64():
    scene, x = paper_batch(3)
    expected = evaluate_batch(scene, x)
    for same in [x.tolist(), np.asfortranarray(x), x.T.copy().T]:
        assert np.array_equal(evaluate_batch(scene, same).cv, expected.cv)
    single = x.astype(np.float32)
    assert np.array_equal(evaluate_batch(scene, single).cv, evaluate_batch(scene, single.astype(np.float64)).cv)
    ints = np.rint(x).astype(np.int64)
    assert np.array_equal(evaluate_batch(scene, ints).cv, evaluate_batch(scene, ints.astype(float)).cv)
    with pytest.raises(TypeError, match=r"np.asarray\(x, dtype=float64\)"):
        evaluate_batch(scene, [["a"] * 17])


def test_scenes_in_code_get_set_values_and_compare_by_content():
    scene = Scene.builtin("paper-search")
    assert scene.get("train.phi0_deg") == 86.0
    assert scene.get("gear.curve.radii_mm")[:3] == [21.0, 28.0, 50.0]
    assert scene.get("bounds")["picking_angle_deg"] == [-5.0, 15.0]
    # Numbers, lists and strings, as the scene file holds them.
    assert scene.with_set("train.gamma0_deg", -50.0).get("train.gamma0_deg") == -50.0
    assert scene.with_set("train.gamma0_deg", -50).get("train.gamma0_deg") == -50.0
    two = scene.with_set("search.goals", ["module", "picking_tip_speed"])
    assert len(two.goal_names()) == 2
    assert scene.with_set("train.rotation", "counterclockwise").get("train.rotation") == "counterclockwise"
    # Equality by content, and hashing to match.
    assert scene == Scene.builtin("paper-search") and hash(scene) == hash(Scene.builtin("paper-search"))
    assert scene != scene.with_set("train.gamma0_deg", -50.0) and scene != "paper-search"
    # A batch row back into a scene: the values of free_parameters() order.
    names = [n for n, _, _ in scene.free_parameters()]
    values = scene.free_values()
    assert list(values) == names and values["train.arm_length_mm"] == 145.0
    row = np.array(list(values.values()))
    assert scene.with_values(names, row) == scene
    row[3] = 40.0
    changed = scene.with_values(names, row)
    assert changed.get("gear.curve.radii_mm[3]") == 40.0
    assert evaluate(changed).objectives == evaluate(scene.with_set("gear.curve.radii_mm[3]", 40.0)).objectives


def test_hostile_scene_edits_raise_the_right_exception_types():
    from noncirc import UnknownNameError

    scene = Scene.builtin("paper-search")
    # Messages name the Python call, not the CLI's --set.
    with pytest.raises(UnknownNameError, match=r'^Scene.with_set\("train.gamma_deg", -50.0\): unknown key'):
        scene.with_set("train.gamma_deg", -50.0)
    with pytest.raises(TypeError, match="type object"):
        scene.with_set("train.gamma0_deg", object())
    with pytest.raises(NoncircError, match="not a finite number"):
        scene.with_set("train.gamma0_deg", float("nan"))
    with pytest.raises(NoncircError, match="unknown search goal"):
        scene.with_set("search.goals", ["nope"])
    with pytest.raises(UnknownNameError, match="train.phi0_deg"):
        scene.get("train.phi_deg")
    names = [n for n, _, _ in scene.free_parameters()]
    with pytest.raises(NoncircError, match="17 names but 2 values"):
        scene.with_values(names, [1.0, 2.0])
    with pytest.raises(NoncircError, match="not a finite number"):
        scene.with_values(["train.phi0_deg"], [float("inf")])
    with pytest.raises(UnknownNameError):
        scene.with_values(["train.nope"], [1.0])
    with pytest.raises(TypeError, match="sequence of numbers"):
        scene.with_values(["train.phi0_deg"], "abc")


def test_evaluate_holds_everything_the_cli_json_holds():
    import json
    import subprocess
    from pathlib import Path

    cli = NONCIRC_BIN
    scene = Scene.builtin("paper")
    r = evaluate(scene)
    printed = json.loads(subprocess.run([str(cli), "evaluate", "paper", "--format", "json"], check=True, capture_output=True, text=True).stdout)
    assert r.report == printed
    n = len(r.carrier_deg)
    assert r.ratio.shape == (n,) and r.attitude_deg.shape == (n,)
    # The pair closes 1:1, so the driven gear's turn per driver turn, the mean of
    # 1/ratio over driver angles sampled evenly, is one.
    gear = printed["gear"]
    assert np.all(r.ratio > 0) and gear["centre_distance_mm"] == r.centre_distance_mm
    assert abs(np.mean(1.0 / r.ratio) - 1.0) < 1e-9
    # Arm I's attitude at picking, from the per-sample array, near the event's own.
    picking = printed["events"]["picking_carrier_deg"]
    j = int(np.argmin(np.abs(r.carrier_deg - picking)))
    assert abs(r.attitude_deg[j] - printed["events"]["picking_attitude_deg"]) < 5.0


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda s: Scene.from_string("[train\nphi0_deg = 1"), "SceneError", "line 1"),
        (lambda s: Scene.from_string('[train]\nphi0_deg = "a"'), "SceneError", r"line 2.*expected f64"),
        (lambda s: s.with_set("train.arm_length_mm", -1.0), "ParameterError", r"train.arm_length_mm \(S\) = -1 is out of range"),
        (lambda s: s.with_set("resolution.samples_per_turn", 3), "ParameterError", "multiple of 6"),
        (lambda s: s.with_set("bounds.picking_angle_deg", [5.0, -5.0]), "ParameterError", "lower bound 5"),
        (lambda s: evaluate(s, closure_rel_tol=-1.0), "ParameterError", "closure_rel_tol = -1"),
        (lambda s: s.with_values(["train.phi0_deg"], [float("inf")]), "ParameterError", "not a finite number"),
        (lambda s: s.with_set("gear.curve.radii_mm[0]", -5.0), "ModelError", "pitch radius must be positive"),
        (lambda s: evaluate(s, samples_per_turn=24), "ModelError", "closure not resolved at 24 samples"),
        (lambda s: s.with_set("train.phi0_dg", 1.0), "UnknownNameError", "nearest are train.phi0_deg"),
        (lambda s: Scene.builtin("papr"), "UnknownNameError", "the built-ins are paper, "),
        (lambda s: evaluate_batch(Scene.builtin("paper-search"), np.zeros((1, 17)), measures=["loop_heigth_mm"]), "UnknownNameError", "loop_height_mm"),
    ],
)
def test_each_kind_of_bad_input_raises_its_own_noncirc_error(call, kind, message):
    import noncirc

    cls = getattr(noncirc, kind)
    assert issubclass(cls, noncirc.NoncircError) and issubclass(cls, ValueError)
    with pytest.raises(cls, match=message) as caught:
        call(Scene.builtin("paper"))
    # Exactly this kind, not a sibling.
    others = {"SceneError", "ParameterError", "ModelError", "UnknownNameError"} - {kind}
    assert not any(isinstance(caught.value, getattr(noncirc, o)) for o in others)


def test_an_internal_failure_is_no_input_error():
    import noncirc

    # A bug must not pass for bad input: InternalError is a RuntimeError, outside the
    # NoncircError (ValueError) family that callers catch to report their own mistakes.
    assert issubclass(noncirc.InternalError, RuntimeError)
    assert not issubclass(noncirc.InternalError, ValueError)
    assert not issubclass(noncirc.InternalError, noncirc.NoncircError)


def test_results_are_typed_and_tabulate_with_units():
    import json

    pd = pytest.importorskip("pandas")
    scene, x = paper_batch(6)
    b = evaluate_batch(scene, x, measures="all")
    frame = b.to_pandas()
    assert len(frame) == 6
    # Parameters, objectives and measures are named with their units.
    for column in ["train.phi0_deg", "picking_angle_deg", "interference_mm", "picking_tip_speed_m_s", "removal_length_mm", "cv", "valid", "error"]:
        assert column in frame.columns, column
    assert np.array_equal(frame["picking_angle_deg"].to_numpy(), b.value("picking_angle"), equal_nan=True)
    # The default goal, the least normalised margin, is maximised: its quantity is the
    # negative of what the search minimises.
    assert b.goal_names == ["least_normalised_margin"] and b.goal_maximised == [True]
    assert np.array_equal(frame["least_normalised_margin"].to_numpy(), np.where(b.valid, -b.goals[:, 0], np.nan), equal_nan=True)
    with pytest.raises(KeyError, match="neither an objective nor a measure"):
        b.value("picking_angel")
    # By default the events' measures, which cost nothing; none, or one by name.
    default = evaluate_batch(scene, x)
    assert "picking_tip_speed_m_s" in default.measure_names and "removal_length_mm" not in default.measure_names
    assert np.array_equal(default.value("picking_tip_speed_m_s"), b.value("picking_tip_speed_m_s"), equal_nan=True)
    assert evaluate_batch(scene, x, measures=[]).measures.shape == (6, 0)
    with pytest.raises(TypeError, match="measures must be"):
        evaluate_batch(scene, x, measures="loop_height_mm")
    only = evaluate_batch(scene, x, measures=["loop_height_mm"])
    assert only.measure_names == ["loop_height_mm"] and np.array_equal(only.measures[:, 0], b.value("loop_height_mm"), equal_nan=True)
    json.dumps(b.to_dict())

    r = evaluate(Scene.builtin("paper"))
    table = r.to_pandas()
    assert list(table.index) == Scene.builtin("paper").objective_names()
    assert table.loc["module", "unit"] == "mm" and not table.loc["module", "met"]
    samples = r.samples_to_pandas()
    assert list(samples.columns) == ["carrier_deg", "tip_x_mm", "tip_y_mm", "planet_x_mm", "planet_y_mm", "ratio", "attitude_deg"]
    assert json.loads(json.dumps(r.to_dict()))["report"] == r.report

    s = optimise(scene, algorithm="nsga2", seed=2, budget=3000, threads=1)
    front = s.to_pandas()
    assert len(front) == len(s.pareto) >= 1
    assert list(front.columns) == [p[0] for p in scene.free_parameters()] + ["least_normalised_margin", "cv"]
    assert s.goals[0].maximised and s.goals[0].unit == "" and isinstance(s.goals[0].value, float)
    assert json.loads(json.dumps(s.to_dict()))["best_scene"].startswith("name")


def test_the_package_docstring_example_runs():
    import doctest

    import noncirc

    result = doctest.testmod(noncirc)
    assert result.attempted >= 4 and result.failed == 0


def test_search_constraints_read_as_their_measures_in_evaluate_and_a_search():
    scene = Scene.builtin("paper-search").with_set(
        "search.constraints", '["picking_height_mm <= -90", "loop_width_mm >= 1000"]'
    )
    e = evaluate(scene)
    height, width = e.constraints["picking_height_mm <= -90"], e.constraints["loop_width_mm >= 1000"]
    assert height.value == e.measures["picking_height_mm"].value and height.at_most and height.bound == -90
    assert height.met == (height.value <= -90)
    assert not width.met and width.violation == pytest.approx(1000 - e.measures["loop_width_mm"].value, rel=1e-12)
    assert not e.feasible
    # A search cannot meet a metre-wide loop: its design is reported infeasible, and says why.
    with pytest.warns(RuntimeWarning, match=r"every objective and search constraint \(the best misses .*loop_width_mm >= 1000"):
        run = optimise(scene, budget=480, seed=3, progress=False)
    assert not run.feasible
    assert "loop_width_mm >= 1000" in run.missed
    assert [c.constraint for c in run.constraints] == scene.constraint_names()
    with pytest.raises(ValueError, match="loop_width_mm"):
        Scene.builtin("paper-search").with_set("search.constraints", '["loop_widht_mm <= 50"]')


STREAMED_BATCH = """
import resource, sys
import numpy as np
import noncirc

n = int(sys.argv[1])
scene = noncirc.Scene.builtin("paper-search")
p = scene.free_parameters()
lo, hi = np.array([q[1] for q in p]), np.array([q[2] for q in p])
x = lo + np.random.default_rng(0).random((n, len(p))) * (hi - lo)
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
r = noncirc.evaluate_batch(scene, x, measures=[], threads=2)
rise = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base) * 1024
arrays = sum(v.nbytes for k, v in vars(r).items() if isinstance(v, np.ndarray) and k != "x")
print(x.nbytes, arrays, rise, int(r.valid.sum()))
"""


def test_a_large_batch_is_streamed_within_its_outputs():
    # In a process of its own (its peak memory is the batch's): 300 000 designs, 41 MB of
    # input, 72 MB of output arrays. Read and evaluated a piece at a time, the batch adds
    # its outputs and a piece; it added 307 MB when it copied every row and kept every
    # row's results before writing them.
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-c", STREAMED_BATCH, "300000"], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    given, arrays, rise, valid = map(int, done.stdout.split())
    assert valid > 100_000
    assert rise < arrays + given, f"peak rose {rise / 1e6:.0f} MB for {arrays / 1e6:.0f} MB of outputs"
