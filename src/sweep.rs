//! Parameter sweeps: every objective's response, and the chosen measures', to one
//! parameter (three-arm paper §4.2), evaluated in parallel.

use noncirc_core::{Evaluator, Measure, Measured, Scene};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;

use crate::{Error, Result};

/// One row of a parameter sweep: the value and every objective's value.
#[derive(Debug, Clone, Serialize)]
pub struct SweepRow {
    pub value: f64,
    pub objectives: BTreeMap<String, f64>,
    /// The measures asked for (`--measure`), by name; a measure the design does not have
    /// (no runner-up extreme, say) is absent.
    pub measures: BTreeMap<String, f64>,
    pub violation: Option<f64>,
    pub error: Option<String>,
}

/// Most steps of a sweep (each is a full evaluation; a million take about 20 s).
pub const MAX_SWEEP_STEPS: usize = 1_000_000;

/// The response of every objective, and of the given measures, to one parameter
/// (three-arm paper §4.2), in parallel.
pub fn sweep(
    scene: &Scene,
    param: &str,
    from: f64,
    to: f64,
    steps: usize,
    measures: &[Measure],
) -> Result<Vec<SweepRow>> {
    let p = noncirc_core::Param::parse(param, scene)?;
    if !(2..=MAX_SWEEP_STEPS).contains(&steps) || !from.is_finite() || !to.is_finite() {
        return Err(Error::Input(format!(
            "sweep needs finite --from/--to and --steps from 2 to {MAX_SWEEP_STEPS} \
             (got {from}, {to}, {steps})"
        )));
    }
    let values: Vec<f64> = (0..steps)
        .map(|i| from + (to - from) * i as f64 / (steps - 1) as f64)
        .collect();
    Ok(values
        .par_iter()
        .map_init(Evaluator::new, |ev, &v| {
            let mut s = scene.clone();
            p.set(&mut s, v);
            match ev.evaluate(&s) {
                Ok(e) => SweepRow {
                    value: v,
                    objectives: e
                        .objectives
                        .iter()
                        .map(|o| (o.kind.name().to_string(), o.value))
                        .collect(),
                    measures: {
                        let on = Measured::new(&e, &s);
                        (measures.iter())
                            .filter_map(|m| Some((m.name(), m.value(&on)?)))
                            .collect()
                    },
                    violation: Some(e.total_violation()),
                    error: None,
                },
                Err(err) => SweepRow {
                    value: v,
                    objectives: BTreeMap::new(),
                    measures: BTreeMap::new(),
                    violation: None,
                    error: Some(err.to_string()),
                },
            }
        })
        .collect())
}
