"""noncirc.repair: the nearest design that works, as `noncirc repair`."""

import json

import noncirc
import pytest


def test_the_papers_design_is_repaired_with_its_changes_listed(tmp_path):
    scene = noncirc.Scene.builtin("paper-search")
    seen = []
    result = noncirc.repair(scene, budget=20_000, seed=1, threads=2, progress=lambda info: seen.append(info))
    assert isinstance(result, noncirc.RepairResult)
    # The paper's design misses the module objective; the repaired one meets all nine.
    assert result.violations_before["module"] > 2.0
    assert result.repaired and result.teeth_failures == []
    assert all(v == 0.0 for v in result.violations_after.values())
    assert seen and seen[-1]["evaluations"] <= seen[-1]["budget"] + 100
    # The repaired scene is a scene: it evaluates to the same objectives.
    evaluation = noncirc.evaluate(result.scene)
    assert evaluation.feasible
    assert evaluation.objectives["module"].value == pytest.approx(result.after["module"].value, rel=1e-12)
    # Every change is the scenes' difference, largest first.
    for c in result.changes:
        assert scene.get(c.name) == c.before
        assert result.scene.get(c.name) == pytest.approx(c.after, rel=1e-12)
        assert c.delta == pytest.approx(c.after - c.before, abs=1e-12)
    sizes = [abs(c.delta_percent_of_box) for c in result.changes]
    assert sizes == sorted(sizes, reverse=True)
    table = result.to_pandas()
    assert list(table.columns) == ["name", "symbol", "before", "after", "delta", "delta_percent_of_box"]
    assert len(table) == 17
    assert json.dumps(result.to_dict())
    # The repaired design goes to the workshop: its solids, with the teeth setting that
    # cuts them, read back by OpenCascade as valid closed solids (docs/cad.md).
    done = noncirc.cad(result.scene, tmp_path, formats=["step"])
    assert done.failures == []
    assert {p.name for p in done.paths} == {f"{p.name}.step" for p in done.parts} | {"train.step", "assembly.json"}
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.STEPControl import STEPControl_Reader

    for part in done.parts:
        reader = STEPControl_Reader()
        reader.ReadFile(str(tmp_path / f"{part.name}.step"))
        reader.TransferRoots()
        assert BRepCheck_Analyzer(reader.OneShape()).IsValid(), part.name


def test_a_bad_weight_is_refused_by_name():
    with pytest.raises(noncirc.NoncircError, match="design scale"):
        noncirc.repair(noncirc.Scene.builtin("paper-search"), design_scale=-1.0)
