"""Dynamics against an independent engine: the train of `noncirc dynamics` rebuilt in
MuJoCo (bodies and hinges from noncirc's geometry, the motion prescribed from noncirc's
kinematics) and solved by `mj_inverse`. The hinge torques MuJoCo needs are the moments
noncirc's meshes supply, and by virtual work (the sun's mesh does no work: its pitch point
stands still) they give the input torque.

The CLI binary (`cli_binary.NONCIRC_BIN`) computes the dynamics; tests/run_all.sh builds it.
"""

import json
import math
import subprocess
from pathlib import Path

import mujoco
import numpy as np
import pytest
from cli_binary import NONCIRC_BIN

ROOT = Path(__file__).resolve().parents[2]
BIN = NONCIRC_BIN


def noncirc_dynamics(*sets: str) -> dict:
    args = [str(BIN), "dynamics", "paper", "--format", "json"]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def body_xml(name: str, axle_mm, angle: float, blank: dict, child: str = "") -> str:
    """A body on a z hinge at `axle_mm` in its parent, its frame turned by `angle`, with
    `blank`'s mass, centre of mass (mm, own frame) and moment of inertia about it."""
    x, y = (v * 1e-3 for v in axle_mm)
    cx, cy = (v * 1e-3 for v in blank["centroid_mm"])
    j = blank["inertia_kg_m2"]
    return (
        f'<body name="{name}" pos="{x!r} {y!r} 0" euler="0 0 {angle!r}">'
        f'<joint name="{name}" type="hinge" axis="0 0 1"/>'
        f'<inertial pos="{cx!r} {cy!r} 0" mass="{blank["mass_kg"]!r}" '
        f'diaginertia="{j!r} {j!r} {j!r}"/>{child}</body>'
    )


def model(d: dict, gravity: float) -> mujoco.MjModel:
    """The carrier on the frame's z axis; each arm set k on it, turned by −σ·k·2π/arms
    (arm k is arm I a k-th of a turn later), holding its intermediate and its planet with
    the arm. The carrier's own centre of mass is on its axis (a negligible body here: at
    constant speed it takes no torque)."""
    sigma = d["joint_d1"][0][0]
    sets = []
    for k in range(d["arms"]):
        turn = -sigma * k * 2 * math.pi / d["arms"]
        c, s = math.cos(turn), math.sin(turn)

        def on_set(p):
            return (c * p[0] - s * p[1], s * p[0] + c * p[1])

        # The gears' own frames at joint angle 0 coincide with the carrier's (the joint
        # angles are measured from it), hence the hinges' frames are turned by `turn`.
        sets.append(
            body_xml(f"intermediate{k}", on_set(d["intermediate_axle_on_carrier_mm"]), turn, d["intermediate"])
            + body_xml(f"planet{k}", on_set(d["planet_axle_on_carrier_mm"]), turn, d["planet_with_arm"])
        )
    xml = (
        f'<mujoco><compiler angle="radian"/><option gravity="0 {-gravity!r} 0"/><worldbody>'
        '<body name="carrier"><joint name="carrier" type="hinge" axis="0 0 1"/>'
        '<inertial pos="0 0 0" mass="1e-6" diaginertia="1e-9 1e-9 1e-9"/>'
        + "".join(sets)
        + "</body></worldbody></mujoco>"
    )
    return mujoco.MjModel.from_xml_string(xml)


def mujoco_torques(d: dict, gravity: float):
    """Per node: MuJoCo's hinge torques (carrier, then each set's intermediate and planet)
    and the input torque by virtual work, Σ Q·dq/dθ."""
    m = model(d, gravity)
    data = mujoco.MjData(m)
    omega = d["carrier_speed_rad_s"]
    n, arms = len(d["carrier_deg"]), d["arms"]
    hinges, torque = [], []
    for j in range(n):
        q, dq, ddq = [d["joint_rad"][j][0]], [d["joint_d1"][j][0]], [0.0]
        for k in range(arms):
            node = (j - k * n // arms) % n
            q += d["joint_rad"][node][1:]
            dq += d["joint_d1"][node][1:]
            ddq += d["joint_d2"][node][1:]
        data.qpos[:] = q
        data.qvel[:] = np.array(dq) * omega
        data.qacc[:] = np.array(ddq) * omega**2
        mujoco.mj_inverse(m, data)
        hinges.append(data.qfrc_inverse.copy())
        torque.append(float(data.qfrc_inverse @ np.array(dq)))
    return np.array(hinges), np.array(torque)


@pytest.mark.parametrize("arms,rate", [(3, 180), (3, 300), (2, 180), (4, 240)])
def test_mujoco_needs_the_same_hinge_torques_and_input_torque(arms, rate):
    d = noncirc_dynamics(
        f"train.arms={arms}",
        f"train.picks_per_minute={rate}",
        "resolution.samples_per_turn=240",
        # MuJoCo's inverse dynamics has no tip load; gravity stays.
        "dynamics.picking_force_n=0",
    )
    hinges, torque = mujoco_torques(d, gravity=9.81)
    peak = max(abs(t) for t in d["input_torque_nm"])
    assert peak > 1.0
    diff = np.max(np.abs(torque - np.array(d["input_torque_nm"])))
    assert diff < 1e-4 * peak, (diff, peak)
    # Arm set I's hinges: the intermediate's and the planet's mesh moments.
    for got, want in [(hinges[:, 1], d["intermediate_moment_nm"]), (hinges[:, 2], d["planet_moment_nm"])]:
        scale = max(abs(w) for w in want)
        assert np.max(np.abs(got - np.array(want))) < 1e-4 * scale


def test_gravity_alone_at_a_crawl_is_the_weights_moment():
    # At 1e-3 r/min inertia vanishes: the input torque is what lifts the bodies' weights,
    # the rate of their potential energy, in MuJoCo as in noncirc.
    d = noncirc_dynamics("train.carrier_speed_rpm=0.001", "dynamics.picking_force_n=0")
    _, torque = mujoco_torques(d, gravity=9.81)
    peak = max(abs(t) for t in d["input_torque_nm"])
    assert 0.01 < peak < 10.0
    assert np.max(np.abs(torque - np.array(d["input_torque_nm"]))) < 1e-4 * peak


def test_the_python_result_is_the_cli_report_typed():
    import noncirc

    scene = noncirc.Scene.builtin("paper")
    d = noncirc.dynamics(scene)
    cli = noncirc_dynamics()
    assert np.array_equal(d.input_torque_nm, cli["input_torque_nm"])
    assert np.array_equal(d.mesh_force_intermediate_planet_n, cli["mesh_force_n"][1])
    assert d.planet_with_arm.mass_kg == pytest.approx(cli["planet_with_arm"]["mass_kg"], rel=0, abs=0)
    assert d.sun_shaft_n.shape == (len(d.carrier_deg), 2)
    table = d.to_pandas()
    assert len(table) == len(d.carrier_deg)
    assert {"input_torque_nm", "sun_shaft_x_n", "sun_shaft_y_n", "shaking_moment_nm"} <= set(table.columns)
    assert d.summary["torque_peak_nm"] == pytest.approx(np.max(np.abs(d.input_torque_nm)))


def test_a_bad_body_is_refused_by_name():
    import noncirc

    with pytest.raises(noncirc.NoncircError, match="dynamics.face_width_mm"):
        noncirc.Scene.builtin("paper").with_set("dynamics.face_width_mm", 0)
    with pytest.raises(noncirc.NoncircError, match="dynamics.arm_mass_kg"):
        noncirc.Scene.builtin("paper").with_set("dynamics.arm_mass_kg", -1.0)
    # The CLI: exit 2, the field named.
    done = subprocess.run([str(BIN), "dynamics", "--set", "dynamics.gear_density_kg_m3=-5"], capture_output=True, text=True)
    assert done.returncode == 2 and "dynamics.gear_density_kg_m3" in done.stderr, done.stderr
    done = subprocess.run([str(BIN), "dynamics", "ellipse-gear"], capture_output=True, text=True)
    assert done.returncode == 2 and "three_arm" in done.stderr, done.stderr


def test_the_strength_is_typed_and_the_cli_s():
    import noncirc

    shaper = 'gear.teeth.cutter={kind="shaper",teeth=100}'
    scene = noncirc.Scene.builtin("two-arm").with_set("gear.teeth.cutter", {"kind": "shaper", "teeth": 100})
    d = noncirc.dynamics(scene)
    done = subprocess.run([str(BIN), "dynamics", "two-arm", "--set", shaper, "--format", "json"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    cli = json.loads(done.stdout)["strength"]
    s = d.strength
    assert isinstance(s, noncirc.Strength) and d.strength_unavailable is None
    assert [g.name for g in s.gears] == ["sun", "intermediate", "planet"]
    for g, raw in zip(s.gears, cli["gears"]):
        assert isinstance(g, noncirc.GearStrength)
        assert np.array_equal(g.bending_mpa, raw["bending_mpa"])
        # The peak is the cycle's largest, and the safety factor the limit over it.
        assert g.bending_peak_mpa == np.max(g.bending_mpa)
        assert g.contact_safety == pytest.approx(s.contact_limit_mpa / np.max(g.contact_mpa), rel=1e-12)
    assert s.bending_safety_min == min(g.bending_safety for g in s.gears)
    table = s.to_pandas()
    assert list(table["name"]) == ["sun", "intermediate", "planet"]
    assert {"bending_safety", "contact_safety", "form_factor_least", "form_factor_largest"} <= set(table.columns)
    # The paper's teeth cannot be cut: no strength, and why.
    p = noncirc.dynamics(noncirc.Scene.builtin("paper"))
    assert p.strength is None and "concave" in p.strength_unavailable


def test_a_material_without_a_name_or_an_allowable_stress_is_refused():
    import noncirc

    with pytest.raises(noncirc.NoncircError, match="dynamics.material"):
        noncirc.Scene.builtin("paper").with_set("dynamics.material", "")
    with pytest.raises(noncirc.NoncircError, match="dynamics.bending_limit_mpa"):
        noncirc.Scene.builtin("paper").with_set("dynamics.bending_limit_mpa", 0)
    done = subprocess.run([str(BIN), "dynamics", "--set", "dynamics.contact_limit_mpa=-1"], capture_output=True, text=True)
    assert done.returncode == 2 and "dynamics.contact_limit_mpa" in done.stderr, done.stderr


def test_a_batch_s_dynamics_measures_are_the_dynamics_report_s():
    import noncirc

    scene = noncirc.Scene.builtin("two-arm").with_set("gear.teeth.cutter", {"kind": "shaper", "teeth": 100})
    x = np.array([list(scene.free_values().values())])
    names = ["input_torque_peak_nm", "sun_shaft_peak_n", "bending_safety"]
    b = noncirc.evaluate_batch(scene, x, measures=names)
    assert b.measure_names == names and b.measure_units == ["N·m", "N", ""]
    d = noncirc.dynamics(scene)
    assert b.measures[0, 0] == d.summary["torque_peak_nm"]
    assert b.measures[0, 1] == d.summary["sun_shaft_peak_n"]
    assert b.measures[0, 2] == d.strength.bending_safety_min
    # "all" brings the dynamics' measures, not the safety factors (they cut the teeth).
    every = noncirc.evaluate_batch(scene, x, measures="all").measure_names
    assert "input_torque_rms_nm" in every and "bending_safety" not in every


def test_the_speed_with_a_flywheel_is_typed_and_the_flywheel_needed_holds_the_allowed():
    import noncirc

    scene = noncirc.Scene.builtin("paper")
    d = noncirc.dynamics(scene)
    v = d.speed
    assert isinstance(v, noncirc.SpeedFluctuation)
    # The turn's mean speed over time is the working speed; the drive torque the mean torque.
    w = v.carrier_speed_rad_s
    assert len(w) / np.sum(1.0 / w) == pytest.approx(d.carrier_speed_rad_s, rel=1e-12)
    assert v.coefficient == pytest.approx((w.max() - w.min()) * np.mean(1.0 / w), rel=1e-12)
    assert v.drive_torque_nm == pytest.approx(np.mean(d.load_torque_nm), rel=1e-12)
    # With the flywheel reported as needed, the coefficient is the allowed one.
    fitted = noncirc.dynamics(scene.with_set("dynamics.flywheel_inertia_kg_m2", d.flywheel_needed_kg_m2))
    assert fitted.speed.coefficient == pytest.approx(d.speed_fluctuation_allowed, rel=1e-6)
    assert "carrier_speed_constant_drive_rad_s" in d.to_pandas().columns
    with pytest.raises(noncirc.NoncircError, match="dynamics.speed_fluctuation_allowed"):
        scene.with_set("dynamics.speed_fluctuation_allowed", 0)
