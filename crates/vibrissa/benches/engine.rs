//! The one engine on every scene class: the cost of a scan per output point against the paper's
//! uniform rod (issue: tapered ρ ≥ 0.3, pre-curved, compliant and inclined scenes at most 2× per
//! point; the ρ = 0.1 rod and the rat presets at most 5× the uniform 201-point scan; a scan stopped
//! by slip no dearer than the part of the full scan it covers).
//!
//! Criterion times every scene; the table printed first is measured in one interleaved run
//! (round-robin over the scenes, minimum of the repetitions, in the thread's CPU time where
//! Linux gives it) so that the ratios see the same machine load; a filter that no benchmark
//! matches prints the table alone:
//!
//! ```sh
//! cargo bench -p vibrissa --bench engine
//! cargo bench -p vibrissa --bench engine -- table-only
//! ```

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use vibrissa::{scan, Precurvature, Rod, ScanOptions, ScanResult, Scene, Stiffness, Surface};

#[path = "support/clock.rs"]
mod clock;

struct Case {
    name: &'static str,
    rod: Rod,
    surface: Surface,
    opts: ScanOptions,
}

fn preset(file: &str) -> Scene {
    let path = format!("{}/../../data/scenes/{file}", env!("CARGO_MANIFEST_DIR"));
    toml::from_str(&std::fs::read_to_string(path).expect("preset")).expect("preset parses")
}

fn cases() -> Vec<Case> {
    let full = ScanOptions::default(); // η from the scene, d ∈ [0, 0.5], 201 points, tol 1e-10
    let s = |f: &dyn Fn(&mut Scene)| {
        let mut sc = Scene::default();
        f(&mut sc);
        sc
    };
    let lin = |k0, k1| Precurvature::Linear { k0, k1 };
    let list: Vec<(&'static str, Scene, ScanOptions)> = vec![
        ("uniform", Scene::default(), full.clone()),
        // the same physics written as a general profile: taper ratio 1 is dispatched to the
        // uniform path, a table of b = 1 runs the tabulated profile (its whole extra cost)
        (
            "taper 1.0 (uniform)",
            s(&|x| x.stiffness = Stiffness::Taper { ratio: 1.0 }),
            full.clone(),
        ),
        (
            "table b = 1",
            s(&|x| {
                x.stiffness = Stiffness::Table {
                    s: vec![0.0, 0.25, 0.5, 0.75, 1.0],
                    b: vec![1.0; 5],
                }
            }),
            full.clone(),
        ),
        (
            "taper 0.7",
            s(&|x| x.stiffness = Stiffness::Taper { ratio: 0.7 }),
            full.clone(),
        ),
        (
            "taper 0.3 eta 0.9",
            s(&|x| {
                x.stiffness = Stiffness::Taper { ratio: 0.3 };
                x.eta = 0.9
            }),
            full.clone(),
        ),
        (
            "k0 +0.3",
            s(&|x| x.precurvature = lin(0.3, 0.0)),
            full.clone(),
        ),
        (
            "k0 -0.3",
            s(&|x| x.precurvature = lin(-0.3, 0.0)),
            full.clone(),
        ),
        (
            "k0 +1",
            s(&|x| x.precurvature = lin(1.0, 0.0)),
            full.clone(),
        ),
        (
            "k0 0.5 - s",
            s(&|x| x.precurvature = lin(0.5, -1.0)),
            full.clone(),
        ),
        (
            "compliance 0.5",
            s(&|x| x.support_compliance = 0.5),
            full.clone(),
        ),
        (
            "compliance 1",
            s(&|x| x.support_compliance = 1.0),
            full.clone(),
        ),
        ("surface -0.3", s(&|x| x.surface_angle = -0.3), full.clone()),
        ("surface +0.3", s(&|x| x.surface_angle = 0.3), full.clone()),
        ("surface +0.2", s(&|x| x.surface_angle = 0.2), full.clone()),
        (
            "taper 0.1 eta 0.97",
            s(&|x| {
                x.stiffness = Stiffness::Taper { ratio: 0.1 };
                x.eta = 0.97
            }),
            full.clone(),
        ),
        ("rat long", preset("rat_mystacial_long.toml"), full.clone()),
        (
            "rat short",
            preset("rat_mystacial_short.toml"),
            full.clone(),
        ),
        (
            "uniform, slip mu0 0.7",
            Scene::default(),
            ScanOptions {
                mu0: Some(0.7),
                ..full.clone()
            },
        ),
    ];
    list.into_iter()
        .map(|(name, scene, opts)| {
            let (rod, surface) = scene.parts().expect("valid scene");
            Case {
                name,
                rod,
                surface,
                opts,
            }
        })
        .collect()
}

fn run(c: &Case) -> ScanResult {
    scan(&c.rod, &c.surface, &c.opts).expect("scan runs")
}

/// Minimum time per scan over `reps` round-robin repetitions of all cases: the thread's CPU
/// time where [`clock::thread_cpu`] has it, else the wall time.
fn interleaved(cases: &[Case], reps: usize) -> Vec<Duration> {
    let mut best = vec![Duration::MAX; cases.len()];
    for _ in 0..reps {
        for (c, b) in cases.iter().zip(best.iter_mut()) {
            let ((), spent) = clock::timed(|| {
                black_box(run(c));
            });
            *b = (*b).min(spent);
        }
    }
    best
}

fn table(cases: &[Case]) {
    let times = interleaved(cases, 15);
    let grid_points = |r: &ScanResult| r.points.iter().filter(|p| p.event.is_none()).count();
    let results: Vec<ScanResult> = cases.iter().map(run).collect();
    let per_point = |i: usize| times[i].as_secs_f64() / grid_points(&results[i]).max(1) as f64;
    let (t_u, pp_u) = (times[0].as_secs_f64(), per_point(0));
    let clock = clock::name();
    println!(
        "\n({clock}, minimum of 15)\n{:<24} {:>7} {:>10} {:>10} {:>9} {:>9}  stop",
        "scene", "points", "scan ms", "µs/point", "×/point", "×scan"
    );
    for (i, c) in cases.iter().enumerate() {
        println!(
            "{:<24} {:>7} {:>10.3} {:>10.2} {:>9.2} {:>9.2}  {}",
            c.name,
            grid_points(&results[i]),
            times[i].as_secs_f64() * 1e3,
            per_point(i) * 1e6,
            per_point(i) / pp_u,
            times[i].as_secs_f64() / t_u,
            results[i].stop
        );
    }
    // the slip-stopped scan against the full scan over the same stretch of d (same grid spacing)
    let slip = &results[cases.len() - 1];
    if let vibrissa::StopReason::Slip { d, .. } = slip.stop {
        let covered = grid_points(slip); // grid points 0..covered-1 at spacing 0.5/200
        let part = Case {
            name: "uniform, d up to the slip",
            rod: cases[0].rod.clone(),
            surface: cases[0].surface.clone(),
            opts: ScanOptions {
                d_max: 0.5 * (covered - 1) as f64 / 200.0 + 0.0025,
                points: covered + 1,
                ..cases[0].opts.clone()
            },
        };
        let pair = [
            Case {
                name: "slip",
                rod: cases[0].rod.clone(),
                surface: cases[0].surface.clone(),
                opts: cases[cases.len() - 1].opts.clone(),
            },
            part,
        ];
        let t = interleaved(&pair, 15);
        println!(
            "slip at d = {d:.6}: {:.3} ms; full scan over the same stretch ({} points): {:.3} ms; ratio {:.2}",
            t[0].as_secs_f64() * 1e3,
            covered + 1,
            t[1].as_secs_f64() * 1e3,
            t[0].as_secs_f64() / t[1].as_secs_f64()
        );
    }
}

fn bench(c: &mut Criterion) {
    let cases = cases();
    table(&cases);
    let mut g = c.benchmark_group("engine");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(300));
    g.measurement_time(Duration::from_secs(2));
    for case in &cases {
        g.bench_function(case.name, |b| b.iter(|| black_box(run(case))));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
