//! Criterion benches of issue #6 (speed versus accuracy), through the public `vibrissa` API:
//!
//! - `shape/*`: one solve per method of the paper's Fig. 3 rod (α = −π/8, φ1 = π/8, convex), each
//!   from the same warm start (the RK4 shape at 0.9·(α, φ1)); the relative error in `f` against
//!   the closed form is printed once before timing;
//! - `scan/*`: the full stiction scan, η = 0.75, d ∈ [0, 0.5], 201 points (max error in μ against
//!   the closed form at the first, middle and last point printed);
//! - `sweep50/*`: 50 scans, η = 0.60 … 0.95, on a rayon pool of 1 thread and of all cores (the
//!   parallel speed-up is the ratio of the two, measured in the same run).
//!
//! Run: `cargo bench --bench speed` (add `-- --quick` for a fast pass).
use bvp::{BvpSolver, Guess, Integrator, NewtonOptions, Shooting, ShootingOptions};
use criterion::{criterion_group, criterion_main, Criterion};
use elastica::{Branch, Elastica};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::Duration;
use vibrissa::equations::{Ends, RodBvp};
use vibrissa::profile::Uniform;
use vibrissa::{
    scan, solve, BranchChoice, Method, Rod, ScanOptions, SolverConfig, Surface, Target,
};

fn cfg(method: Method, tol: f64, rk4: Option<usize>) -> SolverConfig {
    SolverConfig {
        method,
        tol,
        rk4_steps: rk4,
        ..SolverConfig::default()
    }
}

fn bench_shape(c: &mut Criterion) {
    let (alpha, phi1) = (-PI / 8.0, PI / 8.0);
    let rod = Rod::uniform();
    let f_ref = Elastica::new(Branch::Convex, alpha, phi1).unwrap().f;
    let warm = solve(
        &rod,
        0.9 * alpha,
        Target::Phi1(0.9 * phi1),
        &BranchChoice::Convex,
        &cfg(Method::Shooting, 1e-10, Some(20)),
    )
    .unwrap();
    let start = BranchChoice::Guess(Box::new(warm));
    let mut group = c.benchmark_group("shape");
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    let runs: [(&str, SolverConfig, bool); 7] = [
        ("rk4-512", cfg(Method::Shooting, 1e-12, Some(512)), true),
        ("dop853-1e-10", cfg(Method::Shooting, 1e-10, None), true),
        ("dop853-1e-12", cfg(Method::Shooting, 1e-12, None), true),
        (
            "multiple8-1e-10",
            cfg(Method::MultipleShooting, 1e-10, None),
            true,
        ),
        (
            "collocation4-1e-8",
            cfg(Method::Collocation4, 1e-8, None),
            true,
        ),
        (
            "collocation6-1e-8",
            cfg(Method::Collocation6, 1e-8, None),
            true,
        ),
        ("analytic", cfg(Method::Analytic, 1e-10, None), false),
    ];
    for (name, cf, warm_start) in runs {
        let choice = if warm_start {
            start.clone()
        } else {
            BranchChoice::Convex
        };
        let s = solve(&rod, alpha, Target::Phi1(phi1), &choice, &cf).unwrap();
        eprintln!(
            "shape/{name}: rel. error in f {:.2e} ({} rhs evals, {} Newton iterations)",
            (s.f - f_ref).abs() / f_ref,
            s.stats.rhs_evals,
            s.stats.newton_iters
        );
        group.bench_function(name, |b| {
            b.iter(|| solve(&rod, alpha, Target::Phi1(phi1), &choice, &cf).unwrap())
        });
    }
    // The bare BVP solve (crate bvp on the rod model), without the closed-form start, branch
    // check and shape post-processing of `vibrissa::solve`.
    let rod = RodBvp {
        profile: Uniform,
        compliance: 0.0,
        alpha,
        ends: Ends::Phi1 { phi1 },
    };
    let guess = {
        let BranchChoice::Guess(w) = &start else {
            unreachable!()
        };
        let mut g = Guess::from(w.solution().unwrap());
        g.params = vec![w.f];
        g
    };
    for tol in [1e-10, 1e-12] {
        let mut solver = Shooting::new(ShootingOptions {
            integrator: Integrator::Adaptive {
                rtol: tol,
                atol: tol,
            },
            newton: NewtonOptions {
                tol,
                ..NewtonOptions::default()
            },
            ..ShootingOptions::default()
        })
        .unwrap();
        let sol = solver.solve(&rod, &guess).unwrap();
        eprintln!(
            "shape/bvp-dop853-{tol:e}: rel. error in f {:.2e} ({})",
            (sol.params[0] - f_ref).abs() / f_ref,
            sol.stats
        );
        group.bench_function(format!("bvp-dop853-{tol:e}"), |b| {
            b.iter(|| solver.solve(&rod, &guess).unwrap())
        });
    }
    group.finish();
}

fn scan_opts(method: Method, tol: f64) -> ScanOptions {
    ScanOptions {
        d_max: 0.5,
        points: 201,
        solver: cfg(method, tol, None),
        ..ScanOptions::default()
    }
}

fn bench_scan(c: &mut Criterion) {
    let (rod, surface) = (Rod::uniform(), Surface::flat(0.75).unwrap());
    let cf = elastica::ClosedFormScan::new(0.75).unwrap();
    let mut group = c.benchmark_group("scan");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(4));
    for (name, method, tol) in [
        ("shooting-1e-10", Method::Shooting, 1e-10),
        ("shooting-1e-6", Method::Shooting, 1e-6),
    ] {
        let o = scan_opts(method, tol);
        let r = scan(&rod, &surface, &o).unwrap();
        // μ_max against the closed form: a single well-defined number per scan
        let mm = cf.mu_max().unwrap();
        eprintln!(
            "scan/{name}: {} points, stop {}, mu_max {:.12} (closed form {:.12}, error {:.1e})",
            r.points.len(),
            r.stop,
            r.mu_max,
            mm.mu,
            (r.mu_max - mm.mu).abs()
        );
        group.bench_function(name, |b| {
            b.iter(|| black_box(scan(&rod, &surface, &o).unwrap()))
        });
    }
    group.finish();
}

fn sweep(surfaces: &[Surface], o: &ScanOptions) -> f64 {
    let rod = Rod::uniform();
    surfaces
        .par_iter()
        .map(|s| scan(&rod, s, o).map_or(f64::NAN, |r| r.mu_max))
        .sum()
}

fn bench_sweep(c: &mut Criterion) {
    let models: Vec<Surface> = (0..50)
        .map(|i| Surface::flat(0.60 + 0.35 * i as f64 / 49.0).unwrap())
        .collect();
    let o = scan_opts(Method::Shooting, 1e-10);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut group = c.benchmark_group("sweep50");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(5));
    for threads in [1, cores] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        group.bench_function(format!("threads-{threads}"), |b| {
            b.iter(|| pool.install(|| black_box(sweep(&models, &o))))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_shape, bench_scan, bench_sweep);
criterion_main!(benches);
