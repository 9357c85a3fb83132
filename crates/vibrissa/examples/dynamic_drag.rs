//! The dynamic drag's slow limit (issue 32), measured: the paper's rod (uniform, clamped,
//! η = 0.75, μs = 0.5, μk = 0.3) dragged by `vibrissa::dynamics::drag` at a sequence of foot
//! speeds; the first slip's foot displacement against the quasi-static one of `vibrissa::drag`,
//! d = 0.0210132486189 (docs/reference.md), its error and the observed order of convergence
//! `log(e_i/e_{i+1}) / log(v_i/v_{i+1})` between successive speeds; then the same at one speed
//! with the time step halved (the time discretization's share of the error) and the energy
//! balance of the first slip.
//!
//! Run: `cargo run --release -p vibrissa --example dynamic_drag` (about 3 minutes on one core).

use std::time::Instant;
use vibrissa::dynamics::{drag, DynDragOptions, DynDragResult};
use vibrissa::{Rod, Surface, VibrissaError};

/// The quasi-static first slip (`vibrissa scan --mu0 0.5`, docs/reference.md).
const D_QS: f64 = 0.021013248618925968;

fn run(speed: f64, dt: f64, d_max: f64) -> Result<(DynDragResult, f64), VibrissaError> {
    let o = DynDragOptions {
        speed,
        dt,
        d_max,
        ..DynDragOptions::default()
    };
    let t0 = Instant::now();
    let r = drag(&Rod::uniform(), &Surface::flat(0.75)?, &o)?;
    Ok((r, t0.elapsed().as_secs_f64()))
}

fn main() -> Result<(), VibrissaError> {
    println!("paper's rod, eta 0.75, mu_s 0.5, mu_k 0.3, ramp 2, dt 0.01; quasi-static d = {D_QS}");
    println!("speed     d_first_slip           error       order   steps  time_s");
    let mut prev: Option<(f64, f64)> = None;
    for v in [0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001] {
        let (r, el) = run(v, 0.01, 0.0212)?;
        let d = r.first_slip().unwrap_or(f64::NAN);
        let e = (d - D_QS).abs();
        let order = prev.map_or(f64::NAN, |(pv, pe)| (pe / e).ln() / (pv / v).ln());
        println!(
            "{v:<8} {d:.16} {e:11.3e} {order:7.3} {:7} {el:7.1}",
            r.stats.steps
        );
        prev = Some((v, e));
    }
    println!("the time step at speed 0.05:");
    for dt in [0.02, 0.01, 0.005, 0.0025] {
        let (r, el) = run(0.05, dt, 0.045)?;
        let d = r.first_slip().unwrap_or(f64::NAN);
        let bal = r
            .first_slip_balance()
            .map(|e| (e.released, e.friction, e.imbalance));
        println!(
            "dt {dt:<7} d {d:.16} error {:10.3e}; first slip to stick: {bal:?} (released, friction, balance); {} ({el:.1} s)",
            (d - D_QS).abs(),
            r.stats
        );
    }
    Ok(())
}
