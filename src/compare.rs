//! Two arms against three (the three-arm paper's relative-speed claim): for each arm count,
//! the least speed of the tip relative to the seedling that a design meeting every
//! objective can have at one picking rate, found by a search per seed; and the paper's own
//! design run with each arm count.
//!
//! The speed compared is a measure (`in_tray_speed_m_s` unless asked otherwise): the mean
//! speed while the tip is inside the tray, the pass a high-speed camera films. The speed at
//! the picking instant itself is a poor target for a search: the instant is the tip's
//! deepest point, where a cusp of the path can bring the speed to zero (docs/replication.md).
//! A speed is the carrier's angular speed times the path's rate per radian (mm/rad), so
//! each reduction splits into a carrier factor (the arm counts' ratio, at one picking rate)
//! and a shape factor (the paths').

use noncirc_core::{
    anatomy, quantile, Evaluation, Evaluator, Goal, Measure, Measured, ObjectiveKind, Scene,
    SceneKind,
};
use serde::Serialize;
use std::collections::BTreeMap;
use std::f64::consts::TAU;

use crate::search::RunOptions;
use crate::{Error, Result};

/// The measure compared unless asked otherwise.
pub const DEFAULT_MEASURE: &str = "in_tray_speed_m_s";

/// What to compare.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    /// Arm counts (each 1 to 4); the first is the one the others are compared against.
    pub arms: Vec<usize>,
    /// Search seeds: one search per arm count and seed.
    pub seeds: Vec<u64>,
    /// The picking rate every train runs at (picks per minute).
    pub picks_per_minute: f64,
    /// The speed compared and minimised by each search: a measure in m/s.
    pub measure: Measure,
    /// Each search's budget (default: the scene's).
    pub budget: Option<u64>,
    pub threads: usize,
}

/// A design's speeds relative to the seedling (m/s) at its arm count's carrier speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Speeds {
    /// Whether it meets every objective at the scene's resolution and no gears of
    /// different arm sets overlap (`gear_overlap_mm`, not an objective).
    pub feasible: bool,
    /// The deepest overlap of different arm sets' gears (mm; 0: clear).
    pub gear_overlap_mm: Option<f64>,
    /// At the picking instant (`picking_tip_speed_m_s`).
    pub picking_tip_speed_m_s: Option<f64>,
    /// Mean while the tip is inside the tray (`in_tray_speed_m_s`).
    pub in_tray_speed_m_s: Option<f64>,
    /// The compared measure.
    pub compared_m_s: Option<f64>,
    /// The compared measure per radian of carrier (mm/rad): the path's share of it.
    pub compared_mm_per_rad: Option<f64>,
}

/// One search's best design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SearchRow {
    pub arms: usize,
    pub seed: u64,
    pub carrier_rpm: f64,
    pub speeds: Speeds,
    pub seconds: f64,
    /// The design's free parameters.
    pub design: BTreeMap<String, f64>,
    /// The design's scene (not serialised: `design` holds what differs).
    #[serde(skip)]
    pub scene: Option<Scene>,
}

/// An arm count's feasible searches, and the paper's design with that arm count.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArmSummary {
    pub arms: usize,
    pub carrier_rpm: f64,
    pub feasible_searches: usize,
    /// Median, least and largest compared speed over the feasible searches (m/s).
    pub median_m_s: Option<f64>,
    pub min_m_s: Option<f64>,
    pub max_m_s: Option<f64>,
    /// The median per radian of carrier (mm/rad).
    pub median_mm_per_rad: Option<f64>,
    /// The paper's design with this arm count at the same picking rate (its objectives are
    /// not required).
    pub paper_design: Speeds,
}

/// An arm count against the first one.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reduction {
    pub arms: usize,
    pub against: usize,
    /// `1 − v/v_against` of the medians over the seeds (%).
    pub of_medians_pct: Option<f64>,
    /// Seed by seed (the same seed feasible at both arm counts): median, least and
    /// largest (%), and how many seeds.
    pub paired_seeds: usize,
    pub paired_median_pct: Option<f64>,
    pub paired_min_pct: Option<f64>,
    pub paired_max_pct: Option<f64>,
    /// The carrier's speed against the other's (`against / arms`) and the medians' speed
    /// per radian against the other's: their product is `1 − of_medians_pct/100`.
    pub carrier_factor: f64,
    pub shape_factor: Option<f64>,
    /// The paper's design, the same path at both arm counts: the carrier factor alone (%).
    pub paper_design_pct: Option<f64>,
}

/// The comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    pub picks_per_minute: f64,
    pub measure: String,
    pub searches: Vec<SearchRow>,
    pub arms: Vec<ArmSummary>,
    pub reductions: Vec<Reduction>,
}

/// The median of `v` (`None` when empty).
fn median(v: &[f64]) -> Option<f64> {
    (!v.is_empty()).then(|| quantile(v, 0.5))
}

/// `b/a`, where `a` is a positive number (a speed of zero has no ratio).
fn ratio(a: f64, b: f64) -> Option<f64> {
    (a > 0.0 && a.is_finite() && b.is_finite()).then(|| b / a)
}

/// `1 − b/a` in per cent.
fn reduction_pct(a: f64, b: f64) -> Option<f64> {
    ratio(a, b).map(|r| 100.0 * (1.0 - r))
}

/// `scene` with `arms` arm sets at `rate` picks per minute (a one-arm train has no
/// interference objective; a transplanter's box moves one pot per pick).
pub fn with_arms(scene: &Scene, arms: usize, rate: f64) -> Scene {
    let mut s = scene.clone();
    s.train.arms = arms;
    s.train.picks_per_minute = Some(rate);
    if s.kind == SceneKind::Transplanter {
        s.moving_box.input_turns_per_carrier_turn = arms as f64;
    }
    if arms == 1 {
        s.objectives.retain(|&k| k != ObjectiveKind::Interference);
    }
    s
}

/// The speeds of `scene`'s design, `measure` among them.
pub fn speeds(scene: &Scene, measure: Measure) -> Result<Speeds> {
    Ok(speeds_of(
        scene,
        &Evaluator::new().evaluate(scene)?,
        measure,
    ))
}

/// The speeds of `scene`'s design from its evaluation `eval`.
fn speeds_of(scene: &Scene, eval: &Evaluation, measure: Measure) -> Speeds {
    let anatomy = match (&eval.kinematics, &eval.events) {
        (Some(kin), Some(ev)) => Some(anatomy(kin, &scene.agronomy, ev)),
        _ => None,
    };
    let on = Measured::with_anatomy(eval, scene, anatomy);
    let value = |m: &str| Measure::parse(m).ok()?.value(&on);
    let compared = measure.value(&on);
    let omega = scene.train.carrier_rpm() * TAU / 60.0;
    let gear_overlap_mm = value("gear_overlap_mm");
    Speeds {
        feasible: eval.total_violation() == 0.0 && gear_overlap_mm == Some(0.0),
        gear_overlap_mm,
        picking_tip_speed_m_s: value("picking_tip_speed_m_s"),
        in_tray_speed_m_s: value("in_tray_speed_m_s"),
        compared_m_s: compared,
        compared_mm_per_rad: compared.map(|v| v * 1000.0 / omega),
    }
}

/// The values of `scene`'s free parameters, by name.
fn free_values(scene: &Scene) -> Result<BTreeMap<String, f64>> {
    (scene.search.free.iter())
        .filter_map(|f| {
            let param = noncirc_core::Param::parse(&f.name, scene);
            (param.map(|p| Some((f.name.clone(), p.get(scene)?)))).transpose()
        })
        .collect::<std::result::Result<_, _>>()
        .map_err(Error::from)
}

/// Checks the options, naming the bad one.
fn validate(options: &CompareOptions) -> Result<()> {
    if options.arms.is_empty() || options.seeds.is_empty() {
        return Err(Error::Input(
            "compare needs at least one arm count and one seed".into(),
        ));
    }
    let rate = options.picks_per_minute;
    if !(rate.is_finite() && rate > 0.0 && rate <= 1e6) {
        return Err(Error::Input(format!(
            "picks per minute = {rate}: expected a number above 0, at most 1e6"
        )));
    }
    if options.measure.unit() != "m/s" {
        return Err(Error::Input(format!(
            "compare measure {}: expected a speed (m/s), it is in {}",
            options.measure.name(),
            options.measure.unit()
        )));
    }
    let mut arms = options.arms.clone();
    arms.sort_unstable();
    arms.dedup();
    if arms.len() < options.arms.len() {
        return Err(Error::Input(format!(
            "compare arms {:?}: each arm count once",
            options.arms
        )));
    }
    let mut seeds = options.seeds.clone();
    seeds.sort_unstable();
    seeds.dedup();
    if seeds.len() < options.seeds.len() {
        return Err(Error::Input(format!(
            "compare seeds {:?}: each seed once (a seed repeats its search)",
            options.seeds
        )));
    }
    Ok(())
}

/// Runs the comparison from `search_scene` (its search space and settings; the goal is the
/// compared measure, minimised) and `paper`, the design run as drawn with each arm count.
/// `progress` hears each search as it ends.
pub fn compare(
    search_scene: &Scene,
    paper: &Scene,
    options: &CompareOptions,
    progress: &mut dyn FnMut(&SearchRow),
) -> Result<Comparison> {
    validate(options)?;
    for scene in [search_scene, paper] {
        if !matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter) {
            return Err(Error::Input(format!(
                "compare runs arm counts of a mechanism: scene '{}' is {}, not a three_arm or \
                 transplanter scene",
                scene.name,
                scene.kind.name()
            )));
        }
    }
    let rate = options.picks_per_minute;
    let measure = options.measure;
    // Every arm count's scene is checked before the first search runs.
    let scenes = (options.arms.iter())
        .map(|&arms| {
            let mut scene = with_arms(search_scene, arms, rate);
            scene.search.goals = vec![Goal::Measure {
                measure,
                maximise: false,
            }];
            if let Some(b) = options.budget {
                scene.search.budget = b;
            }
            scene.validate()?;
            Ok(scene)
        })
        .collect::<Result<Vec<_>>>()?;
    let mut searches = Vec::new();
    for scene in &scenes {
        let arms = scene.train.arms;
        for &seed in &options.seeds {
            let mut scene = scene.clone();
            scene.search.seed = seed;
            let outcome =
                crate::search::run(&scene, &RunOptions::new(Some(options.threads))?, &mut [])?;
            let best = outcome.confirmed.best;
            let row = SearchRow {
                arms,
                seed,
                carrier_rpm: scene.train.carrier_rpm(),
                // The confirmed evaluation; a best design that could not be evaluated (a
                // search too short to find one that closes) has no speeds.
                speeds: match &best {
                    Some((s, Some(eval))) => speeds_of(s, eval, measure),
                    _ => Speeds {
                        feasible: false,
                        gear_overlap_mm: None,
                        picking_tip_speed_m_s: None,
                        in_tray_speed_m_s: None,
                        compared_m_s: None,
                        compared_mm_per_rad: None,
                    },
                },
                seconds: outcome.seconds,
                design: match &best {
                    Some((s, _)) => free_values(s)?,
                    None => Default::default(),
                },
                scene: best.map(|(s, _)| s),
            };
            progress(&row);
            searches.push(row);
        }
    }
    let feasible =
        |arms: usize| (searches.iter()).filter(move |r| r.arms == arms && r.speeds.feasible);
    let arm_summaries: Vec<ArmSummary> = (options.arms.iter())
        .map(|&arms| {
            let v: Vec<f64> = feasible(arms)
                .filter_map(|r| r.speeds.compared_m_s)
                .collect();
            let per_rad: Vec<f64> = (feasible(arms))
                .filter_map(|r| r.speeds.compared_mm_per_rad)
                .collect();
            Ok(ArmSummary {
                arms,
                carrier_rpm: rate / arms as f64,
                feasible_searches: v.len(),
                median_m_s: median(&v),
                min_m_s: v.iter().copied().reduce(f64::min),
                max_m_s: v.iter().copied().reduce(f64::max),
                median_mm_per_rad: median(&per_rad),
                paper_design: speeds(&with_arms(paper, arms, rate), measure)?,
            })
        })
        .collect::<Result<_>>()?;
    let first = &arm_summaries[0];
    let reductions = (arm_summaries[1..].iter())
        .map(|b| {
            let paired: Vec<f64> = (options.seeds.iter())
                .filter_map(|&seed| {
                    let at = |arms| {
                        feasible(arms)
                            .find(|r| r.seed == seed)
                            .and_then(|r| r.speeds.compared_m_s)
                    };
                    reduction_pct(at(first.arms)?, at(b.arms)?)
                })
                .collect();
            let both = |f: fn(&ArmSummary) -> Option<f64>| Some((f(first)?, f(b)?));
            let paper = |s: &ArmSummary| s.paper_design.compared_m_s;
            Reduction {
                arms: b.arms,
                against: first.arms,
                of_medians_pct: both(|s| s.median_m_s).and_then(|(x, y)| reduction_pct(x, y)),
                paired_seeds: paired.len(),
                paired_median_pct: median(&paired),
                paired_min_pct: paired.iter().copied().reduce(f64::min),
                paired_max_pct: paired.iter().copied().reduce(f64::max),
                carrier_factor: first.arms as f64 / b.arms as f64,
                shape_factor: both(|s| s.median_mm_per_rad).and_then(|(x, y)| ratio(x, y)),
                paper_design_pct: both(paper).and_then(|(x, y)| reduction_pct(x, y)),
            }
        })
        .collect();
    Ok(Comparison {
        picks_per_minute: rate,
        measure: measure.name(),
        searches,
        arms: arm_summaries,
        reductions,
    })
}

/// The comparison as a table: each search, then each arm count, then each count's
/// reduction against the first.
pub fn comparison_table(c: &Comparison) -> String {
    use std::fmt::Write;
    let mut t = String::new();
    let fmt =
        |v: Option<f64>, digits: usize| v.map_or("—".to_string(), |v| format!("{v:.digits$}"));
    let _ = writeln!(
        t,
        "Least {} (m/s) of a design meeting every objective, at {} picks per minute",
        c.measure, c.picks_per_minute
    );
    let _ = writeln!(
        t,
        "\n{:>4} {:>5} {:>8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>7}",
        "arms", "seed", "carrier", "feasible", "compared", "(mm/rad)", "in tray", "at pick", "time"
    );
    let _ = writeln!(
        t,
        "{:>4} {:>5} {:>8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>7}",
        "", "", "(r/min)", "", "(m/s)", "", "(m/s)", "(m/s)", "(s)"
    );
    for r in &c.searches {
        let s = &r.speeds;
        let _ = writeln!(
            t,
            "{:>4} {:>5} {:>8.1} {:>8} {:>10} {:>10} {:>10} {:>10} {:>7.1}",
            r.arms,
            r.seed,
            r.carrier_rpm,
            if s.feasible { "yes" } else { "no" },
            fmt(s.compared_m_s, 4),
            fmt(s.compared_mm_per_rad, 1),
            fmt(s.in_tray_speed_m_s, 4),
            fmt(s.picking_tip_speed_m_s, 4),
            r.seconds
        );
    }
    let _ = writeln!(
        t,
        "\n{:>4} {:>8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>16}",
        "arms", "carrier", "feasible", "median", "least", "largest", "(mm/rad)", "paper's design"
    );
    for a in &c.arms {
        let _ = writeln!(
            t,
            "{:>4} {:>8.1} {:>8} {:>10} {:>10} {:>10} {:>10} {:>16}",
            a.arms,
            a.carrier_rpm,
            a.feasible_searches,
            fmt(a.median_m_s, 4),
            fmt(a.min_m_s, 4),
            fmt(a.max_m_s, 4),
            fmt(a.median_mm_per_rad, 1),
            fmt(a.paper_design.compared_m_s, 4)
        );
    }
    for r in &c.reductions {
        let pct = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.1} %"));
        let _ = writeln!(
            t,
            "\n{} arms against {}: {} lower (medians); seed by seed {} (least {}, largest {}, \
             {} seeds)\n  = 1 − carrier factor {:.3} × shape factor {}; the paper's design \
             (the same path): {} lower",
            r.arms,
            r.against,
            pct(r.of_medians_pct),
            pct(r.paired_median_pct),
            pct(r.paired_min_pct),
            pct(r.paired_max_pct),
            r.paired_seeds,
            r.carrier_factor,
            fmt(r.shape_factor, 3),
            pct(r.paper_design_pct),
        );
    }
    t
}

/// The scene of the least-speed feasible design found for `arms` arm sets, if any, named
/// after its search scene, arm count and seed.
pub fn best_scene(c: &Comparison, arms: usize) -> Option<Scene> {
    let best = (c.searches.iter())
        .filter(|r| r.arms == arms && r.speeds.feasible)
        .filter_map(|r| Some((r.speeds.compared_m_s?, r)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, r)| r)?;
    let mut scene = best.scene.clone()?;
    scene.name = format!("{}-arms-{arms}-seed-{}", scene.name, best.seed);
    Some(scene)
}
