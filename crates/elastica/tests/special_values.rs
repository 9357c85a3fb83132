//! The paper's printed values (to their printed digits), our high-precision values
//! (data/elastica/special_values.csv, mpmath quadrature), turning points and buckling limits.

use elastica::{
    convex_force, flex_force, lower_limit, turning_point, Branch, ClosedFormScan, Elastica,
    ElasticaError, Phase0End,
};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, FRAC_PI_8, PI};

const CSV: &str = include_str!("../../../data/elastica/special_values.csv");

/// Value of the named row (the n-th with that name).
fn special(name: &str, n: usize) -> f64 {
    CSV.lines()
        .filter(|l| l.split(',').next() == Some(name))
        .nth(n)
        .and_then(|l| l.split(',').nth(3))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no row {name} #{n}"))
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

#[test]
fn lower_limit_section_3_1() {
    let (f_, eta_) = lower_limit();
    assert!(rel(f_, special("f_lower", 0)) < 1e-14, "{f_}");
    assert!(rel(eta_, special("eta_lower", 0)) < 1e-14, "{eta_}");
    // Printed eta_ = 0.4569 agrees to its 4 digits (0.456947 -> 0.4569).
    assert_eq!((eta_ * 1e4).round() / 1e4, 0.4569);
    // Printed f_ = 3.4373 does NOT: f_ = K(1/2)^2 = 3.437593, i.e. 3.4376 to 4 decimals. The
    // paper's value is off by 2.9e-4 (noted in data/elastica/README.md); we do not tune to it.
    assert_eq!((f_ * 1e4).round() / 1e4, 3.4376);
    assert!((f_ - 3.4373).abs() > 2e-4);
}

#[test]
fn figure_3_forces() -> Result<(), ElasticaError> {
    let a = -FRAC_PI_8;
    let p = 0.5 * (FRAC_PI_2 + 2.0 * a);
    let fc = convex_force(a, p)?;
    let ff = flex_force(a, p)?;
    assert!(rel(fc, special("fig3_f_convex", 0)) < 1e-13);
    assert!(rel(ff, special("fig3_f_flex", 0)) < 1e-13);
    assert_eq!((fc * 100.0).round() / 100.0, 4.72); // printed 4.72
    assert_eq!((ff * 10.0).round() / 10.0, 19.0); // printed 19.0
    Ok(())
}

#[test]
fn turning_point_formula() -> Result<(), ElasticaError> {
    for (i, a) in [-0.01, -0.1, -FRAC_PI_8, -0.5, -FRAC_PI_4]
        .into_iter()
        .enumerate()
    {
        let (p, fa) = turning_point(a)?;
        // f_a = 4 K^2(sin(a/2)) against (2.8) / (2.15) at phi1 = pi/2 + 2a exactly, and mpmath
        let fc = Elastica::turning(Branch::Convex, a)?.f;
        let ff = Elastica::turning(Branch::OneFlex, a)?.f;
        assert!(rel(fa, fc) < 1e-14, "a={a}: {fa} {fc}");
        assert!(rel(fa, ff) < 1e-14, "a={a}: {fa} {ff}");
        assert!(rel(fa, special("turning_f", i)) < 1e-14, "a={a}");
        // at the rounded double p the distance to the turning point is ~1e-17 and f moves like
        // its square root: ~1e-8 is what the input allows
        assert!(rel(fa, convex_force(a, p)?) < 1e-7 && rel(fa, flex_force(a, p)?) < 1e-7);
    }
    Ok(())
}

#[test]
fn buckling_limits() -> Result<(), ElasticaError> {
    let (b1, b2) = (PI * PI / 4.0, 9.0 * PI * PI / 4.0);
    // phi1 = FRAC_PI_2 is the closest double below pi/2 (k ~ 3e-17)
    assert!(rel(convex_force(0.0, FRAC_PI_2)?, b1) < 1e-15);
    assert!(rel(flex_force(0.0, FRAC_PI_2)?, b2) < 1e-15);
    // the approach is quadratic in pi/2 - phi1
    for e in [1e-3, 1e-5, 1e-7] {
        let dc = rel(convex_force(0.0, FRAC_PI_2 - e)?, b1);
        let df = rel(flex_force(0.0, FRAC_PI_2 - e)?, b2);
        assert!(dc < e * e && df < e * e, "e={e}: {dc} {df}");
    }
    // ...but the corner (0, pi/2) is singular: along the turning-point locus f -> pi^2
    assert!(rel(turning_point(-1e-9)?.1, PI * PI) < 1e-15);
    Ok(())
}

#[test]
fn scan_start_and_turning() -> Result<(), ElasticaError> {
    for (i, eta) in [0.6, 0.75].into_iter().enumerate() {
        let s = ClosedFormScan::new(eta)?;
        assert!(rel(s.start.phi1, special("scan_start_phi1", i)) < 1e-13);
        assert!(rel(s.start.f, special("scan_start_f", i)) < 1e-13);
        assert!(rel(s.start.x1, special("scan_start_x1", i)) < 1e-13);
        assert!((s.start.y1 - eta).abs() < 1e-14);
    }
    let s = ClosedFormScan::new(0.75)?;
    assert_eq!(s.phase0_end, Phase0End::TurningPoint);
    assert!(rel(s.alpha_t, special("turning_alpha", 1)) < 1e-12);
    assert!(rel(s.phi1_t, special("turning_phi1", 0)) < 1e-12);
    assert!(rel(s.turning.f, special("turning_f_eta", 0)) < 1e-12);
    // eta = 0.6 (text under Fig. 9-11): the convex phase ends close to alpha = -pi/4 with
    // phi1 = 0. Precisely: the turning-point rod at alpha = -pi/4 has y1 = 0.60150 > 0.6, so the
    // tip becomes horizontal first, at alpha = -0.785371 (2.7e-5 above -pi/4); no phase 1.
    let s = ClosedFormScan::new(0.6)?;
    assert_eq!(s.phase0_end, Phase0End::TipHorizontal);
    assert_eq!(s.phi1_t, 0.0);
    assert!((s.alpha_t + FRAC_PI_4).abs() < 1e-4);
    assert!(
        rel(
            Elastica::turning(Branch::Convex, -FRAC_PI_4)?.y1,
            special("y1_turning_at_minus_pi_4", 0)
        ) < 1e-13
    );
    assert!(matches!(
        s.phase1_at_phi1(0.0),
        Err(ElasticaError::NoFlexPhase { .. })
    ));
    Ok(())
}
