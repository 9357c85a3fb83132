//! Out-of-domain input gives the right typed error (never NaN, never a panic); near the domain
//! ends results are finite and accurate.

use elastica::{
    convex_force, flex_force, solve_eta, turning_point, Branch, ClosedFormScan, Elastica,
    ElasticaError,
};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

#[test]
fn alpha_out_of_range() {
    let e = Elastica::new(Branch::Convex, 0.3, 0.1).unwrap_err();
    assert!(matches!(e, ElasticaError::AlphaOutOfRange { alpha, .. } if alpha == 0.3));
    let msg = e.to_string();
    assert!(
        msg.contains("alpha = 0.3 is outside the valid range [-1.5707963267948966, 0]"),
        "{msg}"
    );
    let e = Elastica::new(Branch::OneFlex, -0.9, 0.0).unwrap_err();
    assert!(matches!(e, ElasticaError::AlphaOutOfRange { min, .. } if min == -FRAC_PI_4));
    assert!(matches!(
        turning_point(-1.0),
        Err(ElasticaError::AlphaOutOfRange { .. })
    ));
}

#[test]
fn phi1_out_of_range() {
    for (b, a, p) in [
        (Branch::Convex, -0.2, -0.01),
        (Branch::Convex, -0.2, 1.2),
        (Branch::OneFlex, 0.0, 1.6),
        // convex alpha < -pi/4: the phi1 range [0, pi/2 + 2 alpha] is empty
        (Branch::Convex, -1.0, 0.0),
    ] {
        let e = Elastica::new(b, a, p).unwrap_err();
        assert!(
            matches!(e, ElasticaError::Phi1OutOfRange { phi1, branch, .. } if phi1 == p && branch == b),
            "{e}"
        );
        assert!(e.to_string().contains("valid range"));
    }
    // a few ulp above pi/2 + 2 alpha (computed in floating point) is the turning point
    let a = -0.3f64;
    assert!(Elastica::new(Branch::Convex, a, FRAC_PI_2 + 2.0 * a + 2e-16).is_ok());
    assert!(Elastica::new(Branch::Convex, a, FRAC_PI_2 + 2.0 * a + 1e-14).is_err());
}

#[test]
fn not_finite() {
    for (a, p) in [
        (f64::NAN, 0.1),
        (-0.1, f64::NAN),
        (f64::NEG_INFINITY, 0.0),
        (0.0, f64::INFINITY),
    ] {
        assert!(matches!(
            convex_force(a, p),
            Err(ElasticaError::NotFinite { .. })
        ));
        assert!(matches!(
            flex_force(a, p),
            Err(ElasticaError::NotFinite { .. })
        ));
    }
    let e = Elastica::new(Branch::Convex, -0.1, 0.3).unwrap();
    assert!(matches!(
        e.point_at(f64::NAN),
        Err(ElasticaError::NotFinite { .. })
    ));
    assert!(matches!(
        e.point_at(1.5),
        Err(ElasticaError::OutOfRange { .. })
    ));
    assert!(matches!(e.shape(1), Err(ElasticaError::OutOfRange { .. })));
    assert!(matches!(
        ClosedFormScan::new(f64::NAN),
        Err(ElasticaError::NotFinite { .. })
    ));
}

#[test]
fn eta_out_of_range() {
    for eta in [0.3, 0.45, 1.0, 1.2] {
        let e = ClosedFormScan::new(eta).unwrap_err();
        assert!(matches!(e, ElasticaError::EtaOutOfRange { .. }), "{e}");
        assert!(e.to_string().contains("valid range"));
    }
    // no convex rod with alpha = 0 reaches y1 = 0.3
    assert!(matches!(
        solve_eta(Branch::Convex, 0.0, 0.3),
        Err(ElasticaError::NoRoot { .. })
    ));
    let s = ClosedFormScan::new(0.75).unwrap();
    assert!(matches!(
        s.phase0_at_alpha(-0.7),
        Err(ElasticaError::AlphaOutOfRange { .. })
    ));
    assert!(matches!(
        s.phase1_at_phi1(0.01),
        Err(ElasticaError::Phi1OutOfRange { .. })
    ));
}

/// Near the ends of the domain: finite, and continuous with the interior.
#[test]
fn near_domain_ends() -> Result<(), ElasticaError> {
    for b in [Branch::Convex, Branch::OneFlex] {
        for a in [0.0, -1e-12, -0.4, -FRAC_PI_4 + 1e-12, -FRAC_PI_4] {
            let top = (FRAC_PI_2 + 2.0 * a).max(0.0);
            for p in [0.0, 1e-300, 1e-12, top * (1.0 - 1e-12), top] {
                if p > top {
                    continue;
                }
                let e = Elastica::new(b, a, p)?;
                for v in [e.f, e.x1, e.y1, e.m_base] {
                    assert!(v.is_finite());
                }
                for q in e.shape(17)? {
                    assert!(q.x.is_finite() && q.y.is_finite() && q.phi.is_finite());
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Any input: either a finite result or a typed error, never NaN, never a panic.
    #[test]
    fn never_nan(a in -3.0f64..1.0, p in -1.0f64..2.0, s in -0.5f64..1.5, flex in any::<bool>()) {
        let b = if flex { Branch::OneFlex } else { Branch::Convex };
        if let Ok(e) = Elastica::new(b, a, p) {
            prop_assert!(e.f.is_finite() && e.f > 0.0);
            prop_assert!(e.x1.is_finite() && e.y1.is_finite() && e.m_base.is_finite());
            if let Ok(q) = e.point_at(s) {
                prop_assert!(q.x.is_finite() && q.y.is_finite() && q.phi.is_finite() && q.kappa.is_finite());
            }
        }
    }

    /// In the domain the tip is at most one rod length away and y is increasing.
    #[test]
    fn in_domain_sane(a in -FRAC_PI_4..0.0f64, fr in 0.0f64..=1.0, flex in any::<bool>()) {
        let b = if flex { Branch::OneFlex } else { Branch::Convex };
        let e = Elastica::new(b, a, fr * (FRAC_PI_2 + 2.0 * a)).unwrap();
        prop_assert!(e.x1.hypot(e.y1) <= 1.0 + 1e-12);
        let pts = e.shape(33).unwrap();
        for w in pts.windows(2) {
            prop_assert!(w[1].y >= w[0].y - 1e-12);
        }
    }
}
