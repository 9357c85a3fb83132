//! Contact physics over random scenes (property test), contact anywhere along the rod: no scan
//! row has a contact pulling (normal force ≤ 0), a contact needing more friction than μ0, or any
//! point of the rod beyond the surface line; an event row ends the scan only where its
//! condition holds.

use proptest::prelude::*;
use vibrissa::drag::ContactState;

#[path = "support/contact_rate.rs"]
mod contact_rate;
use contact_rate::rate;
use vibrissa::{scan, Event, Precurvature, ScanOptions, Scene, SolverConfig, Stiffness};

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
    #[test]
    fn no_row_pulls_slips_or_penetrates(
        ratio in 0.1..1.0f64, k0 in -1.0..1.0f64, k1 in -0.5..0.5f64, c in 0.0..1.0f64,
        beta in -0.3..0.3f64, flat in proptest::bool::ANY, eta in 0.5..0.95f64,
        mu0 in proptest::option::of(0.1..1.5f64),
    ) {
        let scene = scene_of(eta, ratio, (k0, k1), c, if flat { 0.0 } else { beta });
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
        prop_assert_eq!(r.contacts.len(), r.points.len());
        for ((p, shape), cs) in r.points.iter().zip(&r.shapes).zip(&r.contacts) {
            let above = shape
                .iter()
                .map(|q| nx * (q.x + p.d) + ny * q.y - line)
                .fold(f64::MIN, f64::max);
            prop_assert!(above <= 1e-12, "d = {} ({:?}): the rod is {above:e} beyond the surface", p.d, p.event);
            // the row's totals and its peak ratio are its contacts'
            let n: f64 = cs.iter().map(|k| k.normal).sum();
            prop_assert!((n - p.normal).abs() <= 1e-12 * (1.0 + n.abs()), "d = {}: N {n} of {}", p.d, p.normal);
            if p.event.is_some() {
                continue;
            }
            prop_assert!((peak(cs).0 - p.mu_peak).abs() <= 1e-12 * p.mu_peak, "d = {}: mu_peak {}", p.d, p.mu_peak);
            prop_assert!(p.normal > 0.0, "pulled at d = {}: N = {}", p.d, p.normal);
            prop_assert!(p.mu.abs() <= p.mu_peak + 1e-12, "d = {}: |mu| {} > mu_peak {}", p.d, p.mu, p.mu_peak);
            if let Some(m) = mu0 {
                for k in cs {
                    prop_assert!(
                        gap(k, m) <= force_tol(p),
                        "d = {}: a contact needs {} > mu0 = {m} ({k})", p.d, k.tangential.abs() / k.normal
                    );
                }
            }
        }
        if let Some(ev) = r.points.last().filter(|p| p.event.is_some()) {
            match ev.event {
                Some(Event::Slip) => {
                    let (ratio, k) = peak(r.contacts.last().unwrap());
                    prop_assert!((ratio - ev.mu_peak).abs() <= 1e-12 * ratio, "slip row mu_peak {}", ev.mu_peak);
                    let gap = gap(k, mu0.unwrap());
                    let allowed = force_tol(ev) + located(&r, mu0.unwrap()) + force_error(&rod, &surface, &o, &r);
                    prop_assert!(gap.abs() < allowed, "slip row mu_peak {}: |T| - mu0 N = {gap:e} ({k})", ev.mu_peak);
                }
                Some(Event::LiftOff) => prop_assert!(ev.normal == 0.0),
                _ => {}
            }
        }
    }
}

/// How well a row's contact forces are determined, as a share of its total normal force `N`:
/// 1e-9 with one contact; with two (in a scan both hold without slip, and the segment between
/// them carries a nearly indeterminate pair of tangential forces) 5e-8: on the scene of
/// `a_slip_in_a_trapped_state_is_located_to_the_accuracy_of_the_ratio` the slip row's ratio is
/// 4.6e-9, 1.8e-8 and 6.5e-9 off μ0 at tol 1e-10, 1e-11 and 1e-12 (the event function scatters
/// by 1e-9 over λ steps of 1e-13 there). A contact's ratio `|T_j|/N_j` is then determined to
/// this over `N_j`: a tip that carries 0.9 % of the load has its ratio known to 100 times less
/// (`a_slip_of_a_contact_with_a_small_share_of_the_load_is_located_on_its_forces`).
fn force_tol(p: &vibrissa::ScanPoint) -> f64 {
    let share = if p.contact.name().contains('+') {
        5e-8
    } else {
        1e-9
    };
    share * p.normal
}

/// A slip is located to `1e-13·(1 + d)` in `d` (`events::locate`, Brent's method or Newton's
/// on the branch's polynomial, as in tests/contact_forces.rs), and `inside` may back the point
/// off by a few such steps: allowed `4e-13·(1 + d)` times the mean rate at which the slipping
/// contact's `|T| − μ0 N` changes from the row before. Where the ratio rises steeply that is
/// more than [`force_tol`]: a tip that slips at d = 1.3e-5, its `|T| − μ0 N` rising at 4.6e4
/// (from −0.59 at d = 0), was located 7.4e-14 beyond its slip in `d`, 3.4e-9 in `|T| − μ0 N`
/// (`a_steep_slip_is_located_to_its_place_in_d`).
fn located(r: &vibrissa::ScanResult, mu0: f64) -> f64 {
    let n = r.points.len();
    if n < 2 {
        return 0.0;
    }
    let (ev, prev) = (&r.points[n - 1], &r.points[n - 2]);
    let (now, before) = (&r.contacts[n - 1], &r.contacts[n - 2]);
    4e-13 * (1.0 + ev.d) * rate(before, now, &|k| gap(k, mu0), ev.d - prev.d)
}

/// How well the friction condition `|T_j| − μ0 N_j` of the last row of the scan `r` (of `rod`
/// on `surface` with the options `o`) is determined: the largest difference, contact by
/// contact, between the row's value and its value solved to the tolerance 1e-12 at the same
/// `d`, and between the values solved at the scan's tolerance and at 1e-12 at five
/// displacements 1e-9·d apart around it (all without μ0); 0 where the row is within
/// [`force_tol`] (not solved then), or where a solve does not reach those displacements with
/// the row's contacts (the check is then `force_tol`'s alone). A slip row is located to the accuracy of its forces: `|T|
/// − μ0 N` within `force_tol` plus this. With two contacts that hold near a state where their
/// tangential pair is indeterminate (a tip nearly tangent to the surface next to a side, with a
/// small share of the load), the pair's forces are determined only to the residual's rounding
/// over the Jacobian's smallest singular value, at every tolerance:
/// - `a_slip_where_the_pair_scatters_is_located_to_the_accuracy_of_its_forces` (1 case in
///   ~4000): the tip, with 0.37 % of the load, read `|T| − μ0 N` with a scatter of 1.5e-7
///   between solves 1e-11 apart in `d` at tol 1e-10; its slip at d 4.321962e-3, 4.321997e-3
///   and 4.322089e-3 at tol 1e-10, 1e-11 and 1e-12;
/// - `a_slip_of_a_tip_with_under_a_hundredth_of_the_load_is_located_to_the_accuracy_of_its_forces`
///   (1 case in ~40000): the tip, with 0.76 % of the load, slips with its ratio 5.6e-6, 1.96e-5
///   and 3.5e-5 below μ0 at tol 1e-10, 1e-11 and 1e-12.
fn force_error(
    rod: &vibrissa::Rod,
    surface: &vibrissa::Surface,
    o: &ScanOptions,
    r: &vibrissa::ScanResult,
) -> f64 {
    let (ev, cs) = (r.points.last().unwrap(), r.contacts.last().unwrap());
    let m = o.mu0.unwrap();
    if cs.iter().all(|k| gap(k, m).abs() < force_tol(ev)) {
        return 0.0;
    }
    // the row's `d` and four more 1e-9·d apart (the scatter between solves)
    let at: Vec<f64> = std::iter::once(0.0)
        .chain((-2..=2).map(|i| ev.d * (1.0 + 1e-9 * f64::from(i))))
        .collect();
    let solved = |tol: f64| {
        let oo = ScanOptions {
            mu0: None,
            keep_shapes: None,
            solver: SolverConfig {
                tol,
                ..o.solver.clone()
            },
            ..o.clone()
        };
        let t = vibrissa::scan_at(rod, surface, &oo, &at).ok()?;
        let same =
            t.points.len() == at.len() && t.contacts.iter().skip(1).all(|k| k.len() == cs.len());
        same.then_some(t.contacts)
    };
    let (Some(a), Some(b)) = (solved(o.solver.tol), solved(1e-12)) else {
        return 0.0;
    };
    let differ = |x: &[ContactState], y: &[ContactState]| {
        (x.iter().zip(y))
            .map(|(p, q)| (gap(p, m) - gap(q, m)).abs())
            .fold(0.0, f64::max)
    };
    let row = differ(cs, &b[3]);
    (a.iter().zip(&b).skip(1))
        .map(|(x, y)| differ(x, y))
        .fold(row, f64::max)
}

/// The largest friction ratio of a row's contacts, and its contact.
fn peak(cs: &[ContactState]) -> (f64, &ContactState) {
    cs.iter()
        .map(|k| ((k.tangential / k.normal).abs(), k))
        .fold(
            (f64::NEG_INFINITY, &cs[0]),
            |a, b| if b.0 > a.0 { b } else { a },
        )
}

/// A scene of the property's kind: the rod tapered to `ratio`, its rest curvature `k0 + k1·s`,
/// on a support of compliance `c`, the surface at `eta` inclined by `beta`.
fn scene_of(eta: f64, ratio: f64, (k0, k1): (f64, f64), c: f64, beta: f64) -> Scene {
    Scene {
        eta,
        stiffness: Stiffness::Taper { ratio },
        precurvature: Precurvature::Linear { k0, k1 },
        support_compliance: c,
        surface_angle: beta,
        ..Scene::default()
    }
}

/// A contact's friction condition `|T| − μ0 N` (> 0: beyond its slip limit).
fn gap(k: &ContactState, mu0: f64) -> f64 {
    k.tangential.abs() - mu0 * k.normal
}

/// A scan of the property's kind (21 points, μ0, the tolerance `tol`) of a found scene that ends
/// in a slip of the contacts `label`.
struct Slip {
    rod: vibrissa::Rod,
    surface: vibrissa::Surface,
    o: ScanOptions,
    r: vibrissa::ScanResult,
}

impl Slip {
    fn of(scene: &Scene, mu0: f64, tol: f64, label: &str) -> Slip {
        let (rod, surface) = scene.parts().unwrap();
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
        assert_eq!(ev.contact.name(), label, "tol {tol}");
        Slip { rod, surface, o, r }
    }

    /// The slip row.
    fn row(&self) -> &vibrissa::ScanPoint {
        self.r.points.last().unwrap()
    }

    /// The row's contacts.
    fn contacts(&self) -> &[ContactState] {
        self.r.contacts.last().unwrap()
    }

    /// The slipping contact (the largest ratio), its ratio and its `|T| − μ0 N`.
    fn slipping(&self) -> (&ContactState, f64, f64) {
        let (ratio, k) = peak(self.contacts());
        (k, ratio, gap(k, self.o.mu0.unwrap()))
    }

    /// [`force_error`] of the slip row.
    fn force_error(&self) -> f64 {
        force_error(&self.rod, &self.surface, &self.o, &self.r)
    }
}

#[test]
fn a_slip_in_a_trapped_state_is_located_to_the_accuracy_of_the_ratio() {
    // Found by the property test (1 case in ~300): side+tip from the start, the side slips at
    // d = 3.797e-4 with its ratio 4.6e-9 below μ0 (the test asked for 1e-9).
    let scene = scene_of(
        0.5,
        0.2546355076966698,
        (0.15640310972623728, -0.48454719233092025),
        0.861187433436653,
        -0.24846025346123243,
    );
    for tol in [1e-10, 1e-12] {
        let s = Slip::of(&scene, 0.3047897780415233, tol, "side+tip");
        let ev = s.row();
        assert!((ev.d - 3.797347e-4).abs() < 1e-9, "tol {tol}: d {}", ev.d);
        let (k, ratio, gap) = s.slipping();
        assert_eq!(ratio, ev.mu_peak);
        assert!(gap.abs() < force_tol(ev), "tol {tol}: {gap:e} ({k})");
    }
}

#[test]
fn a_slip_of_a_contact_with_a_small_share_of_the_load_is_located_on_its_forces() {
    // Found by the property test (1 case in ~700): side+tip from the start, the tip carries
    // 0.0115 of the normal force 1.26 and slips at d = 3.627e-5. The pair's tangential forces
    // scatter by ~5e-8 between solves 1e-12 apart in d (|T| − μ0 N read −3.5e-10 and 5.1e-8
    // there), which is 4e-6 in the tip's ratio: the slip was located with its ratio 9.8e-7
    // below μ0, its |T| − μ0 N 1.2e-8 (the property test asked for 5e-8 in the ratio).
    let mu0 = 1.0528586762355867;
    let scene = scene_of(
        0.5857746675094058,
        0.31625863509412033,
        (0.2372887305479562, -0.3158748784555789),
        0.07061986699401053,
        0.0,
    );
    let s = Slip::of(&scene, mu0, SolverConfig::default().tol, "side+tip");
    let ev = s.row();
    let (k, ratio, gap) = s.slipping();
    assert!(k.tip && k.normal < 0.01 * ev.normal, "{k}");
    assert_eq!(ratio, ev.mu_peak);
    assert!(gap.abs() < force_tol(ev), "{gap:e} ({k})");
    // the side holds inside its cone
    let side = &s.contacts()[0];
    assert!(side.tangential.abs() < mu0 * side.normal, "{side}");
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

#[test]
fn a_slip_where_the_pair_scatters_is_located_to_the_accuracy_of_its_forces() {
    // Found by the property test (1 case in ~4000): see `force_error`.
    let scene = scene_of(
        0.653608533038177,
        0.17609540907737736,
        (0.08515494552305769, -0.16748713150749825),
        0.01521319613434393,
        0.0,
    );
    let s = Slip::of(
        &scene,
        1.1531346476782884,
        SolverConfig::default().tol,
        "side+tip",
    );
    let (k, _, gap) = s.slipping();
    let err = s.force_error();
    assert!(
        gap.abs() < force_tol(s.row()) + err,
        "{gap:e}, {err:e} ({k})"
    );
}

#[test]
fn a_slip_where_the_pair_jumped_is_located_where_its_forces_are() {
    // Found by the property test (1 case in ~20000): the tip (0.33 % of the load) slipped at d
    // 3.32982e-5 at tol 1e-10, 1.07e-7 before its place at tol 1e-11 and 1e-12 (3.34030e-5,
    // 3.34051e-5), its ratio 3.2e-3 below μ0. Predictions accepted by the chord corrector at a
    // residual of 9.9e-13 (its tol 1e-12) are 5.2e-6 off in the pair's forces, where one Newton
    // step from the same prediction is not: the slip's search ended on that jump of its event
    // function. A search that ends on a jump is searched again on polished points
    // (`events::jumped`): at tol 1e-10 the slip lies 9.4e-10 from its place at 1e-12.
    // That held on the shooter's meshes of the time, not robustly: with the first mesh of the
    // segment between the side and the tip changed by −4 … +8 steps (11 meshes), the slip row
    // at tol 1e-10 lay 1.0e-7 before its place again on 7 of them, and no search ended on a jump
    // that `jumped` sees. Since the moving ends' derivatives are exact (2026-12-04) its row's
    // `|T| − μ0 N` is −1.25e-7, beyond `force_tol` (2.5e-8) but within the scatter of its forces
    // between solves (`force_error`: 1.9e-7; 1.1e-8 and 1.0e-7 at tol 1e-12 and 1e-11): the
    // slip row is located to the accuracy of its forces, as in
    // `a_slip_where_the_pair_scatters_is_located_to_the_accuracy_of_its_forces`, and its d lies
    // 1.5e-9 from the place at tol 1e-12.
    let scene = scene_of(
        0.6781129469334398,
        0.16631999848652218,
        (0.40835671737503, -0.4855372665710997),
        0.37360913957559866,
        0.0,
    );
    let slip = |tol: f64| {
        let s = Slip::of(&scene, 1.03955030814294, tol, "side+tip");
        let ev = s.row();
        let (k, _, gap) = s.slipping();
        assert!(k.tip && k.normal < 0.004 * ev.normal, "{k}");
        let err = s.force_error();
        assert!(
            gap.abs() < force_tol(ev) + err,
            "tol {tol}: {gap:e}, {err:e} ({k})"
        );
        ev.d
    };
    let d12 = slip(1e-12);
    for tol in [1e-10, 1e-11] {
        let d = slip(tol);
        assert!((d - d12).abs() < 1e-8, "tol {tol}: d {d} against {d12}");
    }
}

#[test]
fn a_steep_slip_is_located_to_its_place_in_d() {
    // Found by the property test (1 case in ~60000): see `located`.
    let mu0 = 0.7663985270243021;
    let scene = scene_of(
        0.8525133476129556,
        0.885712249242131,
        (-0.3124435083735785, -0.03935817366903851),
        0.8837056243394072,
        -0.27125233635231083,
    );
    let s = Slip::of(&scene, mu0, SolverConfig::default().tol, "tip");
    let ev = s.row();
    let (_, _, gap) = s.slipping();
    let allowed = located(&s.r, mu0);
    // the rise is steep: the location's allowance is more than the ratio's own
    assert!(allowed > force_tol(ev), "{allowed:e}");
    assert!(
        gap.abs() < force_tol(ev) + allowed,
        "{gap:e} against {allowed:e}"
    );
}

#[test]
fn a_slip_of_a_tip_with_under_a_hundredth_of_the_load_is_located_to_the_accuracy_of_its_forces() {
    // Found by the property test (1 case in ~40000): see `force_error`.
    let mu0 = 0.24337272974074414;
    let scene = scene_of(
        0.7704582845302023,
        0.11444989898604135,
        (0.30438120045882777, -0.49983131585505614),
        0.4860313608769264,
        0.0,
    );
    let s = Slip::of(&scene, mu0, SolverConfig::default().tol, "side+tip");
    let ev = s.row();
    let (k, _, gap) = s.slipping();
    assert!(k.tip && k.normal < 0.01 * ev.normal, "{k}");
    let err = s.force_error();
    assert!(
        gap.abs() < force_tol(ev) + located(&s.r, mu0) + err,
        "{gap:e}, {err:e} ({k})"
    );
}

#[test]
#[ignore = "open: a free part 4e-12 beyond the surface beside a side that begins to lie (1 case in ~100000)"]
fn a_rod_beside_a_side_that_begins_to_lie_stays_on_its_side_of_the_surface() {
    // Found by the property test (1 case in ~100000, the same on the code before this test):
    // at d = 0.05 the rod is 4.0e-12 beyond the surface at s = 0.655, 7.7e-4 past the side
    // contact at s = 0.654230 (outside the clearance's 1e-4 around it), 2.5e-3 in d before
    // that side begins to lie along the surface (the scan's stop, d = 0.0525002). The row
    // property asks 1e-12. Near a lie-down the rod's relative curvature at the side falls to
    // zero, and the gap beyond it is the tangency's slope error times the distance.
    let scene = scene_of(
        0.5367524486468567,
        0.2631584035303767,
        (-0.14186964187652307, 0.4888339154031344),
        0.41974577261597823,
        0.1679660548909434,
    );
    let (rod, surface) = scene.parts().unwrap();
    let o = ScanOptions {
        points: 21,
        keep_shapes: Some(201),
        ..ScanOptions::default()
    };
    let r = scan(&rod, &surface, &o).unwrap();
    let b = surface.angle();
    let (nx, ny) = (-b.sin(), b.cos());
    let line = nx * r.surface_point[0] + ny * r.surface_point[1];
    for (p, shape) in r.points.iter().zip(&r.shapes) {
        let above = (shape.iter())
            .map(|q| nx * (q.x + p.d) + ny * q.y - line)
            .fold(f64::MIN, f64::max);
        assert!(above <= 1e-12, "d = {}: {above:e} beyond", p.d);
    }
}
