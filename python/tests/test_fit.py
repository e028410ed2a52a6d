"""Fitting a design to a target from Python (docs/inverse.md): the round trip at a small
budget, the typed result, and bad targets refused by name."""

from pathlib import Path

import pytest

import noncirc

ROOT = Path(__file__).resolve().parents[2]
ROUNDTRIP = ROOT / "scenes" / "targets" / "roundtrip.toml"


def test_the_round_trip_fits_and_its_result_is_typed():
    scene = noncirc.Scene.builtin("paper-search")
    result = noncirc.fit(scene, target=ROUNDTRIP, budget=20000, seed=2, threads=2, progress=False)
    # Far from its start (tens of mm) to within a few tenths of a millimetre.
    assert result.feasible
    assert result.path_hausdorff_mm < 2.0
    assert result.measures["path_hausdorff_mm"].value == result.path_hausdorff_mm
    assert result.measures["path_hausdorff_mm"].tolerance == 0.5
    assert [p.name for p in result.poses] == ["picking", "planting"]
    assert all(p.position_error_mm < 2.0 for p in result.poses)
    assert set(result.design) == {name for name, *_ in scene.free_parameters()}
    # The fitted scene carries the target and evaluates to the same fit.
    again = noncirc.evaluate(result.scene)
    assert again.report["fit"]["path_hausdorff_mm"] == pytest.approx(result.path_hausdorff_mm, abs=1e-9)
    table = result.to_pandas()
    assert list(table.columns) == ["name", "value", "unit", "tolerance", "met"]
    assert "pose2_attitude_deg" in set(table["name"])


def test_the_same_seed_fits_alike_on_one_and_two_threads():
    scene = noncirc.Scene.builtin("paper-search")
    one = noncirc.fit(scene, target=ROUNDTRIP, budget=2000, seed=4, threads=1, progress=False)
    two = noncirc.fit(scene, target=ROUNDTRIP, budget=2000, seed=4, threads=2, progress=False)
    assert one.design == two.design and one.cost == two.cost


@pytest.mark.parametrize(
    "text, names",
    [
        ("0,0\n100,0\n100,100\n", "needs at least 4 points, got 3"),
        ("0,0\n100,100\n100,0\n0,100\n", "target.x_mm[0]: the target path crosses itself"),
        ("0,0\n100,0\nnan,100\n0,100\n", "target.x_mm[2] must be a finite number"),
        ("0,0\n3000,0\n3000,3000\n0,3000\n", "target.x_mm[1]: out of the arm's reach"),
    ],
)
def test_a_bad_target_raises_parameter_error_naming_it(tmp_path, text, names):
    path = tmp_path / "target.csv"
    path.write_text(text)
    with pytest.raises(noncirc.ParameterError, match=names.replace("[", r"\[").replace("]", r"\]").replace("(", r"\(")):
        noncirc.fit(noncirc.Scene.builtin("paper-search"), target=path, budget=100, progress=False)
