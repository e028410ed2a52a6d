//! noncirc-core: the pure numerical core of noncirc (no I/O, no threads).
//!
//! Units: millimetres and radians inside; degrees only where a person reads or writes.

pub mod accuracy;
pub mod anatomy;
pub mod angle;
pub mod curve;
pub mod error;
pub mod evaluation;
pub mod events;
pub mod gear;
pub mod measures;
pub mod moving_box;
pub mod objectives;
pub mod params;
pub mod planetary;
pub mod quadrature;
pub mod resolution;
pub mod scene;
pub mod search;

pub use curve::{CurveSpec, PitchCurve, Polar};
pub use error::{Error, Result};
pub use evaluation::{Evaluation, Evaluator, StageCounts};
pub use gear::{GearPair, ModuleReport, ModuleRule};
pub use objectives::{Agronomy, Bounds, ObjectiveKind, ObjectiveValue};
pub use params::Param;
pub use planetary::{Kinematics, TrainSpec};
pub use resolution::Resolution;
pub use scene::{FreeParam, GearSpec, Scene, SceneKind, SearchSpec};
