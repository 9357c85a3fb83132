//! The closed-form scan as one curve across the fold in φ1 (`ClosedFormScan::curve_at`).

use elastica::{ClosedFormScan, ElasticaError};

/// η = 0.75 has a turning point and a fold in φ1 (data/elastica/README.md): the curve must join
/// the pieces continuously, keep `y1 = η` (checked through the phase functions it calls), and have
/// `d` increasing up to its end at t = 3.
#[test]
fn curve_is_continuous_and_d_increases_for_eta_075() {
    let cf = ClosedFormScan::new(0.75).unwrap();
    assert_eq!(cf.curve_end(), 3.0);
    // Joints: t = 1 is the turning point, t = 2 the fold (both sides give the same rod).
    let p1 = cf.curve_at(1.0).unwrap();
    assert!((p1.alpha - cf.alpha_t).abs() < 1e-14 && (p1.phi1 - cf.phi1_t).abs() < 1e-12);
    let fold = cf.fold.expect("eta = 0.75 has a fold in phi1");
    let lower = cf.curve_at(2.0).unwrap();
    let upper = cf.phase1_upper_at_phi1(cf.phi1_min()).unwrap();
    assert!((lower.d - fold.d).abs() < 1e-6, "{} vs {}", lower.d, fold.d);
    assert!((upper.d - fold.d).abs() < 1e-6, "{} vs {}", upper.d, fold.d);
    let mut prev = cf.curve_at(0.0).unwrap();
    assert_eq!(prev.d, 0.0);
    for i in 1..=300 {
        let p = cf.curve_at(3.0 * i as f64 / 300.0).unwrap();
        assert!(
            p.d > prev.d,
            "d not increasing at t = {}",
            3.0 * i as f64 / 300.0
        );
        // μ continuous on this grid: steps in μ stay small where d moves little.
        assert!(
            (p.mu - prev.mu).abs() < 0.2,
            "jump in mu at t = {}",
            i as f64 / 100.0
        );
        prev = p;
    }
}

/// η = 0.6 ends phase 0 with a horizontal tip: the curve is phase 0 alone.
#[test]
fn curve_for_eta_06_is_phase0_only_and_rejects_t_outside() {
    let cf = ClosedFormScan::new(0.6).unwrap();
    assert_eq!(cf.curve_end(), 1.0);
    assert!(cf.curve_at(1.0).unwrap().phi1.abs() < 1e-9);
    assert!(matches!(
        cf.curve_at(1.5),
        Err(ElasticaError::OutOfRange { .. })
    ));
    assert!(matches!(
        cf.curve_at(f64::NAN),
        Err(ElasticaError::NotFinite { .. })
    ));
}
