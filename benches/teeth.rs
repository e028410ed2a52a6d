//! A toothed pair with every check (undercut, tip land, whole-cycle mesh, contact ratio)
//! at the default settings, and its cost against the number of flank samples and mesh
//! steps; the arc tables apart; pairs cut on one thread and on two (throughput).

/// The binaries' allocator (the CLI and the Python extension set it too).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use noncirc::core::{CurveSpec, PitchCurve, ToothSpec, ToothedPair};
use rayon::prelude::*;
use std::hint::black_box;

fn moving_box_ellipse() -> PitchCurve {
    CurveSpec::Ellipse {
        semi_major_mm: 30.0,
        eccentricity: 1.0 / (2.0 + 3f64.sqrt()),
    }
    .build()
    .unwrap()
}

fn fourier() -> PitchCurve {
    CurveSpec::Fourier {
        c0_mm: 30.0,
        cos_mm: vec![0.0, 1.5],
        sin_mm: vec![0.0, 0.0, 0.6],
    }
    .build()
    .unwrap()
}

fn teeth(c: &mut Criterion) {
    let ellipse = moving_box_ellipse();
    let mut group = c.benchmark_group("toothed_pair_ellipse_z18");
    for flank_samples in [8usize, 12, 18, 24, 48] {
        let spec = ToothSpec {
            flank_samples,
            ..ToothSpec::default()
        };
        group.bench_with_input(
            BenchmarkId::from_parameter(flank_samples),
            &spec,
            |b, spec| b.iter(|| ToothedPair::cut(black_box(&ellipse), 60.0, 18, spec).unwrap()),
        );
    }
    group.finish();
    let mut group = c.benchmark_group("toothed_pair_default");
    let spec = ToothSpec::default();
    let fourier = fourier();
    group.bench_function("ellipse_z24", |b| {
        b.iter(|| ToothedPair::cut(black_box(&ellipse), 60.0, 24, &spec).unwrap())
    });
    group.bench_function("fourier_z30", |b| {
        b.iter(|| ToothedPair::cut(black_box(&fourier), 60.0, 30, &spec).unwrap())
    });
    for steps in [1usize, 4] {
        let spec = ToothSpec {
            mesh_steps_per_pitch: steps,
            ..spec
        };
        group.bench_function(format!("ellipse_z18_mesh_steps_{steps}"), |b| {
            b.iter(|| ToothedPair::cut(black_box(&ellipse), 60.0, 18, &spec).unwrap())
        });
    }
    group.bench_function("ellipse_arc_tables", |b| {
        b.iter(|| noncirc::core::PairTrack::new(black_box(&ellipse), 60.0, 256).unwrap())
    });
    group.finish();
    // Throughput: 16 pairs (the ellipse at 18 teeth) on a pool of one and of two threads.
    let mut group = c.benchmark_group("sixteen_toothed_pairs");
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        group.bench_function(BenchmarkId::new("threads", threads), |b| {
            b.iter(|| {
                pool.install(|| {
                    (0..16)
                        .into_par_iter()
                        .map(|_| ToothedPair::cut(black_box(&ellipse), 60.0, 18, &spec).unwrap())
                        .count()
                })
            })
        });
    }
    group.finish();
}

criterion_group!(benches, teeth);
criterion_main!(benches);
