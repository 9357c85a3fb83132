//! Criterion benches: collocation, each scheme on Bratu (λ = 1, lower branch) and the Mattiasson
//! cantilever (P = 5) at tol 1e-6 and 1e-10, from the samples' cold guesses (full mesh adaptation).
//! The final node count of each case is printed once before it is timed.
use bvp::samples::{Bratu, Cantilever};
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

fn bench(c: &mut Criterion) {
    let bratu = Bratu { lambda: 1.0 };
    case(c, "bratu", &bratu, &bratu.guess());
    let cantilever = Cantilever { load: 5.0 };
    case(c, "cantilever_p5", &cantilever, &cantilever.guess());
}

criterion_group!(benches, bench);
criterion_main!(benches);
