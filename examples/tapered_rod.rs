//! A tapered, pre-curved whisker on a compliant support, pressed with its tip to the height
//! 0.8 L by a force at α = −0.2 rad: its tip force, the signals at its foot and its shape.
//!
//! `cargo run --release --example tapered_rod`

use std::f64::consts::FRAC_PI_2;
use vibrissa::{BranchChoice, Rod, Shape, SolverConfig, Target, VibrissaError};

/// Builds and solves the rod; returns its shape.
pub fn run() -> Result<Shape, VibrissaError> {
    // tip/base radius 0.3, rest curvature κ0(s) = −0.5 + 0.2 s (1/L), foot turning by 0.1·m(0)
    let rod = Rod::builder()
        .taper(0.3)
        .precurvature(-0.5, 0.2)
        .support_compliance(0.1)
        .build()?;
    let shape = vibrissa::solve(
        &rod,
        -0.2,
        Target::Eta(0.8),
        &BranchChoice::Convex,
        &SolverConfig::default(),
    )?;
    println!(
        "tip force f = {:.6} at alpha = {} (fx = {:.6}, fy = {:.6}), tip at ({:.6}, {:.6}), slope {:.6}",
        shape.f, shape.alpha, shape.fx, shape.fy, shape.x1, shape.y1, shape.phi1
    );
    println!(
        "at the foot: m(0) = {:.6} EI/L, the support turned it to phi(0) = pi/2 + {:.6}",
        shape.m_base,
        shape.phi0 - FRAC_PI_2
    );
    println!("s, x, y, phi, kappa, m");
    for p in shape.samples(6) {
        println!(
            "{:.2}, {:.6}, {:.6}, {:.6}, {:.6}, {:.6}",
            p.s, p.x, p.y, p.phi, p.kappa, p.m
        );
    }
    Ok(shape)
}

#[allow(dead_code)] // the tests call `run`
fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
