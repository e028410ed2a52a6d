//! noncirc: the library over `noncirc-core` — scene files, reports, parallel evaluation
//! and search, CAD export, and (feature `figures`) figures.
//!
//! The core stays free of I/O and threads; files and threads live here; the terminal
//! (arguments, progress bar, signals) lives in `noncirc-cli`.

pub mod accuracy;
pub mod batch;
pub mod cad;
pub mod compare;
pub mod dynamics;
pub mod export;
#[cfg(feature = "figures")]
pub mod figures;
pub mod files;
pub mod fit;
pub mod inverse;
#[cfg(feature = "figures")]
pub mod plots;
pub mod repair;
pub mod report;
pub mod robustness;
pub mod scene_file;
pub mod scene_reference;
pub mod search;
#[cfg(feature = "solids")]
pub mod solids;
pub mod sweep;
pub mod teeth;

pub use noncirc_core as core;

pub use error::{Error, Result};

mod error;
