//! Adaptive time steps against fixed ones (issue 32), measured: the uniform clamped–free rod
//! released from its rest shape with a velocity in the first mode's shape (tip velocity 1e-4,
//! Blevins table 8-1), followed by `vibrissa::dynamics::free` over five and a quarter periods (`T = 2π/β₁²`),
//! with fixed steps `T/n` and with `time_tol` (first step `T/50`).
//!
//! For each run: steps taken, steps rejected, Newton iterations, the CPU time of the thread
//! (`benches/support/clock.rs`), the period error
//! (the fifth upward zero crossing of the tip's x by cubic Hermite interpolation, divided by
//! five, against `T`), the energy drift `max |E/E0 − 1|` and the step lengths' range. With
//! `--drag`, the first slip of the dynamic drag (v = 0.05, grid 100, collocation tol 1e-8)
//! with fixed steps and with `time_tol`, against the limit dt → 0, d = 0.021003157884
//! (docs/performance.md).
//!
//! Run: `cargo run --release -p vibrissa --example adaptive_steps [-- --drag]` (about a minute;
//! `--drag` about 40 s).

use std::f64::consts::PI;
use vibrissa::dynamics::{
    drag, first_mode_velocity, free, DynDragOptions, DynamicsOptions, DynamicsResult, TimeScheme,
    CLAMPED_FREE_BETA1,
};
use vibrissa::{Rod, Surface};

#[path = "../benches/support/clock.rs"]
mod clock;

#[path = "../tests/support/crossing.rs"]
mod crossing;
use crossing::upward_crossing;

const PERIODS: f64 = 5.0;

fn drift(r: &DynamicsResult) -> f64 {
    let e0 = r.samples[0].kinetic + r.samples[0].elastic;
    r.samples.iter().fold(0.0f64, |m, p| {
        m.max(((p.kinetic + p.elastic) / e0 - 1.0).abs())
    })
}

fn row(label: &str, o: &DynamicsOptions, period: f64) -> Result<(), vibrissa::VibrissaError> {
    let (r, el) = clock::timed(|| free(&Rod::uniform(), &first_mode_velocity(1e-4), o));
    let (r, el) = (r?, el.as_secs_f64());
    let tp = upward_crossing(&r, (PERIODS - 0.4) * period) / PERIODS;
    let (lo, hi) = r
        .samples
        .windows(2)
        .fold((f64::INFINITY, 0.0f64), |(l, h), w| {
            let d = w[1].t - w[0].t;
            (l.min(d), h.max(d))
        });
    println!(
        "{label:>16} {:6} {:5} {:7} {el:7.2} {:11.3e} {:11.3e} {:9.2e} {:9.2e}",
        r.stats.steps,
        r.stats.rejected_steps,
        r.stats.newton_iterations,
        tp / period - 1.0,
        drift(&r),
        lo,
        hi
    );
    Ok(())
}

fn free_table() -> Result<(), vibrissa::VibrissaError> {
    let w1 = CLAMPED_FREE_BETA1 * CLAMPED_FREE_BETA1;
    let period = 2.0 * PI / w1;
    println!(
        "free oscillation, tip velocity 1e-4, period from the {PERIODS}th crossing, T = {period}; \
         cpu_s: {}",
        clock::name()
    );
    println!(
        "             run  steps  rej.  newton  cpu_s   period_err  energy_drift  h_min     h_max"
    );
    // Newmark's rule for the fixed steps too: the adaptive steps' scheme, compared like for like
    let base = DynamicsOptions {
        t_end: (PERIODS + 0.25) * period,
        time_scheme: Some(TimeScheme::Newmark),
        ..DynamicsOptions::default()
    };
    for n in [25usize, 50, 100, 200] {
        let o = DynamicsOptions {
            dt: period / n as f64,
            ..base.clone()
        };
        row(&format!("fixed T/{n}"), &o, period)?;
    }
    for tol in [1e-8, 1e-9, 1e-10, 1e-11] {
        let o = DynamicsOptions {
            dt: period / 50.0,
            time_tol: Some(tol),
            ..base.clone()
        };
        row(&format!("time_tol {tol:e}"), &o, period)?;
    }
    Ok(())
}

fn drag_table() -> Result<(), vibrissa::VibrissaError> {
    let limit = 0.021003157884;
    let surface = Surface::flat(0.75)?;
    let base = DynDragOptions {
        speed: 0.05,
        d_max: 0.025,
        grid: 100,
        tol: 1e-8,
        ..DynDragOptions::default()
    };
    println!("dynamic drag, v = 0.05, grid 100, tol 1e-8: the first slip against d = {limit}");
    println!("             run  steps  rej.  solves  newton  cpu_s   first_slip_d     error");
    let mut runs: Vec<(String, DynDragOptions)> = [0.04, 0.02, 0.01, 0.005]
        .iter()
        .map(|&dt| {
            (
                format!("fixed dt {dt}"),
                DynDragOptions { dt, ..base.clone() },
            )
        })
        .collect();
    for tol in [1e-6, 1e-7, 1e-8, 1e-9] {
        runs.push((
            format!("time_tol {tol:e}"),
            DynDragOptions {
                dt: 0.01,
                time_tol: Some(tol),
                ..base.clone()
            },
        ));
    }
    for (label, o) in runs {
        let (r, el) = clock::timed(|| drag(&Rod::uniform(), &surface, &o));
        let (r, el) = (r?, el.as_secs_f64());
        let d = r.first_slip().unwrap_or(f64::NAN);
        println!(
            "{label:>16} {:6} {:5} {:7} {:7} {el:7.2} {d:14.10} {:11.3e}",
            r.stats.steps,
            r.stats.rejected_steps,
            r.stats.solves,
            r.stats.newton_iterations,
            d - limit
        );
    }
    Ok(())
}

fn main() -> Result<(), vibrissa::VibrissaError> {
    if std::env::args().any(|a| a == "--drag") {
        drag_table()
    } else {
        free_table()
    }
}
