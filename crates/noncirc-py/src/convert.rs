//! Conversions between Python and noncirc: values as JSON, point lists as arrays, the
//! resolution from keyword arguments, and the thread pools of batches.

use crate::errors::{internal, parameter, Result};
use noncirc::core::Resolution;
use numpy::ndarray::Array2;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// A Python value as JSON (`json.dumps`, no NaN): a wrong type is a `TypeError`, a
/// non-finite number a `NoncircError`, each naming the call.
pub(crate) fn py_to_json(value: &Bound<'_, PyAny>, call: &str) -> Result<serde_json::Value> {
    let json = value.py().import("json")?;
    let kwargs = PyDict::new(value.py());
    kwargs.set_item("allow_nan", false)?;
    let text: String = match json.call_method("dumps", (value,), Some(&kwargs)) {
        Ok(t) => t.extract()?,
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyTypeError>(value.py()) => {
            return Err(PyTypeError::new_err(format!(
                "{call}: a value of type {} is not a number, bool, string, list or dict",
                value.get_type().name()?
            ))
            .into())
        }
        Err(_) => {
            return Err(parameter(format!(
                "{call}: {} is not a finite number: every number in a scene must be finite",
                value.repr()?
            )))
        }
    };
    serde_json::from_str(&text).map_err(internal)
}

/// A serialisable summary as a Python dict (through its JSON, as the CLI prints it).
pub(crate) fn summary_dict<'py>(
    py: Python<'py>,
    summary: &impl serde::Serialize,
) -> Result<Bound<'py, PyDict>> {
    let text = serde_json::to_string(summary).map_err(internal)?;
    Ok(py
        .import("json")?
        .call_method1("loads", (text,))?
        .downcast_into::<PyDict>()?)
}

/// A JSON value as a Python value (`json.loads`).
pub(crate) fn json_to_py(py: Python<'_>, value: &serde_json::Value) -> Result<PyObject> {
    let text = serde_json::to_string(value).map_err(internal)?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// The resolution from keyword arguments over the scene's own.
pub(crate) fn resolution(
    scene: &noncirc::core::Scene,
    samples_per_turn: Option<usize>,
    closure_rel_tol: Option<f64>,
) -> Result<Resolution> {
    let mut r = scene.resolution;
    if let Some(n) = samples_per_turn {
        r.samples_per_turn = n;
    }
    if let Some(t) = closure_rel_tol {
        r.closure_rel_tol = t;
    }
    r.validate()?;
    Ok(r)
}

pub(crate) fn points(list: &[noncirc::core::Vec2]) -> Array2<f64> {
    Array2::from_shape_fn(
        (list.len(), 2),
        |(i, j)| if j == 0 { list[i].x } else { list[i].y },
    )
}

/// Rayon pools by thread count, built once; `None` for one thread (the caller's own).
pub(crate) fn pool(threads: Option<usize>) -> Result<Option<Arc<rayon::ThreadPool>>> {
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<rayon::ThreadPool>>>> = OnceLock::new();
    let n = noncirc::search::threads_or_all(threads)?;
    if n == 1 {
        return Ok(None);
    }
    let mut pools = POOLS
        .get_or_init(Default::default)
        .lock()
        .map_err(internal)?;
    if let Some(p) = pools.get(&n) {
        return Ok(Some(p.clone()));
    }
    let p = Arc::new(noncirc::search::thread_pool(n)?);
    pools.insert(n, p.clone());
    Ok(Some(p))
}
