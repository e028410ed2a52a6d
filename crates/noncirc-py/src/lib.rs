//! The `noncirc._noncirc` extension: a thin layer over the `noncirc` library. Input and model
//! errors become `noncirc.NoncircError` (a `ValueError`), by kind its subclasses
//! `SceneError`, `ParameterError`, `ModelError` and `UnknownNameError`; files that cannot be
//! read or written `OSError` (with its errno subclass, e.g. `FileNotFoundError`); failures
//! inside noncirc `InternalError` (a `RuntimeError`). Heavy work runs with the GIL released,
//! and a search or batch stopped by Ctrl-C raises `KeyboardInterrupt`.
//!
//! One module per concern: [`errors`] (the exceptions and the bridge's error type),
//! [`convert`] (values, arrays, resolution, pools), [`scene`] (the `Scene` class),
//! [`evaluate`] (one design and batches), [`search`] (`optimise`, migrants) and [`studies`]
//! (robustness, sensitivity).

mod convert;
mod errors;
mod evaluate;
mod scene;
mod search;
mod signals;
mod studies;

use pyo3::prelude::*;

/// mimalloc serves an evaluation's short-lived vectors faster than glibc (docs/performance.md).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[pymodule]
fn _noncirc(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(evaluate::evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate::measures, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate::evaluate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(search::optimise, m)?)?;
    m.add_function(wrap_pyfunction!(search::fit, m)?)?;
    m.add_function(wrap_pyfunction!(search::inverse, m)?)?;
    m.add_function(wrap_pyfunction!(search::repair, m)?)?;
    m.add_function(wrap_pyfunction!(search::emigrants, m)?)?;
    m.add_function(wrap_pyfunction!(search::immigrate, m)?)?;
    m.add_function(wrap_pyfunction!(studies::robustness, m)?)?;
    m.add_function(wrap_pyfunction!(studies::dynamics, m)?)?;
    m.add_function(wrap_pyfunction!(studies::sensitivity, m)?)?;
    m.add_function(wrap_pyfunction!(studies::cad, m)?)?;
    errors::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
