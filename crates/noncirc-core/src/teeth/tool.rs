//! The cutting tool as it cuts one gear: a rack or an involute shaper, its heights, tip
//! rounding and the fillet's reach, from the tooth spec's proportions (the right side; the
//! left mirrors it).

use super::{Cutter, ToothSpec};
use crate::error::{Error, Result};

/// The tool's rounding centre relative to the pitch point, per tool kind (right side).
#[derive(Debug, Clone, Copy)]
pub(super) enum Rounding {
    /// Rack: centre at `u0 + du` along the pitch line, height `v` (mm).
    Rack { du: f64, v: f64 },
    /// Shaper of pitch radius `rc`: centre at radius `r` and angle `phi` from the flank's
    /// pitch crossing (rad).
    Shaper { rc: f64, r: f64, phi: f64 },
}

/// The tool as it cuts one gear: heights and the rounding, for the right side (the left
/// mirrors it).
#[derive(Debug, Clone, Copy)]
pub(super) struct Tool {
    pub(super) sin: f64,
    pub(super) cos: f64,
    pub(super) tip: f64,
    pub(super) root: f64,
    pub(super) radius: f64,
    /// `λ` at the flank–fillet junction, right side (mm, negative: below the pitch curve).
    pub(super) lambda_form: f64,
    pub(super) rounding: Rounding,
    /// Rolling past `u0` at which the fillet reaches the root, right side (mm).
    pub(super) fillet_reach: f64,
    /// Which of the two points where the rounding's normal passes through the pitch point
    /// cuts: the far one from the pitch point (+1) while the rounding's centre is inside
    /// the pitch curve, the near one (−1) when a large profile shift lifts it outside.
    pub(super) cutting_side: f64,
    /// Tooth thickness on the pitch curve (mm).
    pub(super) thickness: f64,
}

impl Tool {
    /// The tool for a gear of module `m` with profile shift `shift` (× m) and tooth
    /// thickness `thickness` (mm), from the spec's proportions.
    pub(super) fn new(spec: &ToothSpec, m: f64, shift: f64, thickness: f64) -> Result<Self> {
        let alpha = spec.pressure_angle_deg.to_radians();
        let (sin, cos) = alpha.sin_cos();
        let tip = (spec.addendum + shift) * m;
        let root = -(spec.dedendum - shift) * m;
        let radius = spec.tip_radius * m;
        let (lambda_form, rounding, fillet_reach) = match spec.cutter {
            Cutter::Rack => {
                let v = root + radius;
                let form = root + radius * (1.0 - sin);
                let du = -v * sin / cos + radius / cos;
                (form / sin, Rounding::Rack { du, v }, du)
            }
            Cutter::Shaper { teeth } => {
                let rc = 0.5 * m * f64::from(teeth);
                let rb = rc * cos;
                let ra = rc - root;
                let reach = (ra - radius) * (ra - radius) - rb * rb;
                if reach <= 0.0 {
                    return Err(Error::OutOfRange {
                        name: "gear.teeth.cutter.teeth".into(),
                        value: f64::from(teeth),
                        expected: "a shaper whose tip rounding stays outside its base circle"
                            .into(),
                    });
                }
                // Roll angle of the rounding's tangency on the cutter's involute.
                let t = (radius + reach.sqrt()) / rb;
                let inv = alpha.tan() - alpha;
                let phi = -inv + t - ((rb * t - radius) / rb).atan();
                let r = ra - radius;
                (
                    rb * (alpha.tan() - t),
                    Rounding::Shaper { rc, r, phi },
                    rc * phi,
                )
            }
        };
        let space = std::f64::consts::PI * m - thickness;
        if fillet_reach >= 0.5 * space {
            return Err(Error::OutOfRange {
                name: "gear.teeth.tip_radius".into(),
                value: spec.tip_radius,
                expected: format!(
                    "a rounding that fits on the tool's tooth tip: {} roundings would overlap",
                    match spec.cutter {
                        Cutter::Rack => "the rack's".to_string(),
                        Cutter::Shaper { teeth } => format!("the {teeth}-tooth shaper's"),
                    }
                ),
            });
        }
        if lambda_form >= 0.0 {
            return Err(Error::OutOfRange {
                name: "gear.teeth.tip_radius".into(),
                value: spec.tip_radius,
                expected: "a tool tip rounding that ends below the pitch curve".into(),
            });
        }
        Ok(Self {
            sin,
            cos,
            tip,
            root,
            radius,
            cutting_side: if root + radius < 0.0 { 1.0 } else { -1.0 },
            lambda_form,
            rounding,
            fillet_reach,
            thickness,
        })
    }

    /// Where the tool's straight flank ends (mm, negative: below the pitch curve).
    pub(super) fn form_height(&self) -> f64 {
        self.lambda_form * self.sin
    }
}
