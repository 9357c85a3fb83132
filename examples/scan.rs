//! The stiction scan of the paper's rod (η = 0.75): μ(d) while the foot is dragged, the
//! measurable range of μ0, and μ0 read back from a slip displacement.
//!
//! `cargo run --release --example scan`

use vibrissa::{Inference, Rod, ScanOptions, ScanResult, Surface, VibrissaError};

/// Runs the scan and the inference at half the measurable range.
pub fn run() -> Result<(ScanResult, Inference), VibrissaError> {
    let (rod, surface) = (Rod::uniform(), Surface::flat(0.75)?);
    let opts = ScanOptions {
        points: 51,
        ..ScanOptions::default()
    };
    let scan = vibrissa::scan(&rod, &surface, &opts)?;
    for p in scan.points.iter().step_by(10) {
        println!(
            "d = {:.3}: mu = {:.6}, normal force {:.4}, m(0) = {:.4}",
            p.d, p.mu, p.normal, p.m_base
        );
    }
    println!(
        "measurable: mu0 in [0, {:.6}] for slips at d in [0, {:.6}] (ended by {}); the scan stopped: {}",
        scan.mu_max, scan.d_at_mu_max, scan.range_end, scan.stop
    );
    let d0 = 0.5 * scan.d_at_mu_max;
    let inference = vibrissa::infer(&rod, &surface, d0, &opts)?;
    println!("a slip at d0 = {d0:.6} means mu0 = {:.6}", inference.mu0);
    Ok((scan, inference))
}

#[allow(dead_code)] // the tests call `run`
fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
