//! The rod in time against a peer (issue 32): the uniform clamped–free rod released from its rest
//! shape with a velocity in the first mode's shape (tip amplitude 1e-4), followed for 1.2 periods
//! by `vibrissa::dynamics::free` (Newmark in time, Lobatto6 collocation in s), at 25, 50, 100
//! and 200 steps per period; and the pair 50 + 100 whose Richardson extrapolation gives the
//! period to 1e-6 (measured 6.8e-7, docs/dependencies.md). The period errors of the single runs
//! are Newmark's own, `πΔt/atan(ωΔt/2)` against `2π/ω`: 5.2e-3, 1.3e-3, 3.3e-4, 8.2e-5.
//!
//! Printed first, the error-against-time table: the four runs with the default options and with
//! grid 50, tol 1e-8 (fit to period errors of 1e-4 and above), timed in one interleaved run
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
    drag, first_mode_velocity, free, DynDragOptions, DynamicsOptions, DynamicsResult,
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

fn run(steps_per_period: usize) -> DynamicsResult {
    run_with(steps_per_period, &DynamicsOptions::default())
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
        ("grid 200, tol 1e-10 (default)", DynamicsOptions::default()),
        (
            "grid 50, tol 1e-8",
            DynamicsOptions {
                grid: 50,
                tol: 1e-8,
                ..DynamicsOptions::default()
            },
        ),
    ];
    let mut best = [[Duration::MAX; 4]; 2];
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
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
