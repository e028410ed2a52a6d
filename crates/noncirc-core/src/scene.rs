//! Scenes: what is being designed and asked, as plain serialisable data (no I/O here).

use crate::agronomy::Agronomy;
use crate::cad_spec::CadSpec;
use crate::constraint::Constraint;
use crate::curve::{CurveSpec, PitchCurve};
use crate::dynamics_spec::DynamicsSpec;
use crate::error::{Error, Result};
use crate::gear::ModuleRule;
use crate::goal::Goal;
use crate::moving_box::BoxSpec;
use crate::objective_kind::{Bounds, ObjectiveKind};
use crate::planetary::{Kinematics, TrainSpec};
use crate::resolution::Resolution;
use crate::target::Target;
use crate::teeth::ToothSpec;
use crate::tolerance::Tolerances;
use noncirc_search::Algorithm;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// A gear pair's specification: the driver's pitch curve and the tooth-cutting rules.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearSpec {
    /// The driving (sun) gear's pitch curve. Default: the three-arm paper's 12-point spline.
    #[serde(default = "CurveSpec::paper")]
    pub curve: CurveSpec,
    /// The train with two pairs: the pitch curve of the intermediate's second layer (its
    /// layer B, on the same shaft as the conjugate of `curve`), which drives the planet,
    /// its conjugate. Its own angles are the intermediate's. Unset (left out of a written
    /// scene): the paper's train, the planet congruent to the sun.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub second_curve: Option<CurveSpec>,
    /// Module rules (spec §1.4).
    #[serde(default)]
    pub module: ModuleRule,
    /// How teeth are cut and checked (`noncirc teeth`, and the module rule `teeth`).
    /// Left out of a written scene while it is the default, so older scenes and their
    /// checkpoints keep their form.
    #[serde(default, skip_serializing_if = "ToothSpec::is_default")]
    pub teeth: ToothSpec,
}

impl GearSpec {
    /// The sun's pitch curve and, for the train with two pairs, the intermediate's layer B
    /// (its errors named as the second pair's).
    pub fn curves(&self) -> Result<(PitchCurve, Option<PitchCurve>)> {
        let second = (self.second_curve.as_ref())
            .map(|c| c.build().map_err(|e| Error::SecondPair(Box::new(e))))
            .transpose()?;
        Ok((self.curve.build()?, second))
    }
}

impl Default for GearSpec {
    fn default() -> Self {
        Self {
            curve: CurveSpec::paper(),
            second_curve: None,
            module: ModuleRule::default(),
            teeth: ToothSpec::default(),
        }
    }
}

/// What a scene designs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum SceneKind {
    /// A non-circular gear pair alone: closure, ratio, module.
    Gear,
    /// The planetary transplanting mechanism (three arm sets as in the paper, or
    /// `train.arms`) and its objectives; `three_arm` in a scene file.
    #[default]
    #[serde(rename = "three_arm")]
    Mechanism,
    /// The variable-speed moving box alone.
    MovingBox,
    /// The mechanism plus the moving box, coupled through the picking window.
    Transplanter,
}

impl SceneKind {
    /// The kind's name in a scene file: `gear`, `three_arm`, `moving_box`, `transplanter`.
    pub fn name(self) -> &'static str {
        match self {
            SceneKind::Gear => "gear",
            SceneKind::Mechanism => "three_arm",
            SceneKind::MovingBox => "moving_box",
            SceneKind::Transplanter => "transplanter",
        }
    }
}

/// A free parameter of a search: a scene path and its bounds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FreeParam {
    /// Scene path, e.g. `train.phi0_deg` or `gear.curve.radii_mm[3]`.
    pub name: String,
    pub lower: f64,
    pub upper: f64,
}

/// How to search the scene's design space (used by `noncirc optimise`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SearchSpec {
    /// The free parameters; empty means the default space around the scene's design.
    pub free: Vec<FreeParam>,
    /// The algorithm (by name in scene files: see `noncirc optimise --help`).
    pub algorithm: Algorithm,
    /// Evaluation budget.
    #[serde(with = "crate::whole_number")]
    pub budget: u64,
    /// Population size of population-based algorithms.
    pub population: usize,
    /// Random seed.
    #[serde(with = "crate::whole_number")]
    pub seed: u64,
    /// Resolution used for screening; every reported design is re-evaluated at the scene's.
    pub screening: Resolution,
    /// Goals beyond feasibility, by name in scene files: objective margins (maximised),
    /// `least_margin`, `picking_tip_speed` and `box_travel` (minimised), `min:NAME` /
    /// `max:NAME` of any measure. Empty: `least_margin`.
    pub goals: Vec<Goal>,
    /// Bounds on any measure that a design must meet beside the objectives, written
    /// `NAME <= VALUE` or `NAME >= VALUE` (`picking_height_mm <= -90`): every search
    /// counts a missed one as a missed objective, and every evaluation reports them. Left
    /// out of a written scene while empty (a checkpoint written before they existed keeps
    /// its scene's hash).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub constraints: Vec<Constraint>,
    /// Confirm the reported designs under the module rule `teeth` (their teeth cut and
    /// checked, `gear.module.teeth` teeth) while the search itself screens with the
    /// scene's own rule: the teeth's cost is paid once per reported design. Left out of a
    /// written scene while false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub confirm_with_teeth: bool,
}

impl SearchSpec {
    /// Largest population: a generation of 100 000 designs takes about two seconds.
    pub const MAX_POPULATION: usize = noncirc_search::MAX_POPULATION;
    /// Most free parameters (every number of the largest built-in scene is about 60).
    pub const MAX_FREE: usize = 1_000;
    /// Most constraints (two bounds on each of the hundred or so measures).
    pub const MAX_CONSTRAINTS: usize = 200;
}

impl Default for SearchSpec {
    fn default() -> Self {
        Self {
            free: Vec::new(),
            algorithm: Algorithm::De,
            budget: 60_000,
            population: 48,
            seed: 1,
            screening: Resolution::FAST,
            goals: Vec::new(),
            constraints: Vec::new(),
            confirm_with_teeth: false,
        }
    }
}

fn all_objectives() -> Vec<ObjectiveKind> {
    ObjectiveKind::DEFAULT.to_vec()
}

/// A scene: the design, what is asked of it and at which resolution.
///
/// The default scene is the three-arm paper's design; a scene is edited by path and
/// checked whole:
///
/// ```
/// use noncirc_core::{Param, Scene};
///
/// let mut scene = Scene::default();
/// let gamma0 = Param::parse("train.gamma0_deg", &scene).unwrap();
/// gamma0.set(&mut scene, -50.0);
/// assert_eq!(scene.train.gamma0_deg, -50.0);
/// assert!(scene.validate().is_ok());
/// scene.train.arm_length_mm = -1.0; // refused by name
/// assert!(scene.validate().unwrap_err().to_string().contains("arm_length_mm"));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name.
    #[serde(default)]
    pub name: String,
    /// One-line description.
    #[serde(default)]
    pub description: String,
    /// What is designed.
    #[serde(default)]
    pub kind: SceneKind,
    /// Which objectives are evaluated (default: all eight; a gear scene may ask the module).
    #[serde(default = "all_objectives")]
    pub objectives: Vec<ObjectiveKind>,
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
    /// The moving box.
    #[serde(default)]
    pub moving_box: BoxSpec,
    /// Search settings.
    #[serde(default)]
    pub search: SearchSpec,
    /// Manufacturing and assembly tolerances (`noncirc robustness`, robust goals). Left
    /// out of a written scene while they are the defaults.
    #[serde(default, skip_serializing_if = "Tolerances::is_default")]
    pub tolerances: Tolerances,
    /// The tip path and key poses a fit aims at (`noncirc fit`, the fit measures). Shared
    /// between a scene's copies.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<Arc<Target>>,
    /// The bodies and loads of the dynamics at working speed (`noncirc dynamics`). Left
    /// out of a written scene while it is the default.
    #[serde(default, skip_serializing_if = "DynamicsSpec::is_default")]
    pub dynamics: DynamicsSpec,
    /// The solid models' dimensions that the design does not give (`noncirc cad`). Left
    /// out of a written scene while they are the defaults.
    #[serde(default, skip_serializing_if = "CadSpec::is_default")]
    pub cad: CadSpec,
}

impl Default for Scene {
    fn default() -> Self {
        Self {
            name: String::new(),
            description: String::new(),
            kind: SceneKind::default(),
            objectives: all_objectives(),
            resolution: Resolution::default(),
            gear: GearSpec::default(),
            train: TrainSpec::default(),
            agronomy: Agronomy::default(),
            bounds: Bounds::default(),
            moving_box: BoxSpec::default(),
            search: SearchSpec::default(),
            tolerances: Tolerances::default(),
            target: None,
            dynamics: DynamicsSpec::default(),
            cad: CadSpec::default(),
        }
    }
}

impl Scene {
    /// The scene's train solved at `resolution`: its pitch curves built, its pairs closed
    /// and arm I moved through one turn (a three-arm or transplanter scene's motion).
    pub fn kinematics(&self, resolution: &Resolution) -> Result<Kinematics> {
        let (curve, second) = self.gear.curves()?;
        Kinematics::solve(&curve, second.as_ref(), &self.train, resolution)
    }
}
