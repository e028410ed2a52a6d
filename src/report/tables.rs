//! The reports as readable text: aligned tables, objective gauges, the search summary and
//! sweeps, with names in the papers' order.

use super::RequirementRow;
use noncirc_core::BoxReport;

/// Formats `(label, value)` rows as an aligned two-column table.
pub fn table(rows: &[(&str, String)]) -> String {
    let width = rows.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
    rows.iter()
        .map(|(k, v)| format!("{k:<width$}  {v}\n"))
        .collect()
}

/// Objectives as gauge rows.
pub fn objective_table(objectives: &[RequirementRow]) -> String {
    let mut out = String::new();
    for o in objectives {
        let bounds = match (o.lower, o.upper) {
            (Some(l), Some(u)) => format!("[{l}, {u}]"),
            (Some(l), None) => format!(">= {l}"),
            (None, Some(u)) => format!("<= {u}"),
            (None, None) => String::new(),
        };
        let status = if o.violation == 0.0 {
            format!("met (margin {:.2} {})", o.margin, o.unit)
        } else {
            format!("MISSED by {:.2} {}", o.violation, o.unit)
        };
        out += &format!(
            "{:<32} {:>9.2} {:<3} {:<14} {} {}\n",
            o.label,
            o.value,
            o.unit,
            bounds,
            gauge(o.value, o.lower, o.upper),
            status
        );
    }
    out
}

/// The moving box's report as a table.
pub fn box_table(b: &BoxReport) -> String {
    table(&[
        (
            "eccentricity k",
            format!("{:.6} (speed ratio {:.4})", b.eccentricity, b.speed_ratio),
        ),
        (
            "ellipse semi-major axis",
            format!(
                "{:.3} mm (centre distance {:.3} mm)",
                b.semi_major_mm, b.centre_distance_mm
            ),
        ),
        (
            "picking window (driver)",
            format!("{:.2}° .. {:.2}°", b.window_deg[0], b.window_deg[1]),
        ),
        (
            "box travel, elliptical",
            format!(
                "{:.4} mm (numerical {:.4} mm)",
                b.elliptic_delta_h_mm, b.elliptic_delta_h_numeric_mm
            ),
        ),
        (
            "box travel, constant speed",
            format!("{:.4} mm", b.uniform_delta_h_mm),
        ),
        (
            "box travel, sinusoidal shaft",
            format!("{:.4} mm", b.sinusoidal_delta_h_mm),
        ),
        (
            "limit (1/6 pot width)",
            format!(
                "{:.3} mm: {}",
                b.limit_mm,
                if b.within_limit { "kept" } else { "EXCEEDED" }
            ),
        ),
        (
            "best window centre",
            format!("{:.4}°", b.best_window_centre_deg),
        ),
        (
            "box speed",
            format!("{:.2} .. {:.2} mm/s", b.speed_min_mm_s, b.speed_max_mm_s),
        ),
        (
            "largest slider normal force",
            format!("{:.3} N", b.slider_force_max_n),
        ),
    ])
}

/// A 24-character gauge: `|` marks the bounds, `#` the value, `=` the admissible span.
fn gauge(value: f64, lower: Option<f64>, upper: Option<f64>) -> String {
    const W: usize = 24;
    let (lo, hi) = match (lower, upper) {
        (Some(l), Some(u)) => (l - 0.5 * (u - l), u + 0.5 * (u - l)),
        (Some(l), None) => {
            let s = l.abs().max((value - l).abs()).max(1.0);
            (l - s, l + s)
        }
        (None, Some(u)) => {
            let s = u.abs().max((value - u).abs()).max(1.0);
            (u - s, u + s)
        }
        (None, None) => (value - 1.0, value + 1.0),
    };
    let pos = |x: f64| {
        ((x - lo) / (hi - lo) * (W - 1) as f64)
            .round()
            .clamp(0.0, (W - 1) as f64) as usize
    };
    let mut cells = vec!['.'; W];
    let (a, b) = (lower.map_or(0, pos), upper.map_or(W - 1, pos));
    for c in cells.iter_mut().take(b + 1).skip(a) {
        *c = '=';
    }
    if let Some(l) = lower {
        cells[pos(l)] = '|';
    }
    if let Some(u) = upper {
        cells[pos(u)] = '|';
    }
    cells[pos(value)] = '#';
    format!("[{}]", cells.into_iter().collect::<String>())
}

/// A search summary as a table.
pub fn summary_table(s: &crate::search::Summary) -> String {
    let mut out = table(&[
        ("scene", s.scene.clone()),
        (
            "algorithm",
            format!("{} (seed {}, {} threads)", s.algorithm, s.seed, s.threads),
        ),
        (
            "evaluations",
            format!(
                "{} at {} samples/turn + {} confirmations at {}",
                s.evaluations,
                s.screening_samples_per_turn,
                s.confirmations,
                s.confirming_samples_per_turn
            ),
        ),
        (
            "time",
            format!(
                "{:.2} s{}",
                s.seconds,
                if s.stopped_early {
                    " (stopped early)"
                } else {
                    ""
                }
            ),
        ),
        (
            "first feasible",
            match (s.first_feasible_evaluations, s.seconds_to_first_feasible) {
                (Some(n), Some(t)) => format!("after {n} evaluations, {t:.2} s"),
                _ => "none found".into(),
            },
        ),
        (
            "result",
            if s.feasible {
                format!("FEASIBLE: meets {}", s.requirements())
            } else if s.evaluations == 0 {
                "NO DESIGN EVALUATED: stopped before the first generation ended (a generation \
                 cut short is dropped whole; run again, or resume the checkpoint)"
                    .to_string()
            } else {
                let missed = s.missed();
                format!(
                    "NOT FEASIBLE: no design found meets {}; the best misses {} \
                     (a larger --budget, another --seed or --algorithm de|cmaes may find one)",
                    s.requirements(),
                    if missed.is_empty() {
                        "them all (the model refused it)".to_string()
                    } else {
                        missed.join(", ")
                    }
                )
            },
        ),
    ]);
    out += if s.goals.len() >= 2 {
        "\nbest design: the Pareto set's best on the first goal (pareto.csv lists every \
         member, sorted by it; docs/search.md; docs/scenes.md: the fields and the papers' \
         symbols):\n"
    } else {
        "\nbest design (docs/scenes.md: the fields and the papers' symbols):\n"
    };
    for k in keys_in_scene_order(&s.best) {
        let symbol = noncirc_core::symbol(k).unwrap_or_default();
        let unit = noncirc_core::field(k).map_or("", |f| f.unit);
        out += &format!("  {k:<28} {symbol:<8} {:>10.4} {unit}\n", s.best[k]);
    }
    out += "\nobjectives at the default resolution (value, violation, unit):\n";
    for kind in noncirc_core::ObjectiveKind::ALL {
        let k = kind.name();
        if let Some(v) = s.objectives.get(k) {
            out += &format!(
                "  {k:<28} {v:>10.4}  {:>8.4}  {}\n",
                s.violations.get(k).copied().unwrap_or(0.0),
                kind.unit()
            );
        }
    }
    if !s.constraints.is_empty() {
        out += "\nsearch constraints at the default resolution (value, violation, unit):\n";
        for c in &s.constraints {
            out += &format!(
                "  {:<28} {:>10.4}  {:>8.4}  {}\n",
                c.label, c.value, c.violation, c.unit
            );
        }
    }
    out
}

/// A map's keys (scene paths) in [`scene_order`].
pub fn keys_in_scene_order<V>(map: &std::collections::BTreeMap<String, V>) -> Vec<&String> {
    let mut keys: Vec<&String> = map.keys().collect();
    keys.sort_by(|a, b| scene_order(a, b));
    keys
}

/// Orders scene paths as a scene file does (docs/scenes.md): by field, then list elements
/// by index; names that are no field last, in natural order.
pub fn scene_order(a: &str, b: &str) -> std::cmp::Ordering {
    let rank = |p: &str| {
        let key = p.split('[').next().unwrap_or(p);
        noncirc_core::fields()
            .position(|f| f.key == key)
            .unwrap_or(usize::MAX)
    };
    rank(a).cmp(&rank(b)).then_with(|| natural_cmp(a, b))
}

/// Orders names as a person does: runs of digits by their value (`radii_mm[2]` before
/// `radii_mm[10]`), the rest by character.
pub fn natural_cmp(a: &str, b: &str) -> std::cmp::Ordering {
    use std::cmp::Ordering;
    fn digit(c: char) -> bool {
        c.is_ascii_digit()
    }
    /// The leading run of `s` (all digits or none) and the rest.
    fn run(s: &str) -> (&str, &str) {
        let digits = s.starts_with(digit);
        s.split_at(s.find(|c: char| digit(c) != digits).unwrap_or(s.len()))
    }
    let (mut x, mut y) = (a, b);
    loop {
        match (x.is_empty(), y.is_empty()) {
            (true, true) => return Ordering::Equal,
            (true, false) => return Ordering::Less,
            (false, true) => return Ordering::Greater,
            _ => {}
        }
        let ((px, rx), (py, ry)) = (run(x), run(y));
        let order = if px.starts_with(digit) && py.starts_with(digit) {
            px.len().cmp(&py.len()).then(px.cmp(py))
        } else {
            px.cmp(py)
        };
        if order.is_ne() {
            return order;
        }
        (x, y) = (rx, ry);
    }
}

/// A sweep as a table: one row per value, one column per objective.
pub fn sweep_table(param: &str, rows: &[crate::sweep::SweepRow]) -> String {
    // The objectives in the paper's order, then the measures asked for.
    let evaluated = rows.iter().find(|r| !r.objectives.is_empty());
    let names: Vec<String> = (noncirc_core::ObjectiveKind::ALL.iter())
        .map(|k| k.name().to_string())
        .filter(|n| evaluated.is_some_and(|r| r.objectives.contains_key(n)))
        .collect();
    let measures: Vec<String> = rows
        .iter()
        .flat_map(|r| r.measures.keys().cloned())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    // Objectives are measures too: one lookup gives every column's unit.
    let unit = |n: &str| noncirc_core::Measure::parse(n).map_or("", |m| m.unit());
    let mut out = format!("{param:>24}");
    for n in names.iter().chain(&measures) {
        out += &format!(" {:>17}", n);
    }
    out += "   violation\n";
    // Units under the names.
    let shown = |u: &str| {
        if u.is_empty() {
            "–".to_string()
        } else {
            format!("({u})")
        }
    };
    let param_unit = noncirc_core::field(param).map_or("", |f| f.unit);
    out += &format!("{:>24}", shown(param_unit));
    for n in names.iter().chain(&measures) {
        out += &format!(" {:>17}", shown(unit(n)));
    }
    out += "  (normalised)\n";
    for r in rows {
        out += &format!("{:>24.4}", r.value);
        match &r.error {
            Some(e) => out += &format!("  error: {e}"),
            None => {
                for n in &names {
                    out += &format!(" {:>17.4}", r.objectives[n]);
                }
                for n in &measures {
                    match r.measures.get(n) {
                        Some(v) => out += &format!(" {v:>17.4}"),
                        None => out += &format!(" {:>17}", "-"),
                    }
                }
                out += &format!("   {:.4}", r.violation.unwrap_or(f64::NAN));
            }
        }
        out += "\n";
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{natural_cmp, scene_order, sweep_table};

    /// A sweep's table lists the objectives in the paper's order (not alphabetically) and
    /// the measures after them, with a row of units under the names.
    #[test]
    fn the_sweep_table_is_in_the_papers_order_with_units() {
        let objectives = [
            ("module", 0.19),
            ("interference", 45.0),
            ("picking_angle", 0.3),
        ];
        let row = crate::sweep::SweepRow {
            value: -50.0,
            objectives: objectives
                .iter()
                .map(|&(n, v)| (n.to_string(), v))
                .collect(),
            measures: [("picking_tip_speed_m_s".to_string(), 0.8)].into(),
            violation: Some(2.3),
            error: None,
        };
        let table = sweep_table("train.gamma0_deg", &[row]);
        let lines: Vec<Vec<&str>> = table
            .lines()
            .map(|l| l.split_whitespace().collect())
            .collect();
        assert_eq!(
            lines[0],
            [
                "train.gamma0_deg",
                "interference",
                "picking_angle",
                "module",
                "picking_tip_speed_m_s",
                "violation"
            ]
        );
        assert_eq!(
            lines[1],
            ["(°)", "(mm)", "(deg)", "(mm)", "(m/s)", "(normalised)"]
        );
        assert_eq!(lines[2][0], "-50.0000");
    }

    /// The best design's parameters come in a scene file's order: the radii by index, then
    /// the train as docs/scenes.md lists it (Φ0, β0, S, H1, γ0), not alphabetically.
    #[test]
    fn parameters_sort_in_scene_order() {
        let mut names = vec![
            "train.pusher_offset_mm",
            "train.gamma0_deg",
            "gear.curve.radii_mm[10]",
            "train.arm_length_mm",
            "no.such_field",
            "train.phi0_deg",
            "gear.curve.radii_mm[2]",
            "train.beta0_deg",
        ];
        names.sort_by(|a, b| scene_order(a, b));
        assert_eq!(
            names,
            [
                "gear.curve.radii_mm[2]",
                "gear.curve.radii_mm[10]",
                "train.phi0_deg",
                "train.beta0_deg",
                "train.arm_length_mm",
                "train.pusher_offset_mm",
                "train.gamma0_deg",
                "no.such_field",
            ]
        );
    }

    /// Parameters are listed as a person counts: radius 2 before radius 10.
    #[test]
    fn names_sort_in_natural_order() {
        let mut names = vec![
            "train.phi0_deg",
            "gear.curve.radii_mm[10]",
            "gear.curve.radii_mm[2]",
            "gear.curve.radii_mm[1]",
            "gear.curve.radii_mm[0]",
            "gear.curve.radii_mm[11]",
            "a2b",
            "a10",
            "a",
        ];
        names.sort_by(|a, b| natural_cmp(a, b));
        assert_eq!(
            names,
            [
                "a",
                "a2b",
                "a10",
                "gear.curve.radii_mm[0]",
                "gear.curve.radii_mm[1]",
                "gear.curve.radii_mm[2]",
                "gear.curve.radii_mm[10]",
                "gear.curve.radii_mm[11]",
                "train.phi0_deg"
            ]
        );
    }
}
