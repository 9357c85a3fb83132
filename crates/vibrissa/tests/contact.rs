//! Contact physics over random scenes (property test), contact anywhere along the rod: no scan
//! row has a contact pulling (normal force ≤ 0), a contact needing more friction than μ0, or any
//! point of the rod beyond the surface line; an event row ends the scan only where its
//! condition holds.

use proptest::prelude::*;
use vibrissa::{scan, Event, Precurvature, ScanOptions, Scene, SolverConfig, Stiffness};

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
    #[test]
    fn no_row_pulls_slips_or_penetrates(
        ratio in 0.1..1.0f64, k0 in -1.0..1.0f64, k1 in -0.5..0.5f64, c in 0.0..1.0f64,
        beta in -0.3..0.3f64, flat in proptest::bool::ANY, eta in 0.5..0.95f64,
        mu0 in proptest::option::of(0.1..1.5f64),
    ) {
        let scene = Scene {
            eta,
            stiffness: Stiffness::Taper { ratio },
            precurvature: Precurvature::Linear { k0, k1 },
            support_compliance: c,
            surface_angle: if flat { 0.0 } else { beta },
            ..Scene::default()
        };
        let (rod, surface) = scene.parts().unwrap();
        let o = ScanOptions {
            points: 21,
            mu0,
            keep_shapes: Some(201),
            solver: SolverConfig::default(),
            ..ScanOptions::default()
        };
        // a rod whose rest shape does not reach the surface has no start (a typed error)
        let Ok(r) = scan(&rod, &surface, &o) else { return Ok(()); };
        // the surface line through the start's contact point
        let b = surface.angle();
        let (nx, ny) = (-b.sin(), b.cos());
        let line = nx * r.surface_point[0] + ny * r.surface_point[1];
        for (p, shape) in r.points.iter().zip(&r.shapes) {
            let above = shape
                .iter()
                .map(|q| nx * (q.x + p.d) + ny * q.y - line)
                .fold(f64::MIN, f64::max);
            prop_assert!(above <= 1e-12, "d = {} ({:?}): the rod is {above:e} beyond the surface", p.d, p.event);
            if p.event.is_some() {
                continue;
            }
            prop_assert!(p.normal > 0.0, "pulled at d = {}: N = {}", p.d, p.normal);
            prop_assert!(p.mu.abs() <= p.mu_peak + 1e-12, "d = {}: |mu| {} > mu_peak {}", p.d, p.mu, p.mu_peak);
            if let Some(m) = mu0 {
                prop_assert!(p.mu_peak <= m + ratio_tol(p), "d = {}: a contact needs {} > mu0 = {m}", p.d, p.mu_peak);
            }
        }
        if let Some(ev) = r.points.last().filter(|p| p.event.is_some()) {
            match ev.event {
                Some(Event::Slip) => {
                    let m = mu0.unwrap();
                    prop_assert!((ev.mu_peak - m).abs() < ratio_tol(ev), "slip row mu_peak {}", ev.mu_peak);
                }
                Some(Event::LiftOff) => prop_assert!(ev.normal == 0.0),
                _ => {}
            }
        }
    }
}

/// How well a row's friction ratio is determined: 1e-9 with one contact; with two (in a scan
/// both hold without slip, and the segment between them carries a nearly indeterminate pair of
/// tangential forces) 5e-8: on the scene of
/// `a_slip_in_a_trapped_state_is_located_to_the_accuracy_of_the_ratio` the slip row's ratio is
/// 4.6e-9, 1.8e-8 and 6.5e-9 off μ0 at tol 1e-10, 1e-11 and 1e-12 (the event function scatters
/// by 1e-9 over λ steps of 1e-13 there).
fn ratio_tol(p: &vibrissa::ScanPoint) -> f64 {
    if p.contact.name().contains('+') {
        5e-8
    } else {
        1e-9
    }
}

#[test]
fn a_slip_in_a_trapped_state_is_located_to_the_accuracy_of_the_ratio() {
    // Found by the property test (1 case in ~300): side+tip from the start, the side slips at
    // d = 3.797e-4 with its ratio 4.6e-9 below μ0 (the test asked for 1e-9).
    let mu0 = 0.3047897780415233;
    let scene = Scene {
        eta: 0.5,
        stiffness: Stiffness::Taper {
            ratio: 0.2546355076966698,
        },
        precurvature: Precurvature::Linear {
            k0: 0.15640310972623728,
            k1: -0.48454719233092025,
        },
        support_compliance: 0.861187433436653,
        surface_angle: -0.24846025346123243,
        ..Scene::default()
    };
    let (rod, surface) = scene.parts().unwrap();
    for tol in [1e-10, 1e-12] {
        let o = ScanOptions {
            points: 21,
            mu0: Some(mu0),
            solver: SolverConfig {
                tol,
                ..SolverConfig::default()
            },
            ..ScanOptions::default()
        };
        let r = scan(&rod, &surface, &o).unwrap();
        let ev = r.points.last().unwrap();
        assert_eq!(ev.event, Some(Event::Slip), "tol {tol}: {}", r.stop);
        assert_eq!(ev.contact.name(), "side+tip");
        assert!((ev.d - 3.797347e-4).abs() < 1e-9, "tol {tol}: d {}", ev.d);
        assert!(
            (ev.mu_peak - mu0).abs() < ratio_tol(ev),
            "tol {tol}: {}",
            ev.mu_peak
        );
    }
}

#[test]
fn a_start_whose_trapped_pair_is_indeterminate_is_named() {
    // Found by the property test (1 case in ~4000): pressed, the rod touches at a side 6.9e-4
    // before the tip, its tip slope 1.1e-5 from the surface's. With both holding, the equilibrium's
    // Jacobian has a zero singular value (the other five 0.096–78): the correction at d = 0
    // returned a tangential pair with |T|/N = 1121 on a frictionless press (a start row above
    // μ0), and the scan ended in a solver message at d = 4.9e-8. The 36 trapped starts of the
    // third grid (docs/robustness.md) scan as before (four measured: σ_min/σ_max 2e-14–5e-11).
    let scene = Scene {
        eta: 0.8413669277962146,
        stiffness: Stiffness::Taper {
            ratio: 0.16943620646015384,
        },
        precurvature: Precurvature::Linear {
            k0: -0.2573809280260109,
            k1: 0.3228532552789773,
        },
        support_compliance: 0.9131006102450641,
        ..Scene::default()
    };
    let (rod, surface) = scene.parts().unwrap();
    for method in [
        vibrissa::Method::Shooting,
        vibrissa::Method::MultipleShooting,
    ] {
        let o = ScanOptions {
            points: 21,
            mu0: Some(0.7224091749390847),
            solver: SolverConfig {
                method,
                ..SolverConfig::default()
            },
            ..ScanOptions::default()
        };
        let r = scan(&rod, &surface, &o).unwrap();
        let vibrissa::StopReason::ContactChange { d, message } = &r.stop else {
            panic!("{method:?}: {}", r.stop);
        };
        assert_eq!(*d, 0.0);
        assert!(
            message.contains("singular to working precision"),
            "{message}"
        );
        // the start's own row: the frictionless press, no tangential force
        assert_eq!(r.points.len(), 1);
        let p = &r.points[0];
        assert_eq!((p.d, p.event, p.contact.name()), (0.0, None, "side+tip"));
        assert!(p.mu_peak < 1e-9, "{method:?}: mu_peak {}", p.mu_peak);
    }
}

#[test]
fn a_lying_end_that_peels_back_to_the_tip_ends_the_same_way_on_every_grid() {
    // Found by the property test (1 case in ~1000): the rod's end lies on the surface and the
    // lying part's inner end reaches the tip at d = 0.3353793043. The tip alone would turn into
    // the surface there; its tip-tangent function is ±1e-14 at the switch, and its sign (set by
    // the grid) decided whether the march stopped ("tip does not hold") or lay down again at once
    // (a touchdown row, then "side does not hold"). A function within 1e-12 of zero at a change
    // is now at zero: every grid has the peel-back row and the same stop.
    let scene = Scene {
        eta: 0.9236573154463448,
        stiffness: Stiffness::Taper {
            ratio: 0.10923509292023136,
        },
        precurvature: Precurvature::Linear {
            k0: -0.015525374084602602,
            k1: 0.0,
        },
        ..Scene::default()
    };
    for n in [11, 201, 2001] {
        let r = scan_at(&scene, n).unwrap();
        let events: Vec<_> = r.points.iter().filter_map(|p| p.event).collect();
        assert_eq!(events, [Event::PeelBack], "{n} points");
        let vibrissa::StopReason::ContactChange { d, message } = &r.stop else {
            panic!("{n} points: {}", r.stop);
        };
        assert!(
            message.contains("the contact state tip does not hold"),
            "{message}"
        );
        assert!((d - 0.3353793043).abs() < 1e-9, "{n} points: d {d}");
    }
}

/// Found by the property test: near d = 0.39 this rod turns S-shaped at its tip and rises above
/// the surface at s ≈ 0.967 while the tip still arrives from below, a maximum inside one mesh
/// interval whose end slopes have the same sign. The scan stops there with penetration, and no
/// row is above the surface.
#[test]
fn an_s_shaped_tip_that_rises_above_the_surface_is_a_penetration() {
    let scene = Scene {
        eta: 0.7238972629710195,
        stiffness: Stiffness::Taper {
            ratio: 0.7034764277413978,
        },
        precurvature: Precurvature::Linear {
            k0: 0.35384608576947507,
            k1: 0.22365066836351954,
        },
        support_compliance: 0.5511142318116053,
        ..Scene::default()
    };
    let (rod, surface) = scene.parts().unwrap();
    // the paper's tip-only model from the state connected to the straight rod (this rod,
    // pressed onto the surface, leans the other way and lifts off at once)
    let o = ScanOptions {
        points: 21,
        contact: vibrissa::ContactModel::Tip,
        solver: SolverConfig {
            start: vibrissa::StartKind::Connected,
            ..SolverConfig::default()
        },
        ..ScanOptions::default()
    };
    let r = scan(&rod, &surface, &o).unwrap();
    match r.stop {
        vibrissa::StopReason::Penetration { d, s, y } => {
            assert!(d > 0.375 && d < 0.4, "{d}");
            assert!(s > 0.9 && s < 1.0, "{s}");
            assert!((y - scene.eta).abs() < 1e-9, "{y}");
        }
        ref other => panic!("expected penetration, got {other}"),
    }
    assert!(r.points.iter().all(|p| p.y_max <= scene.eta + 1e-9));
}

/// The scan's rows at `d` of a grid of `points`.
fn scan_at(scene: &Scene, points: usize) -> Option<vibrissa::ScanResult> {
    let (rod, surface) = scene.parts().ok()?;
    let o = ScanOptions {
        points,
        ..ScanOptions::default()
    };
    scan(&rod, &surface, &o).ok()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
    /// Issue 19/23: the march's step control and event location do not depend on the output
    /// grid. Over random scenes a scan at 2001 points reaches as far as one at 11 and 201, stops
    /// for the same reason, and every event (contact changes and the end), μ_max and
    /// `d_at_mu_max` agree to 1e-9; on a flat surface the rod is on or below it at every event
    /// to 1e-10. (Run with 400 cases twice before it was committed: it found μ_max missing the
    /// fold's own point, a spurious maximum at the pole of μ before lift-off, and a touchdown of
    /// a vanishing tail before a peel-back; all fixed.)
    #[test]
    fn events_and_the_maximum_do_not_depend_on_the_output_grid(
        ratio in 0.1..1.0f64, k0 in -1.0..1.0f64, c in 0.0..1.0f64, eta in 0.55..0.95f64,
    ) {
        let scene = Scene {
            eta,
            stiffness: Stiffness::Taper { ratio },
            precurvature: Precurvature::Linear { k0, k1: 0.0 },
            support_compliance: c,
            ..Scene::default()
        };
        let runs: Vec<_> = [11, 201, 2001].iter().map(|&n| scan_at(&scene, n)).collect();
        let [Some(a), Some(b), Some(f)] = &runs[..] else {
            // no start (out of reach) is the same for every grid
            prop_assert!(runs.iter().all(Option::is_none), "{scene:?}: a grid-dependent start");
            return Ok(());
        };
        let events = |r: &vibrissa::ScanResult| -> Vec<(f64, Event)> {
            r.points.iter().filter_map(|p| p.event.map(|e| (p.d, e))).collect()
        };
        let ef = events(f);
        for r in [a, b] {
            let kind = |r: &vibrissa::ScanResult| r.stop.to_string().split(" at ").next().unwrap_or("").to_string();
            prop_assert_eq!(kind(r), kind(f));
            // (unbounded where the range ends at lift-off)
            prop_assert!(r.mu_max == f.mu_max || (r.mu_max - f.mu_max).abs() <= 1e-9 * f.mu_max.max(1.0), "mu_max {} / {}", r.mu_max, f.mu_max);
            prop_assert!((r.d_at_mu_max - f.d_at_mu_max).abs() <= 1e-9, "d_at_mu_max {} / {}", r.d_at_mu_max, f.d_at_mu_max);
            let er = events(r);
            prop_assert_eq!(er.len(), ef.len(), "events {:?} / {:?}", er, ef);
            for ((d1, e1), (d2, e2)) in er.iter().zip(&ef) {
                prop_assert_eq!(e1, e2);
                prop_assert!((d1 - d2).abs() <= 1e-9, "{:?} at {} / {}", e1, d1, d2);
            }
        }
        for p in f.points.iter().filter(|p| p.event.is_some()) {
            prop_assert!(p.y_max <= eta + 1e-10, "{:?} at d = {}: y_max - eta = {:e}", p.event, p.d, p.y_max - eta);
        }
    }
}
