//! noncirc: the facade over `noncirc-core` — scene files, reports, parallel evaluation.
//!
//! The core stays free of I/O and threads; files, terminals and threads live here.

pub mod accuracy;
pub mod export;
pub mod figures;
pub mod files;
pub mod plots;
pub mod report;
pub mod scene_file;
pub mod search;

pub use noncirc_core as core;

/// The library's error at its edges (files, figures, searches): any error, with its message.
pub type BoxError = Box<dyn std::error::Error + Send + Sync>;

/// A request the caller can fix (a flag, a path that would overwrite their work), as
/// opposed to a failure while carrying it out: the CLI exits with 2 for it.
#[derive(Debug)]
pub struct InputError(pub String);

impl std::fmt::Display for InputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}
