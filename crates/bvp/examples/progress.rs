//! A collocation solve with its progress shown (what scipy's `solve_bvp(..., verbose=2)` prints):
//! every mesh pass with its nodes, Newton iterations, residual and the intervals where the
//! collocation residual exceeds the tolerance. The library prints nothing; the observer here does.
//!
//! ```text
//! cargo run --release -p bvp --example progress [-- ID EPS TOL]     (default: 20 1e-3 1e-6)
//! ```

use bvp::testset::CashMazzia;
use bvp::{Collocation, CollocationOptions, Progress, Scheme};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let id: u8 = args.get(1).map_or(Ok(20), |s| s.parse())?;
    let eps: f64 = args.get(2).map_or(Ok(1e-3), |s| s.parse())?;
    let tol: f64 = args.get(3).map_or(Ok(1e-6), |s| s.parse())?;
    let p = CashMazzia::new(id).ok_or("no such problem")?;
    let mut solver = Collocation::new(CollocationOptions {
        scheme: Scheme::Lobatto6,
        tol,
        ..CollocationOptions::default()
    })?;
    println!(
        "Cash–Mazzia {id} ({}), eps {eps:e}, tol {tol:e}",
        p.description()
    );
    println!("pass  nodes  newton  converged  residual   max rms    intervals > tol");
    let mut show = |pr: &Progress<'_>| {
        let max = pr.residuals.iter().fold(0.0_f64, |m, v| m.max(*v));
        let over = pr.residuals.iter().filter(|r| **r > tol).count();
        println!(
            "{:>4}  {:>5}  {:>6}  {:>9}  {:>9.2e}  {:>9.2e}  {over}",
            pr.pass,
            pr.mesh.len(),
            pr.newton_iters,
            pr.newton_converged,
            pr.residual,
            max
        );
    };
    match solver.solve_observed(&p.at(eps), &p.guess(eps, 101), &mut show) {
        Ok(sol) => println!("solved: {sol}"),
        Err(e) => println!("failed: {e}"),
    }
    Ok(())
}
