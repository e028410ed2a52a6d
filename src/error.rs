//! The library's error: the core's refusals, unreadable scenes, requests the caller can fix,
//! and the files, figures and outputs that failed, each naming what it was about.

use crate::scene_file::SceneError;
use std::path::PathBuf;

/// Everything the library can fail with.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The model refused a value (it names the value).
    #[error(transparent)]
    Core(#[from] noncirc_core::Error),
    /// A scene file or `--set` assignment that cannot be read.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A request the caller can fix: a setting out of range, a path that would overwrite
    /// their work, a file too large or not a file.
    #[error("{0}")]
    Input(String),
    /// A file or directory that could not be read, written or created.
    #[error("cannot {action} {}: {source}", path.display())]
    File {
        action: &'static str,
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A file that reads but holds something the core refuses (a damaged checkpoint).
    #[error("{}: {source}", path.display())]
    Content {
        path: PathBuf,
        #[source]
        source: noncirc_core::Error,
    },
    /// A figure that could not be drawn or encoded.
    #[error("figure: {0}")]
    Figure(String),
    /// A report or scene that could not be serialised.
    #[error("cannot serialise {what}: {message}")]
    Serialise { what: &'static str, message: String },
    /// The worker threads could not be started.
    #[error("cannot start {threads} worker threads: {message}")]
    Threads { threads: usize, message: String },
}

impl Error {
    /// Whether the caller can fix it by changing what they asked (the CLI exits with 2):
    /// a value, a scene, a request, a file they named that cannot be read or holds the
    /// wrong thing; rather than a failure while carrying it out, such as a write (exit 1).
    pub fn is_input(&self) -> bool {
        matches!(
            self,
            Error::Core(_)
                | Error::Scene(_)
                | Error::Input(_)
                | Error::Content { .. }
                | Error::File { action: "read", .. }
        )
    }

    /// A file error naming the path.
    pub fn file(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::File {
            action,
            path: path.into(),
            source,
        }
    }
}

/// The library's result.
pub type Result<T> = std::result::Result<T, Error>;
