"""docs/python.md's examples run as written (the pymoo one in test_pymoo.py)."""

import re
from pathlib import Path

DOC = Path(__file__).resolve().parents[2] / "docs" / "python.md"


def blocks():
    return re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)


def test_the_worked_example_and_the_long_search_example_run_as_written(tmp_path, monkeypatch, capsys):
    worked, long_search = blocks()[:2]
    assert "noncirc.evaluate(scene)" in worked and "resume=" in long_search
    monkeypatch.chdir(tmp_path)  # the example writes run.ckpt
    namespace: dict = {}
    exec(compile(worked, str(DOC), "exec"), namespace)
    exec(compile(long_search, str(DOC), "exec"), namespace)
    # What the comments promise: the confirmed result is feasible, the resumed search
    # ran to its raised budget, the checkpoint exists.
    assert namespace["result"].feasible and namespace["r"].evaluations >= 400_000
    assert (tmp_path / "run.ckpt").exists()
    printed = capsys.readouterr().out
    assert "85.0175" in printed and "Objective(name='picking_angle'" in printed


def test_the_robust_design_example_runs_as_written(capsys):
    block = next(b for b in blocks() if "noncirc.robustness(" in b)
    exec(compile(block, str(DOC), "exec"), {})
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "0.0" and lines[1] == "0.0"
    assert lines[2] == "(9, 1024)" and lines[3] == "train.arm_length_mm"


def test_the_fit_example_runs_as_written(monkeypatch, capsys):
    block = next(b for b in blocks() if "noncirc.fit(" in b)
    monkeypatch.chdir(DOC.parents[1])  # the example names the target from the repository
    exec(compile(block, str(DOC), "exec"), {})
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "True 0.084"
    assert lines[1].startswith("FitMeasure(name='pose1_position_mm'")


def test_the_inverse_example_runs_as_written(monkeypatch, capsys):
    block = next(b for b in blocks() if "noncirc.inverse(" in b)
    monkeypatch.chdir(DOC.parents[1])  # the example names the target from the repository
    exec(compile(block, str(DOC), "exec"), {})
    lines = capsys.readouterr().out.splitlines()
    assert lines == ["True True 160.9", "0.73 1.41"]


def test_the_repair_example_runs_as_written(capsys):
    block = next(b for b in blocks() if "noncirc.repair(" in b)
    exec(compile(block, str(DOC), "exec"), {})
    lines = capsys.readouterr().out.splitlines()
    assert lines == ["True 20.6", "True", "r8 34.5"]


def test_the_dask_example_runs_as_a_script(tmp_path):
    """As a user pastes it into a file: its own process, Dask's workers importing it."""
    import subprocess
    import sys

    block = next(b for b in blocks() if "LocalCluster" in b)
    script = tmp_path / "cluster.py"
    script.write_text(block)
    out = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    line = out.stdout.strip().splitlines()[-1]
    assert line.startswith("(10000, 9) ") and line.endswith("[True, True, True, True]"), line
