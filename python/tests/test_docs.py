"""The Python examples of docs/python.md, docs/robustness.md and docs/cad.md run as written, as a user
runs them: each block saved to a file and run with `python` in a folder of its own (which
sees the repository's `scenes/`, as the examples name its targets), not inside pytest; what
their comments promise is checked on what they print."""

import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
DOC = REPO / "docs" / "python.md"
DOCS = [DOC, REPO / "docs" / "robustness.md", REPO / "docs" / "cad.md"]


def blocks(doc: Path = DOC) -> list[str]:
    """The doc's Python blocks, those indented under a list item dedented as a reader
    copies them."""
    found = re.findall(r"^( *)```python\n(.*?)^\1```", doc.read_text(), re.S | re.M)
    return [textwrap.dedent(body) for _, body in found]


def block_with(text: str) -> str:
    return next(b for b in blocks() if text in b)


def run_as_script(block: str, folder: Path) -> list[str]:
    """`python example.py` in `folder`; its printed lines (a failure shows its stderr)."""
    (folder / "scenes").symlink_to(REPO / "scenes")
    script = folder / "example.py"
    script.write_text(block)
    done = subprocess.run([sys.executable, str(script)], cwd=folder, capture_output=True,
                          text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.splitlines()


# The blocks whose output a test below checks; every other block runs in
# `test_every_other_block_runs_as_a_script`.
CHECKED = ("noncirc.evaluate(scene)", "resume=", "r = noncirc.robustness(scene, samples=1024)",
           "noncirc.fit(", "noncirc.inverse(", "noncirc.repair(", "LocalCluster")
OTHERS = [(doc.name, i) for doc in DOCS for i, b in enumerate(blocks(doc))
          if not any(c in b for c in CHECKED)]


def test_the_worked_example_runs_as_written(tmp_path):
    lines = run_as_script(block_with("noncirc.evaluate(scene)"), tmp_path)
    # As the comments say.
    assert lines[0] == "86.0 [21.0, 28.0, 50.0]" and lines[1].startswith("85.0175")
    assert lines[2].startswith("Objective(name='picking_angle', value=0.297")
    assert lines[3] == "False" and lines[4] == "(120, 2) (802, 2)"
    # The search's result is feasible, and confirmed so.
    assert lines[-2].startswith("True {") and lines[-1] == "True"


def test_the_long_search_example_resumes_to_its_raised_budget(tmp_path):
    lines = run_as_script(block_with("resume="), tmp_path)
    assert lines[-1] == "True"
    assert (tmp_path / "run.ckpt").exists()


def test_the_robust_design_example_runs_as_written(tmp_path):
    lines = run_as_script(block_with("r = noncirc.robustness(scene, samples=1024)"), tmp_path)
    assert lines[0] == "0.0" and lines[1] == "0.0"
    assert lines[2] == "(9, 1024)" and lines[3] == "train.arm_length_mm"


def test_the_fit_example_runs_as_written(tmp_path):
    lines = run_as_script(block_with("noncirc.fit("), tmp_path)
    assert lines[0] == "True 0.084"
    assert lines[1].startswith("FitMeasure(name='pose1_position_mm'")


def test_the_inverse_example_runs_as_written(tmp_path):
    lines = run_as_script(block_with("noncirc.inverse("), tmp_path)
    assert lines == ["True True 160.9", "0.73 1.67"]


def test_the_repair_example_runs_as_written(tmp_path):
    lines = run_as_script(block_with("noncirc.repair("), tmp_path)
    assert lines == ["True 20.6", "True", "r8 34.5"]


def test_the_dask_example_runs_as_a_script(tmp_path):
    """Dask's workers are processes that import the script: the example's guard matters."""
    line = run_as_script(block_with("LocalCluster"), tmp_path)[-1]
    assert line.startswith("(10000, 9) ") and line.endswith("[True, True, True, True]"), line


@pytest.mark.parametrize("doc,index", OTHERS)
def test_every_other_block_runs_as_a_script(doc, index, tmp_path):
    run_as_script(blocks(REPO / "docs" / doc)[index], tmp_path)


def test_every_block_is_run():
    """No block escapes: the checked ones and the others are all of them."""
    every = sum(len(blocks(doc)) for doc in DOCS)
    checked = sum(any(c in b for c in CHECKED) for doc in DOCS for b in blocks(doc))
    assert checked == len(CHECKED) and checked + len(OTHERS) == every
