//! The `Scene` class: a scene read, edited and checked whole, immutable from Python.

use crate::convert::{json_to_py, py_to_json};
use crate::errors::{call_error, internal, invalid, parameter, Result, UnknownNameError};
use noncirc::core::SceneProblem;
use noncirc::scene_file::{
    apply_overrides, apply_values, check_scene, load_scene, parse_scene, value_at, BUILTIN,
};
use pyo3::exceptions::{PyFileNotFoundError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// A scene: what is designed and asked. Immutable: `with_set` returns a new scene.
#[pyclass(module = "noncirc._noncirc", frozen)]
#[derive(Clone)]
pub(crate) struct Scene {
    pub(crate) inner: noncirc::core::Scene,
}

#[pymethods]
impl Scene {
    /// Loads a scene file (TOML or JSON).
    #[staticmethod]
    fn from_file(path: &str) -> Result<Self> {
        if !std::path::Path::new(path).exists() {
            return Err(
                PyFileNotFoundError::new_err((2, "no such scene file", path.to_string())).into(),
            );
        }
        Ok(Self {
            inner: load_scene(Some(path))?,
        })
    }

    /// Parses scene text (TOML, or JSON if it starts with `{`).
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_string(text: &str, origin: &str) -> Result<Self> {
        Ok(Self {
            inner: parse_scene(text, origin)?,
        })
    }

    /// A built-in scene by name (see `Scene.builtins()`).
    #[staticmethod]
    fn builtin(name: &str) -> Result<Self> {
        if !BUILTIN.iter().any(|(n, _)| *n == name) {
            return Err(UnknownNameError::new_err(format!(
                "unknown built-in scene '{name}': the built-ins are {}",
                (BUILTIN.iter().map(|(n, _)| *n))
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
            .into());
        }
        Ok(Self {
            inner: load_scene(Some(name))?,
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
    fn with_set(&self, key: &str, value: &Bound<'_, PyAny>) -> Result<Self> {
        let call = format!("Scene.with_set({key:?}, {})", value.repr()?);
        let inner = match value.downcast::<PyString>() {
            Ok(text) => apply_overrides(self.inner.clone(), &[format!("{key}={}", text.to_cow()?)]),
            Err(_) => apply_values(
                self.inner.clone(),
                &[(key.to_string(), py_to_json(value, &call)?)],
            ),
        }
        .map_err(|e| call_error(e, &call))?;
        Ok(Self { inner })
    }

    /// The value at `key` (`"train.phi0_deg"`, `"gear.curve.radii_mm[3]"`, `"bounds"`): a
    /// float, int, str, list or dict, as the scene file holds it.
    fn get(&self, py: Python<'_>, key: &str) -> Result<PyObject> {
        let value = value_at(&self.inner, key)
            .map_err(|e| call_error(e, &format!("Scene.get({key:?})")))?;
        json_to_py(py, &value)
    }

    /// A copy with the numeric parameters `names` set to the values of `row` (a row of an
    /// `evaluate_batch` input, in `free_parameters()` order): no text is parsed, so it is
    /// fast. The scene is checked whole.
    fn with_values(&self, names: Vec<String>, row: &Bound<'_, PyAny>) -> Result<Self> {
        let row: Vec<f64> = row
            .extract()
            .or_else(|_| row.call_method0("tolist").and_then(|l| l.extract()))
            .map_err(|_| {
                PyTypeError::new_err(format!(
                    "Scene.with_values: row must be a sequence of numbers, got {}",
                    row.get_type()
                        .name()
                        .map(|n| n.to_string())
                        .unwrap_or_default()
                ))
            })?;
        if names.len() != row.len() {
            return Err(invalid(format!(
                "Scene.with_values: {} names but {} values",
                names.len(),
                row.len()
            )));
        }
        let mut inner = self.inner.clone();
        for (name, &v) in names.iter().zip(&row) {
            let param = noncirc::core::Param::parse(name, &inner)?;
            if !v.is_finite() {
                return Err(parameter(format!(
                    "Scene.with_values: {name} = {v} is not a finite number"
                )));
            }
            param.set(&mut inner, v);
        }
        let inner = check_scene(inner, "Scene.with_values")?;
        Ok(Self { inner })
    }

    /// The free parameters' current values, `{name: value}` in `free_parameters()` order.
    fn free_values<'py>(&self, py: Python<'py>) -> Result<Bound<'py, PyDict>> {
        let problem = SceneProblem::new(&self.inner)?;
        let out = PyDict::new(py);
        for name in problem.names() {
            let param = noncirc::core::Param::parse(name, &self.inner)?;
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
    fn to_toml(&self) -> Result<String> {
        toml::to_string(&self.inner).map_err(internal)
    }

    /// The scene as JSON text (what pickling uses).
    fn to_json(&self) -> Result<String> {
        serde_json::to_string(&self.inner).map_err(internal)
    }

    /// Rebuilds a scene from `to_json()`.
    #[staticmethod]
    fn from_json(text: &str) -> Result<Self> {
        Self::from_string(text, "<json>")
    }

    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }

    /// The search space: `[(name, lower, upper), ...]` (the default space if none is given).
    fn free_parameters(&self) -> Result<Vec<(String, f64, f64)>> {
        let p = SceneProblem::new(&self.inner)?;
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
    fn goal_names(&self) -> Result<Vec<String>> {
        let problem = SceneProblem::new(&self.inner)?;
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

    /// The search constraints (`search.constraints`) as written, in order:
    /// `picking_height_mm <= -90`.
    fn constraint_names(&self) -> Vec<String> {
        (self.inner.search.constraints.iter())
            .map(|c| c.text())
            .collect()
    }

    fn __reduce__(&self, py: Python<'_>) -> Result<(PyObject, (String,))> {
        let rebuild = py.get_type::<Scene>().getattr("from_json")?.unbind();
        Ok((rebuild, (self.to_json()?,)))
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene(name={:?}, kind={:?})",
            self.inner.name,
            self.inner.kind.name()
        )
    }
}
