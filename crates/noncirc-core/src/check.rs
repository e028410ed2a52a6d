//! The scene's checks: its own numbers (agronomy, bounds) against their intervals in the
//! field table ([`crate::reference`]), then what code checks (the models' numbers, which
//! each model checks as a library API of its own, rules over several fields, names,
//! lists); and the search settings.

use crate::error::{finite, Error, Result};
use crate::goal::Goal;
use crate::objective_kind::ObjectiveKind;
use crate::params::{pulled_values, Param};
use crate::reference::{interval_checks, TABLES};
use crate::scene::{Scene, SceneKind, SearchSpec};

impl Scene {
    /// Checks the numbers of one scene table (`agronomy`) against their intervals in the
    /// field table.
    pub(crate) fn check_fields(&self, table: &str) -> Result<()> {
        (interval_checks().iter())
            .filter(|c| TABLES[c.table].0 == table)
            .try_for_each(|c| c.check(self))
    }

    /// Whether `self` and `other` hold the same numbers in `table`, one of the tables
    /// whose numbers the field table checks ([`crate::reference::Checker::Table`]); false
    /// for any other.
    fn same_numbers(&self, other: &Scene, table: &str) -> bool {
        match table {
            "agronomy" => self.agronomy == other.agronomy,
            "bounds" => self.bounds == other.bounds,
            "dynamics" => self.dynamics == other.dynamics,
            "cad" => self.cad == other.cad,
            _ => false,
        }
    }

    /// Whether an evaluation of this scene reads the fields of a scene table (`train`): a
    /// mechanism's train and agronomy only in a mechanism scene, the moving box only where
    /// it moves.
    fn reads(&self, table: &str) -> bool {
        match table {
            "train" | "agronomy" | "dynamics" => {
                matches!(self.kind, SceneKind::Mechanism | SceneKind::Transplanter)
            }
            "moving_box" => {
                matches!(self.kind, SceneKind::MovingBox | SceneKind::Transplanter)
            }
            _ => true,
        }
    }

    /// Checks every value an evaluation uses, naming the bad one: the resolution, the
    /// module and teeth settings, the bounds, a mechanism's train and agronomy, the moving
    /// box, and the objectives against the scene's kind.
    pub fn validate(&self) -> Result<()> {
        self.validate_beside(None)
    }

    /// As [`Scene::validate`] for a scene written over a copy of `checked`, a scene that
    /// passed it: a table whose numbers are still `checked`'s is not held to its intervals
    /// again. A search's design writes its free parameters (the curve, the train) over the
    /// base scene, and its agronomy, bounds, dynamics and CAD tables stay the base's: four
    /// comparisons instead of about fifty interval checks. The settings that code checks on
    /// their own (resolution, module, teeth, the bounds' order, tolerances) are passed
    /// over where they equal `checked`'s; the rules over several fields run whole.
    pub(crate) fn validate_beside(&self, checked: Option<&Scene>) -> Result<()> {
        // The scene's own numbers (agronomy, bounds) against their intervals in the field
        // table, then what code checks: the models' numbers, rules over several fields,
        // names and lists.
        let checks = TABLES.map(|(table, _, _)| {
            self.reads(table) && !checked.is_some_and(|c| self.same_numbers(c, table))
        });
        (interval_checks().iter())
            .filter(|c| checks[c.table])
            .try_for_each(|c| c.check(self))?;
        // A part equal to the checked scene's passed these checks there (a search's
        // designs change the curve and the train, not these).
        let beside = |same: fn(&Scene, &Scene) -> bool| checked.is_some_and(|c| same(self, c));
        if !beside(|a, b| a.resolution == b.resolution) {
            self.resolution.validate()?;
        }
        if !beside(|a, b| a.gear.module == b.gear.module) {
            self.gear.module.validate()?;
        }
        if !beside(|a, b| a.gear.teeth == b.gear.teeth) {
            self.gear.teeth.validate()?;
        }
        if !beside(|a, b| a.bounds == b.bounds) {
            self.bounds.check_order()?;
        }
        if !beside(|a, b| a.tolerances == b.tolerances) {
            self.tolerances.validate()?;
        }
        if matches!(self.kind, SceneKind::MovingBox | SceneKind::Transplanter) {
            self.moving_box.validate()?;
        }
        let mechanism = matches!(self.kind, SceneKind::Mechanism | SceneKind::Transplanter);
        if mechanism {
            // Checked with the scene, so that a file or an edit is refused where the
            // value is set, not at the first evaluation.
            self.train.validate()?;
            if !self.dynamics.material.chars().any(char::is_alphabetic) {
                return Err(Error::BadList {
                    list: "dynamics.material",
                    problem: format!(
                        "{:?} names no material: the strength report says which one its \
                         allowable stresses are",
                        self.dynamics.material
                    ),
                });
            }
            let arms = self.train.arms;
            if !self.resolution.samples_per_turn.is_multiple_of(arms) {
                return Err(Error::OutOfRange {
                    name: "resolution.samples_per_turn".into(),
                    value: self.resolution.samples_per_turn as f64,
                    expected: format!("a multiple of train.arms = {arms}"),
                });
            }
            // The box moves one pot per pick, and the train picks once per arm a turn.
            let turns = self.moving_box.input_turns_per_carrier_turn;
            if self.kind == SceneKind::Transplanter && turns != arms as f64 {
                return Err(Error::OutOfRange {
                    name: "moving_box.input_turns_per_carrier_turn".into(),
                    value: turns,
                    expected: format!(
                        "train.arms = {arms}: the box moves one pot per pick, and the train \
                         picks {arms} times a carrier turn"
                    ),
                });
            }
            if arms == 1 && self.objectives.contains(&ObjectiveKind::Interference) {
                return Err(Error::BadList {
                    list: "objectives",
                    problem: "'interference' needs two arms or more: a one-arm train \
                              (train.arms = 1) has no other arm or planet to strike"
                        .into(),
                });
            }
        }
        if self.gear.second_curve.is_some() && !mechanism {
            return Err(Error::BadList {
                list: "gear.second_curve",
                problem: format!(
                    "set in a {} scene, which has one pair: a second pair needs a three_arm \
                     or transplanter scene (its intermediate drives the planet)",
                    self.kind.name()
                ),
            });
        }
        if let Some(target) = &self.target {
            if !mechanism {
                return Err(Error::BadList {
                    list: "target",
                    problem: format!(
                        "a {} scene has no tip path: a target needs a three_arm or \
                         transplanter scene",
                        self.kind.name()
                    ),
                });
            }
            target.validate()?;
        }
        if mechanism && self.objectives.is_empty() {
            return Err(Error::BadList {
                list: "objectives",
                problem: "empty: a mechanism scene needs at least one objective (with none, \
                          every design would report feasible)"
                    .into(),
            });
        }
        for (i, o) in self.objectives.iter().enumerate() {
            if self.objectives[..i].contains(o) {
                return Err(Error::BadList {
                    list: "objectives",
                    problem: format!(
                        "'{}' is listed twice (its violation would count twice)",
                        o.name()
                    ),
                });
            }
        }
        for o in &self.objectives {
            let allowed =
                mechanism || (self.kind == SceneKind::Gear && *o == ObjectiveKind::Module);
            if !allowed {
                let (can, list) = match self.kind {
                    SceneKind::Gear => ("only 'module'", "[\"module\"]"),
                    _ => ("none of them", "[]"),
                };
                return Err(Error::BadList {
                    list: "objectives",
                    problem: format!(
                        "'{}' cannot be evaluated in a {kind} scene (kind = \"{kind}\"), which \
                         evaluates {can}: write objectives = {list}{}",
                        o.name(),
                        if self.objectives == ObjectiveKind::DEFAULT {
                            " (with no `objectives`, a scene takes every objective)"
                        } else {
                            ""
                        },
                        kind = self.kind.name(),
                    ),
                });
            }
        }
        Ok(())
    }

    /// The target whole, as [`Target::prepare`](crate::target::Target::prepare) checks it
    /// (closed, distinct points, no crossing), and the parameters it pulls: once when a
    /// scene is read, not per design (an evaluation prepares it once and keeps it).
    pub fn validate_target(&self) -> Result<()> {
        let Some(target) = &self.target else {
            return Ok(());
        };
        target.prepare()?;
        pulled_values(self).map(drop)
    }

    /// The search settings: goals this scene can compute, each once; free parameters that
    /// exist, each once, with finite ordered bounds a finite width apart. Checked when a
    /// scene is read and when a search starts (not per design: [`Scene::validate`] is).
    pub fn validate_search(&self) -> Result<()> {
        let population = self.search.population;
        if !(1..=SearchSpec::MAX_POPULATION).contains(&population) {
            return Err(Error::OutOfRange {
                name: "search.population".into(),
                value: population as f64,
                expected: format!("1 to {}", SearchSpec::MAX_POPULATION),
            });
        }
        if self.search.free.len() > SearchSpec::MAX_FREE {
            return Err(Error::OutOfRange {
                name: "search.free (count)".into(),
                value: self.search.free.len() as f64,
                expected: format!("at most {}", SearchSpec::MAX_FREE),
            });
        }
        self.search.screening.validate()?;
        let arms = self.train.arms;
        if !self.search.screening.samples_per_turn.is_multiple_of(arms) {
            return Err(Error::OutOfRange {
                name: "search.screening.samples_per_turn".into(),
                value: self.search.screening.samples_per_turn as f64,
                expected: format!("a multiple of train.arms = {arms}"),
            });
        }
        if self.search.confirm_with_teeth && self.gear.module.teeth.is_none() {
            return Err(Error::Missing {
                name: "gear.module.teeth".into(),
                needed_by: "search.confirm_with_teeth cuts that many teeth".into(),
            });
        }
        for (i, goal) in self.search.goals.iter().enumerate() {
            let name = goal.name();
            let problem = if self.search.goals[..i].contains(goal) {
                format!("'{name}' is listed twice")
            } else if let Some(problem) = self.unmeasurable(*goal, &name) {
                problem
            } else if goal.is_robust()
                && !matches!(self.kind, SceneKind::Mechanism | SceneKind::Transplanter)
            {
                format!("'{name}' samples a mechanism's tolerances: a three_arm or transplanter scene needs it")
            } else {
                continue;
            };
            return Err(Error::BadList {
                list: "search.goals",
                problem,
            });
        }
        let constraints = &self.search.constraints;
        if constraints.len() > SearchSpec::MAX_CONSTRAINTS {
            return Err(Error::OutOfRange {
                name: "search.constraints (count)".into(),
                value: constraints.len() as f64,
                expected: format!("at most {}", SearchSpec::MAX_CONSTRAINTS),
            });
        }
        for (i, c) in constraints.iter().enumerate() {
            let text = c.text();
            let as_goal = Goal::Measure {
                measure: c.measure,
                maximise: false,
            };
            let problem = if constraints[..i].contains(c) {
                format!("'{text}' is listed twice")
            } else if !matches!(self.kind, SceneKind::Mechanism | SceneKind::Transplanter) {
                format!(
                    "'{text}' bounds a mechanism's measure: a three_arm or transplanter scene \
                     has it (this one is {})",
                    self.kind.name()
                )
            } else if let Some(problem) = self.unmeasurable(as_goal, &text) {
                problem
            } else {
                continue;
            };
            return Err(Error::BadList {
                list: "search.constraints",
                problem,
            });
        }
        for (i, f) in self.search.free.iter().enumerate() {
            Param::parse(&f.name, self)?;
            finite(&format!("search.free '{}' lower", f.name), f.lower)?;
            finite(&format!("search.free '{}' upper", f.name), f.upper)?;
            let problem = if self.search.free[..i].iter().any(|g| g.name == f.name) {
                format!("'{}' is listed twice", f.name)
            } else if !(f.lower < f.upper && (f.upper - f.lower).is_finite()) {
                format!(
                    "'{}' has bounds [{}, {}]: the lower must be below the upper, a finite \
                     width apart",
                    f.name, f.lower, f.upper
                )
            } else {
                continue;
            };
            return Err(Error::BadList {
                list: "search.free",
                problem,
            });
        }
        Ok(())
    }

    /// Why this scene cannot compute `goal` (named `name` in the message), if it cannot:
    /// a moving box it has not, a target it has not, a key pose its target has not.
    fn unmeasurable(&self, goal: Goal, name: &str) -> Option<String> {
        let poses = self.target.as_ref().map_or(0, |t| t.poses.len());
        if goal.needs_moving_box() && self.kind != SceneKind::Transplanter {
            Some(format!(
                "'{name}' needs a moving box: only a transplanter scene computes it"
            ))
        } else if goal.needs_target() && self.target.is_none() {
            Some(format!(
                "'{name}' measures the fit to a target: the scene has no [target]"
            ))
        } else {
            (goal.pose_slot().filter(|&k| k >= poses)).map(|slot| {
                format!(
                    "'{name}' reads key pose {}: the target has {poses}",
                    slot + 1
                )
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::reference::{Checker, Number, TABLES};
    use crate::scene::Scene;

    /// A design written over a checked scene is refused for any number out of its
    /// interval, in whichever table it is (`validate_beside` compares the tables it does
    /// not check again): each number the field table checks, set to NaN in turn. The base
    /// itself and a design that moves only the train pass; a bad train is refused.
    #[test]
    fn a_design_beside_its_checked_base_is_refused_for_any_bad_number() {
        let base = Scene::default();
        base.validate().unwrap();
        base.validate_beside(Some(&base)).unwrap();
        let mut refused = 0;
        for (table, checker, fields) in TABLES {
            if checker != Checker::Table || !base.reads(table) {
                continue;
            }
            assert!(base.same_numbers(&base, table), "{table} is not compared");
            for field in fields.iter().filter(|f| !f.range.admits(f64::NAN)) {
                let mut design = base.clone();
                let written = match field.number {
                    Some(Number::Scalar(_, set) | Number::Optional(_, set)) => {
                        set(&mut design, f64::NAN)
                    }
                    Some(Number::List(_, set)) => (set(&mut design).and_then(|v| v.first_mut()))
                        .map(|x| *x = f64::NAN)
                        .is_some(),
                    None => false,
                };
                if written {
                    assert!(design.validate().is_err(), "{}", field.key);
                    assert!(
                        design.validate_beside(Some(&base)).is_err(),
                        "{}",
                        field.key
                    );
                    refused += 1;
                }
            }
        }
        assert!(refused > 40, "{refused} numbers");
        let mut moved = base.clone();
        moved.train.phi0_deg += 1.0;
        moved.validate_beside(Some(&base)).unwrap();
        moved.train.arm_length_mm = 0.0;
        assert!(moved.validate_beside(Some(&base)).is_err());
    }

    /// Beside its checked base, a design gets the whole check's verdict whatever it
    /// changes: each number of every table, the tables that code checks (resolution,
    /// module, teeth) as well as the field table's, set to NaN, to 0 and to a large
    /// negative value in turn; bounds out of order; tolerances' counts out of range.
    #[test]
    fn a_design_beside_its_checked_base_gets_the_whole_checks_verdict() {
        let base = Scene::default();
        let mut compared = 0;
        for (_, _, fields) in TABLES {
            for field in fields.iter() {
                for value in [f64::NAN, 0.0, -1e6] {
                    let mut design = base.clone();
                    let written = match field.number {
                        Some(Number::Scalar(_, set) | Number::Optional(_, set)) => {
                            set(&mut design, value)
                        }
                        Some(Number::List(_, set)) => (set(&mut design))
                            .and_then(|v| v.first_mut())
                            .map(|x| *x = value)
                            .is_some(),
                        None => false,
                    };
                    if written {
                        assert_eq!(
                            design.validate_beside(Some(&base)).is_err(),
                            design.validate().is_err(),
                            "{} = {value}",
                            field.key
                        );
                        compared += 1;
                    }
                }
            }
        }
        assert!(compared > 150, "{compared} settings");
        // What the tables do not hold: the bounds' order and the tolerances' counts.
        let bad: [fn(&mut Scene); 3] = [
            |s| s.bounds.picking_angle_deg = [10.0, 5.0],
            |s| s.tolerances.samples = 0,
            |s| s.tolerances.assemblies_per_part_set = s.tolerances.samples + 1,
        ];
        for spoil in bad {
            let mut design = base.clone();
            spoil(&mut design);
            assert!(design.validate().is_err());
            assert!(design.validate_beside(Some(&base)).is_err());
        }
    }
}
