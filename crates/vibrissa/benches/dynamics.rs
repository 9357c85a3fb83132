//! The rod in time against a peer (issue 32): the uniform clamped–free rod released from its rest
//! shape with a velocity in the first mode's shape (tip amplitude 1e-4), followed for 1.2 periods
//! by `vibrissa::dynamics::free` (Newmark's rule in time, Lobatto6 collocation in s), at 25, 50, 100
//! and 200 steps per period; and the pair 50 + 100 whose Richardson extrapolation gives the
//! period to 1e-6 (measured 6.8e-7, docs/dependencies.md). The period errors of the single runs
//! are Newmark's own, `πΔt/atan(ωΔt/2)` against `2π/ω`: 5.2e-3, 1.3e-3, 3.3e-4, 8.2e-5.
//!
//! Printed first, the error-against-time table: the four runs by Newmark's rule with the default
//! grid and tolerance and with grid 50, tol 1e-8 (fit to period errors of 1e-4 and above), and
//! by the default scheme of fixed steps (the energy–momentum step, grid 200, tol 1e-10), timed in one interleaved run
//! (minimum of 5, in the thread's CPU time where Linux gives it, as the bench `engine`), each
//! with its steps, Newton iterations, largest mesh, time per step and the period error read off
//! the tip's upward zero crossing, and Richardson's three pairs; a filter that no benchmark
//! matches prints the table alone (`cargo bench -p vibrissa --bench dynamics -- table-only`).
//!
//! The peer, PyElastica, is timed by `benches/pyelastica_free.py` on the same rod, start and
//! period measurement; docs/performance.md sets the two error-against-time curves side by side.
//!
//! The group `dynamic_drag`: the paper's rod (η = 0.75, μs 0.5, μk 0.3) dragged by
//! `vibrissa::dynamics::drag` at v = 0.05 (dt 0.02, tol 1e-8, grid 100: the test drags'
//! discretization) through its first 10 slips (20 events: each slip and the stick that ends
//! it); the per-slip cost is the time over 10. One run of the same drag (2026-11-30,
//! `cargo run --release -p vibrissa --example drag_slips -- --ten --settings 0.02,100,1e-8`):
//! 443 steps, 633 solves, 6396 Newton iterations, largest mesh 465, 13.0 s of CPU, to the
//! tenth stick at d = 0.3816; every one of the ten slips moves the tip. (Before the restart
//! after each event and the slip test on the held force, 2026-11-29, the same drag took 256
//! steps and 481 solves to d = 0.1967, its last four slips stuck at once.) The slips after the
//! first converge only as dt → 0: at this dt slip 3 lies 3.7e-3 from its limit (docs/model.md,
//! "The velocity mismatch of a stuck phase"); the accuracy against PyElastica (`benches/pyelastica_drag.py`) is
//! compared on the first slip, docs/performance.md.
//!
//! Printed second, the drag at equal accuracy in the first frequency: the same rod and surface
//! dragged over the foot's travel d 0 … 0.4 (whatever its events) at the time step whose
//! Newmark period error equals PyElastica's free-oscillation period error at r 0.02 and 25 …
//! 800 elements (grid 20, tol 1e-6), minimum of 3; the peer's side is `benches/pyelastica_drag.py
//! --d-max 0.4`, the ratios are in docs/performance.md ("The ten-slip drag at equal accuracy in
//! the first frequency"). The group `dynamic_drag` also times that drag at the accuracies of 200
//! and 400 elements (`span_0.4_at_*_elements_accuracy`).
//!
//! The group `modes`: the lowest natural frequency of a state, `vibrissa::modes::modes` with the
//! tip pinned (what `scan --modes` computes per row): the paper's pressed rod (f 2.8266, the
//! force along −y) and the rod tapered to 0.1 pressed at η 0.97 (f 0.0898), whose search for
//! the sign changes of `det D(λ)` starts near λ = −1e6 (docs/model.md, "The rod in time").
//!
//! ```sh
//! cargo bench -p vibrissa --bench dynamics
//! ```

use criterion::{criterion_group, criterion_main, Criterion};
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::Duration;
use vibrissa::dynamics::{
    drag, first_mode_velocity, free, DynDragOptions, DynamicsOptions, DynamicsResult, TimeScheme,
    CLAMPED_FREE_BETA1,
};
use vibrissa::modes::{modes, BaseLoad, ModeOptions, TipCondition};
use vibrissa::{Rod, Surface};

#[path = "support/clock.rs"]
mod clock;
#[path = "../tests/support/crossing.rs"]
mod crossing;

/// The period `2π/β₁²` of the first mode.
fn period() -> f64 {
    2.0 * PI / (CLAMPED_FREE_BETA1 * CLAMPED_FREE_BETA1)
}

/// Newmark's rule, grid 200, tol 1e-10: the scheme the comparison with PyElastica measured
/// (docs/performance.md); the default of fixed steps since 2026-12-04 is the energy–momentum
/// step, whose period errors on this small oscillation are Newmark's (the table's third part).
fn newmark() -> DynamicsOptions {
    DynamicsOptions {
        time_scheme: Some(TimeScheme::Newmark),
        ..DynamicsOptions::default()
    }
}

fn run(steps_per_period: usize) -> DynamicsResult {
    run_with(steps_per_period, &newmark())
}

/// The free oscillation at `steps_per_period` with the grid and tolerance of `base`.
fn run_with(steps_per_period: usize, base: &DynamicsOptions) -> DynamicsResult {
    let o = DynamicsOptions {
        dt: period() / steps_per_period as f64,
        t_end: 1.2 * period(),
        ..base.clone()
    };
    free(&Rod::uniform(), &first_mode_velocity(1e-4), &o).expect("free oscillation")
}

fn oscillate(steps_per_period: usize) -> usize {
    black_box(run(steps_per_period).samples.len())
}

/// The error-against-time table, for the default options (grid 200, tol 1e-10) and for a grid
/// and tolerance fit to the period errors of 1e-3 and above (grid 50, tol 1e-8: the history and
/// the mesh on 50 intervals): each of 25, 50, 100, 200 steps per period timed in one interleaved
/// run (round-robin over both, minimum of 5, the thread's CPU time where Linux gives it, else
/// wall time), its period error against `2π/β₁²`, and Richardson's pairs (their times summed).
fn table() {
    let ns = [25usize, 50, 100, 200];
    let configs = [
        (
            "Newmark, grid 200, tol 1e-10 (default grid and tol)",
            newmark(),
        ),
        (
            "Newmark, grid 50, tol 1e-8",
            DynamicsOptions {
                grid: 50,
                tol: 1e-8,
                ..newmark()
            },
        ),
        (
            "energy-momentum (the default), grid 200, tol 1e-10",
            DynamicsOptions::default(),
        ),
    ];
    let mut best = [[Duration::MAX; 4]; 3];
    for _ in 0..5 {
        for (c, (_, o)) in configs.iter().enumerate() {
            for (i, n) in ns.iter().enumerate() {
                let ((), spent) = clock::timed(|| {
                    black_box(run_with(*n, o));
                });
                best[c][i] = best[c][i].min(spent);
            }
        }
    }
    let clock = clock::name();
    for (c, (name, o)) in configs.iter().enumerate() {
        println!(
            "\n{name} ({clock}, minimum of 5)\n{:>14} {:>6} {:>7} {:>5} {:>10} {:>9} {:>11}",
            "steps/period", "steps", "newton", "mesh", "time ms", "ms/step", "period err"
        );
        let mut periods = [0.0; 4];
        for (i, n) in ns.iter().enumerate() {
            let r = run_with(*n, o);
            periods[i] = crossing::upward_crossing(&r, 0.6 * period());
            let ms = best[c][i].as_secs_f64() * 1e3;
            println!(
                "{n:>14} {:>6} {:>7} {:>5} {ms:>10.2} {:>9.3} {:>11.3e}",
                r.stats.steps,
                r.stats.newton_iterations,
                r.stats.max_nodes,
                ms / r.stats.steps as f64,
                (periods[i] / period() - 1.0).abs()
            );
        }
        for i in 0..3 {
            let rich = (4.0 * periods[i + 1] - periods[i]) / 3.0;
            println!(
                "{:>14} {:>6} {:>7} {:>5} {:>10.2} {:>9} {:>11.3e}",
                format!("{}+{} Rich.", ns[i], ns[i + 1]),
                "",
                "",
                "",
                (best[c][i] + best[c][i + 1]).as_secs_f64() * 1e3,
                "",
                (rich / period() - 1.0).abs()
            );
        }
    }
}

/// PyElastica's period errors of the free oscillation at r 0.02 and 25 … 800 elements
/// (`data/dynamics/pyelastica_free.csv`, `benches/pyelastica_free.py`): the accuracies against
/// the closed-form frequency at which its drags of `benches/pyelastica_drag.py --d-max 0.4`
/// are compared.
const PEER_PERIOD_ERRORS: [(usize, f64); 6] = [
    (25, 3.809e-2),
    (50, 1.873e-2),
    (100, 8.934e-3),
    (200, 4.004e-3),
    (400, 1.532e-3),
    (800, 2.933e-4),
];

/// The time step whose Newmark period error `(ωΔt/2)/atan(ωΔt/2) − 1` is `e` (ω = β₁²), by
/// bisection (the error rises with Δt).
fn dt_of_period_error(e: f64) -> f64 {
    let w = CLAMPED_FREE_BETA1 * CLAMPED_FREE_BETA1;
    let err = |dt: f64| (0.5 * w * dt) / (0.5 * w * dt).atan() - 1.0;
    let (mut lo, mut hi) = (1e-6, 1.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if err(mid) < e {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The drag over the foot's travel 0 … 0.4 (the span of the ten slips, whatever the events) at
/// `dt`, grid 20, tol 1e-6: the grid and tolerance that add nothing to the period error of the
/// step at these accuracies (`cargo run --release -p vibrissa --example free_oscillation -- --at
/// dt,20,1e-6`: 3.81e-2 … 1.52e-3 for Newmark's 3.81e-2 … 1.53e-3; at dt 0.0169, 2.3e-4 for its
/// 2.9e-4).
fn span_drag(dt: f64) -> vibrissa::dynamics::DynDragResult {
    let o = DynDragOptions {
        speed: 0.05,
        dt,
        tol: 1e-6,
        grid: 20,
        d_max: 0.4,
        ..DynDragOptions::default()
    };
    let surface = Surface::flat(0.75).expect("flat surface");
    drag(&Rod::uniform(), &surface, &o).expect("dynamic drag")
}

/// The drag at equal accuracy in the first frequency: for each of PyElastica's resolutions the
/// drag over d 0 … 0.4 at the time step of the same period error ([`span_drag`]), minimum of 3
/// in the thread's CPU time, with its steps, slips, refinements and Newton iterations.
fn drag_table() {
    let runs: Vec<(usize, f64, f64)> = PEER_PERIOD_ERRORS
        .iter()
        .map(|&(n, e)| (n, e, dt_of_period_error(e)))
        .collect();
    let mut best = vec![Duration::MAX; runs.len()];
    for _ in 0..3 {
        for (i, &(_, _, dt)) in runs.iter().enumerate() {
            let (_, spent) = clock::timed(|| black_box(span_drag(dt)));
            best[i] = best[i].min(spent);
        }
    }
    println!(
        "\nthe drag over d 0..0.4 at PyElastica's period errors (grid 20, tol 1e-6; {}, minimum of 3)\n{:>9} {:>11} {:>9} {:>6} {:>6} {:>12} {:>7} {:>10}  stop",
        clock::name(),
        "elements",
        "period err",
        "dt",
        "steps",
        "slips",
        "refinements",
        "newton",
        "time ms"
    );
    for (i, &(n, e, dt)) in runs.iter().enumerate() {
        let r = span_drag(dt);
        println!(
            "{n:>9} {e:>11.3e} {dt:>9.5} {:>6} {:>6} {:>12} {:>7} {:>10.1}  {} at d {:.4}",
            r.stats.steps,
            r.stats.slips,
            r.stats.refinements,
            r.stats.newton_iterations,
            best[i].as_secs_f64() * 1e3,
            format!("{:?}", r.stop).split(' ').next().unwrap_or(""),
            r.samples.last().map_or(0.0, |p| p.d)
        );
    }
}

/// The paper's rod dragged through 10 slips (20 events); returns the slips.
fn ten_slips() -> usize {
    let o = DynDragOptions {
        speed: 0.05,
        dt: 0.02,
        tol: 1e-8,
        grid: 100,
        d_max: 10.0,
        max_events: 20,
        ..DynDragOptions::default()
    };
    let surface = Surface::flat(0.75).expect("flat surface");
    let r = drag(&Rod::uniform(), &surface, &o).expect("dynamic drag");
    black_box(r.stats.slips)
}

fn bench(c: &mut Criterion) {
    table();
    drag_table();
    let mut g = c.benchmark_group("free_oscillation");
    g.sample_size(10).measurement_time(Duration::from_secs(10));
    for n in [25, 50, 100, 200] {
        g.bench_function(format!("{n}_steps_per_period"), |b| b.iter(|| oscillate(n)));
    }
    g.bench_function("period_to_1e-6_richardson_50_100", |b| {
        b.iter(|| oscillate(50) + oscillate(100))
    });
    g.finish();
    let mut g = c.benchmark_group("modes");
    g.sample_size(10);
    for (name, ratio, fy) in [
        ("paper_rod_pressed", 1.0, -2.826622),
        ("taper_0.1_pressed", 0.1, -0.0898),
    ] {
        let rod = Rod::builder().taper(ratio).build().expect("rod");
        let load = BaseLoad {
            m_base: 0.0,
            fx: 0.0,
            fy,
        };
        let o = ModeOptions {
            count: 1,
            ..ModeOptions::default()
        };
        g.bench_function(name, |b| {
            b.iter(|| {
                let r = modes(&rod, &load, TipCondition::Pinned, &o).expect("modes");
                black_box(r.modes[0].omega2)
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("dynamic_drag");
    g.sample_size(10).measurement_time(Duration::from_secs(30));
    g.bench_function("paper_rod_10_slips", |b| b.iter(ten_slips));
    // at the accuracy of PyElastica's 200 and 400 elements in the first frequency
    for (n, e) in [(200, 4.004e-3), (400, 1.532e-3)] {
        let dt = dt_of_period_error(e);
        g.bench_function(format!("span_0.4_at_{n}_elements_accuracy"), |b| {
            b.iter(|| black_box(span_drag(dt).stats.slips))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
