//! Search: known optima, determinism across thread counts, checkpoint and resume.

use noncirc::core::{Algorithm, BatchEvaluator, Fitness, SearchState};
use noncirc::scene_file::load_scene;
use noncirc::search::{Outcome, RunOptions, SearchSettings};

/// A search with no observers of the caller's own.
fn run(scene: &noncirc::core::Scene, opts: &RunOptions) -> noncirc::Result<Outcome> {
    noncirc::search::run(scene, opts, &mut [])
}
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

/// A sequential evaluator of a closure.
struct Closure<F: Fn(&[f64]) -> Fitness> {
    dim: usize,
    goals: usize,
    f: F,
}

impl<F: Fn(&[f64]) -> Fitness> BatchEvaluator for Closure<F> {
    fn dim(&self) -> usize {
        self.dim
    }
    fn goals(&self) -> usize {
        self.goals
    }
    fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
        points.iter().map(|p| (self.f)(p)).collect()
    }
}

/// min Σ (u_i − 0.3)² subject to u_0 ≥ 0.6: optimum u = (0.6, 0.3, …), f* = 0.09.
fn constrained_sphere(u: &[f64]) -> Fitness {
    let f = u.iter().map(|x| (x - 0.3).powi(2)).sum::<f64>();
    Fitness {
        cv: (0.6 - u[0]).max(0.0),
        f: vec![f],
    }
}

#[test]
fn single_objective_solvers_find_the_constrained_optimum() {
    for algorithm in [Algorithm::De, Algorithm::Cmaes, Algorithm::Guided] {
        let mut eval = Closure {
            dim: 6,
            goals: 1,
            f: constrained_sphere,
        };
        let mut state = SearchState::new(algorithm, 6, 1, 24, 7);
        while state.evaluations < 30_000 {
            state.step(&mut eval);
        }
        let best = state.best_confirmed.expect("a feasible design");
        assert!(
            (best.fitness.f[0] - 0.09).abs() < 1e-3,
            "{algorithm:?}: f = {}",
            best.fitness.f[0]
        );
        assert!(
            (best.u[0] - 0.6).abs() < 1e-2 && (best.u[3] - 0.3).abs() < 1e-2,
            "{algorithm:?}: {:?}",
            best.u
        );
    }
}

/// Migration between islands: the best members leave, and take the worst members' places
/// on the other island, whose best screened design follows them; solvers without a
/// population, and islands that have not started, refuse migrants.
#[test]
fn migrants_replace_the_worst_members_of_another_island() {
    let mut eval = Closure {
        dim: 6,
        goals: 1,
        f: constrained_sphere,
    };
    for algorithm in [Algorithm::De, Algorithm::Nsga2] {
        let (mut from, mut to) = (
            SearchState::new(algorithm, 6, 1, 24, 1),
            SearchState::new(algorithm, 6, 1, 24, 2),
        );
        assert!(
            to.immigrate(&from.emigrants(2), 6, 1).is_ok(),
            "nothing to send yet"
        );
        for _ in 0..30 {
            from.step(&mut eval);
        }
        to.step(&mut eval);
        let sent = from.emigrants(3);
        assert_eq!(sent.len(), 3);
        let ranked = from.emigrants(usize::MAX);
        assert_eq!(sent[..], ranked[..3], "{algorithm:?}: the best are sent");
        let before = to.emigrants(usize::MAX);
        assert!(SearchState::new(algorithm, 6, 1, 24, 2)
            .immigrate(&sent, 6, 1)
            .is_err());
        to.immigrate(&sent, 6, 1).unwrap();
        let after = to.emigrants(usize::MAX);
        assert_eq!(after.len(), before.len());
        for m in &sent {
            assert!(after.contains(m), "{algorithm:?}: a migrant is missing");
        }
        // The three worst are gone (the rest stay), and the best follows the migrants.
        let worst = &before[before.len() - 3..];
        assert!(worst.iter().all(|w| !after.contains(w) || sent.contains(w)));
        assert!(before[..before.len() - 3].iter().all(|m| after.contains(m)));
        let best = to.best.as_ref().unwrap();
        assert!(!sent[0].fitness.better_than(&best.fitness));
        // A migrant of another problem (dimension) is refused.
        let mut foreign = sent[0].clone();
        foreign.u.push(0.5);
        assert!(to.immigrate(&[foreign], 6, 1).is_err());
    }
    let mut cmaes = SearchState::new(Algorithm::Cmaes, 6, 1, 24, 1);
    cmaes.step(&mut eval);
    let sent = {
        let mut de = SearchState::new(Algorithm::De, 6, 1, 24, 1);
        de.step(&mut eval);
        de.emigrants(2)
    };
    assert!(cmaes.immigrate(&sent, 6, 1).is_err());
    assert!(cmaes.emigrants(2).is_empty());
}

#[test]
fn nsga2_converges_to_the_zdt1_front() {
    // ZDT1 (d = 8): Pareto front f2 = 1 − √f1 for f1 in [0, 1], reached with u_1.. = 0.
    let zdt1 = |u: &[f64]| {
        let g = 1.0 + 9.0 * u[1..].iter().sum::<f64>() / (u.len() - 1) as f64;
        Fitness {
            cv: 0.0,
            f: vec![u[0], g * (1.0 - (u[0] / g).sqrt())],
        }
    };
    let mut eval = Closure {
        dim: 8,
        goals: 2,
        f: zdt1,
    };
    let mut state = SearchState::new(Algorithm::Nsga2, 8, 2, 60, 3);
    while state.evaluations < 24_000 {
        state.step(&mut eval);
    }
    let front = state.solver.front();
    assert!(front.len() >= 30, "front of {}", front.len());
    let worst_gap = front
        .iter()
        .map(|c| c.fitness.f[1] - (1.0 - c.fitness.f[0].sqrt()))
        .fold(0.0, f64::max);
    assert!(worst_gap < 0.05, "distance to the true front {worst_gap}");
    let (lo, hi) = front.iter().fold((1.0f64, 0.0f64), |(l, h), c| {
        (l.min(c.fitness.f[0]), h.max(c.fitness.f[0]))
    });
    assert!(lo < 0.05 && hi > 0.9, "spread {lo}..{hi}");
}

/// The paper-search scene searched by `algorithm`: 2400 evaluations, 24 a generation, seed 11.
fn short_search(algorithm: Algorithm) -> noncirc::core::Scene {
    let mut scene = load_scene(Some("paper-search")).unwrap();
    SearchSettings {
        algorithm: Some(algorithm),
        budget: Some(2400),
        population: Some(24),
        seed: Some(11),
        screening_samples_per_turn: None,
    }
    .apply(&mut scene)
    .unwrap();
    scene
}

fn options(
    threads: usize,
    checkpoint: Option<std::path::PathBuf>,
    resume: Option<std::path::PathBuf>,
    max_generations: Option<u64>,
) -> RunOptions {
    RunOptions {
        threads,
        checkpoint,
        checkpoint_every: Duration::from_secs(3600),
        resume,
        resume_budget: None,
        stop: Arc::new(AtomicBool::new(false)),
        max_generations,
        on_checkpoint_failure: |_| {},
    }
}

fn fingerprint(state: &SearchState) -> String {
    serde_json::to_string(&(
        &state.best,
        &state.best_confirmed,
        &state.history,
        &state.evaluations,
    ))
    .unwrap()
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    for &algorithm in Algorithm::ALL {
        let scene = short_search(algorithm);
        let one = run(&scene, &options(1, None, None, None)).unwrap();
        let two = run(&scene, &options(2, None, None, None)).unwrap();
        assert!(
            fingerprint(&one.state) == fingerprint(&two.state),
            "{algorithm:?}: 1 and 2 threads differ"
        );
    }
}

/// The studio's worker runs the core's executor on the serial evaluator, a generation at a
/// time: that is the CLI's run, state and summary alike, for every algorithm.
#[test]
fn the_serial_evaluator_run_a_generation_at_a_time_is_the_cli_run() {
    use noncirc::core::{execute, stop_after_generations, Ending, SceneProblem, SerialEvaluator};
    use noncirc::search::{Confirmed, Summary};
    for &algorithm in Algorithm::ALL {
        let scene = short_search(algorithm);
        let cli = run(&scene, &options(2, None, None, None)).unwrap();
        let problem = SceneProblem::new(&scene).unwrap();
        let mut state = SearchState::new(
            algorithm,
            problem.dim(),
            problem.goals(),
            scene.search.population,
            scene.search.seed,
        );
        let mut evaluator = SerialEvaluator::new(problem);
        let budget = scene.search.budget;
        let mut calls = 0;
        while execute(
            &mut state,
            &mut evaluator,
            budget,
            &mut [&mut stop_after_generations(1)],
        ) == Ending::Stopped
        {
            calls += 1;
        }
        assert!(calls > 3, "{algorithm:?}: {calls} slices");
        assert_eq!(
            fingerprint(&state),
            fingerprint(&cli.state),
            "{algorithm:?}"
        );
        let confirmed = Confirmed::new(evaluator.problem(), &state);
        let summary = Summary::new(evaluator.problem(), &state, &confirmed, 2, 0.0, None, false);
        let expected = cli.summary();
        assert_eq!(
            (&summary.best, &summary.objectives, summary.feasible),
            (&expected.best, &expected.objectives, expected.feasible),
            "{algorithm:?}"
        );
    }
}

/// DE scores each trial against its target, and a trial whose module alone puts its
/// violation above the target's is not assembled (`evaluate_against`). On every trial of a
/// search of the default space: the bound is the whole evaluation's fitness, or an
/// infeasible lower bound of its violation above the target's; and the search (population,
/// best designs, confirmations, history) is the one that evaluates every trial whole.
#[test]
fn de_trials_stopped_at_their_module_leave_the_search_as_whole_evaluations_do() {
    use noncirc::core::{execute, SceneProblem, SerialEvaluator};

    /// Each trial evaluated both ways; the bounded fitness goes to the search.
    struct Checked {
        bounded: SerialEvaluator,
        whole: SerialEvaluator,
        stopped: usize,
    }
    impl BatchEvaluator for Checked {
        fn dim(&self) -> usize {
            self.whole.dim()
        }
        fn goals(&self) -> usize {
            self.whole.goals()
        }
        fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
            self.whole.evaluate(points)
        }
        fn confirm(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
            self.whole.confirm(points)
        }
        fn evaluate_against(&mut self, points: &[Vec<f64>], rivals: &[Fitness]) -> Vec<Fitness> {
            let bounded = self.bounded.evaluate_against(points, rivals);
            let whole = self.whole.evaluate(points);
            for ((b, w), rival) in bounded.iter().zip(&whole).zip(rivals) {
                if b != w {
                    self.stopped += 1;
                    assert!(
                        !b.feasible() && b.cv <= w.cv && b.cv > rival.cv,
                        "bound {b:?}, whole {w:?}, rival {rival:?}"
                    );
                    assert!(
                        rival.better_than(w) && rival.better_than(b),
                        "{w:?} {rival:?}"
                    );
                }
            }
            bounded
        }
    }
    /// Every trial evaluated whole (the trait's default `evaluate_against`).
    struct Whole(SerialEvaluator);
    impl BatchEvaluator for Whole {
        fn dim(&self) -> usize {
            self.0.dim()
        }
        fn goals(&self) -> usize {
            self.0.goals()
        }
        fn evaluate(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
            self.0.evaluate(points)
        }
        fn confirm(&mut self, points: &[Vec<f64>]) -> Vec<Fitness> {
            self.0.confirm(points)
        }
    }

    let scene = short_search(Algorithm::De);
    let problem = SceneProblem::new(&scene).unwrap();
    let new_state = || SearchState::new(Algorithm::De, problem.dim(), problem.goals(), 24, 11);
    let (mut checked_state, mut whole_state) = (new_state(), new_state());
    let mut checked = Checked {
        bounded: SerialEvaluator::new(problem.clone()),
        whole: SerialEvaluator::new(problem.clone()),
        stopped: 0,
    };
    execute(&mut checked_state, &mut checked, 2400, &mut []);
    execute(
        &mut whole_state,
        &mut Whole(SerialEvaluator::new(problem)),
        2400,
        &mut [],
    );
    assert_eq!(
        serde_json::to_string(&checked_state).unwrap(),
        serde_json::to_string(&whole_state).unwrap()
    );
    // About half of the trials are stopped at their module, a sixth more once their arm
    // is placed.
    assert!(
        checked.stopped > 600,
        "{} of 2376 trials stopped",
        checked.stopped
    );
}

/// NSGA-II and NSGA-III from random starts reach a feasible Pareto set of the default
/// space with two goals (module up, picking tip speed down) in every one of 10 seeds at the
/// default budget: their feasibility phase (differential-evolution trials while no member
/// is feasible). Before it, 1 and 2 of 10 runs were feasible (docs/search.md).
#[test]
fn multi_objective_runs_are_feasible_from_random_starts() {
    let mut scene = load_scene(Some("paper-search")).unwrap();
    scene.search.goals = ["module", "picking_tip_speed"]
        .map(|g| noncirc::core::Goal::parse(g).unwrap())
        .to_vec();
    for algorithm in [Algorithm::Nsga2, Algorithm::Nsga3] {
        let mut feasible = Vec::new();
        for seed in 1..=10 {
            let mut s = scene.clone();
            SearchSettings {
                algorithm: Some(algorithm),
                seed: Some(seed),
                ..SearchSettings::default()
            }
            .apply(&mut s)
            .unwrap();
            let outcome = run(&s, &options(2, None, None, None)).unwrap();
            let summary = outcome.summary();
            let front = outcome
                .confirmed
                .pareto
                .iter()
                .filter(|(_, f)| f.feasible())
                .count();
            feasible.push((seed, summary.feasible, front));
            // The reported design is the front's best on the first goal, and the front is
            // sorted by that goal's value.
            let pareto = &outcome.confirmed.pareto;
            let module = |f: &Fitness| outcome.problem.goal_values(&f.f)[0];
            assert!(pareto
                .windows(2)
                .all(|w| module(&w[0].1) <= module(&w[1].1)));
            let reported = summary.goals[0].value.unwrap();
            let top = (pareto.iter().filter(|(_, f)| f.feasible()))
                .map(|(_, f)| module(f))
                .fold(f64::NEG_INFINITY, f64::max);
            assert_eq!(reported, top, "{algorithm:?} seed {seed}");
            let names = outcome.problem.names();
            let best: Vec<f64> = names.iter().map(|n| summary.best[&n.to_string()]).collect();
            assert!(
                pareto.iter().any(|(x, _)| *x == best),
                "{algorithm:?} seed {seed}: the reported design is not in the front"
            );
            // The summary's objectives are those of the design its `best` names (they were
            // another design's when the solver's pick and the confirmed front's best
            // differed).
            let mut named = s.clone();
            for (name, v) in names.iter().zip(&best) {
                noncirc::core::Param::parse(name, &named)
                    .unwrap()
                    .set(&mut named, *v);
            }
            let eval = noncirc::core::Evaluator::new().evaluate(&named).unwrap();
            for o in &eval.objectives {
                assert_eq!(
                    summary.objectives[o.kind.name()],
                    o.value,
                    "{algorithm:?} seed {seed}: {}",
                    o.kind.name()
                );
            }
            // summary.json names the parameters in the scene's order.
            let json = serde_json::to_string(&summary).unwrap();
            let at = |k: &str| json.find(&format!("\"{k}\":")).unwrap();
            assert!(at("gear.curve.radii_mm[2]") < at("gear.curve.radii_mm[10]"));
            assert!(at("gear.curve.radii_mm[11]") < at("train.phi0_deg"));
            // The goals in physical terms: the module in mm (maximised), the tip speed in
            // m/s (minimised), equal to a fresh evaluation of each design of the front.
            let names: Vec<_> = (summary.goals.iter())
                .map(|g| (g.name.as_str(), g.unit, g.maximised))
                .collect();
            assert_eq!(
                names,
                [
                    ("module_mm", "mm", true),
                    ("picking_tip_speed_m_s", "m/s", false)
                ]
            );
            for (x, f) in outcome
                .confirmed
                .pareto
                .iter()
                .filter(|(_, f)| f.feasible())
            {
                let mut design = s.clone();
                for (name, v) in outcome.problem.names().iter().zip(x) {
                    noncirc::core::Param::parse(name, &design)
                        .unwrap()
                        .set(&mut design, *v);
                }
                let eval = noncirc::core::Evaluator::new().evaluate(&design).unwrap();
                let module = eval
                    .objective(noncirc::core::ObjectiveKind::Module)
                    .unwrap();
                let speed = eval.events.as_ref().unwrap().picking_tip_speed_m_s;
                let values = outcome.problem.goal_values(&f.f);
                assert!(
                    (values[0] - module.value).abs() < 1e-9,
                    "{values:?} {}",
                    module.value
                );
                assert!((values[1] - speed).abs() < 1e-12, "{values:?} {speed}");
            }
        }
        assert!(
            feasible.iter().all(|&(_, ok, front)| ok && front >= 2),
            "{algorithm:?}: (seed, feasible, confirmed front size) {feasible:?}"
        );
    }
}

#[test]
fn a_killed_and_resumed_run_ends_where_an_uninterrupted_one_does() {
    let scene = short_search(Algorithm::De);
    let dir = std::env::temp_dir().join(format!("noncirc-resume-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cp = dir.join("run.ckpt");
    let whole = run(&scene, &options(2, None, None, None)).unwrap();
    // Stop after 17 generations (as if killed right after a checkpoint), then resume.
    let part = run(&scene, &options(2, Some(cp.clone()), None, Some(17))).unwrap();
    assert!(part.stopped_early && part.state.evaluations < whole.state.evaluations);
    let resumed = run(
        &scene,
        &options(1, Some(cp.clone()), Some(cp.clone()), None),
    )
    .unwrap();
    assert!(
        fingerprint(&resumed.state) == fingerprint(&whole.state),
        "resumed run differs from the uninterrupted one"
    );
    // The checkpoint was replaced atomically: no temporary file is left behind.
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, [std::ffi::OsString::from("run.ckpt")]);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn reported_designs_meet_the_objectives_at_the_default_resolution() {
    let mut scene = load_scene(Some("paper-search")).unwrap();
    SearchSettings {
        budget: Some(30_000),
        population: Some(48),
        seed: Some(1),
        ..SearchSettings::default()
    }
    .apply(&mut scene)
    .unwrap();
    let out = run(&scene, &options(2, None, None, None)).unwrap();
    let summary = out.summary();
    if out.state.best_confirmed.is_some() {
        assert!(
            summary.feasible,
            "confirmed design must stay feasible: {:?}",
            summary.violations
        );
        assert!(summary.violations.values().all(|&v| v == 0.0));
        // best.toml round-trips through `evaluate`.
        let dir = std::env::temp_dir().join(format!("noncirc-out-{}", std::process::id()));
        out.write(&dir).unwrap();
        let best =
            noncirc::scene_file::load_scene(Some(dir.join("best.toml").to_str().unwrap())).unwrap();
        let eval = noncirc::core::Evaluator::new().evaluate(&best).unwrap();
        assert_eq!(eval.total_violation(), 0.0);
        // It keeps the search's space: `optimise best.toml` searches the same one.
        assert_eq!(
            serde_json::to_string(&best.search.free).unwrap(),
            serde_json::to_string(&scene.search.free).unwrap()
        );
        let header = std::fs::read_to_string(dir.join("pareto.csv")).unwrap();
        assert!(
            header
                .lines()
                .next()
                .unwrap()
                .ends_with(",least_normalised_margin,cv"),
            "{header}"
        );
        for file in ["pareto.csv", "pareto.json", "history.csv", "summary.json"] {
            assert!(dir.join(file).exists(), "{file}");
        }
        std::fs::remove_dir_all(dir).ok();
    } else {
        assert!(!summary.feasible);
    }
}

/// Any measure is a search goal: `max:NAME` ranks designs by the measure, negated, and a
/// misspelt name is refused with the nearest names.
#[test]
fn measures_are_search_goals() {
    use noncirc::core::Goal;
    use noncirc::core::SceneProblem;
    use noncirc::core::Section;
    use noncirc::core::{Evaluator, Scene};
    use noncirc::scene_file::apply_overrides;
    let scene: Scene = apply_overrides(
        load_scene(Some("paper-search")).unwrap(),
        &[r#"search.goals=["max:removal_length_mm", "min:picking_branch_gap_mm"]"#.into()],
    )
    .unwrap();
    let problem = SceneProblem::new(&scene).unwrap();
    assert_eq!(problem.goals(), 2);
    // The paper's design, encoded: its goals are its measures.
    let x: Vec<f64> = problem
        .names()
        .iter()
        .map(|n| {
            noncirc::core::Param::parse(n, &scene)
                .unwrap()
                .get(&scene)
                .unwrap()
        })
        .collect();
    let u = problem.encode(&x);
    let mut scratch = scene.clone();
    let (fitness, eval) =
        problem.fitness(&u, &mut Evaluator::new(), &mut scratch, &scene.resolution);
    let eval = eval.unwrap();
    let anatomy = eval.anatomy(&scene.agronomy).unwrap();
    let removal = anatomy.section(Section::Removal).length_mm;
    let gap = eval.events.as_ref().unwrap().picking_branch_gap_mm.unwrap();
    assert!(
        (fitness.f[0] + removal).abs() < 1e-9,
        "{:?} vs {removal}",
        fitness.f
    );
    assert!(
        (fitness.f[1] - gap).abs() < 1e-9,
        "{:?} vs {gap}",
        fitness.f
    );
    let e = Goal::parse("max:removal_lenght_mm")
        .unwrap_err()
        .to_string();
    assert!(e.contains("removal_length_mm"), "{e}");
}

/// `sweep --measure` gives each design's measures, the same values `evaluate` reports.
#[test]
fn sweeps_report_any_measure() {
    use noncirc::core::Measure;
    use noncirc::core::{Evaluator, Measured, Param};
    let scene = load_scene(Some("paper")).unwrap();
    let measures = [
        Measure::parse("loop_height_mm").unwrap(),
        Measure::parse("picking_branch_gap_mm").unwrap(),
    ];
    let rows =
        noncirc::sweep::sweep(&scene, "train.gamma0_deg", -63.0, -43.0, 3, &measures).unwrap();
    assert_eq!(rows.len(), 3);
    for row in &rows {
        let mut s = scene.clone();
        Param::parse("train.gamma0_deg", &s)
            .unwrap()
            .set(&mut s, row.value);
        let eval = Evaluator::new().evaluate(&s).unwrap();
        let on = Measured::new(&eval, &s);
        for m in measures {
            // A measure the design lacks (no runner-up extreme) is absent in both.
            let expected = m.value(&on);
            assert_eq!(
                row.measures.get(&m.name()).copied(),
                expected,
                "{}",
                m.name()
            );
        }
    }
    // γ0 raises the removal loop (docs/parameter-response.md).
    let h: Vec<f64> = rows.iter().map(|r| r.measures["loop_height_mm"]).collect();
    assert!(h[0] < h[1] && h[1] < h[2], "{h:?}");
}

#[test]
fn a_search_can_confirm_its_reported_designs_with_the_teeth() {
    // An elliptic gear search: screened by the curvature rule, confirmed by the teeth.
    let text = r#"
        name = "ellipse-teeth"
        kind = "gear"
        objectives = ["module"]
        [gear.curve]
        kind = "ellipse"
        semi_major_mm = 30
        eccentricity = 0.2
        [gear.module]
        teeth = 20
        [bounds]
        module_min_mm = 2.0
        [search]
        budget = 96
        population = 8
        confirm_with_teeth = true
        free = [{ name = "gear.curve.eccentricity", lower = 0.05, upper = 0.4 }]
    "#;
    let scene = noncirc::scene_file::parse_scene(text, "ellipse-teeth.toml").unwrap();
    let outcome = run(&scene, &options(1, None, None, None)).unwrap();
    let (_, eval) = outcome.confirmed.best.as_ref().unwrap();
    let teeth = eval
        .as_ref()
        .unwrap()
        .teeth
        .as_ref()
        .expect("confirmed with teeth");
    assert_eq!(teeth.teeth, 20);
    // Screening never paid for teeth: without the setting the confirmation has none.
    let mut plain = scene.clone();
    plain.search.confirm_with_teeth = false;
    let outcome = run(&plain, &options(1, None, None, None)).unwrap();
    let (_, eval) = outcome.confirmed.best.as_ref().unwrap();
    assert!(eval.as_ref().unwrap().teeth.is_none());
    // Without a tooth count the setting is refused, named.
    let mut uncounted = scene.clone();
    uncounted.gear.module.teeth = None;
    let err = uncounted.validate_search().unwrap_err().to_string();
    assert!(err.contains("gear.module.teeth"), "{err}");
}

/// A short DE search of the default space under a robust goal (its samples few, for speed).
fn robust_search() -> noncirc::core::Scene {
    let mut scene = short_search(Algorithm::De);
    // Long enough to find designs meeting every objective, whose samples are then drawn.
    (scene.search.budget, scene.search.seed) = (12_000, 1);
    scene.search.goals = vec![noncirc::core::Goal::MarginQuantile(0.1)];
    scene.tolerances.samples = 16;
    scene.tolerances.assemblies_per_part_set = 4;
    scene
}

#[test]
fn a_robust_search_is_the_same_on_one_and_two_threads_and_after_a_resume() {
    let scene = robust_search();
    let search = |o: &RunOptions| run(&scene, o).unwrap();
    let one = search(&options(1, None, None, None));
    let two = search(&options(2, None, None, None));
    assert!(fingerprint(&one.state) == fingerprint(&two.state));
    // It found designs and scored them by their samples (a quantile, not the sentinel).
    let best = one
        .state
        .best_confirmed
        .as_ref()
        .expect("a feasible design");
    assert!(best.fitness.f[0] < 0.0 && best.fitness.f[0] > -10.0);
    let dir = std::env::temp_dir().join(format!("noncirc-robust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cp = dir.join("run.ckpt");
    let part = search(&options(2, Some(cp.clone()), None, Some(20)));
    assert!(part.stopped_early);
    let resumed = search(&options(1, Some(cp.clone()), Some(cp.clone()), None));
    assert!(fingerprint(&resumed.state) == fingerprint(&one.state));
    std::fs::remove_dir_all(dir).ok();
}

/// Any measure bounds a search (`search.constraints`): every algorithm's reported design
/// meets a bound that the unconstrained search's design misses, and the summary and
/// `evaluate` read the same value.
#[test]
fn a_constraint_on_any_measure_holds_in_every_algorithm() {
    use noncirc::core::{Constraint, Evaluator, Measure, Measured};
    // The paper-search scene, 12 000 evaluations, seed 1.
    let search = |algorithm: Algorithm, constraints: Vec<Constraint>| {
        let mut scene = load_scene(Some("paper-search")).unwrap();
        SearchSettings {
            algorithm: Some(algorithm),
            budget: Some(12_000),
            seed: Some(1),
            ..SearchSettings::default()
        }
        .apply(&mut scene)
        .unwrap();
        scene.search.constraints = constraints;
        run(&scene, &options(2, None, None, None)).unwrap()
    };
    let free = search(Algorithm::De, Vec::new());
    let (scene, eval) = free.confirmed.best.clone().unwrap();
    let eval = eval.unwrap();
    assert_eq!(
        eval.total_violation(),
        0.0,
        "the unconstrained search is feasible"
    );
    let measure = Measure::parse("loop_width_mm").unwrap();
    let width = measure.value(&Measured::new(&eval, &scene)).unwrap();
    // A loop at least 3 mm narrower than the unconstrained design's.
    let constraint = Constraint {
        measure,
        bound: (width - 3.0).floor(),
        at_most: true,
    };
    assert!(
        width > constraint.bound,
        "the unconstrained design misses it"
    );
    for algorithm in [
        Algorithm::De,
        Algorithm::Guided,
        Algorithm::Cmaes,
        Algorithm::Nsga2,
        Algorithm::Nsga3,
    ] {
        let out = search(algorithm, vec![constraint]);
        let summary = out.summary();
        let reading = &summary.constraints[0];
        assert_eq!(reading.label, constraint.text());
        assert!(
            reading.value <= constraint.bound && reading.violation == 0.0,
            "{algorithm:?}: {reading:?}"
        );
        // Feasible means every objective and the constraint met.
        let objectives_met = summary.violations.values().all(|&v| v == 0.0);
        assert_eq!(summary.feasible, objectives_met, "{algorithm:?}");
        let (best, _) = out.confirmed.best.as_ref().unwrap();
        let again = Evaluator::new().evaluate(best).unwrap();
        assert_eq!(again.constraints[0].value, reading.value, "{algorithm:?}");
    }
}

/// A search stopped before its first generation ended keeps no design, and its summary
/// says so: no evaluation, nothing feasible, and what a design would have had to meet
/// (the scene's search constraints too, though no design was read to show them).
#[test]
fn a_search_stopped_before_any_design_says_so() {
    let mut scene = load_scene(Some("paper-search")).unwrap();
    scene.search.constraints =
        vec![noncirc::core::Constraint::parse("loop_width_mm <= 50").unwrap()];
    let opts = options(1, None, None, None);
    opts.stop.store(true, std::sync::atomic::Ordering::SeqCst);
    let outcome = run(&scene, &opts).unwrap();
    assert!(outcome.stopped_early);
    assert_eq!(outcome.state.evaluations, 0);
    let summary = outcome.summary();
    assert!(!summary.feasible && summary.constraints.is_empty());
    assert_eq!(
        summary.requirements(),
        "every objective and search constraint"
    );
    let table = noncirc::report::summary_table(&summary);
    assert!(table.contains("NO DESIGN EVALUATED"), "{table}");
}

/// The default goal, `least_margin`, counts the search constraints' margins beside the
/// objectives': a constraint missed by more than any objective sets it, one met with room
/// leaves it as it was.
#[test]
fn the_default_goal_counts_the_constraints_margins() {
    use noncirc::core::{Constraint, Evaluator, Measure, Measured, SceneProblem};
    let scene = load_scene(Some("paper-search")).unwrap();
    let values = |scene: &noncirc::core::Scene| {
        let problem = SceneProblem::new(scene).unwrap();
        let x: Vec<f64> = (problem.names().iter())
            .map(|n| {
                noncirc::scene_file::value_at(scene, n)
                    .unwrap()
                    .as_f64()
                    .unwrap()
            })
            .collect();
        let (fitness, eval) = problem.fitness_at_values(
            &x,
            &mut Evaluator::new(),
            &mut scene.clone(),
            &scene.resolution,
        );
        (fitness, eval.unwrap())
    };
    // The base design's least objective margin, normalised (its goal is minus that).
    let (free, eval) = values(&scene);
    let measure = Measure::parse("loop_width_mm").unwrap();
    let width = measure.value(&Measured::new(&eval, &scene)).unwrap();
    let with = |constraint: Constraint| {
        let mut constrained = scene.clone();
        constrained.search.constraints = vec![constraint];
        values(&constrained).0
    };
    // Missed by twice the width: a normalised margin of -2w / (0.1 · 3w) = -6.67, below
    // every objective's here.
    let missed = Constraint {
        measure,
        bound: 3.0 * width,
        at_most: false,
    };
    let normalised = -2.0 * width / missed.scale();
    assert!(
        normalised < -free.f[0],
        "{normalised} against {}",
        -free.f[0]
    );
    let fitness = with(missed);
    assert!(fitness.cv > free.cv);
    assert!(
        (fitness.f[0] + normalised).abs() < 1e-9,
        "{} against {}",
        fitness.f[0],
        -normalised
    );
    // Met by nine widths (a normalised margin of 9): the objectives' least margin stays.
    let met = Constraint {
        measure,
        bound: 10.0 * width,
        at_most: true,
    };
    let fitness = with(met);
    assert_eq!((fitness.cv, fitness.f[0]), (free.cv, free.f[0]));
}
