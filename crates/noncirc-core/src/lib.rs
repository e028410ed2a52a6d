//! noncirc-core: the pure numerical core of noncirc (no I/O, no threads, no clock).
//!
//! Units: millimetres and radians inside; degrees only where a person reads or writes.
//! Every public item has one path, at the crate root: the modules are private, the list
//! below is the API. The problem-independent optimiser is the crate noncirc-search, whose
//! items are re-exported here.

// Every public item is reachable from the root, and every type in a public signature can
// be named there.
#![warn(unreachable_pub, unnameable_types)]

// The modules, in one-way layers: each module may use its own layer and those below
// (util ← model ← scene ← evaluate ← study), without cycles; scripts/check_layers.py
// checks it.

// Util: errors, plane vectors, angles, quadrature, resolution.
mod angle;
mod error;
mod golden;
mod lanes;
mod quadrature;
mod resolution;
mod segment_tree;
mod vec2;

// Model: pitch curves, gear pairs, the train's motion, teeth, the moving box, the gearbox.
mod blank;
mod curve;
mod gear;
mod gearbox;
mod moving_box;
mod planetary;
mod teeth;

// Scene: what is designed and asked, by name; its checks; the table of its fields; the error messages
// (which name fields by the table's symbols).
mod agronomy;
mod cad_spec;
mod check;
mod constraint;
mod dynamics_spec;
mod goal;
mod measure;
mod messages;
mod objective_kind;
mod params;
mod reference;
mod scene;
mod target;
mod tolerance;
mod whole_number;

// Evaluate: a scene's evaluation, its events, objectives, sections and measures.
mod accuracy;
mod anatomy;
mod dynamics;
mod evaluation;
mod evaluator;
mod events;
mod fit;
mod flywheel;
mod interference;
mod inverse;
mod measure_value;
mod objectives;
mod strength;

// Study: tolerances, sensitivity, and the search problem with its checkpoints.
mod checkpoint;
mod problem;
mod robustness;
mod sensitivity;
mod serial;

// The scene: what is designed and asked, and at which resolution.
pub use agronomy::{Agronomy, Travel};
pub use blank::Blank;
pub use cad_spec::CadSpec;
pub use constraint::{requirements, Constraint, ConstraintValue};
pub use curve::{
    paper_control_points, CartesianCurve, CartesianKind, CurveSpec, Ellipse, Fourier,
    PeriodicSpline, PitchCurve, Polar,
};
pub use dynamics_spec::DynamicsSpec;
pub use goal::{Goal, GoalQuantity, INVALID_CV};
pub use measure::{
    DynamicsQuantity, FitMeasure, Measure, MeasureCost, PoseQuantity, Scalar, Section,
    SectionQuantity,
};
pub use moving_box::BoxSpec;
pub use objective_kind::{scale, Bounds, ObjectiveKind};
pub use params::Param;
pub use planetary::{PusherSide, SunFrame, TrainSpec, ARM_NAMES};
pub use reference::{field, fields, symbol, Bound, Field, Range};
pub use resolution::Resolution;
pub use scene::{FreeParam, GearSpec, Scene, SceneKind, SearchSpec};
pub use target::{DesignPull, Pose, PoseAt, PreparedTarget, Target, TargetKind};

// The model: gear pairs, the train's motion, events, sections, measures.
pub use anatomy::{anatomy, Anatomy, SectionMeasures};
pub use angle::unit;
pub use dynamics::{dynamics, scene_dynamics, Dynamics, DynamicsSummary};
pub use events::{attitude_deg, events, Event, Events, PickingCheck};
pub use flywheel::{Cycle, SpeedFluctuation};
pub use gear::{
    solve_closure, Closure, GearPair, ModuleReading, ModuleReport, ModuleRule, Rotation, SampleGrid,
};
pub use measure_value::Measured;
pub use moving_box::{box_curves, eccentricity_for_ratio, evaluate_box, BoxCurves, BoxReport};
pub use objectives::{advance_per_rad, evaluate_all, travel_sign, ObjectiveValue};
pub use planetary::{ArmState, Kinematics, PitchContact};
pub use strength::{
    cut_train, strength, tooth_forms, train_strength, GearStrength, Strength, ToothForm,
};
pub use teeth::{
    segment_distance, Cutter, Frame, GearTeethReport, MateRoots, Member, MeshReport, PairTrack,
    Side, TeethAccuracy, TeethReport, Tooth, ToothSpec, ToothedGear, ToothedPair, Undercut,
};
pub use vec2::Vec2;

// Evaluation and its accuracy.
pub use accuracy::{observed_order, output_errors, ErrorRow};
pub use error::{Error, Result};
pub use evaluation::{Evaluation, GearSummary, PairGeometry};
pub use evaluator::{Evaluator, KeptGears, Screened, StageCounts};
pub use fit::{target_of, FitReport, PoseFit};
pub use inverse::{invert, Branch, Condition, InverseOutcome, InverseSpec, Place};

// Tolerances, robustness and global sensitivity.
pub use robustness::{
    analyse, least_normalised_margin, quantile, radius_count, robust_score, Deviated,
    ObjectiveSpread, RobustScore, SampleOutcome, ToleranceReport, ToleranceSamples, WorstCase,
    REPORTED_QUANTILES,
};
pub use sensitivity::{
    saltelli_points, sobol_indices, sobol_indices_sharing, Resamples, SobolIndices, Unreliable,
    FEWEST_ROWS, MAX_SHARED_POSITIONS, READABLE_HALF_WIDTH,
};
pub use tolerance::{Spread, Tolerances};

// Search: the scene's problem and its checkpoints; the optimiser (solvers, executor)
// from noncirc-search.
pub use checkpoint::{Checkpoint, Migrants, FORMAT as CHECKPOINT_FORMAT};
pub use noncirc_search::{
    execute, nearest, non_dominated_fronts, refine, stop_after_generations, Algorithm,
    BatchEvaluator, Candidate, Cmaes, Control, Ending, Fitness, HistoryRow, LocalReport,
    LocalSettings, Observer, ResidualBatch, Rng, SearchState, Solver, SolverState,
};
pub use problem::{SceneProblem, REFUSED_RESIDUAL, VIOLATION_WEIGHT};
pub use serial::SerialEvaluator;
