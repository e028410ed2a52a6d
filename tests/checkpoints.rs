//! Checkpoints: every algorithm resumes from one; a damaged, foreign, old or hand-edited
//! checkpoint is refused with what is wrong, never a panic, a hang or a run against the
//! wrong problem (issue 22). The proptest is the fuzz target for checkpoint files.

use noncirc::core::Checkpoint;
use noncirc::core::Scene;
use noncirc::core::SceneProblem;
use noncirc::core::{execute, stop_after_generations};
use noncirc::core::{Algorithm, SearchState};
use noncirc::scene_file::{apply_overrides, load_scene};
use noncirc::search::ParallelEvaluator;
use proptest::prelude::*;
use serde_json::{json, Value};

/// A small search scene: 4 free parameters, screening at 36 samples per turn.
fn scene() -> Scene {
    let sets = [
        r#"search.free=[{name="train.phi0_deg",lower=-90,upper=-30},{name="train.beta0_deg",lower=40,upper=100},{name="train.arm_length_mm",lower=100,upper=160},{name="train.gamma0_deg",lower=-80,upper=-20}]"#,
        "search.screening.samples_per_turn=36",
    ];
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    apply_overrides(load_scene(Some("paper-search")).unwrap(), &sets).unwrap()
}

/// A checkpoint of `algorithm` after 3 generations, as JSON.
fn checkpoint(algorithm: Algorithm) -> Value {
    let scene = scene();
    let problem = SceneProblem::new(&scene).unwrap();
    let mut state = SearchState::new(algorithm, 4, 1, 8, 5);
    execute(
        &mut state,
        &mut ParallelEvaluator::new(&problem, 1).unwrap(),
        10_000,
        &mut [&mut stop_after_generations(3)],
    );
    serde_json::from_slice(&Checkpoint::new(&problem, 10_000, &state).to_json()).unwrap()
}

fn read(v: &Value) -> Result<Checkpoint, String> {
    Checkpoint::from_json(&serde_json::to_vec(v).unwrap()).map_err(|e| e.to_string())
}

const ALL: [Algorithm; 5] = [
    Algorithm::Guided,
    Algorithm::De,
    Algorithm::Cmaes,
    Algorithm::Nsga2,
    Algorithm::Nsga3,
];

#[test]
fn every_algorithm_reads_back_its_checkpoint() {
    for a in ALL {
        let cp = read(&checkpoint(a)).unwrap_or_else(|e| panic!("{a:?}: {e}"));
        assert_eq!(cp.state.generation, 3, "{a:?}");
    }
}

#[test]
fn old_foreign_and_future_files_are_refused_by_name() {
    let mut v = checkpoint(Algorithm::De);
    v.as_object_mut().unwrap().remove("version");
    assert!(read(&v).unwrap_err().contains("not a noncirc checkpoint"));
    let mut v = checkpoint(Algorithm::De);
    v["version"] = json!(99);
    assert!(read(&v).unwrap_err().contains("format version 99"));
    assert!(read(&json!({"name": "x"}))
        .unwrap_err()
        .contains("not a noncirc checkpoint"));
    assert!(Checkpoint::from_json(b"{\"format\": ").is_err());
}

#[test]
fn a_damage_the_parts_cannot_show_is_refused_by_the_state_s_hash() {
    // A flipped digit in a coordinate: a valid state, another search.
    let mut v = checkpoint(Algorithm::De);
    let u = &mut v["state"]["solver"]["De"]["population"][1]["u"][2];
    let x = u.as_f64().unwrap();
    *u = json!(if x < 0.5 { x + 0.1 } else { x - 0.1 });
    assert!(Checkpoint::from_json_unhashed(&serde_json::to_vec(&v).unwrap()).is_ok());
    let e = read(&v).unwrap_err();
    assert!(
        e.contains("the state's hash") && e.contains("damaged"),
        "{e}"
    );
    // The budget is covered too.
    let mut v = checkpoint(Algorithm::Nsga2);
    v["budget"] = json!(20_000);
    assert!(read(&v).unwrap_err().contains("the state's hash"));
}

#[test]
fn a_huge_population_or_a_count_near_the_end_of_u64_neither_allocates_nor_hangs() {
    // DE and NSGA sizes beyond what a scene may ask (1e12 once tried to allocate 24 TB).
    for (algorithm, key) in [(Algorithm::De, "De"), (Algorithm::Nsga3, "Nsga3")] {
        let mut v = checkpoint(algorithm);
        v["state"]["solver"][key]["size"] = json!(1_000_000_000_000u64);
        v["state"]["solver"][key]["population"] = json!([]);
        let e = Checkpoint::from_json_unhashed(&serde_json::to_vec(&v).unwrap())
            .unwrap_err()
            .to_string();
        assert!(e.contains("population size 1000000000000"), "{e}");
    }
    // 2^64 − 3 evaluations against a budget of 2^64 − 1: a generation of 8 saturates the
    // count and the run ends at the budget instead of wrapping round to zero.
    let mut v = checkpoint(Algorithm::De);
    v["state"]["evaluations"] = json!(u64::MAX - 3);
    let mut cp = Checkpoint::from_json_unhashed(&serde_json::to_vec(&v).unwrap()).unwrap();
    let problem = SceneProblem::new(&cp.scene).unwrap();
    let generation = cp.state.generation;
    execute(
        &mut cp.state,
        &mut ParallelEvaluator::new(&problem, 1).unwrap(),
        u64::MAX - 1,
        &mut [&mut stop_after_generations(1000)],
    );
    assert_eq!(cp.state.evaluations, u64::MAX);
    assert_eq!(cp.state.generation, generation + 1);
}

#[test]
fn a_state_that_does_not_fit_its_scene_is_refused() {
    // One coordinate short (once a panic in DE's mutation).
    let mut v = checkpoint(Algorithm::De);
    v["state"]["solver"]["De"]["population"][2]["u"]
        .as_array_mut()
        .unwrap()
        .pop();
    assert!(read(&v)
        .unwrap_err()
        .contains("member 2: point has 3 entries, expected 4"));
    // An empty fitness (once a panic in the best-tracking).
    let mut v = checkpoint(Algorithm::De);
    v["state"]["solver"]["De"]["population"][0]["fitness"]["f"] = json!([]);
    assert!(read(&v).unwrap_err().contains("goals has 0 entries"));
    // A DE population of 3 (once an endless loop looking for 4 distinct members).
    let mut v = checkpoint(Algorithm::De);
    v["state"]["solver"]["De"]["size"] = json!(3);
    assert!(read(&v).unwrap_err().contains("population size 3"));
    // A state for another dimension (once ran against the scene).
    let mut v = checkpoint(Algorithm::Cmaes);
    v["dim"] = json!(17);
    assert!(read(&v).unwrap_err().contains("17 parameters"));
    // An edited scene.
    let mut v = checkpoint(Algorithm::Nsga2);
    v["scene"]["search"]["seed"] = json!(77);
    assert!(read(&v).unwrap_err().contains("the scene was edited"));
    // A state of another algorithm than the one named.
    let mut v = checkpoint(Algorithm::Guided);
    v["algorithm"] = json!("de");
    assert!(read(&v).unwrap_err().contains("algorithm 'de'"));
    // A coordinate outside the unit cube.
    let mut v = checkpoint(Algorithm::Nsga3);
    v["state"]["solver"]["Nsga3"]["population"][1]["u"][0] = json!(7.5);
    assert!(read(&v).unwrap_err().contains("outside the unit cube"));
}

/// Every number and array of a checkpoint, with its path.
fn slots(v: &Value, path: Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let mut p = path.clone();
                p.push(k.clone());
                slots(x, p, out);
            }
        }
        Value::Array(a) => {
            out.push(path.clone());
            for (i, x) in a.iter().enumerate() {
                let mut p = path.clone();
                p.push(i.to_string());
                slots(x, p, out);
            }
        }
        Value::Number(_) => out.push(path),
        _ => {}
    }
}

fn slot<'a>(v: &'a mut Value, path: &[String]) -> &'a mut Value {
    path.iter().fold(v, |v, k| match v {
        Value::Array(a) => &mut a[k.parse::<usize>().unwrap()],
        _ => &mut v[k.as_str()],
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Damaged checkpoints: one number replaced or one array cut short, anywhere. The
    /// state's hash refuses every one; without it (as the fuzz target reads), the checks of
    /// the parts refuse it, or the state they accept runs two more generations without a
    /// panic.
    #[test]
    fn damaged_checkpoints_are_refused_or_run(
        which in 0usize..5,
        pick in any::<prop::sample::Index>(),
        value in prop_oneof![
            Just(json!(-1)), Just(json!(0)), Just(json!(1)), Just(json!(3)),
            Just(json!(1e300)), Just(json!(-1e300)), Just(json!(0.5)), Just(json!("inf")),
            Just(json!(null)), Just(json!([])), Just(json!(u64::MAX)),
        ],
    ) {
        let mut v = checkpoint(ALL[which]);
        let original = read(&v).unwrap().to_json();
        let mut all = Vec::new();
        slots(&v, Vec::new(), &mut all);
        let path = &all[pick.index(all.len())];
        let target = slot(&mut v, path);
        match target {
            Value::Array(a) if !a.is_empty() => { a.pop(); }
            _ => *target = value,
        }
        let bytes = serde_json::to_vec(&v).unwrap();
        // Refused, unless the change means nothing (`0` for `0.0`: the same checkpoint).
        let same = Checkpoint::from_json_unhashed(&bytes).ok().map(|cp| cp.to_json());
        prop_assert!(same == Some(original) || read(&v).is_err());
        if let Ok(mut cp) = Checkpoint::from_json_unhashed(&bytes) {
            let problem = SceneProblem::new(&cp.scene).unwrap();
            let generations = cp.state.generation + 2;
            execute(&mut cp.state, &mut ParallelEvaluator::new(&problem, 1).unwrap(), u64::MAX,
                &mut [&mut stop_after_generations(generations)]);
        }
    }
}
