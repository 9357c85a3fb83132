//! Point objects touching the side: the inverse (`locate`) returns the object a solve put the
//! rod against, every method solves the same contact state, the whisk ends where the object
//! slips off the tip (located there), and an object the rod cannot reach is a typed error.

use vibrissa::{
    locate, solve_peg, whisk, Event, Method, Rod, SolverConfig, StopReason, VibrissaError,
    WhiskOptions,
};

fn peg_at(r: f64, angle: f64) -> [f64; 2] {
    // `angle` clockwise from the unturned rod
    [r * angle.sin(), r * angle.cos()]
}

fn rods() -> Vec<(&'static str, Rod)> {
    vec![
        ("uniform", Rod::uniform()),
        ("taper 0.1", Rod::builder().taper(0.1).build().unwrap()),
        (
            "taper 0.3, k0 -0.5, c 0.2",
            Rod::builder()
                .taper(0.3)
                .precurvature(-0.5, 0.0)
                .support_compliance(0.2)
                .build()
                .unwrap(),
        ),
    ]
}

/// solve --peg → locate gives the object back to 1e-9, frictionless and held by friction.
#[test]
fn locate_returns_the_object() {
    let cfg = SolverConfig::default();
    for (name, rod) in rods() {
        for (r, mu0) in [(0.4, None), (0.7, None), (0.7, Some(0.3)), (0.9, None)] {
            let peg = peg_at(r, 0.3);
            let w = whisk(
                &rod,
                peg,
                &WhiskOptions {
                    theta_max: 1.0,
                    points: 6,
                    mu0,
                    ..WhiskOptions::default()
                },
            )
            .unwrap();
            for p in w
                .points
                .iter()
                .filter(|p| p.event.is_none() && p.normal > 0.0)
            {
                let (x, y, s) = locate(&rod, p.theta, p.m_base, [p.fx, p.fy], &cfg).unwrap();
                let err = ((x - peg[0]).powi(2) + (y - peg[1]).powi(2)).sqrt();
                assert!(
                    err < 1e-9,
                    "{name} r {r} mu0 {mu0:?} theta {}: {err:e}",
                    p.theta
                );
                assert!((s - p.s_c).abs() < 1e-9, "{name}: s {s} vs {}", p.s_c);
            }
        }
    }
}

/// Every method solves the frictionless contact state: s_c, the force and the base moment agree
/// with the rod's own shooter to 1e-8.
#[test]
fn every_method_solves_the_point_contact() {
    let peg = peg_at(0.7, 0.3);
    let theta = 0.6;
    for (name, rod) in rods().into_iter().take(2) {
        let own = solve_peg(&rod, peg, theta, &WhiskOptions::default()).unwrap();
        for method in [Method::MultipleShooting, Method::Collocation6] {
            let o = WhiskOptions {
                solver: SolverConfig {
                    method,
                    tol: 1e-10,
                    segments: 4,
                    ..SolverConfig::default()
                },
                ..WhiskOptions::default()
            };
            let p = solve_peg(&rod, peg, theta, &o).unwrap();
            for (what, a, b) in [
                ("s_c", own.s_c, p.s_c),
                ("f", own.f, p.f),
                ("m_base", own.m_base, p.m_base),
            ] {
                assert!(
                    (a - b).abs() < 1e-8 * (1.0 + a.abs()),
                    "{name} {method:?} {what}: {a} vs {b}"
                );
            }
        }
    }
}

/// The whisk ends where the object slips off the tip: the last row is that event, with the
/// contact at the tip to rounding.
#[test]
fn the_object_slips_off_the_tip() {
    let w = whisk(
        &Rod::uniform(),
        peg_at(0.95, 0.2),
        &WhiskOptions {
            theta_max: 1.4,
            points: 11,
            mu0: Some(0.2),
            ..WhiskOptions::default()
        },
    )
    .unwrap();
    let last = w.points.last().unwrap();
    assert_eq!(last.event, Some(Event::SlipOff));
    assert!((last.s_c - 1.0).abs() < 1e-12, "{}", last.s_c);
    match w.stop {
        StopReason::SlipOff { d } => assert_eq!(d, last.theta),
        ref other => panic!("{other}"),
    }
    // sliding from first touch (a straight rod pinned at a point cannot turn): |T| = mu0 N
    assert!(w
        .points
        .iter()
        .filter(|p| p.normal > 0.0)
        .all(|p| (p.mu.abs() - 0.2).abs() < 1e-9));
}

/// An object behind the rod (it turns the other way) or beyond the reach of a curved rod (its
/// chord, 2 sin(0.75)/1.5 = 0.909 for a rest curvature of 1.5) is out of reach.
#[test]
fn an_object_out_of_reach_is_a_typed_error() {
    let curled = Rod::builder().precurvature(-1.5, 0.0).build().unwrap();
    for (rod, peg) in [
        (Rod::uniform(), peg_at(0.7, -0.3)),
        (curled, peg_at(0.95, 0.3)),
    ] {
        match whisk(&rod, peg, &WhiskOptions::default()) {
            Err(VibrissaError::OutOfReach { .. }) => {}
            other => panic!("{peg:?}: {other:?}"),
        }
    }
    // before first touch: solve_peg says so
    match solve_peg(
        &Rod::uniform(),
        peg_at(0.7, 0.3),
        0.1,
        &WhiskOptions::default(),
    ) {
        Err(VibrissaError::OutOfReach { what, .. }) => assert!(what.contains("first touched")),
        other => panic!("{other:?}"),
    }
}
