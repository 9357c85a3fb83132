//! The uniform scene costs nothing extra: the paper's rod (zero-sized `Uniform` profile,
//! monomorphized) against the same rod written as a `Table` of constant b = 1 (general profile,
//! table lookups per right-hand-side call). Reports both times and their ratio.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Instant;
use vibrissa::{scan, Model, ScanOptions, Scene, SolverConfig, Stiffness};

fn models() -> (Model, Model) {
    let uniform = Model::new(&Scene::default()).unwrap();
    let table = Model::new(&Scene {
        stiffness: Stiffness::Table {
            s: vec![0.0, 0.25, 0.5, 0.75, 1.0],
            b: vec![1.0; 5],
        },
        ..Scene::default()
    })
    .unwrap();
    (uniform, table)
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
    let (uniform, table) = models();
    let o = opts();
    let mut g = c.benchmark_group("scan_eta075_201pts");
    g.sample_size(20);
    g.bench_function("uniform", |b| {
        b.iter(|| scan(black_box(&uniform), &o).unwrap())
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
    let (tu, tt) = (time(&uniform), time(&table));
    println!(
        "uniform {:.3} ms, table(b=1) {:.3} ms, ratio table/uniform = {:.3}",
        tu * 1e3,
        tt * 1e3,
        tt / tu
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
