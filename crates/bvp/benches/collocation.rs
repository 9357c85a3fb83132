//! Criterion benches: collocation, each scheme on Bratu (λ = 1, lower branch) and the Mattiasson
//! cantilever (P = 5) at tol 1e-6 and 1e-10, from the samples' cold guesses (full mesh adaptation).
//! The final node count of each case is printed once before it is timed.
//!
//! `collocation_fixed/…`: one Newton solve on a fixed uniform mesh of 100, 1000 and 10 000
//! intervals (no adaptation) — the size sweep that decides the linear solver of the Newton
//! systems (docs/dependencies.md): separated (Bratu `n = 2`, cantilever `n = 4`), with a parameter
//! (Eigen, `k = 1`) and non-separated boundary conditions.
use bvp::samples::{Bratu, Cantilever, Eigen, LinearNonSeparated};
use bvp::{Bvp, BvpSolver, Collocation, CollocationOptions, Guess, Scheme};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use std::time::Duration;

fn case<P: Bvp>(c: &mut Criterion, name: &str, prob: &P, guess: &Guess) {
    let mut group = c.benchmark_group(format!("collocation/{name}"));
    group.measurement_time(Duration::from_secs(2));
    group.warm_up_time(Duration::from_millis(300));
    group.sample_size(10);
    for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
        for tol in [1e-6, 1e-10] {
            let mut solver = Collocation::new(CollocationOptions {
                scheme,
                tol,
                ..Default::default()
            })
            .expect("valid options");
            let sol = solver.solve(prob, guess).expect("bench problem solves");
            eprintln!(
                "collocation/{name} {scheme:?} tol {tol:e}: {} nodes, {} passes, {} Newton iterations",
                sol.len(),
                sol.stats.mesh_passes,
                sol.stats.newton_iters
            );
            group.bench_with_input(
                BenchmarkId::new(format!("{scheme:?}"), format!("tol={tol:e}")),
                &tol,
                |b, _| b.iter(|| black_box(solver.solve(prob, guess).expect("solves"))),
            );
        }
    }
    group.finish();
}

/// One Newton solve on `intervals` equal intervals, from the problem's guess resampled there.
fn fixed<P: Bvp>(c: &mut Criterion, name: &str, prob: &P, coarse: &Guess, schemes: &[Scheme]) {
    let mut group = c.benchmark_group(format!("collocation_fixed/{name}"));
    group.measurement_time(Duration::from_secs(2));
    group.warm_up_time(Duration::from_millis(300));
    group.sample_size(10);
    let (a, b) = prob.interval();
    for &scheme in schemes {
        for intervals in [100, 1000, 10_000] {
            let mesh = (0..=intervals)
                .map(|i| a + (b - a) * i as f64 / intervals as f64)
                .collect();
            let guess = Guess::from_fn(coarse.n, mesh, coarse.params.clone(), |s, z| {
                coarse.eval(s, z)
            });
            let mut solver = Collocation::new(CollocationOptions {
                scheme,
                adapt: false,
                max_nodes: 2 * intervals,
                ..Default::default()
            })
            .expect("valid options");
            let sol = solver.solve(prob, &guess).expect("bench problem solves");
            eprintln!(
                "collocation_fixed/{name} {scheme:?} {intervals} intervals: {} Newton iterations",
                sol.stats.newton_iters
            );
            group.bench_with_input(
                BenchmarkId::new(format!("{scheme:?}"), intervals),
                &intervals,
                |bch, _| bch.iter(|| black_box(solver.solve(prob, &guess).expect("solves"))),
            );
        }
    }
    group.finish();
}

fn bench(c: &mut Criterion) {
    let both = [Scheme::Lobatto4, Scheme::Lobatto6];
    let bratu = Bratu { lambda: 1.0 };
    fixed(c, "bratu", &bratu, &bratu.guess(), &both);
    let cantilever = Cantilever { load: 5.0 };
    fixed(c, "cantilever_p5", &cantilever, &cantilever.guess(), &both);
    fixed(c, "eigen", &Eigen, &Eigen::guess(), &[Scheme::Lobatto4]);
    let nonsep = LinearNonSeparated;
    fixed(
        c,
        "nonseparated",
        &nonsep,
        &LinearNonSeparated::guess(),
        &[Scheme::Lobatto4],
    );

    let bratu = Bratu { lambda: 1.0 };
    case(c, "bratu", &bratu, &bratu.guess());
    let cantilever = Cantilever { load: 5.0 };
    case(c, "cantilever_p5", &cantilever, &cantilever.guess());
}

criterion_group!(benches, bench);
criterion_main!(benches);
