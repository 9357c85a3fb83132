//! The programs of `examples/` (the tasks users do) run here as tests, against known answers:
//! each example file is included as a module and its `run` called.

#[path = "../examples/tapered_rod.rs"]
mod tapered_rod;

#[path = "../examples/scan.rs"]
mod scan;

#[path = "../examples/bvp_collocation.rs"]
mod bvp_collocation;

#[path = "../examples/continuation.rs"]
mod continuation;

use bvp::samples::{Bratu, BRATU_LAMBDA_C};

#[test]
fn tapered_precurved_rod_on_a_compliant_support() {
    let shape = tapered_rod::run().unwrap();
    // the tip condition and the support law phi(0) = pi/2 + c m(0), c = 0.1
    assert!((shape.y1 - 0.8).abs() < 1e-9, "{}", shape.y1);
    assert!(
        (shape.phi0 - std::f64::consts::FRAC_PI_2 - 0.1 * shape.m_base).abs() < 1e-9,
        "{} {}",
        shape.phi0,
        shape.m_base
    );
    // the sampled shape ends at the tip, where the moment vanishes
    let tip = *shape.samples(6).last().unwrap();
    assert!((tip.x - shape.x1).abs() < 1e-9 && (tip.y - shape.y1).abs() < 1e-9);
    assert!(tip.m.abs() < 1e-9);
}

#[test]
fn scan_and_inference() {
    let (scan, inference) = scan::run().unwrap();
    // the paper's mu_max = 0.725 at eta = 0.75 (its Fig. 8, three digits)
    assert!((scan.mu_max - 0.725).abs() < 5e-4, "{}", scan.mu_max);
    // mu0 is |mu| of the scan at d0, recomputed there by scan_at
    let d0 = inference.d0;
    let opts = vibrissa::ScanOptions::default();
    let at = vibrissa::scan_at(
        &vibrissa::Rod::uniform(),
        &vibrissa::Surface::flat(0.75).unwrap(),
        &opts,
        &[0.0, d0],
    )
    .unwrap();
    assert!((at.points[1].mu.abs() - inference.mu0).abs() < 1e-9);
}

#[test]
fn generic_bvp_by_collocation_with_dense_output() {
    let (sol, worst) = bvp_collocation::run().unwrap();
    // against the closed form of Bratu's problem, between the nodes too (tol 1e-8)
    assert!(worst < 1e-8, "{worst}");
    assert!((sol.at(0.5)[0] - Bratu { lambda: 1.0 }.exact(0, 0.5)[0]).abs() < 1e-8);
}

#[test]
fn continuation_around_the_fold() {
    let (fold, upper) = continuation::run().unwrap();
    // lambda_c = 3.51383071912516 (bvp::samples, from the closed form)
    assert!((fold - BRATU_LAMBDA_C).abs() < 1e-8, "{fold}");
    let exact = Bratu { lambda: 1.0 }.exact(1, 0.5)[0];
    assert!(
        (upper.at(0.5)[0] - exact).abs() < 1e-6,
        "{}",
        upper.at(0.5)[0]
    );
}

#[path = "../examples/many_surfaces.rs"]
mod many_surfaces;

/// The many-surfaces sweep, short: 40 distinct corrugations each scanned to d_max (the example
/// itself runs 10⁵ and prints the RSS; here other tests share the process, so its RSS is not
/// asserted).
#[test]
fn many_surfaces_sweep_runs_every_surface() {
    let mut reports = 0;
    let sweep = many_surfaces::run(40, 10, |_, _, _| reports += 1).unwrap();
    assert_eq!(reports, 5);
    assert_eq!(
        sweep.rss.iter().map(|r| r.0).collect::<Vec<_>>(),
        [0, 10, 20, 30, 40]
    );
    assert!(sweep.rss.iter().all(|r| r.1 > 0));
    assert!(sweep.rhs_evals > 0);
    // every scan pushed the foot on with the tip stuck (the flat surface's mu(0.02) is 0.49)
    assert!(
        sweep.mu_max.is_finite() && sweep.mu_max > 0.0,
        "{}",
        sweep.mu_max
    );
}
