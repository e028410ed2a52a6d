"""Long searches from Python: progress, a clean stop (callback or Ctrl-C), checkpoint and resume."""

import os
import signal
import threading

import numpy as np
import pytest

from noncirc import NoncircError, Scene, UnknownNameError, optimise

SETTINGS = dict(algorithm="de", seed=5, budget=2400, population=24, threads=2)


def test_progress_is_reported_after_every_generation():
    calls = []
    r = optimise(Scene.builtin("paper-search"), progress=calls.append, **SETTINGS)
    assert not r.stopped_early
    # Once before the first generation, then after each of the 100 generations of 24.
    assert len(calls) == 1 + 2400 // 24
    assert [c["evaluations"] for c in calls] == [24 * g for g in range(len(calls))]
    assert all(c["budget"] == 2400 for c in calls)
    assert calls[0]["best_violation"] is None and calls[-1]["best_violation"] is not None
    assert calls[-1]["feasible"] == (r.first_feasible_evaluations is not None)


def test_returning_false_stops_and_a_checkpoint_resumes_to_the_uninterrupted_result(tmp_path):
    scene = Scene.builtin("paper-search")
    whole = optimise(scene, **SETTINGS)
    ckpt = tmp_path / "run.ckpt"
    part = optimise(scene, progress=lambda info: info["generation"] < 30, checkpoint=ckpt, **SETTINGS)
    assert part.stopped_early and part.evaluations == 30 * 24
    resumed = optimise(resume=ckpt, threads=1)
    for key in ["best", "objectives", "evaluations", "confirmations", "first_feasible_evaluations"]:
        assert getattr(resumed, key) == getattr(whole, key), key
    # A resumed search runs the checkpoint's own settings: others are refused, not ignored.
    with pytest.raises(NoncircError, match="seed would be ignored"):
        optimise(resume=ckpt, seed=6)
    with pytest.raises(NoncircError, match="checkpoint interval"):
        optimise(resume=ckpt, checkpoint_every=float("inf"))
    with pytest.raises(NoncircError, match="not both"):
        optimise(scene, resume=ckpt)


def test_an_error_in_the_callback_stops_the_search_and_is_raised():
    def broken(info):
        if info["generation"] == 3:
            raise RuntimeError("callback broke")

    with pytest.raises(RuntimeError, match="callback broke"):
        optimise(Scene.builtin("paper-search"), progress=broken, **SETTINGS)


class InterruptAfter:
    """Sends this process SIGINT from another thread once `reported` holds `count`
    reports, and notes how many it held then (`at_signal`); as a context manager it
    installs Python's handler for the block and never signals after it."""

    def __init__(self, reported: list, count: int):
        self.reported, self.count, self.at_signal = reported, count, None
        self.done = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        while len(self.reported) < self.count:
            if self.done.wait(0.001):
                return
        self.at_signal = len(self.reported)
        os.kill(os.getpid(), signal.SIGINT)

    def __enter__(self):
        # Python raises KeyboardInterrupt only if SIGINT was not ignored when it started
        # (a background job of a non-interactive shell inherits it ignored).
        self.previous = signal.signal(signal.SIGINT, signal.default_int_handler)
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.done.set()
        self.thread.join()
        signal.signal(signal.SIGINT, self.previous)
        return False


def test_ctrl_c_stops_after_the_current_generation_and_keeps_the_checkpoint(tmp_path):
    ckpt = tmp_path / "run.ckpt"
    seen = []
    # The budget is finite so that a missed interrupt fails rather than runs on.
    with InterruptAfter(seen, 3) as interrupt, pytest.raises(KeyboardInterrupt):
        optimise(Scene.builtin("paper-search"), checkpoint=ckpt, progress=seen.append,
                 **{**SETTINGS, "budget": 10**6})
    # The search stopped on the signal, not at its budget; the generation in flight was
    # dropped, so the last report is the last complete generation. (How many generations
    # of 24 designs end in the 20 ms between two checks for Ctrl-C depends on the machine;
    # a signal inside one long generation is the test below.)
    assert interrupt.at_signal <= len(seen) and seen[-1]["evaluations"] < 10**6
    # The checkpoint holds the state the search stopped in: ten more generations from it.
    stopped_at = seen[-1]["evaluations"]
    resumed = optimise(resume=ckpt, budget=stopped_at + 240, threads=1)
    assert resumed.evaluations == stopped_at + 240


def test_ctrl_c_inside_a_long_generation_stops_it_and_keeps_the_last_whole_state(tmp_path):
    import json

    ckpt = tmp_path / "long.ckpt"
    seen = []
    # One generation of 20 000 designs at 30 000 samples a turn: minutes on one thread.
    scene = Scene.builtin("paper-search").with_set("search.screening.samples_per_turn", 30000)
    with InterruptAfter(seen, 1), pytest.raises(KeyboardInterrupt):
        optimise(scene, checkpoint=ckpt, progress=seen.append, algorithm="de", population=20000,
                 budget=40000, threads=1)
    # Counted, not timed: the signal came in the first generation, which is dropped whole
    # (had the search waited for its end, 20 000 evaluations would be kept and reported).
    assert [info["evaluations"] for info in seen] == [0]
    state = json.loads(ckpt.read_text())["state"]
    assert (state["generation"], state["evaluations"]) == (0, 0)


def test_unknown_algorithm_is_an_unknown_name():
    with pytest.raises(UnknownNameError, match="cmaes"):
        optimise(Scene.builtin("paper-search"), algorithm="cmaez")


def test_a_search_that_ends_infeasible_warns():
    with pytest.warns(RuntimeWarning, match="no design found meets every objective"):
        r = optimise(Scene.builtin("paper-search"), algorithm="de", seed=1, budget=96, population=48, threads=1)
    assert r.feasible is False and r.missed


def test_ctrl_c_stops_a_large_batch_after_the_piece_in_flight():
    from noncirc import evaluate_batch

    scene = Scene.builtin("paper-search")
    lo, hi = (np.array([p[k] for p in scene.free_parameters()]) for k in (1, 2))
    x = lo + np.random.default_rng(0).random((1_000_000, len(lo))) * (hi - lo)
    reports = []
    with InterruptAfter(reports, 2) as interrupt, pytest.raises(KeyboardInterrupt):
        evaluate_batch(scene, x, threads=2, progress=lambda info: reports.append(info["evaluations"]))
    # Counted, not timed: pieces of 4 096 rows, each reported after the check for Ctrl-C;
    # after the signal at most the piece in flight ends (one more report if the signal
    # raced one), then the batch stops, far from its 244 pieces.
    assert reports[:2] == [4096, 8192]
    assert len(reports) - interrupt.at_signal <= 1, (len(reports), interrupt.at_signal)
    assert reports[-1] < len(x)


def test_ctrl_c_stops_a_batch_inside_a_long_piece():
    from noncirc import evaluate_batch

    scene = Scene.builtin("paper-search")
    lo, hi = (np.array([p[k] for p in scene.free_parameters()]) for k in (1, 2))
    # One piece of 4 096 rows at 30 000 samples a turn: about 15 s on one thread.
    x = lo + np.random.default_rng(1).random((4096, len(lo))) * (hi - lo)
    reports = []
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            evaluate_batch(scene, x, threads=1, samples_per_turn=30000,
                           progress=lambda info: reports.append(info["evaluations"]))
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    # The piece in flight is abandoned, not reported. (That its rows not yet started are
    # skipped is counted in Rust: batch.rs `a_stopped_batch_skips_the_rows_not_started`;
    # the same watcher stops `optimise` inside a generation, counted in the test above.)
    assert reports == []


def test_a_batch_reports_its_progress_piece_by_piece():
    from noncirc import evaluate_batch

    scene = Scene.builtin("paper-search")
    lo, hi = (np.array([p[k] for p in scene.free_parameters()]) for k in (1, 2))
    x = lo + np.random.default_rng(1).random((9000, len(lo))) * (hi - lo)
    reports = []
    batch = evaluate_batch(scene, x, threads=2, progress=reports.append)
    assert reports == [{"evaluations": n, "total": 9000} for n in (4096, 8192, 9000)]
    assert len(batch.cv) == 9000

    def broken(info):
        raise RuntimeError("callback broke")

    with pytest.raises(RuntimeError, match="callback broke"):
        evaluate_batch(scene, x, progress=broken)


def test_a_progress_bar_draws_on_request_and_stays_off_when_nobody_watches(capsys):
    import io

    from noncirc import ProgressBar

    optimise(Scene.builtin("paper-search"), progress=True, **SETTINGS)
    drawn = capsys.readouterr().err
    # One line redrawn after every generation, ending at the budget, then closed.
    assert drawn.count("\r") == 1 + 2400 // 24 and drawn.endswith("\n")
    assert "2,400/2,400 designs" in drawn.splitlines()[-1]
    # Under pytest stderr is not a terminal: by default nothing is drawn.
    optimise(Scene.builtin("paper-search"), **SETTINGS)
    assert capsys.readouterr().err == ""
    bar = ProgressBar(io.StringIO())
    bar({"budget": 100, "evaluations": 50, "best_violation": 0.25, "feasible": False})
    assert "[############............] 50/100 designs" in bar.stream.getvalue() and "best CV 0.25" in bar.stream.getvalue()
