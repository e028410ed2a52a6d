//! The target of a fit (`[target]`): a closed tip path that the agronomy asks for, as
//! points or as the control points of a closed spline, with its tolerance, and up to four
//! key poses of the arm. Checked whole when read; prepared once (the path's curve, its
//! arc-length samples and the tree of its segments) for the fit measures.

use crate::curve::periodic_cubic_once;
use crate::error::{finite_with, Error, Result};
use crate::segment_tree::SegmentTree;
use crate::vec2::Vec2;
use serde::{Deserialize, Serialize};

/// How the target's points make the path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetKind {
    /// The closed polyline through the points (a measured or sampled path).
    #[default]
    Points,
    /// The closed centripetal cubic spline through the points (a drawn path).
    Spline,
}

/// Where on the trajectory a pose is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PoseAt {
    /// Where the trajectory comes nearest the pose (position, attitude and carrier angle
    /// weighed by their tolerances).
    #[default]
    Nearest,
    /// At the located picking instant.
    Picking,
    /// At the located planting instant.
    Planting,
}

/// A key pose of arm I: the tip's position, optionally the arm's attitude and the carrier
/// angle, each with its tolerance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pose {
    /// Name, for reports (`picking`).
    #[serde(default)]
    pub name: String,
    /// Where on the trajectory it is read.
    #[serde(default)]
    pub at: PoseAt,
    /// Tip position in the machine frame (mm; origin on the carrier axis, y up).
    pub x_mm: f64,
    pub y_mm: f64,
    /// The arm's attitude: the pusher direction's dip below the horizontal (deg, −90 to 90).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attitude_deg: Option<f64>,
    /// Carrier angle of arm I (deg).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub carrier_deg: Option<f64>,
    #[serde(default = "half")]
    pub position_tolerance_mm: f64,
    #[serde(default = "half")]
    pub attitude_tolerance_deg: f64,
    #[serde(default = "two")]
    pub carrier_tolerance_deg: f64,
    /// Whether the pose counts in the fit (false: reported only).
    #[serde(default = "yes")]
    pub counts: bool,
}

/// The target path and poses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Target {
    /// How the points make the path.
    #[serde(default)]
    pub kind: TargetKind,
    /// The points (mm), in the machine frame, in the order of motion.
    pub x_mm: Vec<f64>,
    pub y_mm: Vec<f64>,
    /// The path's tolerance (mm): it scales the path's residuals, and the path is met when
    /// its Hausdorff distance is at most this.
    #[serde(default = "half")]
    pub tolerance_mm: f64,
    /// Arc-length samples of the target path for its distances to the trajectory.
    #[serde(default = "default_samples")]
    pub samples: usize,
    /// Whether the path counts in the fit (false: poses only).
    #[serde(default = "yes")]
    pub counts: bool,
    /// Key poses, at most [`Target::MAX_POSES`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub poses: Vec<Pose>,
    /// Design parameters pulled towards values (a repair's own design): each adds
    /// `(value now − value)/scale` to the residuals. They weigh in the cost, not in `met`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub design: Vec<DesignPull>,
}

/// A design parameter the fit pulls towards a value: a change of one `scale` costs as
/// much as the path off by one tolerance (RMS) or a pose by one of its tolerances.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignPull {
    /// Scene path of the parameter (`train.phi0_deg`, `gear.curve.radii_mm[3]`).
    pub name: String,
    /// The value it is pulled towards (the parameter's unit).
    pub value: f64,
    /// The change that costs one unit of the fit (the parameter's unit; above 0).
    pub scale: f64,
}

fn half() -> f64 {
    0.5
}
fn two() -> f64 {
    2.0
}
fn yes() -> bool {
    true
}
fn default_samples() -> usize {
    128
}

/// A target ready for distances: its path as a fine polyline on a grid and its arc-length
/// samples.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedTarget {
    /// The path as a polyline within a small fraction of the tolerance of its curve.
    tree: SegmentTree,
    /// Equally spaced samples by arc length, the first at the first point.
    samples: Vec<Vec2>,
    /// Length of the path (mm).
    length_mm: f64,
}

impl PreparedTarget {
    /// The path's arc-length samples (mm).
    pub fn samples(&self) -> &[Vec2] {
        &self.samples
    }

    /// The path's length (mm).
    pub fn length_mm(&self) -> f64 {
        self.length_mm
    }

    /// The path as a fine closed polyline (mm).
    pub fn polyline(&self) -> &[Vec2] {
        self.tree.points()
    }

    /// The path's tree of segments.
    pub(crate) fn tree(&self) -> &SegmentTree {
        &self.tree
    }
}

/// Fine segments per turn of a spline path: chords of a 1 m path about 0.25 mm long,
/// whose sag is far below any tolerance a path takes.
const FINE_SEGMENTS: f64 = 4096.0;

impl Target {
    /// Fewest distinct points of a path.
    pub const MIN_POINTS: usize = 4;
    /// Most points (a CSV of a measured path).
    pub const MAX_POINTS: usize = 100_000;
    /// Most key poses.
    pub const MAX_POSES: usize = 4;
    /// Range of [`Target::samples`].
    pub const SAMPLES: [usize; 2] = [16, 4096];
    /// Most design pulls (as many as a search's free parameters).
    pub const MAX_DESIGN: usize = 1_000;

    /// Checks every number and count, naming the bad one (cheap: no geometry).
    pub fn validate(&self) -> Result<()> {
        let (nx, ny) = (self.x_mm.len(), self.y_mm.len());
        if nx != ny {
            return Err(Error::OutOfRange {
                name: "target.y_mm length".into(),
                value: ny as f64,
                expected: format!("as many values as target.x_mm ({nx})"),
            });
        }
        if nx > Self::MAX_POINTS {
            return Err(Error::OutOfRange {
                name: "target.x_mm length".into(),
                value: nx as f64,
                expected: format!("at most {} points", Self::MAX_POINTS),
            });
        }
        for (i, (&x, &y)) in self.x_mm.iter().zip(&self.y_mm).enumerate() {
            in_machine("target.x_mm", i, x)?;
            in_machine("target.y_mm", i, y)?;
        }
        positive_at_most("target.tolerance_mm", self.tolerance_mm, 1e3, "mm")?;
        let [lo, hi] = Self::SAMPLES;
        if !(lo..=hi).contains(&self.samples) {
            return Err(Error::OutOfRange {
                name: "target.samples".into(),
                value: self.samples as f64,
                expected: format!("{lo} to {hi}"),
            });
        }
        if self.poses.len() > Self::MAX_POSES {
            return Err(Error::BadList {
                list: "target.poses",
                problem: format!(
                    "{} poses: at most {} (picking, planting and two more)",
                    self.poses.len(),
                    Self::MAX_POSES
                ),
            });
        }
        for (k, pose) in self.poses.iter().enumerate() {
            pose.validate(k)?;
        }
        if self.design.len() > Self::MAX_DESIGN {
            return Err(Error::OutOfRange {
                name: "target.design (count)".into(),
                value: self.design.len() as f64,
                expected: format!("at most {}", Self::MAX_DESIGN),
            });
        }
        for (k, pull) in self.design.iter().enumerate() {
            let name = |field: &str| format!("target.design[{k}].{field}");
            finite_with(|| name("value"), pull.value)?;
            finite_with(|| name("scale"), pull.scale)?;
            if pull.scale <= 0.0 {
                return Err(Error::OutOfRange {
                    name: name("scale"),
                    value: pull.scale,
                    expected: "above 0 (the parameter's unit)".into(),
                });
            }
            if self.design[..k].iter().any(|p| p.name == pull.name) {
                return Err(Error::BadList {
                    list: "target.design",
                    problem: format!("'{}' is pulled twice", pull.name),
                });
            }
        }
        if !self.counts && !self.poses.iter().any(|p| p.counts) && self.design.is_empty() {
            return Err(Error::BadList {
                list: "target",
                problem: "nothing counts: the path has counts = false, no pose counts and no \
                          design parameter is pulled"
                    .into(),
            });
        }
        Ok(())
    }

    /// Checks the target whole and prepares its path: distinct points (a repeated last
    /// point closes the path and is dropped), at least four, closed (a points path whose
    /// last point is more than three spacings from its first is open), the spline through
    /// them, and no crossing of the path with itself.
    pub fn prepare(&self) -> Result<PreparedTarget> {
        self.validate()?;
        // The distinct points, with their indices in the table.
        let mut kept: Vec<(usize, Vec2)> = Vec::with_capacity(self.x_mm.len());
        for (i, (&x, &y)) in self.x_mm.iter().zip(&self.y_mm).enumerate() {
            let p = Vec2::new(x, y);
            if kept.last().is_none_or(|&(_, q)| q != p) {
                kept.push((i, p));
            }
        }
        while kept.len() > 1 && kept.last().map(|k| k.1) == kept.first().map(|k| k.1) {
            kept.pop();
        }
        if kept.len() < Self::MIN_POINTS {
            return Err(Error::TooFewPoints {
                kind: "target path (target.x_mm, target.y_mm, distinct points)",
                min: Self::MIN_POINTS,
                got: kept.len(),
            });
        }
        let n = kept.len();
        let chord = |i: usize| (kept[(i + 1) % n].1 - kept[i].1).hypot();
        if self.kind == TargetKind::Points {
            let mut spacings: Vec<f64> = (0..n - 1).map(chord).collect();
            spacings.sort_by(f64::total_cmp);
            let median = spacings[spacings.len() / 2];
            let gap = chord(n - 1);
            if gap > 3.0 * median {
                return Err(Error::OpenTarget {
                    name: format!("target.x_mm[{}]", kept[n - 1].0),
                    gap_mm: gap,
                    spacing_mm: median,
                });
            }
        }
        // The fine polyline, and for each of its segments the table's point it starts from.
        let (fine, from) = match self.kind {
            TargetKind::Points => (
                kept.iter().map(|k| k.1).collect::<Vec<_>>(),
                kept.iter().map(|k| k.0).collect::<Vec<_>>(),
            ),
            TargetKind::Spline => {
                let points: Vec<Vec2> = kept.iter().map(|k| k.1).collect();
                let (fine, span) = closed_spline(&points);
                (fine, span.into_iter().map(|s| kept[s].0).collect())
            }
        };
        let tree = SegmentTree::closed(&fine);
        if let Some((i, j, at)) = tree.self_crossing() {
            return Err(Error::TargetCrossing {
                name: format!("target.x_mm[{}]", from[i]),
                other: format!("target.x_mm[{}]", from[j]),
                x_mm: at.x,
                y_mm: at.y,
            });
        }
        let (samples, length_mm) = arc_length_samples(&fine, self.samples);
        Ok(PreparedTarget {
            tree,
            samples,
            length_mm,
        })
    }

    /// Whether a pose is read at an event (picking or planting).
    pub fn needs_events(&self) -> bool {
        self.poses.iter().any(|p| p.at != PoseAt::Nearest)
    }
}

impl Pose {
    /// Checks the pose's numbers, naming them as `target.poses[k].x_mm`.
    fn validate(&self, k: usize) -> Result<()> {
        let name = |field: &str| format!("target.poses[{k}].{field}");
        in_machine(&name("x_mm"), usize::MAX, self.x_mm)?;
        in_machine(&name("y_mm"), usize::MAX, self.y_mm)?;
        if let Some(a) = self.attitude_deg {
            finite_with(|| name("attitude_deg"), a)?;
            if !(-90.0..=90.0).contains(&a) {
                return Err(Error::OutOfRange {
                    name: name("attitude_deg"),
                    value: a,
                    expected: "−90 to 90° (the pusher's dip below the horizontal)".into(),
                });
            }
        }
        if let Some(c) = self.carrier_deg {
            finite_with(|| name("carrier_deg"), c)?;
        }
        positive_at_most(
            &name("position_tolerance_mm"),
            self.position_tolerance_mm,
            1e3,
            "mm",
        )?;
        positive_at_most(
            &name("attitude_tolerance_deg"),
            self.attitude_tolerance_deg,
            90.0,
            "°",
        )?;
        positive_at_most(
            &name("carrier_tolerance_deg"),
            self.carrier_tolerance_deg,
            180.0,
            "°",
        )?;
        Ok(())
    }
}

/// Largest coordinate (mm) of a target: a machine is not ten metres across.
const MAX_COORDINATE_MM: f64 = 1e4;

/// A coordinate of the machine frame (element `i` of list `name`; `usize::MAX`: a scalar).
fn in_machine(name: &str, i: usize, v: f64) -> Result<()> {
    let named = || {
        if i == usize::MAX {
            name.to_string()
        } else {
            format!("{name}[{i}]")
        }
    };
    finite_with(named, v)?;
    if v.abs() > MAX_COORDINATE_MM {
        return Err(Error::OutOfRange {
            name: named(),
            value: v,
            expected: format!("within ±{MAX_COORDINATE_MM} mm of the carrier axis"),
        });
    }
    Ok(())
}

/// A tolerance: finite, above 0, at most `max` (in `unit`).
fn positive_at_most(name: &str, v: f64, max: f64, unit: &str) -> Result<()> {
    finite_with(|| name.to_string(), v)?;
    if v > 0.0 && v <= max {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            name: name.to_string(),
            value: v,
            expected: format!("above 0, at most {max} {unit}"),
        })
    }
}

/// The closed centripetal cubic spline through `points` (distinct), as a fine polyline,
/// with the span each of its segments lies in.
fn closed_spline(points: &[Vec2]) -> (Vec<Vec2>, Vec<usize>) {
    let n = points.len();
    let chord = |i: usize| (points[(i + 1) % n] - points[i]).hypot();
    // Centripetal knots: no cusp or loop within a span (Yuksel et al. 2011).
    let h: Vec<f64> = (0..n).map(|i| chord(i).sqrt()).collect();
    let xs: Vec<f64> = points.iter().map(|p| p.x).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.y).collect();
    let (cx, cy) = (
        periodic_cubic_once(|i| h[i], &xs),
        periodic_cubic_once(|i| h[i], &ys),
    );
    let total: f64 = (0..n).map(chord).sum();
    let mut fine = Vec::new();
    let mut span = Vec::new();
    for i in 0..n {
        let pieces = ((chord(i) / total * FINE_SEGMENTS).ceil() as usize).max(8);
        for k in 0..pieces {
            let t = h[i] * k as f64 / pieces as f64;
            let at = |c: &[f64; 4]| c[0] + t * (c[1] + t * (c[2] + t * c[3]));
            fine.push(Vec2::new(at(&cx[i]), at(&cy[i])));
            span.push(i);
        }
    }
    (fine, span)
}

/// `m` samples equally spaced by arc length along the closed polyline `points`, from its
/// first point, and its length (mm).
fn arc_length_samples(points: &[Vec2], m: usize) -> (Vec<Vec2>, f64) {
    let n = points.len();
    let length: f64 = (0..n)
        .map(|i| (points[(i + 1) % n] - points[i]).hypot())
        .sum();
    let step = length / m as f64;
    let mut samples = Vec::with_capacity(m);
    let (mut i, mut start) = (0, 0.0);
    for k in 0..m {
        let s = k as f64 * step;
        loop {
            let (a, b) = (points[i % n], points[(i + 1) % n]);
            let len = (b - a).hypot();
            if s <= start + len || i + 1 >= n {
                let t = if len > 0.0 {
                    ((s - start) / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                samples.push(a + (b - a) * t);
                break;
            }
            start += len;
            i += 1;
        }
    }
    (samples, length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    fn circle(n: usize, r: f64) -> Target {
        let angles = (0..n).map(|i| TAU * i as f64 / n as f64);
        Target {
            kind: TargetKind::Points,
            x_mm: angles.clone().map(|a| r * a.cos()).collect(),
            y_mm: angles.map(|a| r * a.sin()).collect(),
            tolerance_mm: 0.5,
            samples: 128,
            counts: true,
            poses: Vec::new(),
            design: Vec::new(),
        }
    }

    #[test]
    fn a_polygons_samples_are_equally_spaced_along_its_length() {
        let target = circle(1000, 100.0).prepare().unwrap();
        let n = 1000.0;
        // The polygon's perimeter, 2 n r sin(π/n).
        let perimeter = 2.0 * n * 100.0 * (std::f64::consts::PI / n).sin();
        assert!((target.length_mm() - perimeter).abs() < 1e-9);
        let s = target.samples();
        assert_eq!(s.len(), 128);
        for k in 0..128 {
            let chord = (s[(k + 1) % 128] - s[k]).hypot();
            // Equal arcs of the polygon: equal chords to its sag.
            assert!((chord - (s[1] - s[0]).hypot()).abs() < 1e-3, "{k}: {chord}");
        }
    }

    #[test]
    fn a_spline_through_points_of_a_circle_stays_near_the_circle() {
        let mut t = circle(12, 100.0);
        t.kind = TargetKind::Spline;
        let prepared = t.prepare().unwrap();
        // A cubic spline's error is at most 5/384 h⁴ max|f⁗|: on a circle of radius 100 mm
        // with 12 knots (h ≈ 30° of arc), about 0.1 mm.
        let worst = (prepared.polyline().iter())
            .map(|p| (p.hypot() - 100.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 0.1, "{worst}");
        assert!((prepared.length_mm() - TAU * 100.0).abs() < 0.5);
    }

    #[test]
    fn bad_targets_are_refused_by_name_and_value() {
        let base = circle(40, 100.0);
        let refuse = |edit: &dyn Fn(&mut Target)| {
            let mut t = base.clone();
            edit(&mut t);
            t.prepare().unwrap_err()
        };
        // NaN.
        let e = refuse(&|t| t.x_mm[17] = f64::NAN);
        assert!(
            matches!(&e, Error::NonFinite { name, .. } if name == "target.x_mm[17]"),
            "{e:?}"
        );
        // Lengths that differ.
        let e = refuse(&|t| {
            t.y_mm.pop();
        });
        assert!(
            matches!(&e, Error::OutOfRange { name, value, .. } if name == "target.y_mm length" && *value == 39.0)
        );
        // Too few distinct points (a repeated point is one).
        let e = refuse(&|t| {
            t.x_mm = vec![0.0, 1.0, 1.0, 1.0, 0.0];
            t.y_mm = vec![0.0, 0.0, 0.0, 0.0, 0.0];
        });
        assert!(matches!(e, Error::TooFewPoints { got: 2, .. }), "{e:?}");
        // An open path: the last ten points left out.
        let e = refuse(&|t| {
            t.x_mm.truncate(30);
            t.y_mm.truncate(30);
        });
        match e {
            Error::OpenTarget {
                name,
                gap_mm,
                spacing_mm,
            } => {
                assert_eq!(name, "target.x_mm[29]");
                // From the point at 29·9° back to the first: a chord of 99°.
                let expected = 2.0 * 100.0 * (99.0f64.to_radians() / 2.0).sin();
                assert!((gap_mm - expected).abs() < 1e-9);
                assert!((spacing_mm - 2.0 * 100.0 * (4.5f64.to_radians()).sin()).abs() < 1e-9);
            }
            other => panic!("{other:?}"),
        }
        // A figure of eight crosses itself at the origin.
        let e = refuse(&|t| {
            let a = (0..40).map(|i| TAU * i as f64 / 40.0);
            t.x_mm = a.clone().map(|a| 100.0 * a.sin()).collect();
            t.y_mm = a.map(|a| 50.0 * (2.0 * a).sin()).collect();
        });
        match e {
            Error::TargetCrossing {
                name,
                other,
                x_mm,
                y_mm,
            } => {
                assert!(x_mm.abs() < 1e-9 && y_mm.abs() < 1e-9, "{x_mm} {y_mm}");
                assert!(name.starts_with("target.x_mm[") && other.starts_with("target.x_mm["));
            }
            other => panic!("{other:?}"),
        }
        // A pose's attitude beyond the vertical, and a zero tolerance.
        let pose = Pose {
            name: "planting".into(),
            at: PoseAt::Planting,
            x_mm: 0.0,
            y_mm: -300.0,
            attitude_deg: Some(95.0),
            carrier_deg: None,
            position_tolerance_mm: 0.5,
            attitude_tolerance_deg: 0.5,
            carrier_tolerance_deg: 2.0,
            counts: true,
        };
        let e = refuse(&|t| t.poses = vec![pose.clone()]);
        assert!(
            matches!(&e, Error::OutOfRange { name, value, .. } if name == "target.poses[0].attitude_deg" && *value == 95.0)
        );
        let e = refuse(&|t| t.tolerance_mm = 0.0);
        assert!(matches!(&e, Error::OutOfRange { name, .. } if name == "target.tolerance_mm"));
        let e = refuse(&|t| t.poses = vec![pose.clone(); 5]);
        assert!(matches!(
            &e,
            Error::BadList {
                list: "target.poses",
                ..
            }
        ));
    }
}
