//! Staged evaluation: pitch curve → closure → kinematics → each objective (and the moving
//! box apart), then the search constraints. A scene runs only the stages its outputs
//! need; counters prove it.

use crate::curve::PitchCurve;
use crate::error::{Error, Result};
use crate::evaluation::{Evaluation, GearSummary, PairGeometry};
use crate::events::Picking;
use crate::fit::fit_report;
use crate::gear::{GearPair, ModuleReading};
use crate::measure_value::Measured;
use crate::moving_box::evaluate_box_with;
use crate::objective_kind::ObjectiveKind;
use crate::objectives::{objective_value, ObjectiveValue};
use crate::params::pulled_values;
use crate::planetary::{ClosedGears, Kinematics, SampledTrain};
use crate::quadrature::SpectralIntegrator;
use crate::resolution::Resolution;
use crate::scene::{GearSpec, Scene, SceneKind};
use crate::strength::train_strength;
use crate::target::{PreparedTarget, Target};
use crate::teeth::{TeethReport, ToothedPair};
use serde::Serialize;
use std::sync::Arc;

/// What [`Evaluator::evaluate_unless_beaten`] gives.
// Returned by value and moved once, as `Result<Evaluation>` is: a box would cost an
// allocation per evaluation.
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
pub enum Screened {
    /// The whole evaluation.
    Evaluated(Evaluation),
    /// Stopped part-way: the design's normalised violation is at least this, which is
    /// above the cutoff.
    Beaten { violation_at_least: f64 },
}

/// How many times each stage ran.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct StageCounts {
    pub pitch_curve: u64,
    pub closure: u64,
    pub kinematics: u64,
    pub events: u64,
    /// Per objective, in `ObjectiveKind::ALL` order.
    pub objectives: [u64; 11],
    pub moving_box: u64,
    /// Toothed pairs cut and checked (the module rule `teeth`).
    pub teeth: u64,
    /// Fits to the scene's target measured.
    pub fit: u64,
    /// Strength checks (dynamics at working speed, teeth cut, stresses) run for the
    /// objectives `bending_safety` and `contact_safety`.
    pub strength: u64,
}

/// A design's solved train, kept with the gear section it was solved for, so that designs
/// with the same gears are evaluated on them reassembled ([`Evaluator::evaluate_keeping`]):
/// the Sobol designs that change only the train's assembly.
#[derive(Debug, Clone)]
pub struct KeptGears {
    gear: GearSpec,
    kin: Kinematics,
}

impl KeptGears {
    /// `eval`'s train, `scene` the scene evaluated (`None`: no train was solved).
    pub fn of(scene: &Scene, eval: Evaluation) -> Option<Self> {
        Some(Self {
            gear: scene.gear.clone(),
            kin: eval.kinematics?,
        })
    }
}

/// Runs scenes through the stages they need, counting each stage. Keep one per thread:
/// it holds the planned FFTs that repeated evaluations reuse.
#[derive(Debug, Clone, Default)]
pub struct Evaluator {
    counts: StageCounts,
    integrator: Option<SpectralIntegrator>,
    /// The last target prepared, and what its preparation gave: kept while scenes bring
    /// the same target.
    target: Option<(Arc<Target>, Result<Arc<PreparedTarget>>)>,
}

impl Evaluator {
    pub fn new() -> Self {
        Self::default()
    }

    /// An evaluator with its transforms already planned for `resolution` (if it is valid;
    /// evaluating then reports why not): its clones share the plans, so parallel workers
    /// start without planning their own.
    pub fn planned(resolution: &Resolution) -> Self {
        Self {
            counts: StageCounts::default(),
            integrator: resolution
                .validate()
                .is_ok()
                .then(|| SpectralIntegrator::new(resolution.samples_per_turn)),
            target: None,
        }
    }

    /// The planned transforms for `n` samples per turn (planned on first use).
    fn integrator(&mut self, n: usize) -> &mut SpectralIntegrator {
        self.integrator
            .get_or_insert_with(|| SpectralIntegrator::new(n))
    }

    /// Prepares `scene`'s target, if it has one, so that this evaluator's clones start
    /// with it (a bad target's error is kept and returned by each evaluation).
    pub fn prepare_target(&mut self, scene: &Scene) {
        if let Some(t) = &scene.target {
            let _ = self.prepared(t);
        }
    }

    /// `scene`'s target prepared, if it has one (kept while scenes bring the same target:
    /// what the evaluations measure against).
    pub fn prepared_target(&mut self, scene: &Scene) -> Option<Result<Arc<PreparedTarget>>> {
        scene.target.as_ref().map(|t| self.prepared(t))
    }

    /// `target` prepared (once for a run of scenes that share it, by pointer or value).
    fn prepared(&mut self, target: &Arc<Target>) -> Result<Arc<PreparedTarget>> {
        let cached =
            (self.target.as_ref()).is_some_and(|(t, _)| Arc::ptr_eq(t, target) || **t == **target);
        if !cached {
            self.target = Some((target.clone(), target.prepare().map(Arc::new)));
        }
        self.target.as_ref().expect("just prepared").1.clone()
    }

    /// Stage executions so far.
    pub fn counts(&self) -> StageCounts {
        self.counts
    }

    /// Evaluates `scene` at its own resolution.
    ///
    /// ```
    /// use noncirc_core::{Evaluator, ObjectiveKind, Scene};
    ///
    /// let scene = Scene::default(); // the three-arm paper's design
    /// let eval = Evaluator::new().evaluate(&scene).unwrap();
    /// // Every objective the scene asks for, with its value, bounds and violation.
    /// assert_eq!(eval.objectives.len(), scene.objectives.len());
    /// // The paper's picking angle is met; its sharp pitch curve leaves no module of 2.5 mm.
    /// let picking = eval.objective(ObjectiveKind::PickingAngle).unwrap();
    /// assert!(picking.violation == 0.0 && (picking.value - 0.30).abs() < 0.01);
    /// assert!(eval.objective(ObjectiveKind::Module).unwrap().violation > 2.0);
    /// // The picking and planting instants are located on arm I's path.
    /// let events = eval.events.as_ref().unwrap();
    /// assert!(events.picking.tip_mm.y > events.planting.tip_mm.y);
    /// ```
    pub fn evaluate(&mut self, scene: &Scene) -> Result<Evaluation> {
        self.evaluate_at(scene, &scene.resolution)
    }

    /// The teeth stage: runs only under the module rule `teeth`.
    fn teeth(&mut self, scene: &Scene, curve: &PitchCurve, a: f64) -> Result<Option<TeethReport>> {
        let rule = &scene.gear.module;
        match (rule.rule, rule.teeth) {
            (ModuleReading::Teeth, Some(z)) => {
                self.counts.teeth += 1;
                Ok(Some(
                    ToothedPair::cut(curve, a, z, &scene.gear.teeth)?.report,
                ))
            }
            _ => Ok(None),
        }
    }

    /// Builds the scene's pitch curves, closes the pairs and solves the train at
    /// `resolution` (the stages before the events).
    pub fn solve_train(&mut self, scene: &Scene, resolution: &Resolution) -> Result<Kinematics> {
        self.counts.kinematics += 1;
        Ok(self.close_gears(scene, resolution)?.assemble())
    }

    /// Builds the scene's pitch curves and closes its pairs on the train's grids at
    /// `resolution`, before the arm is placed.
    fn close_gears(&mut self, scene: &Scene, resolution: &Resolution) -> Result<ClosedGears> {
        let sampled = self.sample_train(scene, resolution)?;
        self.close(sampled)
    }

    /// Builds the scene's pitch curves and samples the sun on the train's grid.
    fn sample_train(&mut self, scene: &Scene, resolution: &Resolution) -> Result<SampledTrain> {
        self.counts.pitch_curve += 1;
        let (curve, second) = scene.gear.curves()?;
        SampledTrain::sample(curve, second, &scene.train, resolution)
    }

    /// Closes the sampled train's pairs.
    fn close(&mut self, sampled: SampledTrain) -> Result<ClosedGears> {
        self.counts.closure += 1;
        let integrator = self.integrator(sampled.resolution().samples_per_turn);
        sampled.close(integrator)
    }

    /// As [`Evaluator::evaluate_at`], but stops part-way a design whose normalised
    /// violation ([`Evaluation::normalised_violation`]) is already known to exceed
    /// `cutoff`: a search that keeps such a design nowhere need not finish it. The
    /// module's violation is bounded below once the sun is sampled (by its own curvature)
    /// and known once the gears are closed: a three-arm design whose module alone exceeds
    /// `cutoff` is stopped there (about half of a DE search's trials, a third before the
    /// closure). Once picking is located, the picking angle bounds it (10 % of a DE
    /// search's trials stop there, before the other events); once the events are, the
    /// objectives but the interference do, and a design they put above `cutoff` is not
    /// scanned for interference (another 7 %). Every other design is evaluated whole, as
    /// `evaluate_at` does.
    pub fn evaluate_unless_beaten(
        &mut self,
        scene: &Scene,
        resolution: &Resolution,
        cutoff: f64,
    ) -> Result<Screened> {
        self.evaluate_beside_unless_beaten(scene, None, resolution, cutoff)
    }

    /// As [`Evaluator::evaluate_unless_beaten`] for a scene written over a copy of
    /// `checked`, a scene that passed [`Scene::validate`] ([`Scene::validate_beside`]).
    pub(crate) fn evaluate_beside_unless_beaten(
        &mut self,
        scene: &Scene,
        checked: Option<&Scene>,
        resolution: &Resolution,
        cutoff: f64,
    ) -> Result<Screened> {
        if !matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter) {
            return (self.evaluate_beside(scene, checked, resolution)).map(Screened::Evaluated);
        }
        scene.validate_beside(checked)?;
        resolution.validate()?;
        let gears = if scene.objectives.contains(&ObjectiveKind::Module) {
            // The objective's normalised violation for a module of `mm`, before its teeth's
            // shortfalls (which only add to it); it grows as the module shrinks.
            let violation = |mm: f64| {
                ObjectiveValue::new(ObjectiveKind::Module, mm, &scene.bounds)
                    .normalised_violation(&scene.bounds)
            };
            let beaten = |least: f64| {
                (least > cutoff).then_some(Screened::Beaten {
                    violation_at_least: least,
                })
            };
            let sampled = self.sample_train(scene, resolution)?;
            if let Some(b) = beaten(violation(sampled.module_bound(&scene.gear.module))) {
                return Ok(b);
            }
            let gears = self.close(sampled)?;
            if let Some(b) = beaten(violation(gears.module(&scene.gear.module).module_max_mm)) {
                return Ok(b);
            }
            gears
        } else {
            self.close_gears(scene, resolution)?
        };
        self.counts.kinematics += 1;
        let mut out = Evaluation::empty(scene, *resolution);
        Ok(
            match self.mechanism_unless_beaten(scene, gears.assemble(), &mut out, cutoff)? {
                Some(least) => Screened::Beaten {
                    violation_at_least: least,
                },
                None => Screened::Evaluated(out),
            },
        )
    }

    /// Evaluates a three-arm scene on a train already solved for it (`kin`'s curve and
    /// train are the scene's, or a [`Kinematics::reassembled`] variant of them): the
    /// events, the objectives and the moving box, without closing the gears again. The
    /// tolerance analysis evaluates its assembly variants this way: `scene` is a validated
    /// scene with another train and agronomy, and only those two are checked here.
    pub(crate) fn evaluate_solved(&mut self, scene: &Scene, kin: Kinematics) -> Result<Evaluation> {
        scene.train.validate()?;
        scene.check_fields("agronomy")?;
        if !matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter) {
            return Err(Error::OutOfRange {
                name: "kind".into(),
                value: f64::NAN,
                expected: format!(
                    "a three_arm or transplanter scene (not {})",
                    scene.kind.name()
                ),
            });
        }
        self.counts.kinematics += 1;
        let mut out = Evaluation::empty(scene, kin.resolution());
        self.mechanism(scene, kin, &mut out)?;
        Ok(out)
    }

    /// As [`Evaluator::evaluate`], on the gears `kept` when they are the scene's (the same
    /// gear section and resolution, and a train that [`Kinematics::reassembled`] takes): no
    /// sampling, closure or module again, and the results within rounding of a train
    /// solved anew.
    pub fn evaluate_keeping(
        &mut self,
        scene: &Scene,
        kept: Option<&KeptGears>,
    ) -> Result<Evaluation> {
        let three_arm = matches!(scene.kind, SceneKind::Mechanism | SceneKind::Transplanter);
        let fits = |k: &&KeptGears| {
            three_arm && k.gear == scene.gear && k.kin.resolution() == scene.resolution
        };
        let Some(kept) = kept.filter(fits) else {
            return self.evaluate(scene);
        };
        scene.validate()?;
        match kept.kin.reassembled(&scene.train, 0.0) {
            Ok(kin) => self.evaluate_solved(scene, kin),
            Err(_) => self.evaluate(scene),
        }
    }

    /// The three-arm stages after the train is solved: events, objectives, moving box,
    /// then the search constraints.
    fn mechanism(&mut self, scene: &Scene, kin: Kinematics, out: &mut Evaluation) -> Result<()> {
        // No violation exceeds an infinite cutoff: the evaluation is always whole.
        self.mechanism_unless_beaten(scene, kin, out, f64::INFINITY)
            .map(drop)
    }

    /// As [`Evaluator::mechanism`], but stopped at the first of two bounds that exceeds
    /// `cutoff`, which it returns (`out` is then incomplete): the picking angle's term,
    /// once picking is located, before the other events; and the terms of every objective
    /// but the interference, before the interference scan, the costliest objective. The
    /// latter sum runs in [`Evaluation::normalised_violation`]'s order without the
    /// interference's term. Every term is non-negative and rounding is monotone, so
    /// neither bound is ever above the whole design's violation.
    fn mechanism_unless_beaten(
        &mut self,
        scene: &Scene,
        kin: Kinematics,
        out: &mut Evaluation,
        cutoff: f64,
    ) -> Result<Option<f64>> {
        let resolution = &kin.resolution();
        out.centre_distance_mm = Some(kin.centre_distance());
        let coupled = scene.kind == SceneKind::Transplanter;
        let target = match &scene.target {
            Some(t) => Some((t.clone(), self.prepared(t)?)),
            None => None,
        };
        let target_events = target.as_ref().is_some_and(|(t, _)| t.needs_events());
        let ev = if coupled || target_events || scene.objectives.iter().any(|o| o.needs_events()) {
            self.counts.events += 1;
            let picking = Picking::locate(&kin, &scene.agronomy);
            // With a finite cutoff, the picking angle's term alone may already exceed it
            // (the first of the whole violation's terms that the events give).
            if cutoff < f64::INFINITY && scene.objectives.contains(&ObjectiveKind::PickingAngle) {
                let angle = picking.attitude_deg();
                let least = ObjectiveValue::new(ObjectiveKind::PickingAngle, angle, &scene.bounds)
                    .normalised_violation(&scene.bounds);
                // A value that broke down is left for the whole evaluation to refuse.
                if least > cutoff && !angle.is_nan() {
                    return Ok(Some(least));
                }
            }
            Some(picking.events(&kin, &scene.agronomy))
        } else {
            None
        };
        let gear_module = scene
            .objectives
            .contains(&ObjectiveKind::Module)
            .then(|| kin.module(&scene.gear.module));
        if gear_module.is_some() {
            out.teeth = self.teeth(scene, kin.curve(), kin.centre_distance())?;
            if let Some(second) = kin.second_pair() {
                out.second_teeth = (self.teeth(scene, second.curve(), second.centre_distance()))
                    .map_err(|e| Error::SecondPair(Box::new(e)))?;
            }
        }
        if let (true, Some(ev)) = (scene.objectives.iter().any(|o| o.needs_strength()), &ev) {
            self.counts.strength += 1;
            match train_strength(&kin, ev, scene) {
                Ok(s) => out.strength = Some(s),
                Err(e) => out.strength_unavailable = Some(e.to_string()),
            }
        }
        let objective = |this: &mut Self, kind: ObjectiveKind, out: &Evaluation| {
            this.counts.objectives[kind as usize] += 1;
            let value = objective_value(
                kind,
                &kin,
                ev.as_ref(),
                &scene.agronomy,
                gear_module.as_ref(),
                out.strength.as_ref(),
            );
            let mut value = ObjectiveValue::new(kind, value, &scene.bounds);
            if kind == ObjectiveKind::Module {
                value.add_teeth(out.teeth.as_ref());
                value.add_teeth(out.second_teeth.as_ref());
            }
            value
        };
        // With a finite cutoff, the interference's place in the list is kept for it.
        let deferred = (cutoff < f64::INFINITY)
            .then(|| {
                scene
                    .objectives
                    .iter()
                    .position(|&k| k == ObjectiveKind::Interference)
            })
            .flatten();
        for (i, &kind) in scene.objectives.iter().enumerate() {
            if Some(i) != deferred {
                let value = objective(self, kind, out);
                out.objectives.push(value);
            }
        }
        if let Some(i) = deferred {
            let least = (out.objectives.iter())
                .map(|o| o.normalised_violation(&scene.bounds))
                .sum::<f64>();
            // A value that broke down is left for the safety net below to refuse.
            if least > cutoff && !out.objectives.iter().any(|o| o.value.is_nan()) {
                return Ok(Some(least));
            }
            let value = objective(self, ObjectiveKind::Interference, out);
            out.objectives.insert(i, value);
        }
        if coupled {
            let window = ev
                .as_ref()
                .map(|e| e.picking_window_rad)
                .unwrap_or_default();
            let span = (window[1] - window[0]) * scene.moving_box.input_turns_per_carrier_turn;
            let centre = scene.moving_box.window_centre_deg.to_radians();
            self.counts.moving_box += 1;
            out.moving_box = Some(evaluate_box_with(
                &scene.moving_box,
                Some([centre - span / 2.0, centre + span / 2.0]),
                resolution,
                self.integrator(resolution.samples_per_turn),
            )?);
        }
        out.gear = gear_module.map(|module| GearSummary {
            centre_distance_mm: kin.centre_distance(),
            closure_error_mm: kin.pair().closure().error_estimate,
            perimeter_mm: kin.pair().perimeter(),
            second: kin.second_pair().map(PairGeometry::of),
            module,
        });
        if let Some((target, prepared)) = &target {
            self.counts.fit += 1;
            let design = pulled_values(scene)?;
            out.fit = Some(fit_report(&kin, ev.as_ref(), target, prepared, &design));
        }
        out.events = ev;
        out.kinematics = Some(kin);
        // Safety net: a value that broke down numerically is an error, never a NaN.
        if let Some(o) = out.objectives.iter().find(|o| o.value.is_nan()) {
            return Err(Error::NonFinite {
                name: format!(
                    "objective '{}' (numerical breakdown for this design)",
                    o.kind.name()
                ),
                value: o.value,
            });
        }
        if !scene.search.constraints.is_empty() {
            let measured = Measured::new(out, scene);
            let values = (scene.search.constraints.iter())
                .map(|c| c.score(c.measure.value(&measured)))
                .collect();
            out.constraints = values;
        }
        Ok(None)
    }

    /// Evaluates `scene` at `resolution`, running only the stages its outputs need.
    pub fn evaluate_at(&mut self, scene: &Scene, resolution: &Resolution) -> Result<Evaluation> {
        self.evaluate_beside(scene, None, resolution)
    }

    /// As [`Evaluator::evaluate_at`] for a scene written over a copy of `checked`, a
    /// scene that passed [`Scene::validate`] ([`Scene::validate_beside`]).
    pub(crate) fn evaluate_beside(
        &mut self,
        scene: &Scene,
        checked: Option<&Scene>,
        resolution: &Resolution,
    ) -> Result<Evaluation> {
        scene.validate_beside(checked)?;
        resolution.validate()?;
        let mut out = Evaluation::empty(scene, *resolution);
        match scene.kind {
            SceneKind::Gear => {
                self.counts.pitch_curve += 1;
                let curve = scene.gear.curve.build()?;
                self.counts.closure += 1;
                let integrator = self.integrator(resolution.samples_per_turn);
                let pair = GearPair::solve_with(curve, *resolution, integrator)?;
                let module = pair.module(&scene.gear.module);
                out.teeth = self.teeth(scene, pair.curve(), pair.centre_distance())?;
                out.centre_distance_mm = Some(pair.centre_distance());
                out.gear = Some(GearSummary {
                    centre_distance_mm: pair.centre_distance(),
                    closure_error_mm: pair.closure().error_estimate,
                    perimeter_mm: pair.perimeter(),
                    second: None,
                    module,
                });
                for &kind in &scene.objectives {
                    self.counts.objectives[kind as usize] += 1;
                    let mut value = ObjectiveValue::new(kind, module.module_max_mm, &scene.bounds);
                    value.add_teeth(out.teeth.as_ref());
                    out.objectives.push(value);
                }
                out.gear_pair = Some(pair);
            }
            SceneKind::Mechanism | SceneKind::Transplanter => {
                let kin = self.solve_train(scene, resolution)?;
                self.mechanism(scene, kin, &mut out)?;
            }
            SceneKind::MovingBox => {
                self.counts.moving_box += 1;
                out.moving_box = Some(evaluate_box_with(
                    &scene.moving_box,
                    None,
                    resolution,
                    self.integrator(resolution.samples_per_turn),
                )?);
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::CurveSpec;
    use crate::events::housing_radius;

    /// The objectives' values, as bits.
    fn objective_bits(e: &Evaluation) -> Vec<u64> {
        e.objectives.iter().map(|o| o.value.to_bits()).collect()
    }

    /// A design that changes only the train's assembly is evaluated on the kept gears
    /// (no closure), within rounding of the train solved anew; one with other gears, or a
    /// train the reassembly refuses, is solved anew, bit for bit as `evaluate`.
    #[test]
    fn kept_gears_serve_the_designs_that_change_only_the_assembly() {
        let scene = Scene::default();
        let mut evaluator = Evaluator::new();
        let nominal = evaluator.evaluate(&scene).unwrap();
        let kept = KeptGears::of(&scene, nominal.clone()).unwrap();
        type Change = fn(&mut Scene);
        let assembly: [Change; 5] = [
            |s| s.train.phi0_deg += 2.0,
            |s| s.train.beta0_deg -= 3.0,
            |s| s.train.arm_length_mm += 4.0,
            |s| s.train.pusher_offset_mm -= 2.0,
            |s| s.train.gamma0_deg += 1.5,
        ];
        for change in assembly {
            let mut varied = scene.clone();
            change(&mut varied);
            let closures = evaluator.counts().closure;
            let on_kept = evaluator.evaluate_keeping(&varied, Some(&kept)).unwrap();
            assert_eq!(
                evaluator.counts().closure,
                closures,
                "the gears were closed again"
            );
            let anew = evaluator.evaluate(&varied).unwrap();
            assert_ne!(objective_bits(&anew), objective_bits(&nominal));
            for (a, b) in on_kept.objectives.iter().zip(&anew.objectives) {
                let (a, b) = (a.value, b.value);
                assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{a} vs {b}");
            }
        }
        let mut other_gears = scene.clone();
        if let CurveSpec::Spline { radii_mm, .. } = &mut other_gears.gear.curve {
            radii_mm[3] += 0.5;
        }
        let mut two_pairs = scene.clone();
        two_pairs.gear.second_curve = Some(CurveSpec::Ellipse {
            semi_major_mm: 30.0,
            eccentricity: 0.2,
        });
        let kept_two = KeptGears::of(&two_pairs, evaluator.evaluate(&two_pairs).unwrap()).unwrap();
        two_pairs.train.gamma0_deg += 1.5;
        for (varied, kept) in [(&other_gears, &kept), (&two_pairs, &kept_two)] {
            let closures = evaluator.counts().closure;
            let on_kept = evaluator.evaluate_keeping(varied, Some(kept)).unwrap();
            assert!(evaluator.counts().closure > closures);
            let anew = evaluator.evaluate(varied).unwrap();
            assert_eq!(objective_bits(&on_kept), objective_bits(&anew));
        }
        // The same gears in a scene of another kind: that kind's evaluation, no train.
        let mut gear_only = scene.clone();
        gear_only.kind = SceneKind::Gear;
        gear_only.objectives = vec![ObjectiveKind::Module];
        let on_kept = evaluator.evaluate_keeping(&gear_only, Some(&kept)).unwrap();
        assert!(on_kept.kinematics.is_none() && on_kept.gear_pair.is_some());
        let anew = evaluator.evaluate(&gear_only).unwrap();
        assert_eq!(objective_bits(&on_kept), objective_bits(&anew));
    }

    #[test]
    fn a_fit_is_measured_once_per_evaluation_of_a_scene_with_a_target() {
        let mut scene = Scene::default();
        let mut evaluator = Evaluator::new();
        let plain = evaluator.evaluate(&scene).unwrap();
        assert!(plain.fit.is_none());
        assert_eq!(evaluator.counts().fit, 0);
        // The design's own path and events as its target: met, at the tip path's accuracy.
        let kin = plain.kinematics.unwrap();
        let target = crate::fit::target_of(&kin, plain.events.as_ref().unwrap(), 4000);
        scene.target = Some(Arc::new(target));
        for k in 1..=3 {
            let eval = evaluator.evaluate(&scene).unwrap();
            let fit = eval.fit.unwrap();
            assert!(fit.met && fit.path_hausdorff_mm < 0.05, "{fit:?}");
            assert_eq!(evaluator.counts().fit, k);
        }
        // A bad target never evaluates.
        let mut bad = (**scene.target.as_ref().unwrap()).clone();
        bad.x_mm.truncate(2000);
        bad.y_mm.truncate(2000);
        scene.target = Some(Arc::new(bad));
        assert!(matches!(
            evaluator.evaluate(&scene),
            Err(Error::OpenTarget { .. })
        ));
    }

    #[test]
    fn a_design_pull_adds_its_scaled_change_to_the_residuals_and_the_cost() {
        let mut scene = Scene::default();
        let plain = Evaluator::new().evaluate(&scene).unwrap();
        let kin = plain.kinematics.unwrap();
        let mut target = crate::fit::target_of(&kin, plain.events.as_ref().unwrap(), 512);
        scene.target = Some(Arc::new(target.clone()));
        let unpulled = Evaluator::new().evaluate(&scene).unwrap().fit.unwrap();
        assert_eq!(unpulled.design_rms, None);
        // Φ0 = 86° pulled towards 92° with scale 2°: (86 − 92)/2 = −3; S = 145 mm towards
        // itself: 0. RMS √(9/2), cost up by 9/2.
        let pull = |name: &str, value: f64, scale: f64| crate::target::DesignPull {
            name: name.into(),
            value,
            scale,
        };
        target.design = vec![
            pull("train.phi0_deg", 92.0, 2.0),
            pull("train.arm_length_mm", 145.0, 10.0),
        ];
        scene.target = Some(Arc::new(target.clone()));
        scene.validate_target().unwrap();
        let pulled = Evaluator::new().evaluate(&scene).unwrap().fit.unwrap();
        let n = unpulled.residuals.len();
        assert_eq!(pulled.residuals[..n], unpulled.residuals[..]);
        assert_eq!(pulled.residuals[n..], [-3.0, 0.0]);
        assert!((pulled.design_rms.unwrap() - 4.5f64.sqrt()).abs() < 1e-12);
        assert!((pulled.cost - unpulled.cost - 4.5).abs() < 1e-9);
        assert_eq!(
            pulled.met, unpulled.met,
            "a pull weighs in the cost, not in met"
        );
        // A parameter the scene does not have is named, with the nearest paths.
        target.design = vec![pull("train.phi9_deg", 0.0, 1.0)];
        scene.target = Some(Arc::new(target));
        let e = scene.validate_target().unwrap_err();
        assert!(
            matches!(&e, Error::UnknownName { name, nearest, .. }
                if name == "train.phi9_deg" && nearest.iter().any(|n| n == "train.phi0_deg")),
            "{e:?}"
        );
        assert!(Evaluator::new().evaluate(&scene).is_err());
    }

    /// The module's violation stops a design at two stages: bounded by the sun's
    /// curvature before the closure, and known once the gears are closed. The picking
    /// angle stops it once picking is located, and the objectives but the interference
    /// before the interference scan. Each bound is no more than the whole design's
    /// violation. A cutoff at or above the whole violation gives `evaluate_at`'s
    /// evaluation bit for bit.
    #[test]
    fn a_design_beaten_part_way_is_stopped_at_the_first_stage_that_shows_it() {
        // The default scene's module is 2 mm short (the doctest above); its path is made
        // 10 mm lower than asked, and its arms 10 mm closer than allowed.
        let mut scene = Scene::default();
        let first = Evaluator::new().evaluate(&scene).unwrap();
        let value = |kind| first.objective(kind).unwrap().value;
        scene.bounds.trajectory_height_min_mm = value(ObjectiveKind::TrajectoryHeight) + 10.0;
        scene.bounds.clearance_min_mm = value(ObjectiveKind::Interference) + 10.0;
        let res = scene.resolution;
        let whole = Evaluator::new().evaluate(&scene).unwrap();
        let module = whole.objective(ObjectiveKind::Module).unwrap();
        let module = module.normalised_violation(&scene.bounds);
        let total = whole.normalised_violation(&scene.bounds);
        assert!(module > 0.1 && total > module, "{module} {total}");

        // Stages run: (closures, arms, events, interference scans).
        let stopped = |scene: &Scene, cutoff: f64| {
            let mut evaluator = Evaluator::new();
            let least = match evaluator.evaluate_unless_beaten(scene, &res, cutoff) {
                Ok(Screened::Beaten { violation_at_least }) => violation_at_least,
                other => panic!("{cutoff}: {other:?}"),
            };
            let c = evaluator.counts();
            let scans = c.objectives[ObjectiveKind::Interference as usize];
            (least, (c.closure, c.kinematics, c.events, scans))
        };
        // A cutoff below any violation: stopped at the sun's bound, before the closure.
        let (sun, stages) = stopped(&scene, -1.0);
        assert_eq!(stages, (0, 0, 0, 0));
        assert!(sun > 0.0 && sun < module, "{sun} {module}");
        // Between the bound and the module's violation: stopped after the closure.
        assert_eq!(stopped(&scene, sun), (module, (1, 0, 0, 0)));
        // The objectives but the interference, summed in the whole violation's order.
        let others = (whole.objectives.iter())
            .filter(|o| o.kind != ObjectiveKind::Interference)
            .map(|o| o.normalised_violation(&scene.bounds))
            .sum::<f64>();
        assert!(
            others > module && others < total,
            "{others} {module} {total}"
        );
        // Between the module's violation and the others': stopped before the scan.
        assert_eq!(stopped(&scene, module), (others, (1, 1, 1, 0)));
        // A picking angle 30° out of its bounds: stopped at picking, before the other
        // events and the objectives.
        let mut off = scene.clone();
        let angle = value(ObjectiveKind::PickingAngle);
        off.bounds.picking_angle_deg = [angle + 30.0, angle + 40.0];
        let picking = Evaluator::new().evaluate(&off).unwrap();
        let picking = picking.objective(ObjectiveKind::PickingAngle).unwrap();
        let picking = picking.normalised_violation(&off.bounds);
        assert!(picking > module, "{picking} {module}");
        let mut evaluator = Evaluator::new();
        assert!(matches!(
            evaluator.evaluate_unless_beaten(&off, &res, module),
            Ok(Screened::Beaten { violation_at_least }) if violation_at_least == picking
        ));
        assert_eq!(evaluator.counts().objectives, [0; 11]);
        // Without the module, only the scan is left out.
        let mut without_module = scene.clone();
        without_module
            .objectives
            .retain(|&k| k != ObjectiveKind::Module);
        let plain = Evaluator::new().evaluate(&without_module).unwrap();
        let plain_others = (plain.objectives.iter())
            .filter(|o| o.kind != ObjectiveKind::Interference)
            .map(|o| o.normalised_violation(&scene.bounds))
            .sum::<f64>();
        assert!(plain_others > 0.0);
        assert_eq!(stopped(&without_module, 0.0), (plain_others, (1, 1, 1, 0)));

        let plain_total = plain.normalised_violation(&scene.bounds);
        for (scene, whole, cutoff) in [
            (&scene, &whole, total),
            (&scene, &whole, f64::INFINITY),
            (&without_module, &plain, plain_total),
        ] {
            match Evaluator::new().evaluate_unless_beaten(scene, &res, cutoff) {
                Ok(Screened::Evaluated(e)) => {
                    assert_eq!(objective_bits(&e), objective_bits(whole));
                    assert_eq!(e.events.map(|e| e.picking), whole.events.map(|e| e.picking));
                }
                other => panic!("{cutoff}: {other:?}"),
            }
        }
    }

    #[test]
    fn the_paper_design_picks_outside_the_housing() {
        let mut scene = Scene::default();
        scene.resolution.samples_per_turn = 360;
        let eval = Evaluator::new().evaluate(&scene).unwrap();
        let (kin, events) = (eval.kinematics.as_ref().unwrap(), eval.events.unwrap());
        // Farther from the carrier axis than the housing's disc, by a margin.
        let housing = housing_radius(kin, &scene.agronomy);
        assert!(events.picking.tip_mm.hypot() > housing + 15.0, "{housing}");
    }
}
