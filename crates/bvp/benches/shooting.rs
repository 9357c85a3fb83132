//! Criterion benches: single and multiple shooting on Bratu (λ = 1, lower branch) and the
//! cantilever (P = 5). The achieved accuracy of each configuration is printed once before timing.
//!
//! Run: `cargo bench -p bvp --bench shooting -- --warm-up-time 1 --measurement-time 3`.
use bvp::samples::{Bratu, Cantilever};
use bvp::{Bvp, BvpSolver, Guess, Integrator, Shooting, ShootingOptions};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn opts(integrator: Integrator, segments: usize) -> ShootingOptions {
    ShootingOptions {
        integrator,
        segments,
        ..Default::default()
    }
}

fn configs() -> Vec<(&'static str, ShootingOptions)> {
    let ad = Integrator::Adaptive {
        rtol: 1e-10,
        atol: 1e-10,
    };
    vec![
        ("single/rk4-200", opts(Integrator::Rk4 { steps: 200 }, 1)),
        ("single/dop853-1e-10", opts(ad, 1)),
        ("multiple-4/dop853-1e-10", opts(ad, 4)),
        (
            "multiple-8/rk4-200",
            opts(Integrator::Rk4 { steps: 200 }, 8),
        ),
    ]
}

fn bench_problem<P: Bvp>(
    c: &mut Criterion,
    name: &str,
    p: &P,
    guess: &Guess,
    error: impl Fn(&bvp::Solution) -> f64,
) {
    let mut group = c.benchmark_group(name);
    for (label, o) in configs() {
        let mut solver = Shooting::new(o).unwrap();
        let sol = solver.solve(p, guess).unwrap();
        eprintln!(
            "{name} {label}: error {:.2e}, {} nodes, {}",
            error(&sol),
            sol.len(),
            sol.stats
        );
        group.bench_function(label, |b| {
            b.iter(|| black_box(solver.solve(black_box(p), guess).unwrap()))
        });
    }
    group.finish();
}

fn bench(c: &mut Criterion) {
    // Bratu λ = 1, lower branch from u = ½ s(1 − s); error = max node error vs the closed form.
    let bratu = Bratu { lambda: 1.0 };
    bench_problem(c, "bratu-1", &bratu, &bratu.guess(), |sol| {
        let mut e = 0.0_f64;
        for (i, &s) in sol.mesh.iter().enumerate() {
            let x = bratu.exact(0, s);
            e = e.max(
                (sol.node(i)[0] - x[0])
                    .abs()
                    .max((sol.node(i)[1] - x[1]).abs()),
            );
        }
        e
    });

    // Cantilever P = 5 from the P = 4 solution (single shooting stalls from the straight rod);
    // error = max deviation from Mattiasson's 5-digit table (so ≤ 5e-6 means "all digits").
    let load = 5.0;
    let mut warm = Shooting::new(ShootingOptions {
        segments: 4,
        ..Default::default()
    })
    .unwrap();
    let p4 = Cantilever { load: 4.0 };
    let guess = Guess::from(&warm.solve(&p4, &p4.guess()).unwrap());
    let want = Cantilever::MATTIASSON[2].1;
    bench_problem(c, "cantilever-5", &Cantilever { load }, &guess, |sol| {
        let got = Cantilever::quantities(sol.left(), sol.right());
        (0..4).map(|q| (got[q] - want[q]).abs()).fold(0.0, f64::max)
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
