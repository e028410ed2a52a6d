//! noncirc: the facade over `noncirc-core` — scene files, reports, parallel evaluation.
//!
//! The core stays free of I/O and threads; files, terminals and threads live here.

pub mod accuracy;
pub mod export;
pub mod figures;
pub mod plots;
pub mod report;
pub mod scene_file;
pub mod search;

pub use noncirc_core as core;

/// The library's error at its edges (files, figures, searches): any error, with its message.
pub type BoxError = Box<dyn std::error::Error + Send + Sync>;
