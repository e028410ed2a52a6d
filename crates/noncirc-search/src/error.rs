//! Typed errors of the optimiser. Their messages are the core's for the same variants: the
//! core converts them into its own error unchanged.

/// Everything that can go wrong in a search: an unknown name, or a state that cannot be
/// resumed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A name (of an algorithm) that does not exist.
    #[error("unknown {what} '{name}': the nearest are {}", nearest.join(", "))]
    UnknownName {
        what: &'static str,
        name: String,
        nearest: Vec<String>,
    },
    /// A search state (checkpoint) that cannot be resumed: what is wrong with it.
    #[error("checkpoint: {0}")]
    Checkpoint(String),
}

/// Shorthand for the optimiser's results.
pub type Result<T> = std::result::Result<T, Error>;
