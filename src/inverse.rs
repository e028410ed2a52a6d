//! `noncirc inverse`: the exact inversion's run, its summary (`inverse.json`), its table
//! and the scene with both tabulated curves (`inverse.toml`).

use crate::files::{create_dir, json_text, toml_text, write_file};
use crate::Result;
use noncirc_core::{invert, Branch, Condition, InverseOutcome, InverseSpec, Scene, Target};
use serde::Serialize;
use std::path::Path;

/// How a user names the split of the overall ratio between the pairs.
pub fn parse_split(text: &str) -> Result<f64> {
    let value = match text {
        "equal" => 0.5,
        "first-circular" => 0.0,
        "second-circular" => 1.0,
        other => other.parse::<f64>().map_err(|_| {
            crate::Error::Input(format!(
                "--split {other}: expected equal, first-circular, second-circular or a \
                 share λ from 0 to 1"
            ))
        })?,
    };
    Ok(value)
}

/// The inversion of `target` for `scene` with `spec` (the centre ratio `None`: the scene's
/// own, `a_B/a_A` of its solved train).
pub fn inverse_scene(
    scene: &Scene,
    target: &Target,
    centre_ratio: Option<f64>,
    split: f64,
    branch: Option<Branch>,
    samples_per_turn: usize,
) -> Result<InverseOutcome> {
    let centre_ratio = match centre_ratio {
        Some(k) => k,
        None => {
            let [a1, a2] = scene.kinematics(&scene.resolution)?.centre_distances();
            a2 / a1
        }
    };
    let spec = InverseSpec {
        centre_ratio,
        split,
        branch,
        samples_per_turn,
    };
    Ok(invert(scene, target, &spec)?)
}

/// What `noncirc inverse` reports (`inverse.json`): the geometry the path fixed, how the
/// target was read, the forward check against it and every condition.
#[derive(Debug, Clone, Serialize)]
pub struct InverseSummary<'a> {
    /// Every condition holds and every objective is met.
    pub met: bool,
    /// A design was built (`inverse.toml`).
    pub built: bool,
    pub branch: Branch,
    pub reversed: bool,
    pub arm_length_mm: f64,
    pub planet_radius_mm: f64,
    pub centre_distances_mm: [f64; 2],
    pub split: f64,
    pub half_weight_harmonic: f64,
    pub smoothing_mm: f64,
    /// The largest move of the tip by the ratio's shaping (mm; 0: not shaped).
    pub shaping_mm: f64,
    /// The pusher offset H1 chosen for the poses' attitudes (mm; absent: the scene's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pusher_offset_mm: Option<f64>,
    /// The built design's path against the target (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path_hausdorff_mm: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path_rms_mm: Option<f64>,
    pub conditions: &'a [Condition],
}

/// The summary of `outcome` (inverted with `split`).
pub fn summary(outcome: &InverseOutcome, split: f64) -> InverseSummary<'_> {
    let fit = (outcome.evaluation.as_ref()).and_then(|e| e.fit.as_ref());
    InverseSummary {
        met: outcome.met(),
        built: outcome.scene.is_some(),
        branch: outcome.branch,
        reversed: outcome.reversed,
        arm_length_mm: outcome.arm_length_mm,
        planet_radius_mm: outcome.planet_radius_mm,
        centre_distances_mm: outcome.centre_distances_mm,
        split,
        half_weight_harmonic: outcome.half_weight_harmonic,
        smoothing_mm: outcome.smoothing_mm,
        shaping_mm: outcome.shaping_mm,
        pusher_offset_mm: outcome.pusher_offset_mm,
        path_hausdorff_mm: fit.map(|f| f.path_hausdorff_mm),
        path_rms_mm: fit.map(|f| f.path_rms_mm),
        conditions: &outcome.conditions,
    }
}

impl InverseSummary<'_> {
    /// A table for people: the geometry, then each condition with where it fails.
    pub fn table(&self) -> String {
        let mut out = format!(
            "The path fixes the arm S = {:.3} mm and the planet circle R = {:.3} mm: centre \
             distances {:.3} and {:.3} mm; elbow branch {:?}{}; the target read as a \
             Fourier series smoothed to half weight at harmonic {:.1}, within {:.4} mm of its points.\n",
            self.arm_length_mm,
            self.planet_radius_mm,
            self.centre_distances_mm[0],
            self.centre_distances_mm[1],
            self.branch,
            if self.reversed {
                ", the target read backwards (to run in the carrier's sense)"
            } else {
                ""
            },
            self.half_weight_harmonic,
            self.smoothing_mm
        );
        if let Some(h1) = self.pusher_offset_mm {
            out += &format!(
                "The pusher offset H1 = {h1:.4} mm is set for the poses' attitudes, their \
                 mean error zero (the path fixes the arm's direction, H1 the pusher's).\n"
            );
        }
        if self.shaping_mm > 0.0 {
            out += &format!(
                "The overall ratio shaped for buildable pitch curves, moving the tip by at \
                 most {:.4} mm.\n",
                self.shaping_mm
            );
        }
        if let (Some(h), Some(r)) = (self.path_hausdorff_mm, self.path_rms_mm) {
            out += &format!(
                "The design's path against the target: Hausdorff {h:.4} mm, RMS {r:.4} mm.\n"
            );
        }
        out += "\ncondition                      holds  value          bound          unit\n";
        for c in self.conditions {
            out += &format!(
                "{:<30} {:<6} {:<14} {:<14} {}\n",
                c.name,
                match (c.holds, c.blocks) {
                    (true, _) => "yes",
                    (false, true) => "NO",
                    (false, false) => "no",
                },
                crate::report::signed_fixed(c.value, 4),
                crate::report::signed_fixed(c.bound, 4),
                c.unit
            );
            if !c.holds {
                out += &format!("    {}\n", c.meaning);
                for p in &c.places {
                    out += &format!(
                        "    fails from {:.1} to {:.1} mm along the path{}, worst at ({:.2}, \
                         {:.2}) mm\n",
                        p.path_mm[0],
                        p.path_mm[1],
                        p.carrier_deg.map_or(String::new(), |[a, b]| format!(
                            " (carrier {a:.1}° to {b:.1}°)"
                        )),
                        p.point_mm.x,
                        p.point_mm.y
                    );
                }
            }
        }
        out += match (self.built, self.met) {
            (_, true) => "\nEvery condition holds: the design is in inverse.toml (--out).\n",
            (true, false) => {
                "\nThe design is built (inverse.toml with --out) but misses what is marked \
                 no/NO above (NO: it cannot be made as it is).\n"
            }
            (false, false) => "\nNo design: the conditions marked NO block it.\n",
        };
        out
    }

    /// The failing conditions in one line, for the exit message.
    pub fn failures(&self) -> String {
        let names: Vec<&str> = (self.conditions.iter())
            .filter(|c| !c.holds)
            .map(|c| c.name.as_str())
            .collect();
        format!("the inversion fails: {}", names.join(", "))
    }
}

/// Writes `inverse.json` and, when a design was built, `inverse.toml` into `dir`.
pub fn write(outcome: &InverseOutcome, split: f64, dir: &Path) -> Result<()> {
    create_dir(dir)?;
    if let Some(scene) = &outcome.scene {
        let mut scene = scene.clone();
        scene.name = format!("{}-inverse", scene.name);
        write_file(
            &dir.join("inverse.toml"),
            toml_text(&scene, "the inverted scene")?.as_bytes(),
        )?;
    }
    write_file(
        &dir.join("inverse.json"),
        json_text(&summary(outcome, split), "the inversion")?.as_bytes(),
    )
}
