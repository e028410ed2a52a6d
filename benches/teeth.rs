//! A toothed pair with every check (undercut, tip land, whole-cycle mesh, contact ratio)
//! at the default settings, and its cost against the number of flank samples; the stages
//! apart (arc tables, cutting, mesh check) to say what dominates.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use noncirc::core::{CurveSpec, ToothSpec, ToothedPair};
use std::hint::black_box;

fn teeth(c: &mut Criterion) {
    let ellipse = CurveSpec::Ellipse {
        semi_major_mm: 30.0,
        eccentricity: 1.0 / (2.0 + 3f64.sqrt()),
    }
    .build()
    .unwrap();
    let mut group = c.benchmark_group("toothed_pair_ellipse_z18");
    for flank_samples in [8usize, 16, 24, 48] {
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
    let fourier = CurveSpec::Fourier {
        c0_mm: 30.0,
        cos_mm: vec![0.0, 1.5],
        sin_mm: vec![0.0, 0.0, 0.6],
    }
    .build()
    .unwrap();
    let spec = ToothSpec::default();
    group.bench_function("fourier_z30", |b| {
        b.iter(|| ToothedPair::cut(black_box(&fourier), 60.0, 30, &spec).unwrap())
    });
    let one_step = ToothSpec {
        mesh_steps_per_pitch: 1,
        ..spec
    };
    group.bench_function("fourier_z30_one_mesh_step", |b| {
        b.iter(|| ToothedPair::cut(black_box(&fourier), 60.0, 30, &one_step).unwrap())
    });
    group.bench_function("fourier_arc_tables", |b| {
        b.iter(|| noncirc::core::PairTrack::new(black_box(&fourier), 60.0, 256).unwrap())
    });
    group.finish();
}

criterion_group!(benches, teeth);
criterion_main!(benches);
