//! The rod in time against a peer (issue 32): the uniform clamped–free rod released from its rest
//! shape with a velocity in the first mode's shape (tip amplitude 1e-4), followed for 1.2 periods
//! by `vibrissa::dynamics::free` (Newmark in time, Lobatto6 collocation in s), at 25, 50 and 100
//! steps per period; and the pair 50 + 100 whose Richardson extrapolation gives the period to
//! 1e-6 (measured 6.8e-7, docs/dependencies.md). The period errors of the single runs are
//! Newmark's own, `πΔt/atan(ωΔt/2)` against `2π/ω`: 5.2e-3, 1.3e-3, 3.3e-4.
//!
//! The peer, PyElastica, is timed by `benches/pyelastica_free.py` on the same rod, start and
//! period measurement; docs/performance.md sets the two error-against-time curves side by side.
//!
//! The group `dynamic_drag`: the paper's rod (η = 0.75, μs 0.5, μk 0.3) dragged by
//! `vibrissa::dynamics::drag` at v = 0.05 (dt 0.02, tol 1e-8, grid 100: the test drags'
//! discretization) through its first 10 slips (20 events: each slip and the stick that ends
//! it); the per-slip cost is the time over 10. Measured on 2 cores shared with other builds
//! (load ~9): 28.9 s per drag [26.9, 30.6], 2.9 s per slip; one run of the same drag: 256
//! steps, 481 solves (37 ms each), 4727 Newton iterations, largest mesh 384, to d = 0.1967.
//! The last four of the ten slips (from d = 0.1897 on) stick at the moment they slip (the
//! tip does not move the way it is pushed), so six of them are slips of nonzero length.
//!
//! ```sh
//! cargo bench -p vibrissa --bench dynamics
//! ```

use criterion::{criterion_group, criterion_main, Criterion};
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::Duration;
use vibrissa::dynamics::{
    drag, first_mode_velocity, free, DynDragOptions, DynamicsOptions, CLAMPED_FREE_BETA1,
};
use vibrissa::{Rod, Surface};

fn oscillate(steps_per_period: usize) -> usize {
    let period = 2.0 * PI / (CLAMPED_FREE_BETA1 * CLAMPED_FREE_BETA1);
    let o = DynamicsOptions {
        dt: period / steps_per_period as f64,
        t_end: 1.2 * period,
        ..DynamicsOptions::default()
    };
    let r = free(&Rod::uniform(), &first_mode_velocity(1e-4), &o).expect("free oscillation");
    black_box(r.samples.len())
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
    let mut g = c.benchmark_group("free_oscillation");
    g.sample_size(10).measurement_time(Duration::from_secs(10));
    for n in [25, 50, 100] {
        g.bench_function(format!("{n}_steps_per_period"), |b| b.iter(|| oscillate(n)));
    }
    g.bench_function("period_to_1e-6_richardson_50_100", |b| {
        b.iter(|| oscillate(50) + oscillate(100))
    });
    g.finish();
    let mut g = c.benchmark_group("dynamic_drag");
    g.sample_size(10).measurement_time(Duration::from_secs(30));
    g.bench_function("paper_rod_10_slips", |b| b.iter(ten_slips));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
