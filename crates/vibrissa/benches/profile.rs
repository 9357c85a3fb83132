//! The uniform scene costs nothing extra: the paper's rod (zero-sized `Uniform` profile,
//! monomorphized, fast path) against the same physics written as `Taper { ratio: 1.0 }` (must be
//! dispatched to the uniform path: ratio ≈ 1) and as a `Table` of constant b = 1 (the general
//! profile and the generic scan). Reports the times and the overhead ratios.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Instant;
use vibrissa::{scan, Model, ScanOptions, Scene, SolverConfig, Stiffness};

fn models() -> (Model, Model, Model) {
    let uniform = Model::new(&Scene::default()).unwrap();
    let taper1 = Model::new(&Scene {
        stiffness: Stiffness::Taper { ratio: 1.0 },
        ..Scene::default()
    })
    .unwrap();
    let table = Model::new(&Scene {
        stiffness: Stiffness::Table {
            s: vec![0.0, 0.25, 0.5, 0.75, 1.0],
            b: vec![1.0; 5],
        },
        ..Scene::default()
    })
    .unwrap();
    (uniform, taper1, table)
}

fn opts() -> ScanOptions {
    ScanOptions {
        solver: SolverConfig {
            tol: 1e-10,
            ..SolverConfig::default()
        },
        ..ScanOptions::default()
    }
}

fn bench(c: &mut Criterion) {
    let (uniform, taper1, table) = models();
    let o = opts();
    let mut g = c.benchmark_group("scan_eta075_201pts");
    g.sample_size(20);
    g.bench_function("uniform", |b| {
        b.iter(|| scan(black_box(&uniform), &o).unwrap())
    });
    g.bench_function("taper_1", |b| {
        b.iter(|| scan(black_box(&taper1), &o).unwrap())
    });
    g.bench_function("table_b1", |b| {
        b.iter(|| scan(black_box(&table), &o).unwrap())
    });
    g.finish();
    // the ratio, measured directly (criterion reports the two times separately)
    let time = |m: &Model| {
        let t = Instant::now();
        for _ in 0..10 {
            black_box(scan(m, &o).unwrap());
        }
        t.elapsed().as_secs_f64() / 10.0
    };
    let (tu, t1, tt) = (time(&uniform), time(&taper1), time(&table));
    println!(
        "uniform {:.3} ms, taper(1.0) {:.3} ms (ratio {:.3}), table(b=1) {:.3} ms (ratio {:.3})",
        tu * 1e3,
        t1 * 1e3,
        t1 / tu,
        tt * 1e3,
        tt / tu
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
