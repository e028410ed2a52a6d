//! Closure solve across resolutions: from samples alone, and the whole gear pair.

/// The binaries' allocator (the CLI and the Python extension set it too).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use noncirc::core::solve_closure;
use noncirc::core::Rng;
use noncirc::core::{CurveSpec, GearPair, Resolution};
use rayon::prelude::*;
use std::hint::black_box;

fn closure(c: &mut Criterion) {
    let curve = CurveSpec::paper().build().unwrap();
    let mut group = c.benchmark_group("closure_from_samples");
    for n in [60usize, 120, 360, 1440] {
        let res = Resolution {
            closure_rel_tol: 1e-3,
            ..Resolution::DEFAULT.with_samples(n)
        };
        let rho: Vec<f64> = (0..n)
            .map(|j| curve.eval(std::f64::consts::TAU * j as f64 / n as f64).rho)
            .collect();
        group.throughput(Throughput::Elements(1));
        group.bench_with_input(BenchmarkId::from_parameter(n), &rho, |b, rho| {
            b.iter(|| solve_closure(black_box(rho), &res).unwrap())
        });
    }
    group.finish();
    let mut group = c.benchmark_group("gear_pair_solve");
    for n in [120usize, 360, 1440] {
        let res = Resolution {
            closure_rel_tol: 1e-3,
            ..Resolution::DEFAULT.with_samples(n)
        };
        group.throughput(Throughput::Elements(1));
        group.bench_with_input(BenchmarkId::from_parameter(n), &res, |b, res| {
            b.iter(|| GearPair::solve(black_box(curve.clone()), *res).unwrap())
        });
    }
    group.finish();
}

/// Closure solves of 4096 different valid 12-point spline curves (radii 10–70 mm) at the default
/// 120 samples per turn, on 1 and 2 threads.
fn closure_batch(c: &mut Criterion) {
    let res = Resolution::DEFAULT;
    let n = res.samples_per_turn;
    let mut rng = Rng::new(9);
    // Random radii whose spline dips below zero are refused by the model: draw again.
    let mut curves: Vec<Vec<f64>> = Vec::with_capacity(4096);
    while curves.len() < 4096 {
        let mut spec = CurveSpec::paper();
        if let CurveSpec::Spline { radii_mm, .. } = &mut spec {
            for r in radii_mm.iter_mut() {
                *r = 10.0 + 60.0 * rng.uniform();
            }
        }
        if let Ok(curve) = spec.build() {
            let samples = curve.sample_uniform(0.0, std::f64::consts::TAU / n as f64, n);
            curves.push(samples.iter().map(|p| p.rho).collect());
        }
    }
    let mut group = c.benchmark_group("closure_batch_default_resolution");
    group.throughput(Throughput::Elements(curves.len() as u64));
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        group.bench_with_input(
            BenchmarkId::new("threads", threads),
            &curves,
            |b, curves| {
                b.iter(|| {
                    pool.install(|| {
                        curves
                            .par_iter()
                            .with_max_len(noncirc::search::batch_piece(curves.len(), threads))
                            .map(|rho| {
                                solve_closure(black_box(rho), &res)
                                    .map_or(0.0, |c| c.centre_distance)
                            })
                            .sum::<f64>()
                    })
                })
            },
        );
    }
    group.finish();
}

/// The pitch curve's construction as a search does it per design: 256 random valid
/// 12-point splines of the paper's control angles built from their specification
/// (`spline_12`); and with each spline's control angles moved too (`spline_12_moving_angles`),
/// so that no two consecutive splines share their knots and the spline's system is factored
/// for every one.
fn pitch_curve_build(c: &mut Criterion) {
    let mut rng = Rng::new(5);
    let mut group = c.benchmark_group("pitch_curve_build");
    for (name, moving) in [("spline_12", false), ("spline_12_moving_angles", true)] {
        let mut specs = Vec::with_capacity(256);
        while specs.len() < 256 {
            let mut spec = CurveSpec::paper();
            if let CurveSpec::Spline {
                radii_mm,
                angles_deg,
            } = &mut spec
            {
                for r in radii_mm.iter_mut() {
                    *r = 10.0 + 60.0 * rng.uniform();
                }
                if moving {
                    // Each angle within ±5° of the paper's (they stay 30° apart ± 10°).
                    for a in angles_deg.iter_mut() {
                        *a += 10.0 * (rng.uniform() - 0.5);
                    }
                }
            }
            if spec.build().is_ok() {
                specs.push(spec);
            }
        }
        group.throughput(Throughput::Elements(specs.len() as u64));
        group.bench_function(name, |b| {
            b.iter(|| {
                specs
                    .iter()
                    .map(|spec| black_box(spec).build().unwrap().eval(0.0).rho)
                    .sum::<f64>()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, closure, closure_batch, pitch_curve_build);
criterion_main!(benches);
