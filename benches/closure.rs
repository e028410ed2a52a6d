//! Closure solve across resolutions: from samples alone, and the whole gear pair.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use noncirc::core::gear::solve_closure;
use noncirc::core::{CurveSpec, GearPair, Resolution};
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

criterion_group!(benches, closure);
criterion_main!(benches);
