//! Large systems: scipy's 60-state test problems (`bvp::samples::Big`, without and with two
//! unknown parameters) and the same family at 10, 20 and 40 states, from scipy's guesses at
//! scipy's default tol 1e-3, by Lobatto4, Lobatto6 (no coarsening, as scipy) and multiple
//! shooting (4 segments, DOP853 at rtol = tol/100), with finite-difference Jacobians as scipy's
//! tests use (and analytic ones for collocation at 60 states).
//!
//! After the criterion groups, one table in the same run: the minimum time of each case over
//! 1 s of repeats beside scipy's `solve_bvp` on the same problem
//! (`data/bvp_large/scipy_big.py`, run here if `python3` with scipy is on the path; the repo's
//! CI never runs benches), and the ratio.
//!
//! ```text
//! cargo bench -p bvp --bench large
//! ```
use bvp::samples::{Big, FiniteDifferences};
use bvp::{
    Bvp, BvpSolver, Collocation, CollocationOptions, Guess, Integrator, Scheme, Shooting,
    ShootingOptions, Solution,
};
use criterion::{criterion_group, Criterion};
use std::hint::black_box;
use std::time::{Duration, Instant};

const TOL: f64 = 1e-3;
const STATES: [usize; 4] = [10, 20, 40, 60];

#[derive(Clone, Copy, Debug)]
enum Method {
    Lobatto4,
    Lobatto6,
    MShoot4,
}

fn solve(m: Method, p: &impl Bvp, g: &Guess) -> Solution {
    match m {
        Method::Lobatto4 | Method::Lobatto6 => Collocation::new(CollocationOptions {
            scheme: if matches!(m, Method::Lobatto4) {
                Scheme::Lobatto4
            } else {
                Scheme::Lobatto6
            },
            tol: TOL,
            max_nodes: 1000,
            coarsen: false,
            ..CollocationOptions::default()
        })
        .expect("options")
        .solve(p, g),
        Method::MShoot4 => Shooting::new(ShootingOptions {
            integrator: Integrator::Adaptive {
                rtol: 1e-2 * TOL,
                atol: 1e-2 * TOL,
            },
            segments: 4,
            tol: Some(TOL),
            ..ShootingOptions::default()
        })
        .expect("options")
        .solve(p, g),
    }
    .expect("bench problem solves")
}

const METHODS: [Method; 3] = [Method::Lobatto4, Method::Lobatto6, Method::MShoot4];

fn name(params: bool) -> &'static str {
    if params {
        "big_params"
    } else {
        "big"
    }
}

fn benches(c: &mut Criterion) {
    for params in [false, true] {
        let mut group = c.benchmark_group(format!("large/{}", name(params)));
        group.measurement_time(Duration::from_secs(2));
        group.warm_up_time(Duration::from_millis(300));
        group.sample_size(10);
        for &n in &STATES {
            let p = Big {
                pairs: n / 2,
                params,
            };
            let (fd, g) = (FiniteDifferences(p), p.guess());
            for m in METHODS {
                group.bench_function(format!("{m:?}/fd/{n}"), |b| {
                    b.iter(|| black_box(solve(m, &fd, &g)))
                });
            }
            if n == 60 {
                for m in [Method::Lobatto4, Method::Lobatto6] {
                    group.bench_function(format!("{m:?}/analytic/{n}"), |b| {
                        b.iter(|| black_box(solve(m, &p, &g)))
                    });
                }
            }
        }
        group.finish();
    }
}

/// Minimum time of `f` over at least 1 s of repeats.
fn min_time(mut f: impl FnMut()) -> f64 {
    let (mut best, start) = (f64::INFINITY, Instant::now());
    while start.elapsed() < Duration::from_secs(1) {
        let t = Instant::now();
        f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    best
}

/// scipy's times by case name, if python3 with scipy runs the script.
fn scipy_times() -> Vec<(String, f64)> {
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/bvp_large/scipy_big.py"
    );
    let pairs: Vec<String> = STATES.iter().map(|n| (n / 2).to_string()).collect();
    let Ok(out) = std::process::Command::new("python3")
        .arg(script)
        .args(&pairs)
        .output()
    else {
        return Vec::new();
    };
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            Some((it.next()?.to_string(), it.next()?.parse().ok()?))
        })
        .collect()
}

fn table() {
    let scipy = scipy_times();
    if scipy.is_empty() {
        eprintln!("(python3 with scipy not found: no comparison)");
    }
    println!("\ncase | scipy solve_bvp | Lobatto4 | Lobatto6 | multiple shooting (4) | scipy / L4, L6, shooting");
    for params in [false, true] {
        for &n in &STATES {
            let p = Big {
                pairs: n / 2,
                params,
            };
            let (fd, g) = (FiniteDifferences(p), p.guess());
            let t: Vec<f64> = METHODS
                .iter()
                .map(|&m| min_time(|| drop(black_box(solve(m, &fd, &g)))))
                .collect();
            let key = format!("{}/{n}", name(params));
            let s = scipy.iter().find(|(k, _)| *k == key).map(|x| x.1);
            let ratio = |x: f64| s.map_or("—".into(), |s| format!("{:.1}×", s / x));
            println!(
                "{key} | {} | {:.3} ms | {:.3} ms | {:.3} ms | {}, {}, {}",
                s.map_or("—".into(), |s| format!("{:.3} ms", 1e3 * s)),
                1e3 * t[0],
                1e3 * t[1],
                1e3 * t[2],
                ratio(t[0]),
                ratio(t[1]),
                ratio(t[2])
            );
        }
    }
}

criterion_group!(large, benches);

fn main() {
    large();
    Criterion::default().configure_from_args().final_summary();
    table();
}
