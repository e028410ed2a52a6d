//! The integration tests: one module per file of tests/, linked as one binary (a test
//! binary links the whole library with thin LTO, so one link instead of twenty-two takes
//! minutes off the test command). The figures and the solids need their features: without
//! them those modules are left out, not broken.

mod common;

mod accuracy;
#[cfg(feature = "step")]
mod cad;
mod checkpoints;
mod dynamics;
#[cfg(feature = "figures")]
mod figures;
mod fit;
mod gear;
mod hostile_scenes;
mod inverse;
mod kinematics;
mod moving_box;
mod n_arms;
mod objectives;
mod parameter_response;
mod picking;
mod repair;
mod robustness;
mod scene_reference;
mod scenes;
mod search;
mod teeth_train;
mod two_pairs;
