//! Contact anywhere along the rod: the cost of a whisk against a point object and of a single
//! peg solve against the paper's uniform scan and tip solve (issue: a 201-angle whisk at most 2×
//! the uniform 201-point scan, a peg solve at most 2× a tip solve), and of scans that lie down on
//! the surface. The table printed first is measured in one interleaved run (round-robin, minimum
//! of the repetitions) so that the ratios see the same machine load:
//!
//! ```sh
//! cargo bench -p vibrissa --bench contact
//! ```

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::{Duration, Instant};
use vibrissa::{
    scan, solve, solve_peg, whisk, BranchChoice, Rod, ScanOptions, Scene, SolverConfig, Surface,
    Target, WhiskOptions,
};

type Job = Box<dyn Fn()>;

fn jobs() -> Vec<(&'static str, Job)> {
    let peg = [0.7 * 0.3f64.sin(), 0.7 * 0.3f64.cos()];
    let paper = Surface::flat(0.75).unwrap();
    let scene = |eta: f64, taper: f64| {
        let s = Scene {
            eta,
            ..Scene::default()
        };
        let rod = Rod::builder().taper(taper).build().unwrap();
        (rod, s.surface().unwrap())
    };
    let (lie_rod, lie_surface) = scene(0.9, 0.1);
    let (u6_rod, u6_surface) = scene(0.6, 1.0);
    vec![
        (
            "uniform scan, 201 points",
            Box::new(move || {
                black_box(scan(&Rod::uniform(), &paper, &ScanOptions::default()).unwrap());
            }),
        ),
        (
            "whisk, 201 angles (object at 0.7)",
            Box::new(move || {
                black_box(
                    whisk(
                        &Rod::uniform(),
                        peg,
                        &WhiskOptions {
                            theta_max: 1.0,
                            ..WhiskOptions::default()
                        },
                    )
                    .unwrap(),
                );
            }),
        ),
        (
            "tip solve (alpha -pi/8, eta 0.75)",
            Box::new(|| {
                black_box(
                    solve(
                        &Rod::uniform(),
                        -std::f64::consts::FRAC_PI_8,
                        Target::Eta(0.75),
                        &BranchChoice::Convex,
                        &SolverConfig::default(),
                    )
                    .unwrap(),
                );
            }),
        ),
        (
            "peg solve (theta 0.6)",
            Box::new(move || {
                black_box(solve_peg(&Rod::uniform(), peg, 0.6, &WhiskOptions::default()).unwrap());
            }),
        ),
        (
            "uniform scan eta 0.6 (lies down)",
            Box::new(move || {
                black_box(scan(&u6_rod, &u6_surface, &ScanOptions::default()).unwrap());
            }),
        ),
        (
            "taper 0.1 eta 0.9 (lying start)",
            Box::new(move || {
                black_box(scan(&lie_rod, &lie_surface, &ScanOptions::default()).unwrap());
            }),
        ),
    ]
}

fn table(jobs: &[(&'static str, Job)]) {
    let mut best = vec![Duration::MAX; jobs.len()];
    for _ in 0..10 {
        for ((_, j), b) in jobs.iter().zip(best.iter_mut()) {
            let t = Instant::now();
            j();
            *b = (*b).min(t.elapsed());
        }
    }
    println!("\n{:<36} {:>10}", "job", "ms");
    for ((name, _), t) in jobs.iter().zip(&best) {
        println!("{name:<36} {:>10.3}", t.as_secs_f64() * 1e3);
    }
    let r = |a: usize, b: usize| best[a].as_secs_f64() / best[b].as_secs_f64();
    println!(
        "whisk / uniform scan: {:.2}; peg solve / tip solve: {:.2}",
        r(1, 0),
        r(3, 2)
    );
}

fn bench(c: &mut Criterion) {
    let jobs = jobs();
    table(&jobs);
    let mut g = c.benchmark_group("contact");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(300));
    g.measurement_time(Duration::from_secs(2));
    for (name, j) in &jobs {
        g.bench_function(*name, |b| b.iter(j));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
