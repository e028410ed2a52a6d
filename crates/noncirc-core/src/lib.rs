//! noncirc-core: the pure numerical core of noncirc (no I/O, no threads).
//!
//! Units: millimetres and radians inside; degrees only where a person reads or writes.

pub mod curve;
pub mod error;
pub mod gear;
pub mod quadrature;
pub mod resolution;

pub use curve::{CurveSpec, PitchCurve, Polar};
pub use error::{Error, Result};
pub use gear::{GearPair, ModuleReport, ModuleRule};
pub use resolution::Resolution;
pub mod scene;
pub use scene::{GearSpec, Scene};
pub mod planetary;
pub use planetary::{Kinematics, TrainSpec};
pub mod objectives;
pub use objectives::{Agronomy, Bounds, ObjectiveKind, ObjectiveValue};
