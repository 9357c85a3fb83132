//! The rod in time (issue 32), measured: the uniform clamped–free rod released from its rest
//! shape with a velocity in the first mode's shape (Blevins, table 8-1), followed by
//! `vibrissa::dynamics::free` (Rothe's method: Newmark in time, Lobatto collocation in s).
//!
//! For each collocation scheme and time step: the wall time, the largest collocation mesh,
//! Newton iterations, the period read off the tip's upward zero crossing against 2π/β₁²
//! (Newmark lengthens it by about (ωΔt)²/12; the scheme's exact discrete period is
//! πΔt/atan(ωΔt/2)), the frequency through that dispersion, and the energy drift; then
//! Richardson's extrapolation of the period and long runs (many periods; a large amplitude).
//!
//! Run: `cargo run -p vibrissa --example free_oscillation` (about two minutes on one core).
//! `-- --at dt,grid,tol,dt,grid,tol,...`: only the period error (and Newmark's prediction) of
//! Lobatto6 at each of those settings, one period and a fifth — the check that a coarse grid and
//! tolerance add nothing to the time step's period error (the accuracy the comparison with
//! PyElastica's ten-slip drag matches, docs/performance.md).

use std::f64::consts::PI;
use std::time::Instant;
use vibrissa::dynamics::{
    first_mode_velocity, free, DynamicsOptions, DynamicsResult, TimeScheme, CLAMPED_FREE_BETA1,
};
use vibrissa::Rod;

#[path = "../tests/support/crossing.rs"]
mod crossing;
use crossing::upward_crossing;

fn drift(r: &DynamicsResult) -> f64 {
    let e0 = r.samples[0].kinetic + r.samples[0].elastic;
    r.samples.iter().fold(0.0f64, |m, p| {
        m.max(((p.kinetic + p.elastic + p.dissipated) / e0 - 1.0).abs())
    })
}

/// `--energy-momentum`: the energy–momentum time scheme (the library's default of fixed steps
/// since 2026-12-04), else Newmark's, whose figures docs/model.md and docs/performance.md give.
fn time_scheme() -> Option<TimeScheme> {
    if std::env::args().any(|a| a == "--energy-momentum") {
        Some(TimeScheme::EnergyMomentum)
    } else {
        Some(TimeScheme::Newmark)
    }
}

fn main() -> Result<(), vibrissa::VibrissaError> {
    let rod = Rod::uniform();
    let w1 = CLAMPED_FREE_BETA1 * CLAMPED_FREE_BETA1;
    let period = 2.0 * PI / w1;
    println!("uniform clamped-free rod, first mode, tip velocity amplitude 1e-4; T = 2 pi / beta1^2 = {period}");
    if let Some(e) = std::env::args().skip_while(|a| a != "--energy").nth(1) {
        // amplitude, periods, steps per period, grid, tol: the energy at each period's end
        let v: Vec<f64> = e.split(',').filter_map(|x| x.parse().ok()).collect();
        let (amp, periods, n, grid, tol) = (v[0], v[1], v[2] as usize, v[3] as usize, v[4]);
        let o = DynamicsOptions {
            dt: period / n as f64,
            t_end: periods * period,
            grid,
            tol,
            time_scheme: time_scheme(),
            ..DynamicsOptions::default()
        };
        let t0 = Instant::now();
        let r = free(&rod, &first_mode_velocity(amp), &o)?;
        let e0 = r.samples[0].kinetic + r.samples[0].elastic;
        println!("energy at t = 0: {e0:.6e}");
        for (k, p) in r.samples.iter().enumerate().step_by(n) {
            println!(
                "period {:4}: energy error {:+.3e} (kinetic {:.4e}, elastic {:.4e}, tip x {:+.4e} y {:.6} vx {:+.4e} vy {:+.4e})",
                k / n,
                (p.kinetic + p.elastic) / e0 - 1.0,
                p.kinetic,
                p.elastic,
                p.tip_x,
                p.tip_y,
                p.tip_vx,
                p.tip_vy
            );
        }
        println!(
            "tip velocity amplitude {amp}: worst {:.3e} over {periods} periods ({} steps, {:.1} s)",
            drift(&r),
            r.stats.steps,
            t0.elapsed().as_secs_f64()
        );
        return Ok(());
    }
    if let Some(at) = std::env::args().skip_while(|a| a != "--at").nth(1) {
        let v: Vec<f64> = at.split(',').filter_map(|x| x.parse().ok()).collect();
        println!("dt  grid  tol  period_err  newmark_pred");
        for c in v.chunks_exact(3) {
            let (dt, grid, tol) = (c[0], c[1] as usize, c[2]);
            let o = DynamicsOptions {
                dt,
                grid,
                tol,
                t_end: 1.2 * period,
                time_scheme: time_scheme(),
                ..DynamicsOptions::default()
            };
            let r = free(&rod, &first_mode_velocity(1e-4), &o)?;
            let tp = upward_crossing(&r, 0.6 * period);
            let pred = PI * dt / (w1 * dt / 2.0).atan();
            println!(
                "{dt} {grid} {tol:e} {:.4e} {:.4e}",
                tp / period - 1.0,
                pred / period - 1.0
            );
        }
        return Ok(());
    }
    println!("scheme   steps/T  time_s  max_nodes  newton  period_err  newmark_pred  omega_err(dispersion)  energy_drift");
    for scheme in [bvp::Scheme::Lobatto4, bvp::Scheme::Lobatto6] {
        let mut prev: Option<f64> = None;
        for n in [25usize, 50, 100, 200] {
            let dt = period / n as f64;
            let o = DynamicsOptions {
                dt,
                t_end: 1.2 * period,
                scheme,
                time_scheme: time_scheme(),
                ..DynamicsOptions::default()
            };
            let t0 = Instant::now();
            let r = free(&rod, &first_mode_velocity(1e-4), &o)?;
            let el = t0.elapsed().as_secs_f64();
            let tp = upward_crossing(&r, 0.6 * period);
            let pred = PI * dt / (w1 * dt / 2.0).atan();
            let k = n / 4;
            let x: Vec<f64> = r.samples.iter().map(|p| p.tip_x).collect();
            let wh = ((x[k + 1] + x[k - 1]) / (2.0 * x[k])).acos() / dt;
            let w = 2.0 / dt * (wh * dt / 2.0).tan();
            println!(
                "{scheme:?} {n:7} {el:7.2} {:10} {:7} {:11.3e} {:13.3e} {:22.3e} {:13.3e}",
                r.stats.max_nodes,
                r.stats.newton_iterations,
                tp / period - 1.0,
                pred / period - 1.0,
                w / w1 - 1.0,
                drift(&r)
            );
            if let Some(p) = prev {
                // second order: (4 T(dt/2) − T(dt))/3
                let rich = (4.0 * tp - p) / 3.0;
                println!(
                    "    Richardson with the previous row: period error {:.3e}",
                    rich / period - 1.0
                );
            }
            prev = Some(tp);
        }
    }
    for (amp, periods, n) in [(1e-4, 20.0, 50usize), (0.3, 3.0, 100)] {
        let o = DynamicsOptions {
            dt: period / n as f64,
            t_end: periods * period,
            time_scheme: time_scheme(),
            ..DynamicsOptions::default()
        };
        let t0 = Instant::now();
        let r = free(&rod, &first_mode_velocity(amp), &o)?;
        println!(
            "tip velocity amplitude {amp}: {periods} periods at {n} steps per period: energy drift {:.3e} ({} steps, {:.1} s, largest mesh {})",
            drift(&r),
            r.stats.steps,
            t0.elapsed().as_secs_f64(),
            r.stats.max_nodes
        );
    }
    Ok(())
}
