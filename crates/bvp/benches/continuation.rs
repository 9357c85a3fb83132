//! Criterion bench: pseudo-arclength continuation of Bratu `u'' + λeᵘ = 0`, `u(0) = u(1) = 0`,
//! from λ = 0.1 on the lower branch through the fold (λ_c ≈ 3.5138) back to λ = 0.1 on the upper
//! branch, with adaptive single shooting. Prints the number of points, Newton iterations and the
//! fold location once before timing.
use bvp::continuation::{Continuation, ContinuationOptions, Member};
use bvp::samples::BratuFamily;
use bvp::{BvpSolver, Guess, Shooting, ShootingOptions, Solution};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

struct Summary {
    points: usize,
    newton_iters: usize,
    fold_lambda: f64,
}

fn run(start: &Solution) -> Summary {
    let opts = ContinuationOptions {
        lambda_min: 0.1,
        lambda_max: 10.0,
        ds: 0.05,
        ds_max: 0.5,
        ..Default::default()
    };
    let solver = Shooting::new(ShootingOptions::default()).expect("valid options");
    let cont = Continuation::new(&BratuFamily, solver, start.clone(), 0.1, opts)
        .expect("valid continuation");
    let mut s = Summary {
        points: 0,
        newton_iters: 0,
        fold_lambda: f64::NAN,
    };
    for p in cont {
        let p = p.expect("continuation step");
        s.points += 1;
        s.newton_iters += p.stats.newton_iters;
        if let Some(f) = p.fold {
            s.fold_lambda = f.lambda;
        }
    }
    s
}

fn bench(c: &mut Criterion) {
    let mut solver = Shooting::new(ShootingOptions::default()).expect("valid options");
    let guess = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![]);
    let start = solver
        .solve(&Member::new(&BratuFamily, 0.1), &guess)
        .expect("start solution");
    let s = run(&start);
    eprintln!(
        "bratu continuation (shooting): {} points, {} Newton iterations, fold at λ = {:.14} (λ_c = 3.51383071912516)",
        s.points, s.newton_iters, s.fold_lambda
    );
    let mut group = c.benchmark_group("continuation");
    group.sample_size(10);
    group.bench_function("bratu_fold_shooting", |b| b.iter(|| run(black_box(&start))));
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
