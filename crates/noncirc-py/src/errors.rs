//! noncirc's errors as Python exceptions: input and model errors as `NoncircError` (a
//! `ValueError`) by kind, files as `OSError` with its errno, and failures inside noncirc as
//! `InternalError` (a `RuntimeError`), so that a bug never passes for bad input. Every
//! function of the bridge returns [`Result`], whose [`Error`] converts from each of
//! noncirc's error types, so bodies use `?`.

use noncirc::scene_file::SceneError as SceneFileError;
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    _noncirc,
    NoncircError,
    PyValueError,
    "A noncirc input or model error (a ValueError). Its subclasses say which kind: \
     SceneError, ParameterError, ModelError, UnknownNameError."
);

create_exception!(
    _noncirc,
    SceneError,
    NoncircError,
    "A scene's text, or an edit of it, that cannot be read: its syntax, a value of the \
     wrong kind, an unknown built-in; the message names the file and line or the call."
);

create_exception!(
    _noncirc,
    ParameterError,
    NoncircError,
    "A value the model refuses for a setting or a parameter: out of its range, not \
     finite, a list entry that cannot stand there; the message names the value."
);

create_exception!(
    _noncirc,
    ModelError,
    NoncircError,
    "A design the model cannot build: a pitch curve that is not positive or not \
     star-shaped, a closure the resolution does not resolve, teeth that cannot be cut."
);

create_exception!(
    _noncirc,
    UnknownNameError,
    NoncircError,
    "A name noncirc does not know (a scene key, a parameter, a measure, a goal); the \
     message lists the nearest names it does know."
);

create_exception!(
    _noncirc,
    InternalError,
    PyRuntimeError,
    "A failure inside noncirc, not in what it was given (a value it cannot serialise, a \
     lock poisoned by an earlier panic): a bug, to be reported with the call that raised it."
);

/// An error on its way to Python, as the exception it becomes.
pub(crate) struct Error(PyErr);

/// The result of every function of the bridge.
pub(crate) type Result<T> = std::result::Result<T, Error>;

impl From<Error> for PyErr {
    fn from(e: Error) -> PyErr {
        e.0
    }
}

impl From<PyErr> for Error {
    fn from(e: PyErr) -> Self {
        Error(e)
    }
}

impl From<pyo3::DowncastIntoError<'_>> for Error {
    fn from(e: pyo3::DowncastIntoError<'_>) -> Self {
        Error(e.into())
    }
}

impl From<noncirc::core::Error> for Error {
    fn from(e: noncirc::core::Error) -> Self {
        let message = e.to_string();
        core_kind(&e, message)
    }
}

impl From<noncirc::Error> for Error {
    /// The core's and the scene's errors as above, requests the caller can fix as
    /// `ParameterError`, files as `OSError`, a file's refused content by the core's kind,
    /// the rest as `NoncircError`.
    fn from(e: noncirc::Error) -> Self {
        match e {
            noncirc::Error::Core(e) => e.into(),
            noncirc::Error::Scene(e) => e.into(),
            noncirc::Error::Input(message) => Error(ParameterError::new_err(message)),
            noncirc::Error::File {
                action,
                path,
                source,
            } => {
                // OSError(errno, message, filename) becomes FileNotFoundError and its kin.
                let message = format!("cannot {action}: {source}");
                Error(match source.raw_os_error() {
                    Some(errno) => PyOSError::new_err((errno, message, path)),
                    None => PyOSError::new_err(format!("{message}: {}", path.display())),
                })
            }
            // A file whose content the core refuses (a target, a checkpoint): the core's
            // kind, the file named in front.
            noncirc::Error::Content { path, source } => {
                core_kind(&source, format!("{}: {source}", path.display()))
            }
            other => invalid(other),
        }
    }
}

impl From<SceneFileError> for Error {
    fn from(e: SceneFileError) -> Self {
        let message = e.to_string();
        scene_kind(&e, message)
    }
}

/// A request noncirc cannot carry out as asked (`NoncircError`): the message says why.
pub(crate) fn invalid(message: impl std::fmt::Display) -> Error {
    Error(NoncircError::new_err(message.to_string()))
}

/// A value the caller gave that the model refuses (`ParameterError`).
pub(crate) fn parameter(message: impl std::fmt::Display) -> Error {
    Error(ParameterError::new_err(message.to_string()))
}

/// A failure inside noncirc (`InternalError`).
pub(crate) fn internal(e: impl std::fmt::Display) -> Error {
    Error(InternalError::new_err(format!(
        "{e} (a failure inside noncirc, not in its input: please report it)"
    )))
}

/// A `RuntimeWarning` at the user's call: `stack_level` 1 for a function of the native
/// module called directly, 2 past one of the package's wrappers (`noncirc.optimise`).
pub(crate) fn warn(py: Python<'_>, message: String, stack_level: i32) -> PyResult<()> {
    let message = std::ffi::CString::new(message).map_err(internal)?;
    PyErr::warn(
        py,
        &py.get_type::<pyo3::exceptions::PyRuntimeWarning>(),
        &message,
        stack_level,
    )
}

/// A scene error raised by a call (`Scene.with_set('key', value)`): its message without the
/// CLI's `--set key=value:`, after the call's own name.
pub(crate) fn call_error(e: SceneFileError, call: &str) -> Error {
    let message = format!("{call}: {}", e.detail());
    scene_kind(&e, message)
}

/// A core error as the exception of its kind, with `message` (the error's own, or with
/// the place it came from in front).
fn core_kind(e: &noncirc::core::Error, message: String) -> Error {
    use noncirc::core::Error as E;
    // No catch-all: a new variant must be given its kind here.
    Error(match e {
        E::SecondPair(inner) => return core_kind(inner, message),
        E::UnknownName { .. } => UnknownNameError::new_err(message),
        E::NonFinite { .. }
        | E::OutOfRange { .. }
        | E::ControlAngles { .. }
        | E::TooFewPoints { .. }
        | E::TooManyPoints { .. }
        | E::Missing { .. }
        | E::BadList { .. }
        | E::OpenTarget { .. }
        | E::OutOfReach { .. }
        | E::TargetCrossing { .. } => ParameterError::new_err(message),
        E::NonPositiveRadius { .. }
        | E::NotStarShaped { .. }
        | E::UnderResolved { .. }
        | E::SpikeBetweenSamples { .. }
        | E::Teeth { .. }
        | E::OutlineCrossing { .. }
        | E::Infeasible(_) => ModelError::new_err(message),
        E::Checkpoint(_) => NoncircError::new_err(message),
    })
}

/// A scene error as the exception of its kind, with `message`: unknown keys as
/// `UnknownNameError`, a value the core refuses by the core's kind, unreadable text as
/// `SceneError`, a file that cannot be read as `OSError`.
fn scene_kind(e: &SceneFileError, message: String) -> Error {
    use SceneFileError as S;
    match e {
        S::UnknownKey { .. } => Error(UnknownNameError::new_err(message)),
        S::Invalid { source, .. } => core_kind(source, message),
        S::Io { path, source } => Error(match source.raw_os_error() {
            Some(errno) => PyOSError::new_err((errno, message, path.clone())),
            None => PyOSError::new_err(message),
        }),
        S::Parse { .. } | S::UnknownBuiltin(_) | S::Override { .. } => {
            Error(SceneError::new_err(message))
        }
    }
}

/// Adds the exceptions to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("NoncircError", py.get_type::<NoncircError>())?;
    m.add("UnknownNameError", py.get_type::<UnknownNameError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("ParameterError", py.get_type::<ParameterError>())?;
    m.add("ModelError", py.get_type::<ModelError>())?;
    m.add("InternalError", py.get_type::<InternalError>())?;
    Ok(())
}
