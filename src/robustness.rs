//! Tolerance analysis and global sensitivity of a scene: the core's estimators run over
//! whole scenes (the sensitivity's designs on a thread pool, in order), with reports a
//! person or a program reads.

use noncirc_core::{
    analyse, saltelli_points, sobol_indices_sharing, Evaluator, KeptGears, Measure, Measured,
    Resamples, Scene, SceneKind, SceneProblem, SobolIndices, ToleranceReport, Tolerances,
    Unreliable, REPORTED_QUANTILES,
};
use rayon::prelude::*;
use serde::Serialize;

use crate::search::{map_batch, thread_pool};
use crate::{Error, Result};

/// The success probability over the first `samples` samples.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ConvergencePoint {
    pub samples: usize,
    pub probability: f64,
}

/// A tolerance analysis of a scene's design.
#[derive(Debug, Clone, Serialize)]
pub struct Robustness {
    pub scene: String,
    pub samples_per_turn: usize,
    pub tolerances: Tolerances,
    #[serde(flatten)]
    pub report: ToleranceReport,
    /// The success probability over growing prefixes of the samples (powers of two):
    /// how far the estimate has settled.
    pub convergence: Vec<ConvergencePoint>,
    /// Per objective (the report's order), every sample's margin in its unit (NaN where
    /// the model refused the sample): the figure's distributions.
    #[serde(skip)]
    pub margins: Vec<Vec<f64>>,
}

/// Analyses `scene`'s design under `scene.tolerances` at the scene's resolution, with the
/// linearised worst case when `worst_case`.
pub fn robustness(scene: &Scene, worst_case: bool) -> Result<Robustness> {
    let mut evaluator = Evaluator::planned(&scene.resolution);
    let (report, outcomes) = analyse(&mut evaluator, scene, &scene.resolution, worst_case)?;
    let mut convergence = Vec::new();
    let mut n = 1;
    while n <= outcomes.len() {
        let met = outcomes[..n].iter().filter(|o| o.met).count();
        convergence.push(ConvergencePoint {
            samples: n,
            probability: met as f64 / n as f64,
        });
        n *= 2;
    }
    let margins = (0..report.objectives.len())
        .map(|k| outcomes.iter().map(|o| o.margins[k]).collect())
        .collect();
    Ok(Robustness {
        scene: scene.name.clone(),
        samples_per_turn: scene.resolution.samples_per_turn,
        tolerances: scene.tolerances,
        report,
        convergence,
        margins,
    })
}

/// `x` to three significant places, `—` for NaN.
fn num(x: f64) -> String {
    if x.is_nan() {
        "—".into()
    } else if x != 0.0 && x.abs() < 0.01 {
        format!("{x:.2e}")
    } else {
        format!("{x:.3}")
    }
}

/// What `picking_admissible` means in a tolerance analysis of a scene whose tray the
/// trajectory places, against `placed`, its value in `noncirc evaluate` (mm).
fn picking_admissible_note(placed: f64) -> String {
    format!(
        "picking_admissible here: the tray bolted where the nominal design puts it, the tip's \
         reach into pots twice the tray depth counted too; `noncirc evaluate` places the tray \
         at each design's own picking point, where the reach holds by construction, and reads \
         {placed:.3} mm for this design"
    )
}

/// The analysis as a table.
pub fn robustness_table(r: &Robustness) -> String {
    use std::fmt::Write;
    let rep = &r.report;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "Tolerance analysis of '{}': {} samples ({} sets of machined parts), seed {}, {} \
         samples per turn",
        r.scene, rep.samples, rep.part_sets, rep.seed, r.samples_per_turn
    );
    let [lo, hi] = rep.probability_all_ci95;
    let _ = writeln!(
        t,
        "P({} met) = {:.4}, 95 % interval [{lo:.4}, {hi:.4}] (Wilson; standard error {:.4}; \
         the samples taken as independent)",
        rep.requirements(),
        rep.probability_all,
        rep.probability_all_se
    );
    if !rep.constraints.is_empty() {
        let _ = writeln!(t, "search constraints: {}", rep.constraints.join(", "));
    }
    let _ = writeln!(
        t,
        "refused by the model: {}; picking moved to another branch: {}; planting: {}",
        rep.refused, rep.picking_branch_switches, rep.planting_branch_switches
    );
    if rep.refused == rep.samples {
        let _ = writeln!(
            t,
            "NO SAMPLE COULD BE EVALUATED: the model refused all {} (the tolerances move the \
             design beyond what it takes: smaller tolerances, or `noncirc evaluate` of a \
             deviated design, say why); the margins' quantiles, mean and spread are not \
             defined",
            rep.samples
        );
    }
    if let Some(d) = rep.tray_distance_mm {
        let _ = writeln!(t, "tray surface fixed at {d:.3} mm from the carrier axis");
    }
    if let Some(placed) = rep.picking_admissible_placed_mm {
        let _ = writeln!(t, "{}", picking_admissible_note(placed));
    }
    let q = REPORTED_QUANTILES.map(|q| format!("q{}", q * 100.0));
    let _ = writeln!(
        t,
        "\n{:<22} {:>5} {:>10} {:>10} {:>7} {:>17} {:>9} {:>9} {:>9} {:>9} {:>9} {:>11} {:>11}  dominant",
        "objective",
        "unit",
        "nominal",
        "margin",
        "P(met)",
        "95 % interval",
        q[0],
        q[1],
        q[2],
        q[3],
        q[4],
        "worst pred.",
        "at corner"
    );
    for o in &rep.objectives {
        let (pred, corner, dominant) = match &o.worst_case {
            Some(w) => (
                num(w.predicted_margin),
                num(w.corner_margin),
                format!("{} ({:.0} %)", w.dominant, 100.0 * w.dominant_share),
            ),
            None => ("—".into(), "—".into(), String::new()),
        };
        let mq = o.margin_quantiles.map(num);
        let _ = writeln!(
            t,
            "{:<22} {:>5} {:>10} {:>10} {:>7.4} {:>17} {:>9} {:>9} {:>9} {:>9} {:>9} {:>11} {:>11}  {}",
            o.objective.name(),
            o.unit,
            num(o.nominal_value),
            num(o.nominal_margin),
            o.probability,
            format!("[{:.4}, {:.4}]", o.probability_ci95[0], o.probability_ci95[1]),
            mq[0],
            mq[1],
            mq[2],
            mq[3],
            mq[4],
            pred,
            corner,
            dominant
        );
    }
    let _ = writeln!(
        t,
        "\nmargins in each objective's unit, negative when missed; quantiles over the \
         samples; worst case: linearised over each tolerance, checked at that corner"
    );
    let _ = writeln!(
        t,
        "P over the first n samples: {}",
        (r.convergence.iter())
            .map(|c| format!("{}: {:.3}", c.samples, c.probability))
            .collect::<Vec<_>>()
            .join(", ")
    );
    t
}

/// A parameter of the sensitivity's box.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoxParameter {
    pub name: String,
    /// The papers' symbol, if they name one.
    pub symbol: Option<String>,
    pub lower: f64,
    pub upper: f64,
}

/// One output's Sobol indices.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputIndices {
    pub name: String,
    pub unit: &'static str,
    #[serde(flatten)]
    pub indices: SobolIndices,
    /// What makes these indices unreadable at the samples taken (empty when nothing).
    pub unreliable: Vec<Unreliable>,
}

/// Global sensitivity of a scene's outputs over its search box.
#[derive(Debug, Clone, Serialize)]
pub struct Sensitivity {
    pub scene: String,
    /// Base points `N`; the designs evaluated are `N (k + 2)`.
    pub base_samples: usize,
    pub evaluations: usize,
    /// Designs the model refused (their base points are left out of each index).
    pub refused: usize,
    pub seed: u64,
    pub bootstrap: usize,
    /// The box's share of the search box's widths, about the scene's design.
    pub box_scale: f64,
    /// The parameters with the box sampled.
    pub parameters: Vec<BoxParameter>,
    pub outputs: Vec<OutputIndices>,
    /// Outputs that no base point computed (e.g. a branch gap on a one-branch path).
    pub skipped: Vec<String>,
    /// Base points that would read every output's indices to ±0.05 (a power of two), when
    /// some output's are unreliable at `base_samples`; `None` when all are readable.
    pub base_samples_needed: Option<usize>,
    /// The designs in parameter values, one row per design in SALib's order.
    #[serde(skip)]
    pub x: Vec<Vec<f64>>,
    /// Every design's outputs, in the order of [`Sensitivity::output_names`] (NaN where
    /// the model refused the design or does not compute the output).
    #[serde(skip)]
    pub y: Vec<Vec<f64>>,
    #[serde(skip)]
    pub output_names: Vec<String>,
}

/// The outputs a scene computes: its objectives, then every measure of a three-arm path
/// (the moving box's only in a transplanter scene, the dynamics' only where the
/// objectives include the teeth's strength). The gearbox's overlap is left out: a
/// check that is zero over most of the box, not a response of the path.
fn outputs(scene: &Scene) -> Vec<Measure> {
    // The dynamics' measures where the objectives already pay for the teeth's strength
    // (the dynamics is a small part of it); else a sample costs ten evaluations' time more.
    let strength = scene.objectives.iter().any(|k| k.needs_strength());
    (Measure::all().into_iter())
        .filter(|m| match m {
            Measure::Objective(k) => scene.objectives.contains(k),
            Measure::Dynamics(_) => strength,
            m if m.name() == "box_travel_mm" => scene.kind == SceneKind::Transplanter,
            m => m.name() != "gear_overlap_mm",
        })
        .collect()
}

/// The narrowest box the sensitivity samples, as a share of the search box: a millionth
/// of each width, still far above the model's own resolution (closure to 1e-9 relative).
pub const MIN_BOX_SCALE: f64 = 1e-6;

/// First-order and total Sobol indices of every output of `scene` over its search box
/// (`search.free`, or the default space) scaled by `box_scale` about the scene's design
/// (1: the whole box; 0.1: a tenth of each width, inside the box), from `base_samples`
/// base points, with `bootstrap` resamples for the intervals, on `threads` threads (the
/// result does not depend on it).
pub fn sensitivity(
    scene: &Scene,
    base_samples: usize,
    bootstrap: usize,
    box_scale: f64,
    threads: usize,
) -> Result<Sensitivity> {
    if !(MIN_BOX_SCALE..=1.0).contains(&box_scale) {
        return Err(Error::Input(format!(
            "box scale (--box-scale, box_scale) = {box_scale:?}: expected {MIN_BOX_SCALE:e} to 1, \
             a share of the search box (below it the designs differ by less than the model \
             resolves, and every index would read as noise or 0)"
        )));
    }
    if bootstrap > 10_000 {
        return Err(Error::Input(format!(
            "bootstrap = {bootstrap}: expected 0 to 10000 resamples"
        )));
    }
    if !matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter) {
        return Err(Error::Input(format!(
            "sensitivity needs a three_arm or transplanter scene (this one is {})",
            scene.kind.name()
        )));
    }
    let problem = SceneProblem::new(scene)?;
    let k = problem.dim();
    let seed = scene.search.seed;
    // The box: each width scaled about the design's value, kept inside the search box.
    let (lower, upper) = problem.bounds();
    let names = problem.names();
    let mut sampled = Vec::with_capacity(k);
    for (i, name) in names.iter().enumerate() {
        let (lo, hi) = (lower[i], upper[i]);
        let at = noncirc_core::Param::parse(name, scene)?
            .get(scene)
            .unwrap_or((lo + hi) / 2.0)
            .clamp(lo, hi);
        let half = box_scale * (hi - lo) / 2.0;
        let (a, b) = ((at - half).max(lo), (at + half).min(hi));
        // A design on the box's edge keeps a box of the asked width inside it.
        sampled.push(if b - a < 2.0 * half {
            if a == lo {
                (lo, lo + 2.0 * half)
            } else {
                (hi - 2.0 * half, hi)
            }
        } else {
            (a, b)
        });
    }
    let points: Vec<Vec<f64>> = saltelli_points(k, base_samples, seed)?
        .iter()
        .map(|u| {
            let x: Vec<f64> = (u.iter().zip(&sampled))
                .map(|(u, (a, b))| a + u * (b - a))
                .collect();
            problem.encode(&x)
        })
        .collect();
    let measures = outputs(scene);
    let pool = thread_pool(threads)?;
    let planned = Evaluator::planned(&scene.resolution);
    // One task per base point's k + 2 designs, A first: the designs that change only the
    // train's assembly (A_B^i of Φ0, β0, S, H1, γ0) take A's gears reassembled. A task
    // keeps nothing from the one before, so the results do not depend on the threads.
    let blocks: Vec<&[Vec<f64>]> = points.chunks(k + 2).collect();
    let y: Vec<Vec<f64>> = map_batch(&pool, &planned, scene, &blocks, |(ev, s), block| {
        let mut kept = None;
        (block.iter().enumerate())
            .map(|(i, u)| {
                problem.apply(u, s);
                let eval = ev.evaluate_keeping(s, kept.as_ref());
                let row = match &eval {
                    Ok(e) => {
                        let on = Measured::new(e, s);
                        (measures.iter())
                            .map(|m| m.value(&on).unwrap_or(f64::NAN))
                            .collect()
                    }
                    Err(_) => vec![f64::NAN; measures.len()],
                };
                if i == 0 {
                    kept = eval.ok().and_then(|e| KeptGears::of(s, e));
                }
                row
            })
            .collect::<Vec<Vec<f64>>>()
    })
    .into_iter()
    .flatten()
    .collect();
    let refused = y.iter().filter(|r| r.iter().all(|v| v.is_nan())).count();
    // Each output's indices and bootstrap on its own (the same seed each): in parallel,
    // in the outputs' order whatever the threads. The outputs with every base point share
    // one draw of the resamples (where it is small enough to keep).
    let shared = Resamples::new(base_samples, bootstrap, seed);
    let indices: Vec<_> = pool.install(|| {
        (0..measures.len())
            .into_par_iter()
            .map(|m| {
                let column: Vec<f64> = y.iter().map(|r| r[m]).collect();
                sobol_indices_sharing(&column, k, bootstrap, seed, shared.as_ref())
            })
            .collect()
    });
    let mut out = Vec::new();
    let mut skipped = Vec::new();
    for (measure, indices) in measures.iter().zip(indices) {
        match indices {
            Ok(indices) => out.push(OutputIndices {
                name: measure.name(),
                unit: measure.unit(),
                unreliable: indices.unreliable(),
                indices,
            }),
            Err(_) => skipped.push(measure.name()),
        }
    }
    let base_samples_needed = (out.iter())
        .filter(|o| !o.unreliable.is_empty())
        .map(|o| o.indices.base_samples_needed(base_samples))
        .max();
    Ok(Sensitivity {
        base_samples_needed,
        scene: scene.name.clone(),
        base_samples,
        evaluations: points.len(),
        refused,
        seed,
        bootstrap,
        box_scale,
        parameters: (names.iter().enumerate())
            .map(|(i, n)| BoxParameter {
                name: n.to_string(),
                symbol: noncirc_core::symbol(n),
                lower: sampled[i].0,
                upper: sampled[i].1,
            })
            .collect(),
        outputs: out,
        skipped,
        x: points.iter().map(|u| problem.decode(u)).collect(),
        y,
        output_names: measures.iter().map(|m| m.name()).collect(),
    })
}

/// A parameter's short label: its symbol, else its path.
pub fn parameter_label(p: &BoxParameter) -> String {
    p.symbol.clone().unwrap_or_else(|| p.name.clone())
}

/// The indices as a table: per output, the three parameters of largest total index.
pub fn sensitivity_table(s: &Sensitivity) -> String {
    use std::fmt::Write;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "Sobol indices of '{}' over {} its search box about the design: {} base points, {} \
         designs ({} refused), seed {}, {} bootstrap resamples (± half-width of the 95 % \
         interval)",
        s.scene,
        if s.box_scale == 1.0 {
            "all of".to_string()
        } else {
            format!("{} of", s.box_scale)
        },
        s.base_samples,
        s.evaluations,
        s.refused,
        s.seed,
        s.bootstrap
    );
    if s.refused * 10 > s.evaluations {
        let _ = writeln!(
            t,
            "warning: the model refused {:.0} % of the designs, and a base point counts only \
             where all its k + 2 designs exist ('used' below): the indices describe the part \
             of the box the model takes. A smaller box (--box-scale) refuses fewer.",
            100.0 * s.refused as f64 / s.evaluations as f64
        );
    }
    let _ = writeln!(
        t,
        "\n{:<32} {:>6} {:>5}  largest total indices S_T (first-order S1)",
        "output", "unit", "used"
    );
    for o in &s.outputs {
        let mut order: Vec<usize> = (0..s.parameters.len()).collect();
        order.sort_by(|&a, &b| o.indices.total[b].total_cmp(&o.indices.total[a]));
        let top: Vec<String> = (order.iter().take(3))
            .map(|&i| {
                format!(
                    "{} {:.2}±{:.2} ({:.2})",
                    parameter_label(&s.parameters[i]),
                    o.indices.total[i],
                    o.indices.total_conf[i],
                    o.indices.first[i]
                )
            })
            .collect();
        let _ = writeln!(
            t,
            "{:<32} {:>6} {:>5}  {}",
            o.name,
            o.unit,
            o.indices.rows_used,
            top.join(", ")
        );
    }
    if !s.skipped.is_empty() {
        let _ = writeln!(
            t,
            "\nnot computed at any base point: {}",
            s.skipped.join(", ")
        );
    }
    t.push_str(&unreliable_text(s));
    t
}

/// The warning for indices that cannot be read at the samples taken, output by output
/// (empty when every output's can).
pub fn unreliable_text(s: &Sensitivity) -> String {
    use std::fmt::Write;
    let Some(needed) = s.base_samples_needed else {
        return String::new();
    };
    let labels: Vec<String> = s.parameters.iter().map(parameter_label).collect();
    let flagged: Vec<&OutputIndices> = (s.outputs.iter())
        .filter(|o| !o.unreliable.is_empty())
        .collect();
    let mut t = String::new();
    let _ = writeln!(
        t,
        "\nwarning: the indices of {} of {} outputs cannot be read at {} base points. About \
         {needed} base points (--base-samples {needed}{}) would read them to ±{}{}:",
        flagged.len(),
        s.outputs.len(),
        s.base_samples,
        if needed > 65_536 {
            "; above the most, 65536: a smaller --box-scale or fewer free parameters"
        } else {
            ""
        },
        noncirc_core::READABLE_HALF_WIDTH,
        if (flagged.iter()).any(|o| o.indices.rows_used < noncirc_core::FEWEST_ROWS) {
            format!(
                " (a first step where fewer than {} were used: the intervals there tell the \
                 rest)",
                noncirc_core::FEWEST_ROWS
            )
        } else {
            String::new()
        }
    );
    for o in flagged {
        let reasons: Vec<String> = (o.unreliable.iter())
            .filter(|u| !matches!(u, Unreliable::FewRows { .. }))
            .map(|u| u.describe(&labels))
            .collect();
        let few = if o.indices.rows_used < noncirc_core::FEWEST_ROWS {
            ", too few"
        } else {
            ""
        };
        let _ = writeln!(
            t,
            "  {} ({} used{few}): {}",
            o.name,
            o.indices.rows_used,
            reasons.join("; ")
        );
    }
    t
}
