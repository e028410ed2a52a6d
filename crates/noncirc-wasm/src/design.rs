//! One design being edited: its scene, evaluated on every change, with the views, the
//! parameter guide, the live sweep and the exports the studio shows.

use noncirc::core::{scale, Evaluation, Evaluator, ObjectiveValue, Param, Scene, SceneProblem};
use noncirc::dynamics::{dynamics_from, report_from, strength_from};
use noncirc::fit::{fit_measure_rows, parse_target, target_toml};
use noncirc::report::{check_finite, EvaluationReport};
use noncirc::scene_file::{apply_overrides, apply_values, parse_scene, BUILTIN};
use noncirc::solids::{stl, Assembly, Instance};
use noncirc::teeth::TeethRun;
use serde::Serialize;
use std::sync::Arc;
use wasm_bindgen::prelude::*;

use crate::dynamics::{DynamicsView, QUANTITIES};
use crate::{js_error, to_json};

/// A design: a checked scene and its last evaluation.
#[wasm_bindgen]
pub struct Design {
    scene: Scene,
    evaluator: Evaluator,
    /// The last successful evaluation of `scene` (`None` until [`Design::evaluate`]).
    evaluation: Option<Evaluation>,
    /// The design's toothed gears once cut ([`Design::cut_teeth`]); a change drops them.
    teeth: Option<TeethRun>,
    /// The solids of the 3D view once made ([`Design::solid_parts`]) and the teeth they
    /// were cut from; a change drops them.
    solids: Option<(Assembly, TeethRun)>,
}

/// A free parameter of the scene's search space with its current value.
#[derive(Serialize)]
struct FreeValue {
    name: String,
    value: f64,
    lower: f64,
    upper: f64,
}

/// Beside one parameter: how the worst objective's normalised margin moves with it.
#[derive(Serialize)]
struct GuideRow {
    name: String,
    /// Change of the worst objective's margin over its scale per tenth of the parameter's
    /// range (positive: raise the parameter); `None` where the model refuses a neighbour.
    slope: Option<f64>,
}

/// The parameter guide: the objective it guides by (the one asked for, else the worst),
/// its normalised margin, every parameter's pull on it, and every missed objective.
#[derive(Serialize)]
struct Guide {
    worst: &'static str,
    worst_margin: f64,
    rows: Vec<GuideRow>,
    /// Whether `worst` is the one asked for (not chosen as the worst).
    chosen: bool,
    /// Every objective the design misses, in the scene's order.
    missed: Vec<&'static str>,
}

/// One step of a live sweep: each objective's margin over its scale (`None`: refused).
#[derive(Serialize)]
struct SweepStep {
    value: f64,
    margins: Option<Vec<f64>>,
}

/// Least change of a normalised margin per tenth of a parameter's range that counts as
/// the parameter moving the objective (below it, finite differences see rounding).
const MOVED: f64 = 5e-4;

/// A file for the page to download.
#[derive(Serialize)]
struct File {
    name: String,
    text: String,
}

/// The quantities the dynamics panel plots, as JSON `[[name, label, unit]]`.
#[wasm_bindgen(js_name = dynamicsQuantities)]
pub fn dynamics_quantities() -> String {
    serde_json::to_string(&QUANTITIES).unwrap_or_default()
}

/// Names of the built-in scenes, as JSON.
#[wasm_bindgen(js_name = builtinScenes)]
pub fn builtin_scenes() -> String {
    let names: Vec<&str> = BUILTIN.iter().map(|(name, _)| *name).collect();
    serde_json::to_string(&names).unwrap_or_default()
}

/// A built-in scene's file text.
#[wasm_bindgen(js_name = builtinScene)]
pub fn builtin_scene(name: &str) -> Result<String, JsError> {
    BUILTIN
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| text.to_string())
        .ok_or_else(|| js_error(format!("unknown built-in scene '{name}'")))
}

/// Each objective's margin over its normalising scale (negative when violated).
fn normalised_margins(eval: &Evaluation, scene: &Scene) -> Vec<f64> {
    (eval.objectives.iter())
        .map(|o: &ObjectiveValue| o.margin / scale(o.kind, &scene.bounds))
        .collect()
}

#[wasm_bindgen]
impl Design {
    /// Reads scene text (TOML, or JSON if it starts with `{`) exactly as the CLI reads a
    /// file; `origin` names it in messages.
    #[wasm_bindgen(constructor)]
    pub fn new(text: &str, origin: &str) -> Result<Design, JsError> {
        let scene = parse_scene(text, origin).map_err(js_error)?;
        Ok(Self {
            scene,
            evaluator: Evaluator::new(),
            evaluation: None,
            teeth: None,
            solids: None,
        })
    }

    /// The scene as a TOML file (the CLI's format).
    #[wasm_bindgen(js_name = toToml)]
    pub fn to_toml(&self) -> Result<String, JsError> {
        noncirc::files::toml_text(&self.scene, "the scene").map_err(js_error)
    }

    /// The scene as a JSON file (the CLI reads it too).
    #[wasm_bindgen(js_name = toJson)]
    pub fn to_json(&self) -> Result<String, JsError> {
        noncirc::files::json_text(&self.scene, "the scene").map_err(js_error)
    }

    /// Applies `key.path=value` assignments (one per line) as `--set` does, checks the
    /// scene and evaluates it, returning what [`Design::evaluate`] returns. On an error
    /// (a bad value, or a design the model refuses) the design and its evaluation are
    /// unchanged and the message names the bad value.
    pub fn set(&mut self, assignments: &str) -> Result<String, JsError> {
        let list: Vec<String> = assignments.lines().map(str::to_string).collect();
        // The page shows the message beside the field, which names the key: without the
        // CLI's `--set key=value:`.
        let scene = apply_overrides(self.scene.clone(), &list).map_err(|e| js_error(e.detail()))?;
        self.replace_scene(scene)
    }

    /// Removes an optional value (`train.picks_per_minute`: the carrier speed then sets the
    /// working speed), checks the scene and evaluates it, as [`Design::set`] does.
    pub fn unset(&mut self, path: &str) -> Result<String, JsError> {
        let cleared = [(path.to_string(), serde_json::Value::Null)];
        let scene = apply_values(self.scene.clone(), &cleared).map_err(|e| js_error(e.detail()))?;
        self.replace_scene(scene)
    }

    /// Evaluates `scene` in place of the design's; on an error the design and its
    /// evaluation are unchanged.
    fn replace_scene(&mut self, scene: Scene) -> Result<String, JsError> {
        let previous = std::mem::replace(&mut self.scene, scene);
        match self.evaluate() {
            Ok(json) => {
                self.teeth = None;
                self.solids = None;
                Ok(json)
            }
            Err(e) => {
                self.scene = previous;
                Err(e)
            }
        }
    }

    /// Replaces the scene's target with one read from a file's text (TOML with a
    /// `[target]` table if `is_toml`, else CSV of `x_mm,y_mm` rows) and evaluates, as
    /// [`Design::set`] does; on an error (a bad target named by field) nothing changes.
    #[wasm_bindgen(js_name = setTarget)]
    pub fn set_target(
        &mut self,
        text: &str,
        origin: &str,
        is_toml: bool,
    ) -> Result<String, JsError> {
        let target = parse_target(text, origin, is_toml).map_err(js_error)?;
        let mut scene = self.scene.clone();
        scene.target = Some(Arc::new(target));
        scene.validate_target().map_err(js_error)?;
        self.replace_scene(scene)
    }

    /// Removes the scene's target and evaluates.
    #[wasm_bindgen(js_name = clearTarget)]
    pub fn clear_target(&mut self) -> Result<String, JsError> {
        let mut scene = self.scene.clone();
        scene.target = None;
        self.replace_scene(scene)
    }

    /// The scene's target as a file's `[target]` table (TOML; `noncirc fit --target` and
    /// `setTarget` read it); an error without a target.
    #[wasm_bindgen(js_name = targetToml)]
    pub fn target_toml(&self) -> Result<String, JsError> {
        let target =
            (self.scene.target.as_deref()).ok_or_else(|| js_error("the scene has no target"))?;
        target_toml(target).map_err(js_error)
    }

    /// The pitch curve's kind (`spline`, `bspline`, `fourier`, …).
    #[wasm_bindgen(js_name = curveKind)]
    pub fn curve_kind(&self) -> String {
        serde_json::to_value(&self.scene.gear.curve)
            .ok()
            .and_then(|v| Some(v.get("kind")?.as_str()?.to_string()))
            .unwrap_or_default()
    }

    /// A numeric parameter's value (`train.phi0_deg`, `gear.curve.radii_mm[3]`, …).
    pub fn get(&self, path: &str) -> Result<f64, JsError> {
        let param = Param::parse(path, &self.scene).map_err(js_error)?;
        param
            .get(&self.scene)
            .ok_or_else(|| js_error(format!("{path} is not set in this scene")))
    }

    /// The search space's parameters (the scene's `[[search.free]]`, else the default
    /// space around the design) with their current values, as JSON.
    #[wasm_bindgen(js_name = freeParameters)]
    pub fn free_parameters(&self) -> Result<String, JsError> {
        let problem = SceneProblem::new(&self.scene).map_err(js_error)?;
        let dim = problem.dim();
        let (lower, upper) = (
            problem.decode(&vec![0.0; dim]),
            problem.decode(&vec![1.0; dim]),
        );
        let rows: Vec<FreeValue> = (problem.names().iter().enumerate())
            .map(|(i, name)| FreeValue {
                name: name.to_string(),
                value: self.get(name).unwrap_or(f64::NAN),
                lower: lower[i],
                upper: upper[i],
            })
            .collect();
        to_json(&rows)
    }

    /// Evaluates the design and returns the CLI's `evaluate --format json` report with the
    /// drawings' data (`{report, view}`), as JSON; a design the model refuses is an error
    /// and the previous evaluation stays.
    pub fn evaluate(&mut self) -> Result<String, JsError> {
        let eval = self.evaluator.evaluate(&self.scene).map_err(js_error)?;
        let report = EvaluationReport::new(&self.scene, &eval);
        check_finite(&report).map_err(js_error)?;
        // The evaluation has prepared the target (it would have refused a bad one).
        let prepared = self
            .evaluator
            .prepared_target(&self.scene)
            .transpose()
            .map_err(js_error)?;
        let view = crate::view::View::new(&self.scene, &eval, prepared.as_deref());
        // The fit measures with their tolerances, as `fit.json` lists them.
        let fit_measures = match (&eval.fit, &self.scene.target) {
            (Some(fit), Some(target)) => fit_measure_rows(fit, target),
            _ => Vec::new(),
        };
        self.evaluation = Some(eval);
        to_json(
            &serde_json::json!({ "report": report, "view": view, "fit_measures": fit_measures }),
        )
    }

    /// The mechanism at carrier angle `carrier_deg` (after [`Design::evaluate`]), as JSON.
    pub fn frame(&self, carrier_deg: f64) -> Result<String, JsError> {
        let kin = (self.evaluation.as_ref())
            .and_then(|e| e.kinematics.as_ref())
            .ok_or_else(|| js_error("no three-arm mechanism evaluated yet"))?;
        let frame = crate::view::Frame::new(kin, self.teeth.as_ref(), carrier_deg.to_radians());
        to_json(&frame)
    }

    /// Evaluates the design `n` times without building a report (the page times it).
    #[wasm_bindgen(js_name = evaluateRepeatedly)]
    pub fn evaluate_repeatedly(&mut self, n: u32) -> Result<f64, JsError> {
        let mut sum = 0.0;
        for _ in 0..n {
            sum += (self.evaluator.evaluate(&self.scene).map_err(js_error)?).total_violation();
        }
        Ok(sum)
    }

    /// The parameter guide (the paper's heuristic made visible): for the objective named
    /// `objective` (empty: the one with the least normalised margin among those the free
    /// parameters move; an objective pinned at its bound whatever the design, as "does not
    /// push the seedling" usually is, guides nothing), for each free parameter the central
    /// difference of that margin over ±0.1 % of the parameter's range, per tenth of the
    /// range, and every missed objective, as JSON. An unknown name is an error naming the
    /// scene's objectives.
    pub fn guide(&mut self, objective: &str) -> Result<String, JsError> {
        let problem = SceneProblem::new(&self.scene).map_err(js_error)?;
        let eval = self.evaluator.evaluate(&self.scene).map_err(js_error)?;
        let margins = normalised_margins(&eval, &self.scene);
        let dim = problem.dim();
        let (lower, upper) = (
            problem.decode(&vec![0.0; dim]),
            problem.decode(&vec![1.0; dim]),
        );
        let mut scratch = self.scene.clone();
        // Per parameter: every objective's margin change per tenth of its range.
        let mut slopes: Vec<Option<Vec<f64>>> = Vec::with_capacity(dim);
        for (i, name) in problem.names().iter().enumerate() {
            let param = Param::parse(name, &self.scene).map_err(js_error)?;
            let x = param.get(&self.scene).unwrap_or(f64::NAN);
            let h = 1e-3 * (upper[i] - lower[i]);
            let mut margins_at = |v: f64| {
                param.set(&mut scratch, v);
                let m = (self.evaluator.evaluate(&scratch).ok())
                    .map(|e| normalised_margins(&e, &scratch));
                param.set(&mut scratch, x);
                m
            };
            slopes.push(match (margins_at(x + h), margins_at(x - h)) {
                (Some(up), Some(down)) => Some(
                    (up.iter().zip(&down))
                        .map(|(u, d)| (u - d) / (2.0 * h) * 0.1 * (upper[i] - lower[i]))
                        .collect(),
                ),
                _ => None,
            });
        }
        let moved =
            |k: usize| (slopes.iter().flatten()).any(|s| s[k].is_finite() && s[k].abs() > MOVED);
        let least = |candidates: &mut dyn Iterator<Item = usize>| {
            candidates.min_by(|&a, &b| margins[a].total_cmp(&margins[b]))
        };
        let names: Vec<&'static str> = eval.objectives.iter().map(|o| o.kind.name()).collect();
        let chosen = !objective.is_empty();
        let worst = if chosen {
            names.iter().position(|n| *n == objective).ok_or_else(|| {
                js_error(format!(
                    "unknown objective '{objective}' to guide by (one of {})",
                    names.join(", ")
                ))
            })?
        } else {
            least(&mut (0..margins.len()).filter(|&k| moved(k)))
                .or_else(|| least(&mut (0..margins.len())))
                .ok_or_else(|| js_error("the scene has no objectives"))?
        };
        let rows = (problem.names().iter().zip(&slopes))
            .map(|(name, s)| GuideRow {
                name: name.to_string(),
                slope: s.as_ref().map(|s| s[worst]).filter(|s| s.is_finite()),
            })
            .collect();
        to_json(&Guide {
            worst: names[worst],
            worst_margin: margins[worst],
            rows,
            chosen,
            missed: (eval.objectives.iter())
                .filter(|o| o.violation > 0.0)
                .map(|o| o.kind.name())
                .collect(),
        })
    }

    /// Every objective's normalised margin at `steps` values of `path` from `from` to `to`
    /// (the paper's §4.2 one parameter at a time), as JSON.
    pub fn sweep(&mut self, path: &str, from: f64, to: f64, steps: u32) -> Result<String, JsError> {
        let param = Param::parse(path, &self.scene).map_err(js_error)?;
        if !(2..=1000).contains(&steps) || !from.is_finite() || !to.is_finite() {
            return Err(js_error(format!(
                "sweep of {path}: expected finite ends and 2 to 1000 steps (got {from}, {to}, {steps})"
            )));
        }
        let mut scratch = self.scene.clone();
        let rows: Vec<SweepStep> = (0..steps)
            .map(|i| {
                let value = from + (to - from) * f64::from(i) / f64::from(steps - 1);
                param.set(&mut scratch, value);
                let margins = (self.evaluator.evaluate(&scratch).ok())
                    .map(|e| normalised_margins(&e, &scratch));
                SweepStep { value, margins }
            })
            .collect();
        to_json(&rows)
    }

    /// The pitch curves as the CLI's `gear --export` writes them: DXF and SVG, as JSON
    /// `[{name, text}]`.
    #[wasm_bindgen(js_name = pitchFiles)]
    pub fn pitch_files(&self) -> Result<String, JsError> {
        let pair = (self.evaluation.as_ref())
            .and_then(Evaluation::pair)
            .ok_or_else(|| js_error("no gear pair evaluated yet"))?;
        let second = (self.evaluation.as_ref())
            .and_then(|e| e.kinematics.as_ref())
            .and_then(|k| k.second_pair());
        let outlines = noncirc::export::train_outlines(pair, second).map_err(js_error)?;
        to_json(&[
            File {
                name: "pitch_curves.dxf".into(),
                text: noncirc::export::dxf(&outlines),
            },
            File {
                name: "pitch_curves.svg".into(),
                text: noncirc::export::svg(&outlines),
            },
        ])
    }

    /// The train at its working speed as `noncirc dynamics` computes it (after
    /// [`Design::evaluate`]): the cycle's summary, the carrier's speed with a constant
    /// drive torque, the flywheel needed, and the curves of `quantity` (one of
    /// `dynamicsQuantities`) over the carrier turn, as JSON. An error names a scene without
    /// a train or an unknown quantity.
    pub fn dynamics(&self, quantity: &str) -> Result<String, JsError> {
        let eval = self.evaluated()?;
        let report = report_from(&self.scene, eval, false).map_err(js_error)?;
        let view = DynamicsView::new(&report, quantity).ok_or_else(|| {
            let names: Vec<&str> = QUANTITIES.iter().map(|(n, ..)| *n).collect();
            js_error(format!(
                "unknown dynamics quantity '{quantity}' (one of {})",
                names.join(", ")
            ))
        })?;
        check_finite(&view).map_err(js_error)?;
        to_json(&view)
    }

    /// The teeth's strength as `noncirc dynamics` reports it (cut as `noncirc teeth` cuts
    /// them, stressed by the dynamics' mesh forces), as JSON; an error says why the teeth
    /// cannot be cut. Half a second natively for a design: the page asks for it.
    pub fn strength(&self) -> Result<String, JsError> {
        let eval = self.evaluated()?;
        let d = dynamics_from(&self.scene, eval).map_err(js_error)?;
        let s = strength_from(&self.scene, eval, &d)
            .map_err(|e| js_error(format!("the teeth cannot be cut: {e}")))?;
        check_finite(&s).map_err(js_error)?;
        to_json(&s)
    }

    /// The last evaluation, or an error before the first.
    fn evaluated(&self) -> Result<&Evaluation, JsError> {
        (self.evaluation.as_ref()).ok_or_else(|| js_error("the design is not evaluated yet"))
    }

    /// Cuts the design's teeth as `noncirc teeth` does (the frames then draw them) and
    /// returns its table of checks; a pair that cannot be cut is an error naming why.
    #[wasm_bindgen(js_name = cutTeeth)]
    pub fn cut_teeth(&mut self) -> Result<String, JsError> {
        let run = TeethRun::from_scene(&self.scene, 0.0).map_err(js_error)?;
        let table = run.table();
        self.teeth = Some(run);
        Ok(table)
    }

    /// Draws pitch curves again instead of teeth.
    #[wasm_bindgen(js_name = dropTeeth)]
    pub fn drop_teeth(&mut self) {
        self.teeth = None;
    }

    /// The solids of `noncirc cad` for the 3D view (the teeth cut as `noncirc teeth` cuts
    /// them, or the ones already cut; lines and arcs within 1 µm as the CLI's): each part's
    /// name, thickness and volume, as JSON `[{name, thickness_mm, volume_mm3}]`. An error
    /// says why the teeth cannot be cut or which `[cad]` dimension does not fit.
    #[wasm_bindgen(js_name = solidParts)]
    pub fn solid_parts(&mut self) -> Result<String, JsError> {
        let run = match &self.teeth {
            Some(run) => run.clone(),
            None => TeethRun::from_scene(&self.scene, 0.0).map_err(js_error)?,
        };
        let assembly = Assembly::from_run(&self.scene, &run, 1e-3).map_err(js_error)?;
        let parts: Vec<_> = (assembly.parts.iter().zip(assembly.volumes()))
            .map(|(p, v)| serde_json::json!({ "name": p.name, "thickness_mm": p.thickness_mm, "volume_mm3": v }))
            .collect();
        self.solids = Some((assembly, run));
        to_json(&parts)
    }

    fn solids(&self) -> Result<&(Assembly, TeethRun), JsError> {
        (self.solids.as_ref()).ok_or_else(|| js_error("the solids are not made yet"))
    }

    /// Part `part`'s triangles in its own frame (mm; x, y, z of each corner, outward by
    /// the right-hand rule), its arcs divided within `chord_mm`.
    #[wasm_bindgen(js_name = solidMesh)]
    pub fn solid_mesh(&self, part: usize, chord_mm: f64) -> Result<Vec<f32>, JsError> {
        let p = (self.solids()?.0.parts.get(part)).ok_or_else(|| js_error("no such part"))?;
        let tris = stl::triangles(p, chord_mm).map_err(js_error)?;
        Ok(tris.iter().flatten().flatten().map(|&x| x as f32).collect())
    }

    /// Every copy of the parts at carrier angle `carrier_deg` (a train; a gear pair stands
    /// still), as `noncirc cad --format json`'s `instances`: JSON `[{name, part, at_mm,
    /// angle_deg}]`.
    #[wasm_bindgen(js_name = solidPlacements)]
    pub fn solid_placements(&self, carrier_deg: f64) -> Result<String, JsError> {
        to_json(&self.placements_at(carrier_deg)?)
    }

    /// `assembly.json` as `noncirc cad --carrier-deg θ` writes it.
    #[wasm_bindgen(js_name = solidManifest)]
    pub fn solid_manifest(&self, carrier_deg: f64) -> Result<String, JsError> {
        let mut assembly = self.solids()?.0.clone();
        if assembly.carrier_deg.is_some() {
            assembly.instances = self.placements_at(carrier_deg)?;
            assembly.carrier_deg = Some(carrier_deg);
        }
        serde_json::to_string_pretty(&assembly.manifest(1e-3)).map_err(js_error)
    }

    /// Every copy placed at `carrier_deg` (a gear pair stands still).
    fn placements_at(&self, carrier_deg: f64) -> Result<Vec<Instance>, JsError> {
        let (assembly, run) = self.solids()?;
        let kin = self.evaluation.as_ref().and_then(|e| e.kinematics.as_ref());
        Ok(match (assembly.carrier_deg, kin) {
            (Some(_), Some(kin)) => assembly.train_instances(&self.scene, kin, run, carrier_deg),
            _ => assembly.instances.clone(),
        })
    }

    /// Part `part` as `noncirc cad` writes its STL (binary, chords within 1 µm).
    #[wasm_bindgen(js_name = solidStl)]
    pub fn solid_stl(&self, part: usize) -> Result<Vec<u8>, JsError> {
        let p = (self.solids()?.0.parts.get(part)).ok_or_else(|| js_error("no such part"))?;
        let tris = stl::triangles(p, 1e-3).map_err(js_error)?;
        Ok(stl::binary(&p.name, &tris))
    }

    /// The toothed gears as `noncirc teeth --export` writes them (assembled at carrier
    /// angle `carrier_deg`, lines and arcs within 1 µm of every outline point), as JSON
    /// `[{name, text}]`. Teeth that
    /// fail a check are refused, naming the checks, unless `force` (as `--force`).
    #[wasm_bindgen(js_name = teethFiles)]
    pub fn teeth_files(&self, carrier_deg: f64, force: bool) -> Result<String, JsError> {
        let run = TeethRun::from_scene(&self.scene, carrier_deg).map_err(js_error)?;
        let failures = run.failures();
        if !failures.is_empty() && !force {
            return Err(JsError::new(&format!(
                "not exported: the teeth fail {} ({}); tick \"even if a check fails\" to export \
                 them anyway",
                run.failed_checks(),
                failures.join("; ")
            )));
        }
        let files: Vec<File> = (run.files(1e-3).into_iter())
            .map(|(name, text)| File {
                name: name.into(),
                text,
            })
            .collect();
        to_json(&files)
    }
}
