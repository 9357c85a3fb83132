//! The crate's DOP853 single shooting (variational equations on the same stages) against single
//! shooting through `ode_solvers`' Dop853 (Sparse output, forward-difference Newton matrix,
//! `bvp::odes::OdeShooting`) at equal accuracy: both at rtol = atol = tol, the achieved error in
//! `y` against the exact solution printed once before timing.
//!
//! Problems with closed forms: Bratu λ = 1 (lower branch) and Cash–Mazzia problem 3 at ε = 0.1
//! (`y = cos πx`).
//!
//! Run: `cargo bench -p bvp --features ode_solvers --bench ode_solvers -- --warm-up-time 1 --measurement-time 3`.
use bvp::odes::{OdeShooting, OdeShootingOptions};
use bvp::samples::Bratu;
use bvp::testset::CashMazzia;
use bvp::{Bvp, BvpSolver, Guess, Integrator, Shooting, ShootingOptions, Solution};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn own(tol: f64) -> Shooting {
    Shooting::new(ShootingOptions {
        integrator: Integrator::Adaptive {
            rtol: tol,
            atol: tol,
        },
        ..ShootingOptions::default()
    })
    .unwrap()
}

fn baseline(tol: f64) -> OdeShooting {
    OdeShooting::new(OdeShootingOptions {
        rtol: tol,
        atol: tol,
        ..OdeShootingOptions::default()
    })
    .unwrap()
}

fn bench_problem<P: Bvp>(
    c: &mut Criterion,
    name: &str,
    p: &P,
    guess: &Guess,
    error: &dyn Fn(&Solution) -> f64,
) {
    let mut group = c.benchmark_group(format!("ode_solvers/{name}"));
    for tol in [1e-6, 1e-10] {
        let mut a = own(tol);
        let mut b = baseline(tol);
        let sa = a.solve(p, guess).unwrap();
        let sb = match b.solve(p, guess) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{name} tol {tol:e}: OdeShooting failed: {e}");
                continue;
            }
        };
        eprintln!(
            "{name} tol {tol:e}: bvp::Shooting error {:.2e} ({} Newton, {} rhs); \
             OdeShooting error {:.2e} ({} Newton, {} rhs)",
            error(&sa),
            sa.stats.newton_iters,
            sa.stats.rhs_evals,
            error(&sb),
            sb.stats.newton_iters,
            sb.stats.rhs_evals
        );
        group.bench_function(format!("bvp-dop853/{tol:e}"), |bch| {
            bch.iter(|| a.solve(black_box(p), guess).unwrap())
        });
        group.bench_function(format!("ode_solvers-dop853/{tol:e}"), |bch| {
            bch.iter(|| b.solve(black_box(p), guess).unwrap())
        });
    }
    group.finish();
}

/// Max error of `y` at the solution's nodes.
fn node_error(sol: &Solution, exact: impl Fn(f64) -> f64) -> f64 {
    sol.mesh
        .iter()
        .enumerate()
        .map(|(i, &s)| (sol.node(i)[0] - exact(s)).abs())
        .fold(0.0, f64::max)
}

fn benches(c: &mut Criterion) {
    let bratu = Bratu { lambda: 1.0 };
    bench_problem(c, "bratu", &bratu, &bratu.guess(), &|s| {
        node_error(s, |x| bratu.exact(0, x)[0])
    });
    let p3 = CashMazzia::new(3).unwrap();
    let member = p3.at(0.1);
    bench_problem(c, "cash-mazzia-3", &member, &p3.guess(0.1, 11), &|s| {
        node_error(s, |x| p3.exact(x, 0.1).unwrap()[0])
    });
}

criterion_group!(ode, benches);
criterion_main!(ode);
