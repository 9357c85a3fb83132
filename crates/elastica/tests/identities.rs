//! Identities that any correct elastica satisfies, checked along sampled shapes.

use elastica::ellint::{big_k, big_x, big_y, i1, i3, i4};
use elastica::{turning_point, Branch, ClosedFormScan, Elastica, ElasticaError};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

fn cases() -> Vec<Elastica> {
    let mut v = Vec::new();
    for b in [Branch::Convex, Branch::OneFlex] {
        for a in [0.0, -0.05, -0.3, -0.6, -0.78] {
            for fr in [0.0, 0.3, 0.7, 0.999] {
                v.push(Elastica::new(b, a, fr * (FRAC_PI_2 + 2.0 * a)).unwrap());
            }
        }
    }
    v
}

/// kappa^2 = 2 f [sin(phi - a) - sin(phi1 - a)], i.e. kappa^2/2 = f [..]. (The paper's (2.4)
/// prints kappa^2/2 = 2 f [..]; that is a factor-2 slip, cf. (2.6).)
#[test]
fn first_integral() -> Result<(), ElasticaError> {
    for e in cases() {
        for p in e.shape(101)? {
            let rhs = 2.0 * e.f * ((p.phi - e.alpha).sin() - (e.phi1 - e.alpha).sin());
            assert!(
                (p.kappa * p.kappa - rhs).abs() <= 1e-12 * e.f,
                "{e:?} s={}: {} vs {rhs}",
                p.s,
                p.kappa * p.kappa
            );
        }
    }
    Ok(())
}

/// Unit speed and consistency of slope/curvature by finite differences of the sampled shape.
#[test]
fn unit_speed_and_tangent() -> Result<(), ElasticaError> {
    let n = 2001;
    let h = 1.0 / (n - 1) as f64;
    for e in cases() {
        let pts = e.shape(n)?;
        let kmax = pts.iter().map(|p| p.kappa.abs()).fold(0.0, f64::max);
        for w in pts.windows(2) {
            let (dx, dy) = (w[1].x - w[0].x, w[1].y - w[0].y);
            let chord = dx.hypot(dy) / h;
            // chord/arc = 1 - kappa^2 h^2 / 24 + ...
            assert!(
                (chord - 1.0).abs() <= kmax * kmax * h * h / 20.0 + 1e-10,
                "{chord}"
            );
            // slope at the midpoint vs chord direction; curvature vs slope difference
            let phim = 0.5 * (w[0].phi + w[1].phi);
            let diff = (dy.atan2(dx) - phim + 3.0 * PI).rem_euclid(2.0 * PI) - PI; // wrap at +-pi
            assert!(diff.abs() < (kmax * kmax + e.f) * h * h + 1e-9, "{diff}");
            let dphi = (w[1].phi - w[0].phi) / h;
            assert!((dphi - 0.5 * (w[0].kappa + w[1].kappa)).abs() < 1e-3 * (1.0 + kmax));
        }
    }
    Ok(())
}

/// The shape ends at the tip, and the paper's moment formula
/// m(s) = f [(x - x1) cos a + (y - y1) sin a] reproduces kappa(s), in particular m_base at s = 0.
#[test]
fn tip_and_moment_formula() -> Result<(), ElasticaError> {
    for e in cases() {
        let near = e.point_at(1.0 - 1e-9)?;
        assert!((near.x - e.x1).abs() < 2e-9 && (near.y - e.y1).abs() < 2e-9);
        assert!((near.phi - e.phi1).abs() < 1e-7);
        let (sa, ca) = e.alpha.sin_cos();
        for p in e.shape(41)? {
            let m = e.f * ((p.x - e.x1) * ca + (p.y - e.y1) * sa);
            assert!((m - p.kappa).abs() < 1e-12 * e.f, "{e:?} s={}", p.s);
        }
        let m0 = e.f * (-e.x1 * ca - e.y1 * sa);
        assert!((m0 - e.m_base).abs() < 1e-12 * e.f);
        match e.branch {
            Branch::Convex => assert!(e.m_base <= 0.0),
            Branch::OneFlex => assert!(e.m_base >= 0.0),
        }
    }
    Ok(())
}

/// Remark 2.1: the flex point bisects the arc between the two points of slope pi/2.
#[test]
fn remark_2_1_flex_bisects() -> Result<(), ElasticaError> {
    for e in cases().into_iter().filter(|e| e.branch == Branch::OneFlex) {
        let sb = e.s_b.unwrap();
        let pb = e.point_at(sb)?;
        assert!(pb.kappa.abs() < 1e-12 * e.f, "{e:?}");
        assert!((pb.phi - e.phi_b.unwrap()).abs() < 1e-12);
        if 2.0 * sb <= 1.0 {
            let p2 = e.point_at(2.0 * sb)?;
            assert!((p2.phi - FRAC_PI_2).abs() < 1e-12, "{e:?}: {}", p2.phi);
        }
        // and phi > pi/2 strictly between the two
        if sb > 1e-3 && 2.0 * sb <= 1.0 {
            assert!(e.point_at(sb * 0.5)?.phi > FRAC_PI_2);
            assert!(e.point_at(sb * 1.5)?.phi > FRAC_PI_2);
        }
    }
    Ok(())
}

/// The two branches meet at the turning point: same force, same tip, kappa(0) = 0.
#[test]
fn branches_meet_at_turning_point() -> Result<(), ElasticaError> {
    for a in [-0.01, -0.2, -0.5, -FRAC_PI_4] {
        let (p, fa) = turning_point(a)?;
        // exactly at the turning point (delta = 0 exactly)
        let c = Elastica::turning(Branch::Convex, a)?;
        let f = Elastica::turning(Branch::OneFlex, a)?;
        assert!(((c.f - fa) / fa).abs() < 1e-14 && ((f.f - fa) / fa).abs() < 1e-14);
        assert!((c.x1 - f.x1).abs() < 1e-14 && (c.y1 - f.y1).abs() < 1e-14);
        assert!(c.m_base == 0.0 && f.m_base == 0.0);
        assert_eq!(f.flex_count(), 0);
        // At the double p = fl(pi/2 + 2a) the exact distance delta to the turning point is a few
        // 1e-17, and f, the tip and m_base move like sqrt(delta): agreement to ~1e-8 is all that
        // the *input* allows (ill-conditioned in phi1, not an inaccuracy of the evaluation).
        for b in [Branch::Convex, Branch::OneFlex] {
            let e = Elastica::new(b, a, p)?;
            assert!(((e.f - fa) / fa).abs() < 1e-7, "{e:?}");
            assert!((e.x1 - c.x1).abs() < 1e-7 && (e.y1 - c.y1).abs() < 1e-7);
        }
    }
    Ok(())
}

/// The paper's functions K, X, Y, I1..I4 agree with the Elastica they define.
#[test]
fn paper_functions() -> Result<(), ElasticaError> {
    for e in cases() {
        let (a, p) = (e.alpha, e.phi1);
        let k1 = big_k(p, p, a)?;
        let u = p - a;
        // Appendix A: K = -I1(phi - a, u) + I1(pi/2 - a, u)
        let k_app = -i1(p - a, u)? + i1(FRAC_PI_2 - a, u)?;
        // I1 has a sqrt end-point behaviour at x = pi - u; near the turning point (fr = 0.999)
        // the rounding of pi/2 - a and u is amplified like 1e-16/sqrt(pi - u - x)
        let tol = if e.phi1 > 0.99 * (FRAC_PI_2 + 2.0 * a) {
            1e-10
        } else {
            1e-13
        };
        assert!((k1 - k_app).abs() < tol, "{e:?}: {k1} {k_app}");
        // sqrt(2f) X from I3, I4 (Appendix A), at phi = phi1
        let g = (2.0 * e.f).sqrt();
        let xa = (a.sin() * (i3(p - a, u)? - i3(FRAC_PI_2 - a, u)?)
            - a.cos() * (i4(p - a, u)? - i4(FRAC_PI_2 - a, u)?))
            / g;
        let ya = (-a.cos() * (i3(p - a, u)? - i3(FRAC_PI_2 - a, u)?)
            - a.sin() * (i4(p - a, u)? - i4(FRAC_PI_2 - a, u)?))
            / g;
        assert!((xa - big_x(p, e.f, p, a)?).abs() < tol);
        assert!((ya - big_y(p, e.f, p, a)?).abs() < tol);
        match e.branch {
            Branch::Convex => {
                assert!((0.5 * k1 * k1 - e.f).abs() < 1e-13 * e.f); // (2.8)
                assert!((big_x(p, e.f, p, a)? - e.x1).abs() < 1e-13); // (2.10)
                assert!((big_y(p, e.f, p, a)? - e.y1).abs() < 1e-13);
            }
            Branch::OneFlex => {
                let pb = e.phi_b.unwrap();
                let kb = big_k(pb, p, a)?;
                // phi_b is the end point of the integrals (a zero of the bracket), where they
                // behave like sqrt(phi_b - phi): the rounding of the double phi_b (1e-16) costs
                // ~1e-8. The crate itself never evaluates at a rounded phi_b (theta = pi/2 there).
                let tb = 1e-7;
                assert!((0.5 * (k1 - 2.0 * kb).powi(2) - e.f).abs() < tb * e.f); // (2.15)
                assert!((-kb / (2.0 * e.f).sqrt() - e.s_b.unwrap()).abs() < tb); // (2.16)
                let x = big_x(p, e.f, p, a)? - 2.0 * big_x(pb, e.f, p, a)?; // (2.17)
                let y = big_y(p, e.f, p, a)? - 2.0 * big_y(pb, e.f, p, a)?;
                assert!((x - e.x1).abs() < tb && (y - e.y1).abs() < tb);
            }
        }
    }
    Ok(())
}

/// Scan: every point has y1 = eta, phases join at the turning point, d starts at 0.
#[test]
fn scan_consistency() -> Result<(), ElasticaError> {
    let s = ClosedFormScan::new(0.75)?;
    let pts = s.points(15, 15)?;
    assert_eq!(pts.len(), 30);
    assert_eq!(pts[0].d, 0.0);
    for p in &pts {
        let b = if p.flex == 0 {
            Branch::Convex
        } else {
            Branch::OneFlex
        };
        let e = Elastica::new(b, p.alpha, p.phi1)?;
        // the turning point itself, rebuilt from rounded (alpha, phi1), sits at a distance
        // ~1e-17 from the exact turning point: sqrt conditioning, 1e-8 is what the input allows
        let tol = if p.phi1 == s.phi1_t { 1e-7 } else { 1e-12 };
        assert!((e.y1 - 0.75).abs() < tol, "{p:?}");
        assert!((p.mu - (p.fx / p.fy).abs()).abs() < 1e-12);
    }
    // phase 1 continues phase 0 smoothly
    let near = s.phase1_at_phi1(s.phi1_t - 1e-6)?;
    assert!((near.alpha - s.alpha_t).abs() < 1e-4 && near.flex == 1);
    // the fold: lower and upper sheets meet
    let fold = s.fold.unwrap();
    let up = s.phase1_upper_at_phi1(fold.phi1)?;
    assert!((up.alpha - fold.alpha).abs() < 1e-5);
    let mx = s.mu_max()?;
    assert!(pts.iter().all(|p| p.mu <= mx.mu + 1e-12));
    Ok(())
}
