//! Pitch curves of the driving gear: `rho(psi) > 0`, periodic in `psi` (rad), radii in mm.

mod cartesian;
mod spline;

pub use cartesian::{CartesianCurve, CartesianKind};
pub(crate) use spline::periodic_cubic_once;
pub use spline::PeriodicSpline;

use crate::error::{finite, finite_with, positive_with, Error, Result};
use crate::vec2::Vec2;
use serde::{Deserialize, Serialize};
use wide::f64x2;

pub(crate) const TAU: f64 = std::f64::consts::TAU;

/// `rho` (mm) with its first and second derivatives in `psi` (mm/rad, mm/rad²).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Polar {
    pub rho: f64,
    pub d1: f64,
    pub d2: f64,
}

impl Polar {
    /// Signed curvature `κ = (ρ² + 2ρ'² − ρρ'')/(ρ² + ρ'²)^{3/2}` (1/mm): positive on convex
    /// arcs, smooth through inflections.
    #[inline]
    pub fn curvature(self) -> f64 {
        let s = self.rho * self.rho + self.d1 * self.d1;
        self.curvature_numerator() / (s * s.sqrt())
    }

    /// The curvature's numerator `ρ² + 2ρ'² − ρρ''` (mm²), for a caller that has
    /// `(ρ² + ρ'²)^{-1/2}` at hand.
    #[inline]
    pub fn curvature_numerator(self) -> f64 {
        self.rho * self.rho + 2.0 * self.d1 * self.d1 - self.rho * self.d2
    }

    /// Arc length per radian of ψ, `ds/dψ = √(ρ² + ρ'²)` (mm/rad).
    #[inline]
    pub fn arc_rate(self) -> f64 {
        (self.rho * self.rho + self.d1 * self.d1).sqrt()
    }
}

/// How a pitch curve is specified (the serialisable form, angles in degrees).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CurveSpec {
    /// Periodic cubic spline of rho in psi through polar control points.
    Spline {
        radii_mm: Vec<f64>,
        angles_deg: Vec<f64>,
    },
    /// Closed uniform cubic B-spline of the polar control points read as Cartesian points.
    Bspline {
        radii_mm: Vec<f64>,
        angles_deg: Vec<f64>,
    },
    /// One closed Bézier curve of the control points, first point repeated at the end.
    Bezier {
        radii_mm: Vec<f64>,
        angles_deg: Vec<f64>,
    },
    /// `rho = c0 + Σ_k (cos_k cos kψ + sin_k sin kψ)`, k = 1, 2, ...
    Fourier {
        c0_mm: f64,
        cos_mm: Vec<f64>,
        sin_mm: Vec<f64>,
    },
    /// Ellipse turning about a focus: `rho = A(1-k²)/(1-k cos psi)`.
    Ellipse {
        semi_major_mm: f64,
        eccentricity: f64,
    },
    /// Periodic cubic interpolation of measured samples `(psi, rho)`.
    Table {
        radii_mm: Vec<f64>,
        angles_deg: Vec<f64>,
    },
}

/// The three-arm paper's pitch curve: 12 control points (three-arm paper §4.1).
pub fn paper_control_points() -> (Vec<f64>, Vec<f64>) {
    (
        vec![
            21.0, 28.0, 50.0, 49.0, 58.0, 47.0, 18.0, 12.0, 28.0, 60.0, 48.0, 24.0,
        ],
        vec![
            20.0, 45.0, 76.0, 105.0, 132.0, 165.0, 195.0, 225.0, 255.0, 285.0, 316.0, 345.0,
        ],
    )
}

impl CurveSpec {
    /// The `table` through points of a closed curve in its own frame (mm, star-shaped about
    /// the origin, in either sense): their polar angles wrapped into [0°, 360°) and sorted.
    pub fn table_through(points: &[Vec2]) -> Self {
        let mut polar: Vec<(f64, f64)> = (points.iter())
            .map(|p| {
                // `rem_euclid` rounds a tiny negative angle up to 360 itself.
                let angle = p.y.atan2(p.x).to_degrees().rem_euclid(360.0);
                (if angle < 360.0 { angle } else { 0.0 }, p.hypot())
            })
            .collect();
        polar.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (angles_deg, radii_mm) = polar.into_iter().unzip();
        CurveSpec::Table {
            radii_mm,
            angles_deg,
        }
    }

    /// The paper's 12 control points fed to the periodic spline.
    pub fn paper() -> Self {
        let (radii_mm, angles_deg) = paper_control_points();
        CurveSpec::Spline {
            radii_mm,
            angles_deg,
        }
    }

    /// Validates the specification and builds the evaluable curve.
    pub fn build(&self) -> Result<PitchCurve> {
        match self {
            CurveSpec::Spline {
                radii_mm,
                angles_deg,
            }
            | CurveSpec::Table {
                radii_mm,
                angles_deg,
            } => {
                let kind = if matches!(self, CurveSpec::Spline { .. }) {
                    "spline"
                } else {
                    "table"
                };
                same_length(kind, radii_mm, angles_deg)?;
                let psi: Vec<f64> = angles_deg.iter().map(|d| d.to_radians()).collect();
                Ok(PitchCurve::Spline(PeriodicSpline::new(
                    kind, psi, radii_mm,
                )?))
            }
            CurveSpec::Bspline {
                radii_mm,
                angles_deg,
            }
            | CurveSpec::Bezier {
                radii_mm,
                angles_deg,
            } => {
                let kind = if matches!(self, CurveSpec::Bspline { .. }) {
                    CartesianKind::BSpline
                } else {
                    CartesianKind::Bezier
                };
                let name = if kind == CartesianKind::BSpline {
                    "bspline"
                } else {
                    "bezier"
                };
                same_length(name, radii_mm, angles_deg)?;
                let mut points = Vec::with_capacity(radii_mm.len());
                for (i, (&r, &a)) in radii_mm.iter().zip(angles_deg).enumerate() {
                    positive_with(|| format!("{name} radius {i} (mm)"), r)?;
                    finite_with(|| format!("{name} angle {i} (deg)"), a)?;
                    let t = a.to_radians();
                    points.push(crate::vec2::Vec2::new(r * t.cos(), r * t.sin()));
                }
                let psi: Vec<f64> = angles_deg.iter().map(|d| d.to_radians()).collect();
                spline::check_angles(&psi)?;
                Ok(PitchCurve::Cartesian(CartesianCurve::new(kind, points)?))
            }
            CurveSpec::Fourier {
                c0_mm,
                cos_mm,
                sin_mm,
            } => Ok(PitchCurve::Fourier(Fourier::new(*c0_mm, cos_mm, sin_mm)?)),
            CurveSpec::Ellipse {
                semi_major_mm,
                eccentricity,
            } => Ok(PitchCurve::Ellipse(Ellipse::new(
                *semi_major_mm,
                *eccentricity,
            )?)),
        }
    }
}

fn same_length(kind: &'static str, radii: &[f64], angles: &[f64]) -> Result<()> {
    if radii.len() != angles.len() {
        return Err(Error::OutOfRange {
            name: format!("{kind} angles_deg length"),
            value: angles.len() as f64,
            expected: format!("{} (one angle per radius)", radii.len()),
        });
    }
    Ok(())
}

/// An evaluable pitch curve (validated: `rho > 0`, single-valued in `psi`).
#[derive(Debug, Clone, PartialEq)]
pub enum PitchCurve {
    Spline(PeriodicSpline),
    Cartesian(CartesianCurve),
    Fourier(Fourier),
    Ellipse(Ellipse),
}

impl PitchCurve {
    /// `rho` and its first two derivatives at `psi` (rad, any real value).
    #[inline]
    pub fn eval(&self, psi: f64) -> Polar {
        match self {
            PitchCurve::Spline(s) => s.eval(psi),
            PitchCurve::Cartesian(c) => c.eval(psi),
            PitchCurve::Fourier(f) => f.eval(psi),
            PitchCurve::Ellipse(e) => e.eval(psi),
        }
    }

    /// [`Self::eval`] at each angle (rad), cheaper for the spline when they are in order.
    pub fn eval_each(&self, psi: impl IntoIterator<Item = f64>) -> Vec<Polar> {
        match self {
            PitchCurve::Spline(s) => s.eval_each(psi),
            _ => psi.into_iter().map(|psi| self.eval(psi)).collect(),
        }
    }

    /// Samples at `start + step·j` for `j = 0..n` (rad): as [`Self::eval`] at each point,
    /// cheaper for the spline.
    pub fn sample_uniform(&self, start: f64, step: f64, n: usize) -> Vec<Polar> {
        match self {
            PitchCurve::Spline(s) => s.sample_uniform(start, step, n),
            _ => (0..n).map(|j| self.eval(start + step * j as f64)).collect(),
        }
    }

    /// Perimeter (mm) from `samples` of this curve, uniform over one turn in either sense:
    /// the trapezoid rule of `ds/dψ`, spectrally accurate for a smooth periodic curve.
    pub fn perimeter(&self, samples: &[Polar]) -> f64 {
        arc_rate_sum(samples) * TAU / samples.len() as f64
    }

    /// `(min, max)` of `rho` (mm): exact for the spline and the ellipse, Newton-refined for
    /// the Fourier series, and refined from the given uniform samples otherwise.
    pub fn radius_range(&self, samples: &[Polar]) -> (f64, f64) {
        match self {
            PitchCurve::Spline(s) => s.rho_range(),
            PitchCurve::Ellipse(e) => (e.semi_major * (1.0 - e.k), e.semi_major * (1.0 + e.k)),
            PitchCurve::Fourier(f) => (f.refine(false).1, f.refine(true).1),
            PitchCurve::Cartesian(_) => {
                let rho: Vec<f64> = samples.iter().map(|p| p.rho).collect();
                let min = refined_sample_min(&rho, |r| r);
                let max = -refined_sample_min(&rho, |r| -r);
                (min, max)
            }
        }
    }
}

/// `Σ ds/dψ` over `samples`, added in order: the roots two at a time in vector lanes
/// (`wide::f64x2`, each lane's arithmetic [`Polar::arc_rate`]'s own), since a root alone
/// took as long as the rest of a sample's work.
fn arc_rate_sum(samples: &[Polar]) -> f64 {
    let pairs = samples.chunks_exact(2);
    let last = pairs.remainder();
    let mut sum = 0.0;
    for pair in pairs {
        let rho = f64x2::new([pair[0].rho, pair[1].rho]);
        let d1 = f64x2::new([pair[0].d1, pair[1].d1]);
        let [first, second] = (rho * rho + d1 * d1).sqrt().to_array();
        sum = sum + first + second;
    }
    last.iter().fold(sum, |sum, p| sum + p.arc_rate())
}

/// Minimum of `f(values[j])` over a periodic uniform sample, refined by the parabola through
/// the least sample and its neighbours.
pub(crate) fn refined_sample_min(values: &[f64], f: impl Fn(f64) -> f64) -> f64 {
    let n = values.len();
    let j = (0..n)
        .min_by(|&a, &b| f(values[a]).total_cmp(&f(values[b])))
        .unwrap_or(0);
    parabola_vertex(
        f(values[(j + n - 1) % n]),
        f(values[j]),
        f(values[(j + 1) % n]),
    )
}

/// Least value of the parabola through three equally spaced samples whose middle one is
/// the least (the middle sample if they are not convex).
pub(crate) fn parabola_vertex(ym: f64, y0: f64, yp: f64) -> f64 {
    let curvature = ym - 2.0 * y0 + yp;
    if curvature <= 0.0 {
        return y0;
    }
    let offset = (0.5 * (ym - yp) / curvature).clamp(-1.0, 1.0);
    y0 - 0.25 * (ym - yp) * offset
}

/// Truncated Fourier series pitch curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Fourier {
    c0: f64,
    cos: Vec<f64>,
    sin: Vec<f64>,
}

impl Fourier {
    /// Most harmonics accepted: the extremum search samples densely in proportion to
    /// them, so the cost grows with their square (10 000 took over two minutes).
    pub const MAX_HARMONICS: usize = 256;

    /// Validates finiteness and positivity (`rho > 0` everywhere).
    pub fn new(c0: f64, cos: &[f64], sin: &[f64]) -> Result<Self> {
        positive_with(|| "fourier c0_mm".into(), c0)?;
        let harmonics = cos.len().max(sin.len());
        if harmonics > Self::MAX_HARMONICS {
            return Err(Error::OutOfRange {
                name: "fourier harmonics (length of cos_mm, sin_mm)".into(),
                value: harmonics as f64,
                expected: format!("at most {}", Self::MAX_HARMONICS),
            });
        }
        for (i, v) in cos.iter().enumerate() {
            finite_with(|| format!("fourier cos_mm[{i}]"), *v)?;
        }
        for (i, v) in sin.iter().enumerate() {
            finite_with(|| format!("fourier sin_mm[{i}]"), *v)?;
        }
        let k = cos.len().max(sin.len());
        let pad = |v: &[f64]| {
            let mut out = v.to_vec();
            out.resize(k, 0.0);
            out
        };
        let f = Self {
            c0,
            cos: pad(cos),
            sin: pad(sin),
        };
        let (psi, rho) = f.refine(false);
        if rho <= 0.0 {
            return Err(Error::NonPositiveRadius {
                psi_deg: crate::angle::degrees_in_turn(psi),
                rho_mm: rho,
            });
        }
        Ok(f)
    }

    pub fn eval(&self, psi: f64) -> Polar {
        let mut out = Polar {
            rho: self.c0,
            d1: 0.0,
            d2: 0.0,
        };
        // `(cos kψ, sin kψ)` by turning the last harmonic's by ψ: one sine-cosine for the
        // series (the rounding grows by about an ulp a harmonic).
        let first = crate::angle::unit(psi);
        let mut harmonic = first;
        for (i, (a, b)) in self.cos.iter().zip(&self.sin).enumerate() {
            let k = (i + 1) as f64;
            let (c, s) = (harmonic.x, harmonic.y);
            harmonic = Vec2::new(c * first.x - s * first.y, s * first.x + c * first.y);
            out.rho += a * c + b * s;
            out.d1 += k * (b * c - a * s);
            out.d2 -= k * k * (a * c + b * s);
        }
        out
    }

    /// The minimum (`max = false`) or maximum `(psi, rho)`: dense samples, then Newton on
    /// `rho' = 0` from the best one.
    fn refine(&self, max: bool) -> (f64, f64) {
        let sign = if max { -1.0 } else { 1.0 };
        let m = 64 * (self.cos.len() + 1);
        let mut best = (0.0, self.eval(0.0).rho);
        for j in 0..m {
            let psi = TAU * j as f64 / m as f64;
            let r = self.eval(psi).rho;
            if sign * r < sign * best.1 {
                best = (psi, r);
            }
        }
        let mut psi = best.0;
        for _ in 0..20 {
            let p = self.eval(psi);
            if p.d2 * sign <= 0.0 {
                break;
            }
            let step = p.d1 / p.d2;
            psi -= step.clamp(-TAU / m as f64, TAU / m as f64);
            if step.abs() < 1e-15 {
                break;
            }
        }
        let r = self.eval(psi).rho;
        if sign * r < sign * best.1 {
            (psi, r)
        } else {
            best
        }
    }
}

/// Ellipse turning about a focus (moving-box paper, eq. 6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    /// Major semi-axis `A` (mm).
    pub semi_major: f64,
    /// Eccentricity `k` in [0, 1).
    pub k: f64,
}

impl Ellipse {
    pub fn new(semi_major: f64, k: f64) -> Result<Self> {
        positive_with(|| "ellipse semi_major_mm".into(), semi_major)?;
        finite("ellipse eccentricity", k)?;
        if !(0.0..1.0).contains(&k) {
            return Err(Error::OutOfRange {
                name: "ellipse eccentricity".into(),
                value: k,
                expected: "0 <= k < 1".into(),
            });
        }
        Ok(Self { semi_major, k })
    }

    pub fn eval(&self, psi: f64) -> Polar {
        let c = self.semi_major * (1.0 - self.k * self.k);
        let crate::vec2::Vec2 { x: co, y: s } = crate::angle::unit(psi);
        let d = 1.0 - self.k * co;
        let (d1, d2) = (self.k * s, self.k * co);
        Polar {
            rho: c / d,
            d1: -c * d1 / (d * d),
            d2: -c * (d2 / (d * d) - 2.0 * d1 * d1 / (d * d * d)),
        }
    }

    /// Closed-form driven angle `phi2(phi1)`, unwrapped (moving-box paper eq. 8 integrated).
    pub fn phi2_closed_form(&self, phi1: f64) -> f64 {
        let turns = (phi1 / TAU).round();
        let rest = phi1 - turns * TAU;
        let ratio = (1.0 + self.k) / (1.0 - self.k);
        turns * TAU + 2.0 * (ratio * (rest / 2.0).tan()).atan()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// The roots in lanes, added in order, are the scalar sum of `arc_rate` bit for bit:
        /// odd and even counts, radii and slopes over many scales, and NaN.
        #[test]
        fn arc_rates_in_lanes_sum_as_the_scalar_loop(
            samples in proptest::collection::vec(
                (
                    proptest::prop_oneof![1e-3f64..1e3, proptest::strategy::Just(f64::NAN)],
                    -1e3f64..1e3,
                ),
                0..50,
            ),
        ) {
            let samples: Vec<Polar> =
                samples.iter().map(|&(rho, d1)| Polar { rho, d1, d2: 0.0 }).collect();
            let scalar = samples.iter().fold(0.0, |sum, p| sum + p.arc_rate());
            proptest::prop_assert_eq!(arc_rate_sum(&samples).to_bits(), scalar.to_bits());
        }
    }

    #[test]
    fn fourier_harmonics_by_rotation_match_each_sine_cosine() {
        let n = 24;
        let cos: Vec<f64> = (1..=n).map(|k| 0.8 / k as f64).collect();
        let sin: Vec<f64> = (1..=n).map(|k| 0.5 / (k * k) as f64).collect();
        let f = Fourier::new(40.0, &cos, &sin).unwrap();
        for j in 0..500 {
            let psi = -30.0 + 0.1237 * j as f64;
            let p = f.eval(psi);
            let (mut rho, mut d1, mut d2) = (40.0, 0.0, 0.0);
            for k in 1..=n {
                let (a, b, k) = (cos[k - 1], sin[k - 1], k as f64);
                let (s, c) = (k * psi).sin_cos();
                rho += a * c + b * s;
                d1 += k * (b * c - a * s);
                d2 -= k * k * (a * c + b * s);
            }
            assert!((p.rho - rho).abs() < 1e-13, "{psi}: {} vs {rho}", p.rho);
            assert!((p.d1 - d1).abs() < 1e-12, "{psi}: {} vs {d1}", p.d1);
            assert!((p.d2 - d2).abs() < 1e-11, "{psi}: {} vs {d2}", p.d2);
        }
    }

    #[test]
    fn ellipse_derivatives_match_finite_differences() {
        let e = Ellipse::new(30.0, 0.6).unwrap();
        for k in 0..40 {
            let psi = 0.17 * k as f64;
            let h = 1e-5;
            let p = e.eval(psi);
            assert!(((e.eval(psi + h).rho - e.eval(psi - h).rho) / (2.0 * h) - p.d1).abs() < 1e-5);
            assert!(((e.eval(psi + h).d1 - e.eval(psi - h).d1) / (2.0 * h) - p.d2).abs() < 1e-4);
        }
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        assert!(matches!(
            Ellipse::new(30.0, 1.0),
            Err(Error::OutOfRange { .. })
        ));
        assert!(matches!(
            Ellipse::new(f64::NAN, 0.1),
            Err(Error::NonFinite { .. })
        ));
        let spec = CurveSpec::Spline {
            radii_mm: vec![1.0, 2.0, 3.0],
            angles_deg: vec![0.0, 90.0, 180.0],
        };
        assert!(matches!(
            spec.build(),
            Err(Error::TooFewPoints { got: 3, .. })
        ));
        let spec = CurveSpec::Spline {
            radii_mm: vec![1.0, 2.0, -3.0, 2.0],
            angles_deg: vec![0.0, 90.0, 180.0, 270.0],
        };
        assert!(matches!(spec.build(), Err(Error::NonPositiveRadius { .. })));
        let spec = CurveSpec::Spline {
            radii_mm: vec![1.0, 2.0, 3.0, 2.0],
            angles_deg: vec![0.0, 90.0, 90.0, 270.0],
        };
        assert!(matches!(
            spec.build(),
            Err(Error::ControlAngles { index: 2, .. })
        ));
        let spec = CurveSpec::Fourier {
            c0_mm: 10.0,
            cos_mm: vec![11.0],
            sin_mm: vec![],
        };
        assert!(matches!(spec.build(), Err(Error::NonPositiveRadius { .. })));
    }

    #[test]
    fn paper_curve_builds_in_every_construction() {
        let (r, a) = paper_control_points();
        for spec in [
            CurveSpec::Spline {
                radii_mm: r.clone(),
                angles_deg: a.clone(),
            },
            CurveSpec::Bspline {
                radii_mm: r.clone(),
                angles_deg: a.clone(),
            },
            CurveSpec::Bezier {
                radii_mm: r.clone(),
                angles_deg: a.clone(),
            },
        ] {
            let c = spec.build().unwrap_or_else(|e| panic!("{spec:?}: {e}"));
            assert!(c.eval(1.0).rho > 0.0);
        }
    }
}
