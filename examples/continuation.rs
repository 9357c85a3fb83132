//! Continuation in a parameter with crate `bvp`: Bratu's family u'' + λ eᵘ = 0,
//! u(0) = u(1) = 0 followed by pseudo-arclength from λ = 0.1 around its fold at
//! λ_c = 3.513830719125 onto the upper branch, then a member of that branch taken at λ = 1.
//!
//! `cargo run --release --example continuation`

use bvp::continuation::{Continuation, ContinuationOptions, Member};
use bvp::samples::BratuFamily;
use bvp::{BvpError, BvpSolver, Guess, Shooting, ShootingOptions, Solution};

/// Follows the branch; returns the fold's λ and the upper solution at λ = 1.
pub fn run() -> Result<(f64, Solution), Box<BvpError>> {
    let mut solver = Shooting::new(ShootingOptions::default())?;
    let guess = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![]);
    let start = solver.solve(&Member::new(&BratuFamily, 0.1), &guess)?;
    let opts = ContinuationOptions {
        lambda_min: 0.1,
        ..ContinuationOptions::default()
    };
    let mut cont = Continuation::new(&BratuFamily, solver, start, 0.1, opts)?;
    let mut fold = f64::NAN;
    for point in cont.by_ref() {
        let point = point?;
        let mid = point.solution.at(0.5)[0];
        println!("lambda = {:.6}: u(1/2) = {mid:.6}", point.lambda);
        if let Some(f) = point.fold {
            fold = f.lambda;
            println!("fold at lambda = {:.12}", f.lambda);
        }
        if mid > 4.5 {
            break; // far up the upper branch
        }
    }
    let upper = cont.point_at(1.0)?;
    println!(
        "upper branch at lambda = 1: u(1/2) = {:.9}",
        upper.at(0.5)[0]
    );
    Ok((fold, upper))
}

#[allow(dead_code)] // the tests call `run`
fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
