//! noncirc-core: the pure numerical core of noncirc (no I/O, no threads, no clock).
//!
//! Units: millimetres and radians inside; degrees only where a person reads or writes.
//! Every public item has one path, at the crate root: the modules are private, the list
//! below is the API.

mod accuracy;
mod anatomy;
mod angle;
mod curve;
mod error;
mod evaluation;
mod events;
mod gear;
mod gearbox;
mod measures;
mod moving_box;
mod objectives;
mod params;
mod planetary;
mod quadrature;
mod reference;
mod resolution;
mod robustness;
mod scene;
mod search;
mod sensitivity;
mod teeth;
mod tolerance;
mod vec2;

// The scene: what is designed and asked, and at which resolution.
pub use curve::{
    paper_control_points, CartesianCurve, CartesianKind, CurveSpec, Ellipse, Fourier,
    PeriodicSpline, PitchCurve, Polar,
};
pub use moving_box::BoxSpec;
pub use objectives::{Agronomy, Bounds, ObjectiveKind};
pub use params::Param;
pub use planetary::{PusherSide, Rotation, SunFrame, TrainSpec, ARM_NAMES};
pub use reference::{field, symbol, Field, FIELDS};
pub use resolution::Resolution;
pub use scene::{FreeParam, GearSpec, Scene, SceneKind, SearchSpec};

// The model: gear pairs, the train's motion, events, sections, measures.
pub use anatomy::{anatomy, Anatomy, Section, SectionMeasures};
pub use angle::unit;
pub use events::{attitude_deg, events, housing_radius, Event, Events, PickingCheck};
pub use gear::{
    solve_closure, Closure, GearPair, ModuleReading, ModuleReport, ModuleRule, SampleGrid,
};
pub use gearbox::gear_sets_overlap;
pub use measures::{nearest, Measure, MeasureCost};
pub use moving_box::{box_curves, eccentricity_for_ratio, evaluate_box, BoxCurves, BoxReport};
pub use objectives::{advance_per_rad, evaluate_all, travel_sign, ObjectiveValue, Travel};
pub use planetary::{ArmState, Kinematics};
pub use teeth::{
    segment_distance, signed_area, Cutter, Frame, GearTeethReport, Member, MeshReport, PairTrack,
    Side, TeethReport, Tooth, ToothSpec, ToothedGear, ToothedPair, Undercut, OVERLAP_TOLERANCE_MM,
};
pub use vec2::Vec2;

// Evaluation and its accuracy.
pub use accuracy::{compare, observed_order, ErrorRow};
pub use error::{Error, Result};
pub use evaluation::{Evaluation, Evaluator, GearSummary, StageCounts};

// Tolerances, robustness and global sensitivity.
pub use robustness::{
    analyse, least_normalised_margin, quantile, radius_count, robust_score, sobol, Deviated,
    ObjectiveSpread, RobustScore, SampleOutcome, ToleranceReport, ToleranceSamples, WorstCase,
    BRANCH_SWITCH_RAD, REPORTED_QUANTILES,
};
pub use sensitivity::{saltelli_points, sobol_indices, SobolIndices};
pub use tolerance::{Spread, Tolerances, ASSEMBLY};

// Search: the problem, the solvers, the executor and its checkpoints.
pub use search::{
    das_dennis, execute, non_dominated_fronts, scale, stop_after_generations, Algorithm,
    BatchEvaluator, Candidate, Checkpoint, Cmaes, Control, DifferentialEvolution, Ending, Fitness,
    Goal, GoalQuantity, HistoryRow, Migrants, Nsga, Observer, ParameterGuided, Rng, SceneProblem,
    SearchState, SerialEvaluator, Solver, SolverState, Survival, CHECKPOINT_FORMAT, INVALID_CV,
};
