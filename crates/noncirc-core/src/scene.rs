//! Scenes: what is being designed and asked, as plain serialisable data (no I/O here).

use crate::curve::CurveSpec;
use crate::gear::ModuleRule;
use crate::objectives::{Agronomy, Bounds};
use crate::planetary::TrainSpec;
use crate::resolution::Resolution;
use serde::{Deserialize, Serialize};

/// A gear pair's specification: the driver's pitch curve and the tooth-cutting rules.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearSpec {
    /// The driving (sun) gear's pitch curve. Default: the three-arm paper's 12-point spline.
    #[serde(default = "CurveSpec::paper")]
    pub curve: CurveSpec,
    /// Module rules (spec §1.4).
    #[serde(default)]
    pub module: ModuleRule,
}

impl Default for GearSpec {
    fn default() -> Self {
        Self {
            curve: CurveSpec::paper(),
            module: ModuleRule::default(),
        }
    }
}

/// A scene: the design, what is asked of it and at which resolution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name.
    #[serde(default)]
    pub name: String,
    /// One-line description.
    #[serde(default)]
    pub description: String,
    /// Numerical resolution.
    #[serde(default)]
    pub resolution: Resolution,
    /// The gear pair (the sun; the planets are congruent, the intermediates conjugate).
    #[serde(default)]
    pub gear: GearSpec,
    /// The three-arm train and its arms.
    #[serde(default)]
    pub train: TrainSpec,
    /// Agronomic inputs of the objectives.
    #[serde(default)]
    pub agronomy: Agronomy,
    /// Bounds of the eight objectives.
    #[serde(default)]
    pub bounds: Bounds,
}
