//! Evaluations: one design in full (`evaluate`), many reduced to their numbers
//! (`evaluate_batch`), and the measures they report.

use crate::convert::{json_to_py, points, pool, resolution};
use crate::errors::{internal, invalid, parameter, Result};
use crate::scene::Scene;
use crate::signals::watched;
use noncirc::batch::BatchRows;
use noncirc::core::{Evaluator, Measure, Measured, Scalar, SceneProblem};
use noncirc::report::measure_rows;
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use std::sync::atomic::AtomicBool;

/// Evaluates one design: objectives as a dict, trajectory and pitch curves as arrays.
#[pyfunction]
#[pyo3(signature = (scene, *, samples_per_turn = None, closure_rel_tol = None))]
pub(crate) fn evaluate<'py>(
    py: Python<'py>,
    scene: &Scene,
    samples_per_turn: Option<usize>,
    closure_rel_tol: Option<f64>,
) -> Result<Bound<'py, PyDict>> {
    let res = resolution(&scene.inner, samples_per_turn, closure_rel_tol)?;
    let s = scene.inner.clone();
    let eval = py.allow_threads(|| Evaluator::new().evaluate_at(&s, &res))?;
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
    // The search constraints, keyed as written (`picking_height_mm <= -90`).
    let constraints = PyDict::new(py);
    for c in &eval.constraints {
        let d = PyDict::new(py);
        d.set_item("measure", c.constraint.measure.name())?;
        d.set_item("value", c.value)?;
        d.set_item("unit", c.constraint.measure.unit())?;
        d.set_item("bound", c.constraint.bound)?;
        d.set_item("at_most", c.constraint.at_most)?;
        d.set_item("violation", c.violation)?;
        d.set_item("margin", c.margin)?;
        constraints.set_item(c.constraint.text(), d)?;
    }
    out.set_item("constraints", constraints)?;
    if let Some(e) = &eval.events {
        let d = PyDict::new(py);
        // The names that are measures' are the measures' own.
        let name = |s: Scalar| Measure::Scalar(s).name();
        d.set_item(
            name(Scalar::PickingCarrier),
            e.picking.carrier_rad.to_degrees(),
        )?;
        d.set_item(
            name(Scalar::PlantingCarrier),
            e.planting.carrier_rad.to_degrees(),
        )?;
        d.set_item("picking_attitude_deg", e.picking.attitude_deg)?;
        d.set_item("planting_attitude_deg", e.planting.attitude_deg)?;
        d.set_item(
            "picking_window_deg",
            (
                e.picking_window_rad[0].to_degrees(),
                e.picking_window_rad[1].to_degrees(),
            ),
        )?;
        d.set_item(name(Scalar::PickingTipSpeed), e.picking_tip_speed_m_s)?;
        d.set_item("trajectory_height_mm", e.y_max_mm - e.y_min_mm)?;
        d.set_item(name(Scalar::PickingBranchGap), e.picking_branch_gap_mm)?;
        d.set_item(name(Scalar::PlantingBranchGap), e.planting_branch_gap_mm)?;
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
    // The measures `noncirc evaluate` reports (the teeth's strength only where the
    // objectives computed it).
    for row in measure_rows(&Measured::with_anatomy(&eval, &s, anatomy)) {
        let d = PyDict::new(py);
        d.set_item("value", row.value)?;
        d.set_item("unit", row.unit)?;
        measures.set_item(row.name, d)?;
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
    // summary and module, sections, measures), as the same nested dict: through JSON's
    // value tree, so that pairs are lists and a missing number None, as in the CLI's file.
    let report = noncirc::report::EvaluationReport::new(&s, &eval);
    let report = serde_json::to_value(&report).map_err(internal)?;
    out.set_item("report", json_to_py(py, &report)?)?;
    if let Some(pair) = eval.pair() {
        let outlines = noncirc::export::outlines(pair)?;
        out.set_item("driver_curve", points(&outlines[0].points).into_pyarray(py))?;
        out.set_item("driven_curve", points(&outlines[1].points).into_pyarray(py))?;
        // The train with two pairs: the intermediate's layer B and the planet.
        if let Some(second) = eval.kinematics.as_ref().and_then(|k| k.second_pair()) {
            let outlines = noncirc::export::outlines(second)?;
            out.set_item(
                "second_driver_curve",
                points(&outlines[0].points).into_pyarray(py),
            )?;
            out.set_item(
                "second_driven_curve",
                points(&outlines[1].points).into_pyarray(py),
            )?;
        }
    }
    if let Some(b) = &eval.moving_box {
        out.set_item("moving_box", serde_json::to_string(b).map_err(internal)?)?;
    }
    Ok(out)
}

/// Every measure `evaluate` reports and the goals `min:NAME`/`max:NAME` take:
/// `{name: (unit, description)}`.
#[pyfunction]
pub(crate) fn measures(py: Python<'_>) -> Result<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for m in Measure::all() {
        out.set_item(m.name(), (m.unit(), m.description()))?;
    }
    Ok(out)
}

/// Rows of a batch read, evaluated and written at a time (streamed), and reported to
/// `progress`: about 0.1 s on one core at the default resolution.
const ROWS_PER_PIECE: usize = 4096;

/// The largest array of tip paths `evaluate_batch(trajectories=True)` makes (bytes): 2 GB,
/// a million designs at 120 samples a turn.
const MOST_TRAJECTORY_BYTES: f64 = 2e9;

/// Evaluates an `(n, d)` float64 array of designs (columns: `scene.free_parameters()`), in
/// parallel with the GIL released. Returns arrays: `values`, `violations`,
/// `normalised_violations` (n, k), `constraint_values` and
/// `constraint_normalised_violations` (n, c: `search.constraints`), `cv` (n,: the sum of
/// both normalised violations), `goals` (n, g), `valid` (n,) and `errors`;
/// with `trajectories`, `trajectories` (n, samples_per_turn, 2), each design's tip path in
/// mm (NaN rows for refused designs). `progress(info)` is called after every piece of rows
/// (info: evaluations, total).
#[pyfunction]
#[pyo3(signature = (scene, x, *, samples_per_turn = None, closure_rel_tol = None, threads = None, measures = None, progress = None, trajectories = false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_batch<'py>(
    py: Python<'py>,
    scene: &Scene,
    x: &Bound<'py, PyAny>,
    samples_per_turn: Option<usize>,
    closure_rel_tol: Option<f64>,
    threads: Option<usize>,
    measures: Option<&Bound<'py, PyAny>>,
    progress: Option<&Bound<'py, PyAny>>,
    trajectories: bool,
) -> Result<Bound<'py, PyDict>> {
    let problem = SceneProblem::new(&scene.inner)?;
    // The measures to return besides the objectives. By default those read from the
    // evaluation at no cost (the events' carrier angles, picking window, tip speed, branch
    // gaps, heights); "all" adds the trajectory's sections and loop (about double a
    // design's time), the gearbox's overlap (several times it) and the dynamics (about ten
    // times); a list names them (the teeth's safety factors, objectives, only so); an
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
                    PyTypeError::new_err(format!(
                        "evaluate_batch: measures must be None, \"all\" or a list of measure \
                         names (noncirc.measures()), got {}",
                        m.repr().map(|r| r.to_string()).unwrap_or_default()
                    ))
                })?;
            (names.iter())
                .map(|n| Measure::parse(n))
                .collect::<std::result::Result<_, _>>()?
        }
    };
    let d = problem.dim();
    // Anything `np.asarray(x, dtype=float64)` accepts: ints, float32, lists, any order.
    let converted = py
        .import("numpy")?
        .call_method1("asarray", (x, "float64"))
        .map_err(|e| {
            PyTypeError::new_err(format!(
                "x must be numbers, an (n, {d}) array: np.asarray(x, dtype=float64) failed: {e}"
            ))
        })?;
    let array = converted.downcast::<PyArray2<f64>>().map_err(|_| {
        let shape = converted
            .getattr("shape")
            .map(|t| t.to_string())
            .unwrap_or_default();
        invalid(format!(
            "x must be 2-D, of shape (n, {d}) (columns: Scene.free_parameters()); got shape {shape}"
        ))
    })?;
    let shape = array.shape().to_vec();
    if shape[1] != d {
        return Err(invalid(format!(
            "x must have {d} columns ({}), got shape ({}, {})",
            problem.names().join(", "),
            shape[0],
            shape[1]
        )));
    }
    let res = resolution(&scene.inner, samples_per_turn, closure_rel_tol)?;
    let path_bytes = shape[0] as f64 * res.samples_per_turn as f64 * 16.0;
    if trajectories && path_bytes > MOST_TRAJECTORY_BYTES {
        return Err(parameter(format!(
            "trajectories=True for {} designs at {} samples per turn would take {:.1} GB \
             (at most {:.0} GB): evaluate them in pieces, or at fewer samples_per_turn",
            shape[0],
            res.samples_per_turn,
            path_bytes / 1e9,
            MOST_TRAJECTORY_BYTES / 1e9
        )));
    }
    // Streamed: the input is read, evaluated and written to the outputs a piece of rows at
    // a time, so memory stays at the input and the outputs plus one piece (a whole batch's
    // rows at once took ten times the input: 7.1 GB for a 680 MB array).
    let view = array.readonly();
    let input = view.as_array();
    if let Some(((i, j), v)) = input.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(parameter(format!(
            "x[{i}, {j}] ({}) = {v} is not finite",
            problem.names()[j]
        )));
    }
    let pool = pool(threads)?;
    let n = shape[0];
    let k = scene.inner.objectives.len();
    let c = scene.inner.search.constraints.len();
    let g = problem.goals();
    let batch = BatchRows::new(&problem, &res, &measures).with_tip_paths(trajectories);
    let mut values = Array2::from_elem((n, k), f64::NAN);
    let mut violations = Array2::from_elem((n, k), f64::NAN);
    let mut normalised = Array2::from_elem((n, k), noncirc::core::INVALID_CV);
    let mut constraint_values = Array2::from_elem((n, c), f64::NAN);
    let mut constraint_normalised = Array2::from_elem((n, c), noncirc::core::INVALID_CV);
    let mut goals = Array2::zeros((n, g));
    let mut cv = Array1::zeros(n);
    let mut valid = Array1::from_elem(n, false);
    let mut measured = Array2::from_elem((n, measures.len()), f64::NAN);
    let samples = res.samples_per_turn;
    let mut paths = trajectories.then(|| Array3::from_elem((n, samples, 2), f64::NAN));
    let errors = PyList::empty(py);
    // Ctrl-C is watched while a piece is evaluated ([`watched`]): the rows not yet started
    // are skipped, so a batch stops within one row's evaluation per thread at any
    // resolution. `progress` hears of each piece after that, so no piece is reported after
    // an interrupt.
    let stop = AtomicBool::new(false);
    for first in (0..n).step_by(ROWS_PER_PIECE) {
        let rows: Vec<Vec<f64>> = (first..n.min(first + ROWS_PER_PIECE))
            .map(|i| input.row(i).to_vec())
            .collect();
        let (results, interrupt) = watched(py, &stop, || batch.run(pool.as_deref(), &rows, &stop));
        if let Some(e) = interrupt {
            return Err(e.into());
        }
        let results = results.ok_or_else(|| internal("a batch stopped with no signal"))?;
        for (offset, (fitness, outcome)) in results.into_iter().enumerate() {
            let i = first + offset;
            cv[i] = fitness.cv;
            for (j, v) in fitness.f.iter().enumerate() {
                goals[[i, j]] = *v;
            }
            match outcome {
                Ok(row) => {
                    valid[i] = true;
                    for (j, v) in row.measures.iter().enumerate() {
                        measured[[i, j]] = v.unwrap_or(f64::NAN);
                    }
                    if let (Some(paths), Some(path)) = (&mut paths, &row.tip_path) {
                        if path.len() != samples {
                            return Err(internal(format!(
                                "design {i}'s path has {} points, not {samples}",
                                path.len()
                            )));
                        }
                        for (j, p) in path.iter().enumerate() {
                            paths[[i, j, 0]] = p[0];
                            paths[[i, j, 1]] = p[1];
                        }
                    }
                    for (j, o) in row.objectives.iter().enumerate() {
                        values[[i, j]] = o.value;
                        violations[[i, j]] = o.violation;
                        normalised[[i, j]] =
                            o.violation / noncirc::core::scale(o.kind, &scene.inner.bounds);
                    }
                    for (j, v) in row.constraints.iter().enumerate() {
                        constraint_values[[i, j]] = v.value;
                        // Capped as the fitness is: a NaN measure's infinite violation
                        // stays a number pymoo can sum.
                        constraint_normalised[[i, j]] =
                            v.normalised_violation().min(noncirc::core::INVALID_CV);
                    }
                    errors.append(py.None())?;
                }
                Err(e) => errors.append(e)?,
            }
        }
        py.check_signals()?;
        if let Some(progress) = progress {
            let info = PyDict::new(py);
            info.set_item("evaluations", (first + ROWS_PER_PIECE).min(n))?;
            info.set_item("total", n)?;
            progress.call1((info,))?;
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
    out.set_item(
        "constraint_names",
        (scene.inner.search.constraints.iter())
            .map(|c| c.text())
            .collect::<Vec<_>>(),
    )?;
    out.set_item("constraint_values", constraint_values.into_pyarray(py))?;
    out.set_item(
        "constraint_normalised_violations",
        constraint_normalised.into_pyarray(py),
    )?;
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
    if let Some(paths) = paths {
        out.set_item("trajectories", paths.into_pyarray(py))?;
    }
    Ok(out)
}
