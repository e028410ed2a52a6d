//! Studies of a design: its robustness to the workshop's tolerances and the Sobol
//! sensitivity of its outputs over the search box.

use crate::convert::json_to_py;
use crate::errors::{internal, Result};
use crate::scene::Scene;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A tolerance analysis of the scene's design (`noncirc robustness`): the report as a
/// dict (the CLI's JSON), with `margins`, an (objectives, samples) array of every sample's
/// margin in the objective's unit (NaN where the model refused the sample).
#[pyfunction]
#[pyo3(signature = (scene, *, samples = None, seed = None, worst_case = true))]
pub(crate) fn robustness<'py>(
    py: Python<'py>,
    scene: &Scene,
    samples: Option<usize>,
    seed: Option<u64>,
    worst_case: bool,
) -> Result<Bound<'py, PyDict>> {
    let mut s = scene.inner.clone();
    if let Some(n) = samples {
        s.tolerances.samples = n;
    }
    if let Some(seed) = seed {
        s.tolerances.seed = seed;
    }
    s.tolerances.validate()?;
    let r = py.allow_threads(|| noncirc::robustness::robustness(&s, worst_case))?;
    let value = serde_json::to_value(&r).map_err(internal)?;
    let out = json_to_py(py, &value)?
        .into_bound(py)
        .downcast_into::<PyDict>()?;
    let n = r.margins.first().map_or(0, Vec::len);
    let margins =
        numpy::ndarray::Array2::from_shape_fn((r.margins.len(), n), |(k, i)| r.margins[k][i]);
    out.set_item("margins", margins.into_pyarray(py))?;
    Ok(out)
}

/// The train at its working speed (`noncirc dynamics`): the CLI's JSON as a dict.
#[pyfunction]
pub(crate) fn dynamics<'py>(py: Python<'py>, scene: &Scene) -> Result<Bound<'py, PyDict>> {
    let s = scene.inner.clone();
    let d = py.allow_threads(|| noncirc::dynamics::report_of(&s))?;
    let value = serde_json::to_value(&d).map_err(internal)?;
    Ok(json_to_py(py, &value)?
        .into_bound(py)
        .downcast_into::<PyDict>()?)
}

/// Sobol indices of every output over the scene's search box (`noncirc sensitivity`), in
/// SALib's layout: `problem` (num_vars, names, bounds), `X` (N (k + 2), k) and `Y`
/// (N (k + 2), outputs) in SALib's sample order, `outputs`, and per output `indices[name]`
/// a dict of `S1`, `S1_conf`, `ST`, `ST_conf` arrays; `S1` etc. also as (outputs, k)
/// arrays. The report's other fields as the CLI's JSON gives them, among them
/// `base_samples_needed`; and `unreliable[name]`, a list of dicts (`kind`, and the numbers
/// it names; empty when the output's indices can be read). Where some indices cannot be
/// read at `base_samples`, one `RuntimeWarning` says which and how many base points would do.
#[pyfunction]
#[pyo3(signature = (scene, *, base_samples = 1024, bootstrap = 100, box_scale = 0.25, threads = None))]
pub(crate) fn sensitivity<'py>(
    py: Python<'py>,
    scene: &Scene,
    base_samples: usize,
    bootstrap: usize,
    box_scale: f64,
    threads: Option<usize>,
) -> Result<Bound<'py, PyDict>> {
    let threads = noncirc::search::threads_or_all(threads)?;
    let s = scene.inner.clone();
    let r = py.allow_threads(|| {
        noncirc::robustness::sensitivity(&s, base_samples, bootstrap, box_scale, threads)
    })?;
    if r.base_samples_needed.is_some() {
        crate::errors::warn(
            py,
            noncirc::robustness::unreliable_text(&r).trim().to_string(),
            1,
        )?;
    }
    let value = serde_json::to_value(&r).map_err(internal)?;
    let out = json_to_py(py, &value)?
        .into_bound(py)
        .downcast_into::<PyDict>()?;
    let k = r.parameters.len();
    let matrix = |rows: &Vec<Vec<f64>>, cols: usize| {
        numpy::ndarray::Array2::from_shape_fn((rows.len(), cols), |(i, j)| rows[i][j])
    };
    out.set_item("X", matrix(&r.x, k).into_pyarray(py))?;
    out.set_item("Y", matrix(&r.y, r.output_names.len()).into_pyarray(py))?;
    out.set_item("y_names", r.output_names.clone())?;
    let problem = PyDict::new(py);
    problem.set_item("num_vars", k)?;
    problem.set_item(
        "names",
        r.parameters
            .iter()
            .map(|p| p.name.clone())
            .collect::<Vec<_>>(),
    )?;
    problem.set_item(
        "bounds",
        r.parameters
            .iter()
            .map(|p| vec![p.lower, p.upper])
            .collect::<Vec<_>>(),
    )?;
    out.set_item("problem", problem)?;
    out.set_item(
        "outputs",
        r.outputs.iter().map(|o| o.name.clone()).collect::<Vec<_>>(),
    )?;
    let unreliable = PyDict::new(py);
    for o in &r.outputs {
        let value = serde_json::to_value(&o.unreliable).map_err(internal)?;
        unreliable.set_item(&o.name, json_to_py(py, &value)?)?;
    }
    out.set_item("unreliable", unreliable)?;
    let indices = PyDict::new(py);
    let table = |f: fn(&noncirc::core::SobolIndices) -> &Vec<f64>| {
        numpy::ndarray::Array2::from_shape_fn((r.outputs.len(), k), |(o, i)| {
            f(&r.outputs[o].indices)[i]
        })
    };
    for o in &r.outputs {
        let d = PyDict::new(py);
        d.set_item("S1", o.indices.first.clone().into_pyarray(py))?;
        d.set_item("S1_conf", o.indices.first_conf.clone().into_pyarray(py))?;
        d.set_item("ST", o.indices.total.clone().into_pyarray(py))?;
        d.set_item("ST_conf", o.indices.total_conf.clone().into_pyarray(py))?;
        indices.set_item(&o.name, d)?;
    }
    out.set_item("indices", indices)?;
    out.set_item("S1", table(|s| &s.first).into_pyarray(py))?;
    out.set_item("S1_conf", table(|s| &s.first_conf).into_pyarray(py))?;
    out.set_item("ST", table(|s| &s.total).into_pyarray(py))?;
    out.set_item("ST_conf", table(|s| &s.total_conf).into_pyarray(py))?;
    Ok(out)
}

/// The solids of the scene's gears and train written into `out` (`noncirc cad`,
/// docs/cad.md): `formats` of "step" and "stl"; `assembly.json` always. A dict: `paths`,
/// `failures` (the teeth's failed checks: nothing is written unless `force`), and the
/// manifest's `parts` and `instances`.
#[pyfunction]
#[pyo3(signature = (scene, out, *, carrier_deg = 0.0, formats = vec!["step".to_string(), "stl".to_string()], tolerance_mm = 1e-3, force = false))]
pub(crate) fn cad<'py>(
    py: Python<'py>,
    scene: &Scene,
    out: std::path::PathBuf,
    carrier_deg: f64,
    formats: Vec<String>,
    tolerance_mm: f64,
    force: bool,
) -> Result<Bound<'py, PyDict>> {
    use noncirc::solids::Format;
    let formats: Vec<Format> = (formats.iter())
        .map(|f| match f.as_str() {
            "step" => Ok(Format::Step),
            "stl" => Ok(Format::Stl),
            other => Err(noncirc::Error::Input(format!(
                "formats: unknown format {other:?}: expected \"step\" or \"stl\""
            ))),
        })
        .collect::<std::result::Result<_, _>>()?;
    let s = scene.inner.clone();
    let done = py.allow_threads(|| {
        noncirc::solids::export(&s, carrier_deg, &formats, tolerance_mm, &out, force)
    })?;
    let manifest = match &done.assembly {
        Some(a) => serde_json::to_value(a.manifest(tolerance_mm)).map_err(internal)?,
        None => serde_json::Value::Null,
    };
    let value = serde_json::json!({
        "paths": done.paths,
        "failures": done.failures,
        "manifest": manifest,
    });
    Ok(json_to_py(py, &value)?
        .into_bound(py)
        .downcast_into::<PyDict>()?)
}
