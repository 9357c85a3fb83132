//! Regression tests of the scan: cost of the general profile, penetration at the start, every
//! grid point present when d_max is reported, and the fold in d (snap-through).

use bvp::continuation::{Continuation, ContinuationOptions};
use bvp::{Integrator, NewtonOptions, Shooting, ShootingOptions};
use vibrissa::equations::{Ends, RodBvp, ScanFamily};
use vibrissa::profile::Uniform;
use vibrissa::{
    scan, solve, BranchChoice, ContactModel, Event, Rod, ScanOptions, ScanResult, Scene,
    SolverConfig, Stiffness, StopReason, Target,
};

fn grid_len(o: &ScanOptions, upto: f64) -> usize {
    (0..o.points)
        .filter(|&i| o.d_max * i as f64 / (o.points - 1) as f64 <= upto)
        .count()
}

/// The contract of the output: d_max means every grid point; any other stop at d means every
/// grid point up to d (and none beyond), then the event point at d (except a solver failure). A
/// start that is no valid contact (an event at d = 0) has the event row only. A lift-off found by
/// extrapolation (past the last solved state) has no row: the grid rows end at the last state.
fn check_points(r: &ScanResult, o: &ScanOptions) {
    let last_d = r.points.last().map_or(0.0, |p| p.d);
    let (upto, event) = match &r.stop {
        StopReason::LiftOff { d, limit: Some(_) } => {
            assert!(
                *d > last_d,
                "extrapolated lift-off {d} before the last row {last_d}"
            );
            (last_d, None)
        }
        StopReason::DMax => (o.d_max, None),
        StopReason::Slip { d, .. } => (*d, Some(Event::Slip)),
        StopReason::LiftOff { d, limit: None } => (*d, Some(Event::LiftOff)),
        StopReason::Penetration { d, .. } => (*d, Some(Event::Penetration)),
        StopReason::FoldInD { d } => (*d, Some(Event::FoldInD)),
        StopReason::SlipOff { d } => (*d, Some(Event::SlipOff)),
        StopReason::ContactChange { d, .. } | StopReason::Jam { d, .. } => (*d, None),
        StopReason::Cancelled { d } => (*d, None),
        StopReason::SolverFailure { d, .. } => (*d - 1e-300, None),
    };
    let grid_points = r.points.iter().filter(|p| p.event.is_none()).count();
    // events that change the contact state are rows of their own, in order
    assert!(r.points.windows(2).all(|w| w[0].d <= w[1].d));
    let expected = if event.is_some() && upto == 0.0 {
        0
    } else {
        grid_len(o, upto)
    };
    assert_eq!(grid_points, expected, "stop {}", r.stop);
    if let Some(ev) = event {
        let last = r.points.last().expect("the event point");
        assert_eq!(last.event, Some(ev));
        assert_eq!(last.d, upto);
    }
}

/// A scan of `rod` on `surface` with the method, grid and μ0 given (the rest default), its rows
/// checked against the output contract.
fn run_checked(
    rod: &Rod,
    surface: &vibrissa::Surface,
    method: vibrissa::Method,
    points: usize,
    mu0: Option<f64>,
) -> ScanResult {
    let o = ScanOptions {
        points,
        mu0,
        solver: SolverConfig {
            method,
            ..SolverConfig::default()
        },
        ..ScanOptions::default()
    };
    let r = scan(rod, surface, &o).unwrap();
    check_points(&r, &o);
    r
}

#[test]
fn table_profile_costs_about_as_much_as_the_uniform_branch() {
    // b ≡ 1 written as a table: the same rod as the paper's. One natural step per grid point
    // from a quadratic predictor needs at most 2 Newton iterations per point on this smooth
    // branch (it took 620 = 3.1 per point with output solves off pseudo-arclength points).
    let table = Scene {
        stiffness: Stiffness::Table {
            s: vec![0.0, 0.25, 0.5, 0.75, 1.0],
            b: vec![1.0; 5],
        },
        ..Scene::default()
    };
    let o = ScanOptions::default();
    let (rod, surface) = table.parts().unwrap();
    let rt = scan(&rod, &surface, &o).unwrap();
    let ru = scan(&Rod::uniform(), &surface, &o).unwrap();
    assert_eq!(rt.stop, StopReason::DMax);
    check_points(&rt, &o);
    assert!(
        rt.stats.newton_iters <= 2 * o.points,
        "{} Newton iterations for {} points",
        rt.stats.newton_iters,
        o.points
    );
    // same physics: same answers (to the solver tolerance 1e-10, amplified by conditioning)
    assert!((rt.mu_max - ru.mu_max).abs() < 1e-8);
    assert!((rt.d_at_mu_max - ru.d_at_mu_max).abs() < 1e-6);
    for (a, b) in rt.points.iter().zip(&ru.points) {
        assert!((a.alpha - b.alpha).abs() < 1e-8 && (a.f - b.f).abs() < 1e-8);
    }
}

#[test]
fn start_below_the_surface_stops_at_d0() {
    // taper 0.5, η = 0.6: the starting rod's tip points down (φ1 < 0), so y(s) > η just before
    // the tip — the start already penetrates.
    let scene = Scene {
        eta: 0.6,
        stiffness: Stiffness::Taper { ratio: 0.5 },
        ..Scene::default()
    };
    let (rod, surface) = scene.parts().unwrap();
    let start = solve(
        &rod,
        0.0,
        Target::Eta(0.6),
        &BranchChoice::Convex,
        &SolverConfig::default(),
    )
    .unwrap();
    assert!(start.phi1 < -0.1, "phi1 = {}", start.phi1);
    assert!(start.point_at(0.99).y > 0.6);
    // the paper's tip-only model: a touching side ends the scan
    let o = ScanOptions {
        points: 21,
        contact: ContactModel::Tip,
        ..ScanOptions::default()
    };
    let r = scan(&rod, &surface, &o).unwrap();
    match r.stop {
        StopReason::Penetration { d, s, y } => {
            // pressed onto the surface the rod lies down: its side touches at s < 1
            assert_eq!(d, 0.0);
            assert!(s > 0.5 && s < 1.0, "{s}");
            assert!((y - 0.6).abs() < 1e-9);
        }
        ref other => panic!("expected penetration at d = 0, got {other}"),
    }
    check_points(&r, &o);
}

#[test]
fn penetration_between_grid_points_is_located() {
    // paper rod at η = 0.6 on a coarse grid (spacing 0.1): the tip turns horizontal at
    // d ≈ 0.0937 (closed form in tests/closed_form.rs), between the grid points 0 and 0.1
    let (rod, surface) = Scene {
        eta: 0.6,
        ..Scene::default()
    }
    .parts()
    .unwrap();
    let o = ScanOptions {
        points: 6,
        contact: ContactModel::Tip,
        ..ScanOptions::default()
    };
    let r = scan(&rod, &surface, &o).unwrap();
    let cf = elastica::ClosedFormScan::new(0.6).unwrap();
    match r.stop {
        StopReason::Penetration { d, .. } => assert!((d - cf.turning.d).abs() < 1e-7),
        ref other => panic!("expected penetration, got {other}"),
    }
    check_points(&r, &o);
}

#[test]
fn coarse_grids_keep_every_point() {
    // taper 0.05 used to end "d_max" with 3-5 of 6 points (the continuation's step cap ended
    // the scan silently); its start penetrates (tip curled down). Compliant and inclined scenes
    // run to d_max with all points.
    let scenes = [
        Scene {
            stiffness: Stiffness::Taper { ratio: 0.05 },
            ..Scene::default()
        },
        Scene {
            support_compliance: 0.5,
            ..Scene::default()
        },
        Scene {
            eta: 0.9,
            surface_angle: -0.3,
            ..Scene::default()
        },
    ];
    // the tip-only model from the state connected to the straight rod (pressed, the rod on the
    // inclined surface leans the other way)
    let o = ScanOptions {
        points: 6,
        contact: ContactModel::Tip,
        solver: SolverConfig {
            start: vibrissa::StartKind::Connected,
            ..SolverConfig::default()
        },
        ..ScanOptions::default()
    };
    for (i, scene) in scenes.iter().enumerate() {
        let (rod, surface) = scene.parts().unwrap();
        let r = scan(&rod, &surface, &o).unwrap();
        check_points(&r, &o);
        if i == 0 {
            assert!(matches!(r.stop, StopReason::Penetration { d, .. } if d == 0.0));
        } else {
            assert_eq!(r.stop, StopReason::DMax);
        }
    }
}

#[test]
fn fold_in_d_is_found_where_d_is_largest_on_the_branch() {
    // paper rod at η = 0.95 pushed to d = 0.6: d has a maximum along the branch (snap-through)
    let eta = 0.95;
    let (rod, surface) = Scene {
        eta,
        ..Scene::default()
    }
    .parts()
    .unwrap();
    let o = ScanOptions {
        d_max: 0.6,
        points: 7,
        ..ScanOptions::default()
    };
    let r = scan(&rod, &surface, &o).unwrap();
    let d_fold = match r.stop {
        StopReason::FoldInD { d } => d,
        ref other => panic!("expected a fold in d, got {other}"),
    };
    check_points(&r, &o);
    // reference: a separate pseudo-arclength run with small fixed steps, no fold detection;
    // the maximum of d from the parabola through the three points around the largest d
    let start = solve(
        &rod,
        0.0,
        Target::Eta(eta),
        &BranchChoice::Convex,
        &SolverConfig::default(),
    )
    .unwrap();
    let mut sol = start.solution().unwrap().clone();
    sol.params = vec![start.f, 0.0];
    let family = ScanFamily {
        rod: RodBvp {
            profile: Uniform,
            compliance: 0.0,
            alpha: 0.0,
            ends: Ends::Tip {
                x1: start.x1,
                y1: eta,
            },
        },
        eta,
        x_star: start.x1,
    };
    let shooting = Shooting::new(ShootingOptions {
        integrator: Integrator::Adaptive {
            rtol: 1e-11,
            atol: 1e-11,
        },
        newton: NewtonOptions {
            tol: 1e-11,
            ..NewtonOptions::default()
        },
        ..ShootingOptions::default()
    })
    .unwrap();
    let ds = 2e-3;
    let copts = ContinuationOptions {
        ds,
        ds_min: ds,
        ds_max: ds,
        max_steps: 20_000,
        lambda_min: -0.5,
        lambda_max: 1.0,
        detect_folds: false,
        ..ContinuationOptions::default()
    };
    let mut lam: Vec<f64> = Vec::new();
    for bp in Continuation::new(&family, shooting, sol, 0.0, copts).unwrap() {
        let bp = bp.unwrap();
        lam.push(bp.lambda);
        let n = lam.len();
        if n >= 3 && lam[n - 1] < lam[n - 2] {
            break;
        }
    }
    let n = lam.len();
    assert!(
        n >= 3 && lam[n - 1] < lam[n - 2],
        "no fold in the reference run"
    );
    // equally spaced in arclength: vertex of the parabola through (−1, a), (0, b), (1, c)
    let (a, b, c) = (lam[n - 3], lam[n - 2], lam[n - 1]);
    let t = 0.5 * (a - c) / (a - 2.0 * b + c);
    let d_ref = b - 0.25 * (a - c) * t;
    assert!(
        (d_fold - d_ref).abs() < 1e-6,
        "scan fold at d = {d_fold}, reference {d_ref}"
    );
}

/// The straight rod pressed onto a nearly horizontal line (the press passes close by the
/// buckling point): its start is the mirror image of the one on the line inclined the other
/// way (x → −x: the same force, φ → π − φ, to 1e-9), and it tends to the horizontal line's
/// (bent right) as β → 0+ (|Δf| ≤ 10 β). It used to fail to start for β = 1e-9 or 1e-7 and to
/// press on to a wrong branch (f = 1767) at β = 1e-4.
#[test]
fn press_on_a_nearly_horizontal_line_is_continuous_and_mirror_symmetric() {
    let start = |beta: f64| {
        let s = Scene {
            surface_angle: beta,
            ..Scene::default()
        };
        let (rod, surface) = s.parts().unwrap();
        let o = ScanOptions {
            d_max: 0.01,
            points: 2,
            ..ScanOptions::default()
        };
        scan(&rod, &surface, &o).unwrap().start
    };
    let flat = start(0.0);
    for beta in [1e-9, 1e-7, 1e-4, 1e-3] {
        let (p, m) = (start(beta), start(-beta));
        assert!(
            (p.f - m.f).abs() < 1e-9,
            "beta {beta}: f {} vs {}",
            p.f,
            m.f
        );
        assert!(
            (p.phi1 - (std::f64::consts::PI - m.phi1)).abs() < 1e-9,
            "beta {beta}: phi1 {} vs {}",
            p.phi1,
            m.phi1
        );
        assert!(
            (p.f - flat.f).abs() <= 10.0 * beta && p.phi1 < std::f64::consts::FRAC_PI_2,
            "beta {beta}: f {} (flat {})",
            p.f,
            flat.f
        );
    }
}

#[test]
fn a_side_contact_letting_go_at_the_tip_ends_in_an_extrapolated_lift_off() {
    // Grid 2 of docs/robustness.md: η 0.6, taper 0.1, surface inclined by −0.3. The side contact
    // rolls towards the tip as its normal force falls (s → 1 like a small power of N), the
    // corrector stalls near N ≈ 7e-5 and the scan said "solver failure". The lift-off lies a few
    // 1e-6 further: found from the last states, it agrees between grids to a few percent of that
    // distance (3e-7 over 11 to 3831 points and every method, measured).
    let scene = Scene {
        eta: 0.6,
        stiffness: Stiffness::Taper { ratio: 0.1 },
        surface_angle: -0.3,
        ..Scene::default()
    };
    let (rod, surface) = scene.parts().unwrap();
    let mut ds = Vec::new();
    for points in [11, 201, 2001] {
        let o = ScanOptions {
            points,
            ..ScanOptions::default()
        };
        let r = scan(&rod, &surface, &o).unwrap();
        check_points(&r, &o);
        let StopReason::LiftOff {
            d,
            limit: Some(why),
        } = &r.stop
        else {
            panic!("{points} points: {}", r.stop);
        };
        assert!(why.contains("extrapolated"), "{why}");
        // rows up to the last grid point before it, the contact on the side
        let last = r.points.last().unwrap();
        assert_eq!(last.contact.to_string(), "side");
        assert!(d - last.d <= o.d_max / (points - 1) as f64);
        assert!(r.mu_max.is_infinite() && r.d_at_mu_max == *d);
        ds.push(*d);
    }
    let spread = ds.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - ds.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(spread < 5e-7, "lift-offs {ds:?}");
}

/// The last seed of tests/contact.proptest-regressions: κ0 = −0.40 + 0.50 s, taper 0.51, η 0.62.
fn seed_scene() -> Scene {
    Scene {
        eta: 0.6203844701008809,
        stiffness: Stiffness::Taper {
            ratio: 0.5148359272362121,
        },
        precurvature: vibrissa::Precurvature::Linear {
            k0: -0.39926453253733313,
            k1: 0.4989796992390289,
        },
        ..Scene::default()
    }
}

#[test]
fn a_dip_before_a_nearly_tangent_tip_is_seen_on_the_rod() {
    // κ0 = −0.40 + 0.50 s, taper 0.51, η 0.62 (a seed of tests/contact.rs): as the tip turns
    // nearly tangent to the line, the rod's slope dips below the line's and back inside one
    // long step of the shooter's integrator, and the cubic through the step's ends hides the
    // maximum there. The shooter saw it 2.4e-5 later in d, when it was 8.8e-7 beyond the line.
    // Collocation (fine meshes there) locates the crossing at d = 0.00111039989, s = 0.99182
    // (both orders and multiple shooting within 3e-13 of each other): the shooter must agree.
    let scene = seed_scene();
    let (rod, surface) = scene.parts().unwrap();
    let at = |method| {
        let o = ScanOptions {
            points: 11,
            contact: ContactModel::Tip,
            solver: SolverConfig {
                method,
                ..SolverConfig::default()
            },
            ..ScanOptions::default()
        };
        match scan(&rod, &surface, &o).unwrap().stop {
            StopReason::Penetration { d, s, .. } => (d, s),
            other => panic!("{method:?}: {other}"),
        }
    };
    let (dc, sc) = at(vibrissa::Method::Collocation6);
    for m in [
        vibrissa::Method::Shooting,
        vibrissa::Method::MultipleShooting,
    ] {
        let (d, s) = at(m);
        assert!(
            (d - dc).abs() < 1e-9 && (s - sc).abs() < 1e-6,
            "{m:?}: d {d} s {s}, collocation d {dc} s {sc}"
        );
    }
}

#[test]
fn a_straight_rod_on_a_free_support_buckles_in_its_first_mode() {
    // Grid 2 of docs/robustness.md: a straight uniform rod on a nearly free support (compliance
    // 20) starts nearly straight (f0 = 0.05). Dragging the foot shortens the chord, so the rod
    // buckles: f rises from 0.05 to near the first Euler load within d ~ 1e-4, a branch so steep
    // that the shooter's first step, predicted along the start's tangent, landed on a higher
    // mode (f = 25π² or 9π², 2–4 flex points) and multiple shooting on yet another. Every
    // method must follow the branch connected to the start: the first mode (no flex point at
    // the first rows, f ≈ 9.3 at d = 0.0025) and the same forces (collocation at the default
    // tolerance is within 1e-6 of the shooters in f and 2e-5 in μ on this nearly straight rod;
    // 4e-10 and 1e-8 at tol 1e-11).
    for beta in [0.0, 0.3] {
        let scene = Scene {
            eta: 0.9,
            support_compliance: 20.0,
            surface_angle: beta,
            ..Scene::default()
        };
        let (rod, surface) = scene.parts().unwrap();
        let run = |method| {
            let o = ScanOptions {
                d_max: 0.05,
                points: 21,
                solver: SolverConfig {
                    method,
                    ..SolverConfig::default()
                },
                ..ScanOptions::default()
            };
            let r = scan(&rod, &surface, &o).unwrap();
            check_points(&r, &o);
            assert_eq!(r.stop, StopReason::DMax, "{method:?}");
            r
        };
        let s = run(vibrissa::Method::Shooting);
        for p in &s.points[1..4] {
            assert_eq!(
                p.flex, 0,
                "beta {beta}: d {} f {} flex {}",
                p.d, p.f, p.flex
            );
            assert!(p.f > 8.0 && p.f < 12.0, "beta {beta}: d {} f {}", p.d, p.f);
        }
        for m in [
            vibrissa::Method::MultipleShooting,
            vibrissa::Method::Collocation6,
        ] {
            let o = run(m);
            for (a, b) in s.points.iter().zip(&o.points) {
                assert!(
                    (a.f - b.f).abs() < 1e-5 * (1.0 + a.f) && (a.mu - b.mu).abs() < 1e-4,
                    "beta {beta}, {m:?} at d {}: f {} against {}, mu {} against {}",
                    a.d,
                    a.f,
                    b.f,
                    a.mu,
                    b.mu
                );
            }
        }
    }
}

#[test]
fn a_side_touching_down_beside_the_stuck_tip_slips_at_once() {
    // The last seed of tests/contact.proptest-regressions. At d = 0.00111 a side touches down
    // 0.008 from the stuck tip. Rolling without slip there, it traps the segment to the tip, and
    // the pair of tangential forces that keeps the segment's chord-minus-length frozen needs
    // |T|/N = 1.7e4 from the moment the side forms (docs/model.md). The scan used to go
    // on into that near-indeterminate state and end where the grid led it: a solver failure at
    // d = 0.001484 (11 and 201 points) or 0.001505 (2001), or a fold at 0.0011170. Now every
    // method and grid ends at the touchdown with the named reason, with or without μ0.
    let scene = seed_scene();
    let (rod, surface) = scene.parts().unwrap();
    let mut d_ref = None;
    for method in [
        vibrissa::Method::Shooting,
        vibrissa::Method::MultipleShooting,
        vibrissa::Method::Collocation4,
        vibrissa::Method::Collocation6,
    ] {
        for points in [11, 2001] {
            for mu0 in [None, Some(0.5)] {
                let r = run_checked(&rod, &surface, method, points, mu0);
                let what = format!("{method:?}, {points} points, mu0 {mu0:?}: {}", r.stop);
                let StopReason::ContactChange { d, message } = &r.stop else {
                    panic!("{what}");
                };
                // the touchdown row, located to the tolerance whatever the method
                let last = r.points.last().unwrap();
                assert_eq!(last.event, Some(Event::Touchdown), "{what}");
                assert_eq!(last.d, *d, "{what}");
                let d0 = *d_ref.get_or_insert(*d);
                assert!((d - d0).abs() <= 1e-9, "{what}: d {d} against {d0}");
                assert!((d - 0.00111040).abs() < 1e-8, "{what}");
                assert_eq!(r.range_end, vibrissa::RangeEnd::Event, "{what}");
                assert!(message.contains("traps a segment"), "{what}");
                let ratio: f64 = message
                    .split("|T|/N = ")
                    .nth(1)
                    .and_then(|t| t.split_whitespace().next())
                    .and_then(|t| t.parse().ok())
                    .unwrap_or_else(|| panic!("{what}: no ratio"));
                assert!(ratio > 1e4 && ratio < 3e4, "{what}: ratio {ratio}");
            }
        }
    }
}

/// Rest curvature 0.3 − 0.2 s on a surface inclined by 0.2 (the third grid of
/// docs/robustness.md).
fn graded_scene(eta: f64, taper: f64) -> Scene {
    Scene {
        eta,
        stiffness: Stiffness::Taper { ratio: taper },
        precurvature: vibrissa::Precurvature::Linear { k0: 0.3, k1: -0.2 },
        surface_angle: 0.2,
        ..Scene::default()
    }
}

#[test]
fn a_rod_trapped_between_two_contacts_that_do_not_slip_ends_at_the_bound_of_dry_friction() {
    // Rest curvature 0.3 − 0.2 s on a surface inclined by 0.2 (a grid over the slope of the rest
    // curvature, docs/robustness.md). (a) The uniform rod is pressed into side+tip; dragged with
    // the tip stuck and the side rolling, the segment between them carries a pair of tangential
    // forces that grows at dT/dd ~ 7e5, and the scan ended in a solver message at d = 0.00173
    // with the side at |T|/N ~ 700. (b) A tapered rod whose tip, beside the side, carries that
    // pair with almost no normal force (|T|/N ~ 1e3 at d = 0.099), ended likewise. Without μ0
    // such a set now ends where a contact's ratio reaches 10 (no dry surface provides more):
    // `contact_change`, located as an event, at the same d as the slip of a scan with μ0 = 10.
    for (taper, which, d_stop) in [(1.0, "side contact", 1.13921e-5), (0.2, "tip", 2.07522e-4)] {
        let scene = graded_scene(if taper == 1.0 { 0.55 } else { 0.85 }, taper);
        let (rod, surface) = scene.parts().unwrap();
        let mut first = None;
        for method in [vibrissa::Method::Shooting, vibrissa::Method::Collocation4] {
            let run = |points, mu0| run_checked(&rod, &surface, method, points, mu0);
            let mut at = None;
            for points in [11, 2001] {
                let r = run(points, None);
                let what = format!("taper {taper}, {method:?}, {points} points: {}", r.stop);
                let StopReason::ContactChange { d, message } = &r.stop else {
                    panic!("{what}");
                };
                assert!(message.contains(&format!("the {which} at s = ")), "{what}");
                assert!(message.contains("reached 10"), "{what}");
                assert_eq!(r.range_end, vibrissa::RangeEnd::Event, "{what}");
                // an event: independent of the output grid
                let d0 = *at.get_or_insert(*d);
                assert!((d - d0).abs() <= 1e-9, "{what}: d {d} against {d0}");
                // the methods agree to their tolerance in this stiff state (the pair's dT/dd
                // is 1e5–1e6)
                let d1 = *first.get_or_insert(*d);
                assert!((d - d1).abs() <= 1e-8, "{what}: d {d} against {d1}");
                assert!((d - d_stop).abs() < 1e-9 + 1e-5 * d_stop, "{what}");
            }
            // the same place as a slip at μ0 = 10, reached by the slip event's own path
            let s = run(201, Some(10.0));
            let StopReason::Slip { d, .. } = s.stop else {
                panic!("taper {taper}, {method:?}, mu0 10: {}", s.stop);
            };
            // (collocation's own ratio: in this stiff state it differs from the shooter's by
            // 2e-6 and 4e-6 relative at d = 1e-5 and 2e-4, so its slip row is held to 1e-5
            // relative; measured 1.8e-7 and 3.3e-7)
            let last = s.points.last().unwrap();
            let tol = match method {
                vibrissa::Method::Shooting => 1e-9,
                _ => 1e-4,
            };
            assert!(
                (last.mu_peak - 10.0).abs() < tol,
                "taper {taper}, {method:?}: mu_peak {} at {}",
                last.mu_peak,
                last.d
            );
            let d0 = at.unwrap();
            assert!(
                (d - d0).abs() <= 1e-9,
                "{method:?}: slip at {d}, contact change at {d0}"
            );
        }
    }
}

#[test]
fn a_side_contact_that_begins_to_lie_along_the_surface_is_named() {
    // The third grid of docs/robustness.md. Where the rod's curvature at a side contact (with
    // another contact beyond it) falls to zero, the rod beyond the side runs along the line: a
    // lying stretch pressed by a distributed force, which the model (point contacts) does not
    // have. Before, the clearance search met the rod lying within 3e-14 of the line next to the
    // contact: a second contact 2e-4 away and a fold in an ill-conditioned state, "locating the
    // fold: Newton did not converge" for the mirror image, or a new contact at s = 0 whose state
    // gave NaN. Now both ends are the named event, the press's mirror images agree, and a scan
    // ends there whatever its grid and method.
    let press = |sign: f64, c: f64| {
        let scene = Scene {
            eta: 0.7,
            stiffness: Stiffness::Taper { ratio: 0.2 },
            precurvature: vibrissa::Precurvature::Linear {
                k0: 0.3 * sign,
                k1: -0.2 * sign,
            },
            surface_angle: 0.2 * sign,
            support_compliance: c,
            ..Scene::default()
        };
        let (rod, surface) = scene.parts().unwrap();
        match scan(&rod, &surface, &ScanOptions::default()) {
            Err(vibrissa::VibrissaError::NoStart { reason }) => reason,
            other => panic!("sign {sign}, c {c}: {other:?}"),
        }
    };
    let depth = |reason: &str| -> f64 {
        assert!(
            reason.contains("begins to lie along the surface"),
            "{reason}"
        );
        assert!(reason.contains("s = 0.896447"), "{reason}");
        reason
            .split("at depth = ")
            .nth(1)
            .and_then(|t| t.split(':').next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("no depth: {reason}"))
    };
    for (c, at) in [(0.0, 0.3049804), (0.5, 0.3567969)] {
        let (a, b) = (depth(&press(1.0, c)), depth(&press(-1.0, c)));
        assert!((a - b).abs() <= 1e-9, "c {c}: mirror images at {a} and {b}");
        assert!((a - at).abs() < 1e-6, "c {c}: depth {a}");
    }
    // a scan: η 0.55, ρ 0.5, the same rest curvature
    let scene = graded_scene(0.55, 0.5);
    let (rod, surface) = scene.parts().unwrap();
    let mut first = None;
    for method in [vibrissa::Method::Shooting, vibrissa::Method::Collocation4] {
        for points in [11, 2001] {
            let r = run_checked(&rod, &surface, method, points, None);
            let what = format!("{method:?}, {points} points: {}", r.stop);
            let StopReason::ContactChange { d, message } = &r.stop else {
                panic!("{what}");
            };
            assert!(
                message.contains("begins to lie along the surface"),
                "{what}"
            );
            let d0 = *first.get_or_insert(*d);
            assert!((d - d0).abs() <= 1e-9, "{what}: d {d} against {d0}");
            assert!((d - 0.01237503).abs() < 1e-8, "{what}");
        }
    }
}

#[test]
fn the_first_maximum_does_not_depend_on_a_step_a_rounding_short_of_a_grid_value() {
    // Found by the grid-independence property test (tests/contact.rs, 150 cases). At 11 points
    // a step ended at d = 0.09999999999999999 and the grid value 0.1 followed it: the branch
    // polynomial through two points 1.4e-17 apart was degenerate, the maximum's location failed
    // ("singular Jacobian"), and μ_max was the next step's |μ|, 9.5e-9 low and 4e-5 late in d.
    let scene = Scene {
        eta: 0.8888009720576433,
        stiffness: Stiffness::Taper {
            ratio: 0.5121607776438095,
        },
        precurvature: vibrissa::Precurvature::Linear {
            k0: -0.1952370553073565,
            k1: 0.0,
        },
        support_compliance: 0.4820804246028914,
        ..Scene::default()
    };
    let (rod, surface) = scene.parts().unwrap();
    let run = |points| {
        let o = ScanOptions {
            points,
            ..ScanOptions::default()
        };
        scan(&rod, &surface, &o).unwrap()
    };
    let f = run(2001);
    for points in [11, 201] {
        let r = run(points);
        assert!(
            (r.mu_max - f.mu_max).abs() <= 1e-9 * f.mu_max,
            "{points} points: mu_max {} against {}",
            r.mu_max,
            f.mu_max
        );
        assert!(
            (r.d_at_mu_max - f.d_at_mu_max).abs() <= 1e-9,
            "{points} points: at d {} against {}",
            r.d_at_mu_max,
            f.d_at_mu_max
        );
    }
}

#[test]
fn a_generic_method_that_cannot_start_a_trapped_rod_hands_it_to_the_own_shooter() {
    // The scene of the trapped-rod test above (grid 3 of docs/robustness.md): pressed, the rod
    // touches at a side 0.06 before the tip; dragged with both holding, the segment between them
    // is nearly indeterminate under a pair of tangential forces. Multiple shooting's conditioning
    // check measures ‖J⁻¹‖ · rtol > 1 at d = 0 and the scan start failed with "singular Jacobian"
    // (12 scenes of grid 3); the scan now runs on the rod's own shooter and says so. Lobatto IIIA
    // of order 4 starts it itself, and agrees.
    let (rod, surface) = graded_scene(0.55, 1.0).parts().unwrap();
    let run = |method| run_checked(&rod, &surface, method, 201, None);
    let own = run(vibrissa::Method::Shooting);
    let ms = run(vibrissa::Method::MultipleShooting);
    let coll = run(vibrissa::Method::Collocation4);
    assert_eq!(own.handover, None);
    assert_eq!(coll.handover, None);
    let why = ms.handover.as_deref().expect("a handover");
    assert!(
        why.contains("multiple-shooting") && why.contains("traps the rod"),
        "{why}"
    );
    let stop_d = |r: &ScanResult| match &r.stop {
        StopReason::ContactChange { d, message } if message.contains("reached 10") => *d,
        s => panic!("{s}"),
    };
    // the own shooter's scan, point for point
    assert_eq!(stop_d(&ms), stop_d(&own));
    assert_eq!(ms.points, own.points);
    assert!((stop_d(&ms) - 1.13921e-5).abs() < 1e-9 + 1e-5 * 1.13921e-5);
    // (collocation, independently: 8.5e-11 apart, measured)
    assert!((stop_d(&coll) - stop_d(&own)).abs() < 1e-9);
    // Lobatto IIIA of order 6 starts it, but its corrections scatter along the pair by 2e-5
    // while it locates the bound (the branch check rejects them): the failed march hands over
    let c6 = run(vibrissa::Method::Collocation6);
    let why = c6.handover.as_deref().expect("a handover");
    assert!(why.contains("collocation6 failed at d = "), "{why}");
    assert_eq!(c6.points, own.points);
}
