//! The `noncirc._noncirc` extension: a thin layer over the `noncirc` library. Input and model
//! errors become `noncirc.NoncircError` (a `ValueError`), by kind its subclasses
//! `SceneError`, `ParameterError`, `ModelError` and `UnknownNameError`; files that cannot be read or written `OSError` (with its errno
//! subclass, e.g. `FileNotFoundError`); heavy work runs with the GIL released, and a
//! search stopped by Ctrl-C raises `KeyboardInterrupt`.

use noncirc::batch::BatchRows;
use noncirc::core::Algorithm;
use noncirc::core::Measure;
use noncirc::core::SceneProblem;
use noncirc::core::{Control, Evaluator, Observer, Resolution, SearchState};
use noncirc::scene_file::{
    apply_overrides, apply_values, check_scene, load_scene, parse_scene, value_at, BUILTIN,
};
use noncirc::search::{RunOptions, SearchSettings};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

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

fn err(e: impl std::fmt::Display) -> PyErr {
    NoncircError::new_err(e.to_string())
}

/// A core error as the exception of its kind, with `message` (the error's own, or with
/// the place it came from in front).
fn core_kind(e: &noncirc::core::Error, message: String) -> PyErr {
    use noncirc::core::Error as E;
    // No catch-all: a new variant must be given its kind here.
    match e {
        E::UnknownName { .. } => UnknownNameError::new_err(message),
        E::NonFinite { .. }
        | E::OutOfRange { .. }
        | E::ControlAngles { .. }
        | E::TooFewPoints { .. }
        | E::Missing { .. }
        | E::BadList { .. } => ParameterError::new_err(message),
        E::NonPositiveRadius { .. }
        | E::NotStarShaped { .. }
        | E::UnderResolved { .. }
        | E::SpikeBetweenSamples { .. }
        | E::Teeth { .. }
        | E::OutlineCrossing { .. }
        | E::Infeasible(_) => ModelError::new_err(message),
        E::Checkpoint(_) => NoncircError::new_err(message),
    }
}

/// A core error as the exception of its kind.
fn core_err(e: noncirc::core::Error) -> PyErr {
    let message = e.to_string();
    core_kind(&e, message)
}

/// A library error: the core's and the scene's as above, requests the caller can fix as
/// `ParameterError`, files as `OSError`.
fn lib_err(e: noncirc::Error) -> PyErr {
    match e {
        noncirc::Error::Core(e) => core_err(e),
        noncirc::Error::Scene(e) => scene_err(e),
        noncirc::Error::Input(message) => ParameterError::new_err(message),
        noncirc::Error::File {
            action,
            path,
            source,
        } => {
            // OSError(errno, message, filename) becomes FileNotFoundError and its kin.
            let message = format!("cannot {action}: {source}");
            match source.raw_os_error() {
                Some(errno) => pyo3::exceptions::PyOSError::new_err((errno, message, path)),
                None => {
                    pyo3::exceptions::PyOSError::new_err(format!("{message}: {}", path.display()))
                }
            }
        }
        other => err(other),
    }
}

/// A scene error as the exception of its kind, with `message`: unknown keys as
/// `UnknownNameError`, a value the core refuses by the core's kind, unreadable text as
/// `SceneError`, a file that cannot be read as `OSError`.
fn scene_kind(e: &noncirc::scene_file::SceneError, message: String) -> PyErr {
    use noncirc::scene_file::SceneError as S;
    match e {
        S::UnknownKey { .. } => UnknownNameError::new_err(message),
        S::Invalid { source, .. } => core_kind(source, message),
        S::Io { path, source } => match source.raw_os_error() {
            Some(errno) => pyo3::exceptions::PyOSError::new_err((errno, message, path.clone())),
            None => pyo3::exceptions::PyOSError::new_err(message),
        },
        S::Parse { .. } | S::UnknownBuiltin(_) | S::Override { .. } => SceneError::new_err(message),
    }
}

/// A scene-file or `--set` error as the exception of its kind.
fn scene_err(e: noncirc::scene_file::SceneError) -> PyErr {
    let message = e.to_string();
    scene_kind(&e, message)
}

/// A scene error raised by a call (`Scene.with_set('key', value)`): its message without the
/// CLI's `--set key=value:`, after the call's own name.
fn call_err(e: noncirc::scene_file::SceneError, call: &str) -> PyErr {
    let message = format!("{call}: {}", e.detail());
    scene_kind(&e, message)
}

/// A Python value as JSON (`json.dumps`, no NaN): a wrong type is a `TypeError`, a
/// non-finite number a `NoncircError`, each naming the call.
fn py_to_json(value: &Bound<'_, PyAny>, call: &str) -> PyResult<serde_json::Value> {
    let json = value.py().import("json")?;
    let kwargs = PyDict::new(value.py());
    kwargs.set_item("allow_nan", false)?;
    let text: String = match json.call_method("dumps", (value,), Some(&kwargs)) {
        Ok(t) => t.extract()?,
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyTypeError>(value.py()) => {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "{call}: a value of type {} is not a number, bool, string, list or dict",
                value.get_type().name()?
            )))
        }
        Err(_) => {
            return Err(ParameterError::new_err(format!(
                "{call}: {} is not a finite number: every number in a scene must be finite",
                value.repr()?
            )))
        }
    };
    serde_json::from_str(&text).map_err(err)
}

/// A JSON value as a Python value (`json.loads`).
fn json_to_py(py: Python<'_>, value: &serde_json::Value) -> PyResult<PyObject> {
    let text = serde_json::to_string(value).map_err(err)?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// A scene: what is designed and asked. Immutable: `with_set` returns a new scene.
#[pyclass(module = "noncirc._noncirc", frozen)]
#[derive(Clone)]
struct Scene {
    inner: noncirc::core::Scene,
}

#[pymethods]
impl Scene {
    /// Loads a scene file (TOML or JSON).
    #[staticmethod]
    fn from_file(path: &str) -> PyResult<Self> {
        if !std::path::Path::new(path).exists() {
            return Err(pyo3::exceptions::PyFileNotFoundError::new_err((
                2,
                "no such scene file",
                path.to_string(),
            )));
        }
        Ok(Self {
            inner: load_scene(Some(path)).map_err(scene_err)?,
        })
    }

    /// Parses scene text (TOML, or JSON if it starts with `{`).
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_string(text: &str, origin: &str) -> PyResult<Self> {
        Ok(Self {
            inner: parse_scene(text, origin).map_err(scene_err)?,
        })
    }

    /// A built-in scene by name (see `Scene.builtins()`).
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Self> {
        if !BUILTIN.iter().any(|(n, _)| *n == name) {
            return Err(UnknownNameError::new_err(format!(
                "unknown built-in scene '{name}': the built-ins are {}",
                (BUILTIN.iter().map(|(n, _)| *n))
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
        Ok(Self {
            inner: load_scene(Some(name)).map_err(scene_err)?,
        })
    }

    /// Names of the built-in scenes.
    #[staticmethod]
    fn builtins() -> Vec<String> {
        BUILTIN.iter().map(|(n, _)| n.to_string()).collect()
    }

    /// A copy with `key` set to `value`: a number, bool, list or dict as the scene file
    /// holds it (`with_set("train.gamma0_deg", -50.0)`, `with_set("search.goals",
    /// ["module", "picking_tip_speed"])`), or a str, read as TOML text if it is TOML
    /// ("720", '"ccw"', '["module"]') and else as the string itself. The scene is checked
    /// whole; an error names the call, the key and the bad value.
    fn with_set(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Self> {
        let call = format!("Scene.with_set({key:?}, {})", value.repr()?);
        let inner = match value.downcast::<PyString>() {
            Ok(text) => apply_overrides(self.inner.clone(), &[format!("{key}={}", text.to_cow()?)]),
            Err(_) => apply_values(
                self.inner.clone(),
                &[(key.to_string(), py_to_json(value, &call)?)],
            ),
        }
        .map_err(|e| call_err(e, &call))?;
        Ok(Self { inner })
    }

    /// The value at `key` (`"train.phi0_deg"`, `"gear.curve.radii_mm[3]"`, `"bounds"`): a
    /// float, int, str, list or dict, as the scene file holds it.
    fn get(&self, py: Python<'_>, key: &str) -> PyResult<PyObject> {
        let value =
            value_at(&self.inner, key).map_err(|e| call_err(e, &format!("Scene.get({key:?})")))?;
        json_to_py(py, &value)
    }

    /// A copy with the numeric parameters `names` set to the values of `row` (a row of an
    /// `evaluate_batch` input, in `free_parameters()` order): no text is parsed, so it is
    /// fast. The scene is checked whole.
    fn with_values(&self, names: Vec<String>, row: &Bound<'_, PyAny>) -> PyResult<Self> {
        let row: Vec<f64> = row
            .extract()
            .or_else(|_| row.call_method0("tolist").and_then(|l| l.extract()))
            .map_err(|_| {
                pyo3::exceptions::PyTypeError::new_err(format!(
                    "Scene.with_values: row must be a sequence of numbers, got {}",
                    row.get_type()
                        .name()
                        .map(|n| n.to_string())
                        .unwrap_or_default()
                ))
            })?;
        if names.len() != row.len() {
            return Err(err(format!(
                "Scene.with_values: {} names but {} values",
                names.len(),
                row.len()
            )));
        }
        let mut inner = self.inner.clone();
        for (name, &v) in names.iter().zip(&row) {
            let param = noncirc::core::Param::parse(name, &inner).map_err(core_err)?;
            if !v.is_finite() {
                return Err(ParameterError::new_err(format!(
                    "Scene.with_values: {name} = {v} is not a finite number"
                )));
            }
            param.set(&mut inner, v);
        }
        let inner = check_scene(inner, "Scene.with_values").map_err(scene_err)?;
        Ok(Self { inner })
    }

    /// The free parameters' current values, `{name: value}` in `free_parameters()` order.
    fn free_values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let problem = SceneProblem::new(&self.inner).map_err(core_err)?;
        let out = PyDict::new(py);
        for name in problem.names() {
            let param = noncirc::core::Param::parse(name, &self.inner).map_err(core_err)?;
            out.set_item(name, param.get(&self.inner))?;
        }
        Ok(out)
    }

    /// Scenes are equal when everything in them is (name and description included).
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.downcast::<Scene>().is_ok_and(|o| {
            serde_json::to_value(&self.inner).ok() == serde_json::to_value(&o.get().inner).ok()
        })
    }

    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        serde_json::to_string(&self.inner)
            .unwrap_or_default()
            .hash(&mut h);
        h.finish()
    }

    /// The scene as TOML text.
    fn to_toml(&self) -> PyResult<String> {
        toml::to_string(&self.inner).map_err(err)
    }

    /// The scene as JSON text (what pickling uses).
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner).map_err(err)
    }

    /// Rebuilds a scene from `to_json()`.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        Self::from_string(text, "<json>")
    }

    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }

    /// The search space: `[(name, lower, upper), ...]` (the default space if none is given).
    fn free_parameters(&self) -> PyResult<Vec<(String, f64, f64)>> {
        let p = SceneProblem::new(&self.inner).map_err(core_err)?;
        let lower = p.decode(&vec![0.0; p.dim()]);
        let upper = p.decode(&vec![1.0; p.dim()]);
        Ok(p.names()
            .into_iter()
            .zip(lower.into_iter().zip(upper))
            .map(|(n, (l, u))| (n.to_string(), l, u))
            .collect())
    }

    /// The search goals as the quantities they are, named with their units
    /// (`module_mm`, `picking_tip_speed_m_s`).
    fn goal_names(&self) -> PyResult<Vec<String>> {
        let problem = SceneProblem::new(&self.inner).map_err(core_err)?;
        Ok((problem.goal_quantities().into_iter())
            .map(|q| q.name)
            .collect())
    }

    /// Names of the objectives this scene evaluates, in order.
    fn objective_names(&self) -> Vec<String> {
        self.inner
            .objectives
            .iter()
            .map(|o| o.name().to_string())
            .collect()
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<(PyObject, (String,))> {
        let rebuild = py.get_type::<Scene>().getattr("from_json")?.unbind();
        Ok((rebuild, (self.to_json()?,)))
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene(name={:?}, kind={:?})",
            self.inner.name, self.inner.kind
        )
    }
}

/// The resolution from keyword arguments over the scene's own.
fn resolution(
    scene: &noncirc::core::Scene,
    samples_per_turn: Option<usize>,
    closure_rel_tol: Option<f64>,
) -> PyResult<Resolution> {
    let mut r = scene.resolution;
    if let Some(n) = samples_per_turn {
        r.samples_per_turn = n;
    }
    if let Some(t) = closure_rel_tol {
        r.closure_rel_tol = t;
    }
    r.validate().map_err(core_err)?;
    Ok(r)
}

fn points(list: &[noncirc::core::Vec2]) -> Array2<f64> {
    Array2::from_shape_fn(
        (list.len(), 2),
        |(i, j)| if j == 0 { list[i].x } else { list[i].y },
    )
}

/// Evaluates one design: objectives as a dict, trajectory and pitch curves as arrays.
#[pyfunction]
#[pyo3(signature = (scene, *, samples_per_turn = None, closure_rel_tol = None))]
fn evaluate<'py>(
    py: Python<'py>,
    scene: &Scene,
    samples_per_turn: Option<usize>,
    closure_rel_tol: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let res = resolution(&scene.inner, samples_per_turn, closure_rel_tol)?;
    let s = scene.inner.clone();
    let eval = py
        .allow_threads(|| Evaluator::new().evaluate_at(&s, &res))
        .map_err(core_err)?;
    let out = PyDict::new(py);
    out.set_item("samples_per_turn", res.samples_per_turn)?;
    out.set_item("feasible", eval.total_violation() == 0.0)?;
    out.set_item("total_violation", eval.total_violation())?;
    out.set_item("centre_distance_mm", eval.centre_distance_mm)?;
    let objectives = PyDict::new(py);
    for o in &eval.objectives {
        let d = PyDict::new(py);
        d.set_item("value", o.value)?;
        d.set_item("unit", o.kind.unit())?;
        d.set_item("lower", o.lower)?;
        d.set_item("upper", o.upper)?;
        d.set_item("violation", o.violation)?;
        d.set_item("margin", o.margin)?;
        objectives.set_item(o.kind.name(), d)?;
    }
    out.set_item("objectives", objectives)?;
    if let Some(e) = &eval.events {
        let d = PyDict::new(py);
        d.set_item("picking_carrier_deg", e.picking.carrier_rad.to_degrees())?;
        d.set_item("planting_carrier_deg", e.planting.carrier_rad.to_degrees())?;
        d.set_item("picking_attitude_deg", e.picking.attitude_deg)?;
        d.set_item("planting_attitude_deg", e.planting.attitude_deg)?;
        d.set_item(
            "picking_window_deg",
            (
                e.picking_window_rad[0].to_degrees(),
                e.picking_window_rad[1].to_degrees(),
            ),
        )?;
        d.set_item("picking_tip_speed_m_s", e.picking_tip_speed_m_s)?;
        d.set_item("trajectory_height_mm", e.y_max_mm - e.y_min_mm)?;
        d.set_item("picking_branch_gap_mm", e.picking_branch_gap_mm)?;
        d.set_item("planting_branch_gap_mm", e.planting_branch_gap_mm)?;
        let check = PyDict::new(py);
        for (name, value) in e.check.conditions() {
            check.set_item(name, value)?;
        }
        d.set_item("picking_check_mm", check)?;
        d.set_item("picking_refused", e.check.failures())?;
        out.set_item("events", d)?;
    }
    let anatomy = eval.anatomy(&s.agronomy);
    if let Some(a) = &anatomy {
        let sections = PyDict::new(py);
        for m in &a.sections {
            let d = PyDict::new(py);
            d.set_item("carrier_deg", (m.carrier_deg[0], m.carrier_deg[1]))?;
            d.set_item("span_deg", m.span_deg)?;
            d.set_item("length_mm", m.length_mm)?;
            d.set_item("y_min_mm", m.y_min_mm)?;
            d.set_item("y_max_mm", m.y_max_mm)?;
            sections.set_item(m.section.name(), d)?;
        }
        out.set_item("sections", sections)?;
    }
    let measures = PyDict::new(py);
    for m in Measure::all() {
        if let Some(v) = m.value(&eval, anatomy.as_ref()) {
            let d = PyDict::new(py);
            d.set_item("value", v)?;
            d.set_item("unit", m.unit())?;
            measures.set_item(m.name(), d)?;
        }
    }
    out.set_item("measures", measures)?;
    if let Some(kin) = &eval.kinematics {
        let theta = Array1::from_iter((0..kin.len()).map(|j| kin.theta(j).to_degrees()));
        out.set_item("carrier_deg", theta.into_pyarray(py))?;
        out.set_item("trajectory", points(kin.tips()).into_pyarray(py))?;
        out.set_item(
            "planet_centres",
            points(kin.planet_centres()).into_pyarray(py),
        )?;
        // Per sample of the carrier turn, as the gears figure draws them: the speed ratio
        // of the sun–intermediate pair and arm I's attitude (pusher axis, degrees).
        let a = kin.centre_distance();
        let ratio = Array1::from_iter((kin.pair().samples().iter()).map(|p| (a - p.rho) / p.rho));
        out.set_item("ratio", ratio.into_pyarray(py))?;
        let attitude = Array1::from_iter(
            (kin.planet_angles().iter()).map(|&t| noncirc::core::attitude_deg(kin.pusher_angle(t))),
        );
        out.set_item("attitude_deg", attitude.into_pyarray(py))?;
    }
    // Everything `noncirc evaluate --format json` prints (events of every arm, the gear's
    // summary and module, sections, measures), as the same nested dict.
    let report = noncirc::report::EvaluationReport::new(&s, &eval);
    let report_json = serde_json::to_string(&report).map_err(err)?;
    out.set_item(
        "report",
        py.import("json")?.call_method1("loads", (report_json,))?,
    )?;
    if let Some(pair) = eval.pair() {
        let outlines = noncirc::export::outlines(pair).map_err(lib_err)?;
        out.set_item("driver_curve", points(&outlines[0].points).into_pyarray(py))?;
        out.set_item("driven_curve", points(&outlines[1].points).into_pyarray(py))?;
    }
    if let Some(b) = &eval.moving_box {
        out.set_item("moving_box", serde_json::to_string(b).map_err(err)?)?;
    }
    Ok(out)
}

/// Every measure `evaluate` reports and the goals `min:NAME`/`max:NAME` take:
/// `{name: (unit, description)}`.
#[pyfunction]
fn measures(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for m in Measure::all() {
        out.set_item(m.name(), (m.unit(), m.description()))?;
    }
    Ok(out)
}

/// Rayon pools by thread count, built once; `None` for one thread (the caller's own).
fn pool(threads: Option<usize>) -> PyResult<Option<Arc<rayon::ThreadPool>>> {
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<rayon::ThreadPool>>>> = OnceLock::new();
    let n = noncirc::search::threads_or_all(threads).map_err(lib_err)?;
    if n == 1 {
        return Ok(None);
    }
    let mut pools = POOLS.get_or_init(Default::default).lock().map_err(err)?;
    if let Some(p) = pools.get(&n) {
        return Ok(Some(p.clone()));
    }
    let p = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(err)?,
    );
    pools.insert(n, p.clone());
    Ok(Some(p))
}

/// Rows of a batch evaluated between two checks for Ctrl-C: about 0.1 s on one core at
/// the default resolution (18 µs a design).
const ROWS_PER_SIGNAL_CHECK: usize = 4096;

/// Evaluates an `(n, d)` float64 array of designs (columns: `scene.free_parameters()`), in
/// parallel with the GIL released. Returns arrays: `values`, `violations`,
/// `normalised_violations` (n, k), `cv` (n,), `goals` (n, g), `valid` (n,) and `errors`.
/// `progress(info)` is called after every piece of rows (info: evaluations, total).
#[pyfunction]
#[pyo3(signature = (scene, x, *, samples_per_turn = None, closure_rel_tol = None, threads = None, measures = None, progress = None))]
#[allow(clippy::too_many_arguments)]
fn evaluate_batch<'py>(
    py: Python<'py>,
    scene: &Scene,
    x: &Bound<'py, PyAny>,
    samples_per_turn: Option<usize>,
    closure_rel_tol: Option<f64>,
    threads: Option<usize>,
    measures: Option<&Bound<'py, PyAny>>,
    progress: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let problem = SceneProblem::new(&scene.inner).map_err(core_err)?;
    // The measures to return besides the objectives. By default those read from the
    // evaluation at no cost (the events' carrier angles, picking window, tip speed, branch
    // gaps, heights); "all" adds the trajectory's sections and loop (about double a
    // design's time) and the gearbox's overlap (several times it); a list names them; an
    // empty list returns none.
    let besides_objectives =
        || (Measure::all().into_iter()).filter(|m| !matches!(m, Measure::Objective(_)));
    let measures: Vec<Measure> = match measures {
        None => Measure::batch_default(),
        Some(m) if m.extract::<String>().is_ok_and(|s| s == "all") => {
            besides_objectives().collect()
        }
        Some(m) => {
            let names: Vec<String> = (m.downcast::<PyString>().is_err())
                .then(|| m.extract().ok())
                .flatten()
                .ok_or_else(|| {
                    pyo3::exceptions::PyTypeError::new_err(format!(
                        "evaluate_batch: measures must be None, \"all\" or a list of measure \
                         names (noncirc.measures()), got {}",
                        m.repr().map(|r| r.to_string()).unwrap_or_default()
                    ))
                })?;
            (names.iter())
                .map(|n| Measure::parse(n))
                .collect::<Result<_, _>>()
                .map_err(core_err)?
        }
    };
    let d = problem.dim();
    // Anything `np.asarray(x, dtype=float64)` accepts: ints, float32, lists, any order.
    let converted = py
        .import("numpy")?
        .call_method1("asarray", (x, "float64"))
        .map_err(|e| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "x must be numbers, an (n, {d}) array: np.asarray(x, dtype=float64) failed: {e}"
            ))
        })?;
    let array = converted.downcast::<PyArray2<f64>>().map_err(|_| {
        let shape = converted
            .getattr("shape")
            .map(|t| t.to_string())
            .unwrap_or_default();
        err(format!(
            "x must be 2-D, of shape (n, {d}) (columns: Scene.free_parameters()); got shape {shape}"
        ))
    })?;
    let shape = array.shape().to_vec();
    if shape[1] != d {
        return Err(err(format!(
            "x must have {d} columns ({}), got shape ({}, {})",
            problem.names().join(", "),
            shape[0],
            shape[1]
        )));
    }
    let rows: Vec<Vec<f64>> = {
        let view = array.readonly();
        let a = view.as_array();
        a.outer_iter().map(|r| r.to_vec()).collect()
    };
    if let Some((i, j)) = rows
        .iter()
        .enumerate()
        .find_map(|(i, r)| r.iter().position(|v| !v.is_finite()).map(|j| (i, j)))
    {
        return Err(ParameterError::new_err(format!(
            "x[{i}, {j}] ({}) = {} is not finite",
            problem.names()[j],
            rows[i][j]
        )));
    }
    let res = resolution(&scene.inner, samples_per_turn, closure_rel_tol)?;
    let pool = pool(threads)?;
    let k = scene.inner.objectives.len();
    let g = problem.goals();
    let batch = BatchRows::new(&problem, &res, &measures);
    // In pieces, with a check for Ctrl-C between two: a large batch answers it within a
    // piece's time (about 0.1 s on one core) instead of at its end. `progress` hears of
    // each piece after that check, so no piece is reported after an interrupt.
    let mut results = Vec::with_capacity(rows.len());
    for piece in rows.chunks(ROWS_PER_SIGNAL_CHECK) {
        results.extend(py.allow_threads(|| batch.run(pool.as_deref(), piece)));
        py.check_signals()?;
        if let Some(progress) = progress {
            let info = PyDict::new(py);
            info.set_item("evaluations", results.len())?;
            info.set_item("total", rows.len())?;
            progress.call1((info,))?;
        }
    }
    let n = rows.len();
    let mut values = Array2::from_elem((n, k), f64::NAN);
    let mut violations = Array2::from_elem((n, k), f64::NAN);
    let mut normalised = Array2::from_elem((n, k), noncirc::core::INVALID_CV);
    let mut goals = Array2::zeros((n, g));
    let mut cv = Array1::zeros(n);
    let mut valid = Array1::from_elem(n, false);
    let mut measured = Array2::from_elem((n, measures.len()), f64::NAN);
    let errors = PyList::empty(py);
    for (i, (fitness, outcome)) in results.into_iter().enumerate() {
        cv[i] = fitness.cv;
        for (j, v) in fitness.f.iter().enumerate() {
            goals[[i, j]] = *v;
        }
        match outcome {
            Ok((objectives, measure_values)) => {
                valid[i] = true;
                for (j, v) in measure_values.iter().enumerate() {
                    measured[[i, j]] = v.unwrap_or(f64::NAN);
                }
                for (j, o) in objectives.iter().enumerate() {
                    values[[i, j]] = o.value;
                    violations[[i, j]] = o.violation;
                    normalised[[i, j]] =
                        o.violation / noncirc::core::scale(o.kind, &scene.inner.bounds);
                }
                errors.append(py.None())?;
            }
            Err(e) => errors.append(e)?,
        }
    }
    let out = PyDict::new(py);
    out.set_item(
        "objective_names",
        scene
            .inner
            .objectives
            .iter()
            .map(|o| o.name())
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "objective_units",
        (scene.inner.objectives.iter())
            .map(|o| o.unit())
            .collect::<Vec<_>>(),
    )?;
    out.set_item("values", values.into_pyarray(py))?;
    out.set_item("violations", violations.into_pyarray(py))?;
    out.set_item("normalised_violations", normalised.into_pyarray(py))?;
    out.set_item("cv", cv.into_pyarray(py))?;
    let quantities = problem.goal_quantities();
    out.set_item(
        "goal_names",
        quantities
            .iter()
            .map(|q| q.name.clone())
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "goal_maximised",
        quantities.iter().map(|q| q.maximised).collect::<Vec<_>>(),
    )?;
    // The goals as the search ranks them (all minimised) and as the quantities they are.
    let goal_values = Array2::from_shape_fn((n, g), |(i, j)| {
        problem.goal_list()[j].physical(goals[[i, j]], &scene.inner.bounds)
    });
    out.set_item("goals", goals.into_pyarray(py))?;
    out.set_item("goal_values", goal_values.into_pyarray(py))?;
    out.set_item("valid", valid.into_pyarray(py))?;
    out.set_item("errors", errors)?;
    out.set_item(
        "measure_names",
        measures.iter().map(|m| m.name()).collect::<Vec<_>>(),
    )?;
    out.set_item(
        "measure_units",
        measures.iter().map(|m| m.unit()).collect::<Vec<_>>(),
    )?;
    out.set_item("measures", measured.into_pyarray(py))?;
    out.set_item("samples_per_turn", res.samples_per_turn)?;
    Ok(out)
}

/// The Python side of a search, an observer of the core's executor: after every
/// generation it takes the GIL for a moment to check for Ctrl-C and to call the progress
/// callback. Either stops the search cleanly (the checkpoint, if asked, is written); the
/// error is raised once the search has stopped.
struct PythonObserver {
    progress: Option<PyObject>,
    error: Option<PyErr>,
}

impl Observer for PythonObserver {
    fn poll(&mut self, state: &SearchState, budget: u64) -> Control {
        Python::with_gil(|py| {
            // The callback first, so that it sees the state the search stops in.
            let progress = || -> PyResult<bool> {
                let Some(callback) = &self.progress else {
                    return Ok(true);
                };
                let info = PyDict::new(py);
                info.set_item("generation", state.generation)?;
                info.set_item("evaluations", state.evaluations)?;
                info.set_item("budget", budget)?;
                info.set_item("best_violation", state.best.as_ref().map(|b| b.fitness.cv))?;
                info.set_item("feasible", state.best_confirmed.is_some())?;
                // Returning False stops the search; None or anything else goes on.
                let answer = callback.call1(py, (info,))?;
                let stop =
                    (answer.bind(py).downcast::<pyo3::types::PyBool>()).is_ok_and(|b| !b.is_true());
                Ok(!stop)
            };
            let outcome = progress().and_then(|go_on| py.check_signals().map(|()| go_on));
            match outcome {
                Ok(true) => Control::Continue,
                Ok(false) => Control::Stop,
                Err(e) => {
                    self.error = Some(e);
                    Control::Stop
                }
            }
        })
    }
}

/// Runs a search (GIL released) and returns its summary and confirmed Pareto set.
/// `progress(info)` is called after every generation (return False to stop); Ctrl-C stops
/// the search after the current generation and raises `KeyboardInterrupt`. With
/// `checkpoint`, the state is written there every `checkpoint_every` seconds and at the
/// end; `resume` continues a checkpoint (its scene and settings; `budget` may be raised).
#[pyfunction]
#[pyo3(signature = (scene = None, *, algorithm = None, seed = None, budget = None, population = None, threads = None, screening_samples_per_turn = None, progress = None, checkpoint = None, checkpoint_every = 10.0, resume = None))]
#[allow(clippy::too_many_arguments)]
fn optimise<'py>(
    py: Python<'py>,
    scene: Option<&Scene>,
    algorithm: Option<&str>,
    seed: Option<u64>,
    budget: Option<u64>,
    population: Option<usize>,
    threads: Option<usize>,
    screening_samples_per_turn: Option<usize>,
    progress: Option<PyObject>,
    checkpoint: Option<std::path::PathBuf>,
    checkpoint_every: f64,
    resume: Option<std::path::PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let settings = SearchSettings {
        algorithm: algorithm
            .map(Algorithm::parse)
            .transpose()
            .map_err(|e| core_err(e.into()))?,
        budget,
        population,
        seed,
        screening_samples_per_turn,
    };
    let s =
        match (scene, &resume) {
            (Some(scene), None) => {
                let mut s = scene.inner.clone();
                // The keywords override the scene's search settings, so the summary states
                // what ran.
                settings.apply(&mut s).map_err(core_err)?;
                s
            }
            // The checkpoint holds the scene; this one is not used.
            (None, Some(_)) if settings.ignored_by_resume().is_empty() => {
                noncirc::core::Scene::default()
            }
            (None, Some(_)) => {
                return Err(err(format!(
                    "resume continues the checkpoint's own scene and search; {} would be ignored \
                 (only budget, threads, progress and the checkpoint options apply)",
                    settings.ignored_by_resume().join(", ")
                )))
            }
            (Some(_), Some(_)) => return Err(err(
                "give a scene or resume=, not both: a resumed search uses the checkpoint's scene",
            )),
            (None, None) => return Err(err("optimise needs a scene, or resume= a checkpoint")),
        };
    let opts = RunOptions {
        checkpoint,
        checkpoint_every: noncirc::search::checkpoint_interval(checkpoint_every)
            .map_err(lib_err)?,
        resume_budget: resume.as_ref().and(budget),
        resume,
        ..RunOptions::new(threads).map_err(lib_err)?
    };
    let mut observer = PythonObserver {
        progress,
        error: None,
    };
    let outcome = py
        .allow_threads(|| noncirc::search::run(&s, &opts, &mut [&mut observer]))
        .map_err(lib_err)?;
    if let Some(e) = observer.error {
        return Err(e);
    }
    let summary = outcome.summary();
    if !summary.feasible {
        // Said, not only flagged: a run that found nothing must not pass for a result.
        let missed = summary.missed();
        let message = format!(
            "noncirc.optimise: no design found meets every objective (the best misses {}); \
             a larger budget, another seed or algorithm='de'|'cmaes' may find one",
            if missed.is_empty() {
                "all: the model refused it".to_string()
            } else {
                missed.join(", ")
            }
        );
        let message = std::ffi::CString::new(message).map_err(err)?;
        PyErr::warn(
            py,
            &py.get_type::<pyo3::exceptions::PyRuntimeWarning>(),
            &message,
            // The user's call of `noncirc.optimise`, past the package's wrapper.
            2,
        )?;
    }
    let json = serde_json::to_string(&summary).map_err(err)?;
    let out = py
        .import("json")?
        .call_method1("loads", (json,))?
        .downcast_into::<PyDict>()?;
    let names = outcome.problem.names();
    out.set_item("parameter_names", &names)?;
    out.set_item(
        "goal_names",
        (outcome.problem.goal_quantities().into_iter())
            .map(|q| q.name)
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "objective_names",
        (outcome.problem.base().objectives.iter())
            .map(|o| o.name())
            .collect::<Vec<_>>(),
    )?;
    let front = PyList::empty(py);
    for (x, f) in &outcome.confirmed.pareto {
        let d = PyDict::new(py);
        let params = PyDict::new(py);
        for (n, v) in names.iter().zip(x) {
            params.set_item(*n, *v)?;
        }
        d.set_item("parameters", params)?;
        d.set_item("goals", f.f.clone())?;
        d.set_item("goal_values", outcome.problem.goal_values(&f.f))?;
        d.set_item("cv", f.cv)?;
        front.append(d)?;
    }
    out.set_item("pareto", front)?;
    if let Some((best, _)) = &outcome.confirmed.best {
        out.set_item(
            "best_scene",
            Scene {
                inner: best.clone(),
            },
        )?;
    }
    Ok(out)
}

/// The `count` best members of the search in the checkpoint file `checkpoint`, as JSON
/// text, to send to another island of the same search (`noncirc.dask.islands`).
#[pyfunction]
fn emigrants(checkpoint: std::path::PathBuf, count: usize) -> PyResult<String> {
    let migrants = noncirc::search::emigrants(&checkpoint, count).map_err(lib_err)?;
    serde_json::to_string(&migrants).map_err(err)
}

/// Takes `migrants` (the JSON text of `emigrants` from another island of the same search)
/// into the search in the checkpoint file `checkpoint`, in place of its worst members; a
/// search resumed from it goes on with them.
#[pyfunction]
fn immigrate(checkpoint: std::path::PathBuf, migrants: &str) -> PyResult<()> {
    let migrants: noncirc::core::Migrants = serde_json::from_str(migrants).map_err(|e| {
        ParameterError::new_err(format!("migrants: not the text of emigrants(): {e}"))
    })?;
    noncirc::search::immigrate(&checkpoint, &migrants).map_err(lib_err)
}

/// A tolerance analysis of the scene's design (`noncirc robustness`): the report as a
/// dict (the CLI's JSON), with `margins`, an (objectives, samples) array of every sample's
/// margin in the objective's unit (NaN where the model refused the sample).
#[pyfunction]
#[pyo3(signature = (scene, *, samples = None, seed = None, worst_case = true))]
fn robustness<'py>(
    py: Python<'py>,
    scene: &Scene,
    samples: Option<usize>,
    seed: Option<u64>,
    worst_case: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let mut s = scene.inner.clone();
    if let Some(n) = samples {
        s.tolerances.samples = n;
    }
    if let Some(seed) = seed {
        s.tolerances.seed = seed;
    }
    s.tolerances.validate().map_err(core_err)?;
    let r = py
        .allow_threads(|| noncirc::robustness::robustness(&s, worst_case))
        .map_err(lib_err)?;
    let value = serde_json::to_value(&r).map_err(err)?;
    let out = json_to_py(py, &value)?
        .into_bound(py)
        .downcast_into::<PyDict>()?;
    let n = r.margins.first().map_or(0, Vec::len);
    let margins =
        numpy::ndarray::Array2::from_shape_fn((r.margins.len(), n), |(k, i)| r.margins[k][i]);
    out.set_item("margins", margins.into_pyarray(py))?;
    Ok(out)
}

/// Sobol indices of every output over the scene's search box (`noncirc sensitivity`), in
/// SALib's layout: `problem` (num_vars, names, bounds), `X` (N (k + 2), k) and `Y`
/// (N (k + 2), outputs) in SALib's sample order, `outputs`, and per output `indices[name]`
/// a dict of `S1`, `S1_conf`, `ST`, `ST_conf` arrays; `S1` etc. also as (outputs, k)
/// arrays. The report's other fields as the CLI's JSON gives them.
#[pyfunction]
#[pyo3(signature = (scene, *, base_samples = 1024, bootstrap = 100, box_scale = 0.25, threads = None))]
fn sensitivity<'py>(
    py: Python<'py>,
    scene: &Scene,
    base_samples: usize,
    bootstrap: usize,
    box_scale: f64,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let threads = noncirc::search::threads_or_all(threads).map_err(lib_err)?;
    let s = scene.inner.clone();
    let r = py
        .allow_threads(|| {
            noncirc::robustness::sensitivity(&s, base_samples, bootstrap, box_scale, threads)
        })
        .map_err(lib_err)?;
    let value = serde_json::to_value(&r).map_err(err)?;
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

#[pymodule]
fn _noncirc(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(measures, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(optimise, m)?)?;
    m.add_function(wrap_pyfunction!(emigrants, m)?)?;
    m.add_function(wrap_pyfunction!(immigrate, m)?)?;
    m.add_function(wrap_pyfunction!(robustness, m)?)?;
    m.add_function(wrap_pyfunction!(sensitivity, m)?)?;
    m.add("NoncircError", m.py().get_type::<NoncircError>())?;
    m.add("UnknownNameError", m.py().get_type::<UnknownNameError>())?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("ParameterError", m.py().get_type::<ParameterError>())?;
    m.add("ModelError", m.py().get_type::<ModelError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
