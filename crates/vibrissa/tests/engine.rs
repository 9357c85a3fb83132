//! The one rod engine on every scene class: the rod's own shooter (single shooting) against an
//! independent computation — crate `bvp`'s generic multiple shooting (adaptive DOP853 on 4
//! segments, its own Newton and Lagrange predictor) at tolerance 1e-12 — and the contact events.

use approx::assert_abs_diff_eq;
use vibrissa::{
    infer, scan, solve, BranchChoice, Event, Method, Precurvature, ScanOptions, ScanResult, Scene,
    SolverConfig, StartKind, Stiffness, StopReason, Target,
};

fn scene(f: impl Fn(&mut Scene)) -> Scene {
    let mut s = Scene::default();
    f(&mut s);
    s
}

fn run(s: &Scene, o: &ScanOptions) -> ScanResult {
    let (rod, surface) = s.parts().unwrap();
    scan(&rod, &surface, o).unwrap()
}

fn with_method(o: &ScanOptions, method: Method, tol: f64) -> ScanOptions {
    ScanOptions {
        solver: SolverConfig {
            method,
            tol,
            segments: 4,
            ..o.solver.clone()
        },
        ..o.clone()
    }
}

/// μ at every common grid point to 1e-8, μ_max to 1e-9, the same stop.
fn agrees_with_reference(name: &str, s: &Scene, o: &ScanOptions) {
    let own = run(s, &with_method(o, Method::Shooting, 1e-12));
    let reference = run(s, &with_method(o, Method::MultipleShooting, 1e-12));
    assert_eq!(
        std::mem::discriminant(&own.stop),
        std::mem::discriminant(&reference.stop),
        "{name}: {} vs {}",
        own.stop,
        reference.stop
    );
    let (a, b): (Vec<_>, Vec<_>) = (
        own.points.iter().filter(|p| p.event.is_none()).collect(),
        reference
            .points
            .iter()
            .filter(|p| p.event.is_none())
            .collect(),
    );
    assert_eq!(
        a.len(),
        b.len(),
        "{name}: {} vs {}",
        own.stop,
        reference.stop
    );
    assert!(
        a.len() >= 3,
        "{name}: only {} points ({})",
        a.len(),
        own.stop
    );
    for (p, q) in a.iter().zip(&b) {
        assert_eq!(p.d, q.d);
        assert_abs_diff_eq!(p.mu, q.mu, epsilon = 1e-8);
        assert_eq!(p.flex, q.flex, "{name} d {}", p.d);
    }
    if own.mu_max.is_finite() {
        assert_abs_diff_eq!(own.mu_max, reference.mu_max, epsilon = 1e-9);
    } else {
        assert!(reference.mu_max.is_infinite(), "{name}");
    }
    assert_eq!(own.range_end, reference.range_end, "{name}");
}

/// The cross-check from the state connected to the straight rod (where these scenes were first
/// compared; pressed, some of them lift off at once).
fn coarse(d_max: f64) -> ScanOptions {
    ScanOptions {
        points: 11,
        d_max,
        solver: connected(),
        ..ScanOptions::default()
    }
}

fn connected() -> SolverConfig {
    SolverConfig {
        start: StartKind::Connected,
        ..SolverConfig::default()
    }
}

#[test]
fn every_scene_class_agrees_with_generic_multiple_shooting() {
    let linear = |k0: f64, k1: f64| Precurvature::Linear { k0, k1 };
    let cases: Vec<(&str, Scene, f64)> = vec![
        ("uniform", Scene::default(), 0.5),
        (
            "taper 0.7",
            scene(|s| s.stiffness = Stiffness::Taper { ratio: 0.7 }),
            0.5,
        ),
        (
            "taper 0.3, eta 0.9",
            scene(|s| {
                s.stiffness = Stiffness::Taper { ratio: 0.3 };
                s.eta = 0.9
            }),
            0.5,
        ),
        (
            "taper 0.1, eta 0.97",
            scene(|s| {
                s.stiffness = Stiffness::Taper { ratio: 0.1 };
                s.eta = 0.97
            }),
            0.05,
        ),
        ("k0 = 1", scene(|s| s.precurvature = linear(1.0, 0.0)), 0.5),
        (
            "k0 = -1",
            scene(|s| s.precurvature = linear(-1.0, 0.0)),
            0.5,
        ),
        (
            "k0 = 0.5 - s",
            scene(|s| s.precurvature = linear(0.5, -1.0)),
            0.5,
        ),
        ("compliance 1", scene(|s| s.support_compliance = 1.0), 0.5),
        ("surface 0.3", scene(|s| s.surface_angle = 0.3), 0.5),
        ("surface -0.3", scene(|s| s.surface_angle = -0.3), 0.5),
    ];
    for (name, s, d_max) in cases {
        agrees_with_reference(name, &s, &coarse(d_max));
    }
}

#[test]
fn rat_presets_agree_with_generic_multiple_shooting() {
    for f in ["rat_mystacial_long.toml", "rat_mystacial_short.toml"] {
        let path = format!("{}/../../data/scenes/{f}", env!("CARGO_MANIFEST_DIR"));
        let s: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        agrees_with_reference(f, &s, &coarse(0.04));
    }
}

/// The rat presets' scans do the work their rods ask for, counted (docs/performance.md, "The rat
/// presets under 3×"): a point whose prediction needed a second chord step gets its exact
/// tangent, so the next prediction needs one step (without it the long preset's predictions
/// stayed 8e-6 off: 293 Newton iterations for its 120 rows, 2.4 a row); and the unloaded rest
/// beyond the side is laid out on its span (it had the first segment's count, 22 steps over
/// 0.05 of arc length). Before both: long 164 301 right-hand sides (1 369 a row), short 183 028
/// for 183 rows (1 000). Measured now: long 223 iterations and 118 342 right-hand sides for 120
/// rows (1.9 and 986 a row), short 291 and 142 027 for 183 (1.6, 776).
#[test]
fn the_rat_presets_scan_in_about_one_chord_step_a_point() {
    for f in ["rat_mystacial_long.toml", "rat_mystacial_short.toml"] {
        let path = format!("{}/../../data/scenes/{f}", env!("CARGO_MANIFEST_DIR"));
        let s: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let r = run(&s, &ScanOptions::default());
        assert!(
            matches!(r.stop, StopReason::FoldInD { .. }),
            "{f}: {}",
            r.stop
        );
        let rows = r.points.len() as f64;
        let (its, rhs) = (r.stats.newton_iters as f64, r.stats.rhs_evals as f64);
        assert!(
            its <= 2.0 * rows,
            "{f}: {its} Newton iterations for {rows} rows"
        );
        assert!(
            rhs <= 1100.0 * rows,
            "{f}: {rhs} right-hand sides for {rows} rows"
        );
    }
}

/// Issue case: a pre-curved, compliantly held rod whose normal force goes through zero near
/// d ≈ 1.112. The scan stops there with lift-off; every grid row is pressed (N > 0, fy < 0 on the
/// flat surface); at lift-off the force is along the surface, α = β − π/2 exactly (N = f cos(α − β)),
/// and the generic method finds the same d.
#[test]
fn lift_off_is_located() {
    let s = scene(|s| {
        s.eta = 0.8;
        s.precurvature = Precurvature::Linear { k0: -1.0, k1: 0.0 };
        s.support_compliance = 0.5
    });
    let o = ScanOptions {
        d_max: 1.115,
        points: 224,
        ..ScanOptions::default()
    };
    let r = run(&s, &o);
    let d_lift = match r.stop {
        StopReason::LiftOff { d, .. } => d,
        ref other => panic!("expected lift-off, got {other}"),
    };
    assert!(d_lift < 1.115);
    let (event, grid) = r.points.split_last().unwrap();
    assert_eq!(event.event, Some(Event::LiftOff));
    assert!(grid.iter().all(|p| p.normal > 0.0 && p.fy < 0.0));
    assert_abs_diff_eq!(
        event.alpha,
        s.surface_angle - std::f64::consts::FRAC_PI_2,
        epsilon = 1e-9
    );
    // the measurable range ends at the first maximum of |μ| (≈ 0.665 near d ≈ 0.04), not at the
    // unbounded μ of the lift-off
    assert_eq!(r.range_end, vibrissa::RangeEnd::FirstMaximum);
    assert!(
        r.mu_max < 1.0 && r.d_at_mu_max < 0.1,
        "{} at {}",
        r.mu_max,
        r.d_at_mu_max
    );
    let reference = run(
        &s,
        &with_method(
            &ScanOptions {
                points: 12,
                ..o.clone()
            },
            Method::MultipleShooting,
            1e-12,
        ),
    );
    match reference.stop {
        StopReason::LiftOff { d, .. } => assert_abs_diff_eq!(d, d_lift, epsilon = 1e-7),
        ref other => panic!("reference: {other}"),
    }
    // slipping for μ0 = 5 happens before the lift-off, not at it
    let slip = run(
        &s,
        &ScanOptions {
            mu0: Some(5.0),
            ..o.clone()
        },
    );
    match slip.stop {
        StopReason::Slip { d, mu } => {
            assert!(d < d_lift && d > 1.0, "{d}");
            assert_abs_diff_eq!(mu.abs(), 5.0, epsilon = 1e-9);
        }
        ref other => panic!("{other}"),
    }
}

/// Issue case: on the surface inclined by −0.3 the friction ratio turns negative and passes −0.5
/// between d = 0.875 and 0.9: a slip forwards.
#[test]
fn slip_in_either_direction() {
    let s = scene(|s| s.surface_angle = -0.3);
    let o = ScanOptions {
        d_max: 1.5,
        points: 61,
        mu0: Some(0.5),
        solver: connected(),
        ..ScanOptions::default()
    };
    let r = run(&s, &o);
    match r.stop {
        StopReason::Slip { d, mu } => {
            assert!(d > 0.875 && d < 0.9, "{d}");
            assert_abs_diff_eq!(mu, -0.5, epsilon = 1e-9);
        }
        ref other => panic!("{other}"),
    }
    let last = r.points.last().unwrap();
    assert_eq!(last.event, Some(Event::Slip));
    assert_abs_diff_eq!(last.mu, -0.5, epsilon = 1e-9);
    assert!(r.points.iter().all(|p| p.mu.abs() <= 0.5 + 1e-9));
}

/// The slip point is the last row, also on a coarse grid where no grid point lies past d = 0,
/// and a scan stopped by slip costs about what the full scan spends on the same stretch.
#[test]
fn slip_row_and_cost() {
    let s = Scene::default();
    let o = ScanOptions {
        mu0: Some(0.5),
        points: 11,
        ..ScanOptions::default()
    };
    let r = run(&s, &o);
    assert_eq!(r.points.len(), 2, "{:?}", r.points);
    let ev = &r.points[1];
    assert_eq!(ev.event, Some(Event::Slip));
    assert_abs_diff_eq!(ev.mu, 0.5, epsilon = 1e-10);
    let d_slip = ev.d;
    // the full scan up to the slip, same grid spacing
    let part = run(
        &s,
        &ScanOptions {
            mu0: None,
            d_max: d_slip,
            points: 2,
            ..ScanOptions::default()
        },
    );
    assert!(
        r.stats.rhs_evals <= 2 * part.stats.rhs_evals,
        "slip scan {} rhs evaluations, the same stretch {}",
        r.stats.rhs_evals,
        part.stats.rhs_evals
    );
}

/// Rods with a rest curvature bending against the load have moment and curvature signs that
/// differ: the branch is told by the moment (load reversals), so both branches solve and scan.
#[test]
fn precurved_rods_solve_on_both_branches() {
    for k0 in [0.1, 0.3, 0.5, -0.3, 1.0] {
        let s = scene(|s| s.precurvature = Precurvature::Linear { k0, k1: 0.0 });
        let m = s.rod().unwrap();
        // the state connected to the straight rod's branches (pressed, these rods bend their
        // own way)
        let cfg = SolverConfig {
            start: StartKind::Connected,
            ..SolverConfig::default()
        };
        let c = solve(&m, -0.2, Target::Eta(0.75), &BranchChoice::Convex, &cfg).unwrap();
        assert_eq!(c.load_reversals, 0, "k0 {k0}");
        let f = solve(&m, -0.3, Target::Phi1(0.2), &BranchChoice::Flex, &cfg).unwrap();
        assert_eq!(f.load_reversals, 1, "k0 {k0}");
        let any = solve(&m, -0.2, Target::Eta(0.75), &BranchChoice::Any, &cfg).unwrap();
        assert_abs_diff_eq!(any.f, c.f, epsilon = 1e-9 * c.f);
        let r = run(
            &s,
            &ScanOptions {
                solver: cfg.clone(),
                ..ScanOptions::default()
            },
        );
        assert!(r.points.len() > 10, "k0 {k0}: {}", r.stop);
    }
}

/// A rod leaning left (κ0 > 0) pressed straight down bends further left: its tip slope never
/// falls to a small φ1. The default solve then answers with the state connected to the uniform
/// rod, the same as asking for that start (python/tests found this scene failing).
#[test]
fn slope_goal_out_of_the_press_falls_back_to_the_connected_state() {
    let s = scene(|s| {
        s.stiffness = Stiffness::Taper { ratio: 0.5 };
        s.precurvature = Precurvature::Linear { k0: 0.3, k1: 0.0 };
    });
    let m = s.rod().unwrap();
    let conn = SolverConfig {
        start: StartKind::Connected,
        ..SolverConfig::default()
    };
    let t = Target::Phi1(0.3);
    let a = solve(&m, -0.3, t, &BranchChoice::Convex, &SolverConfig::default()).unwrap();
    let b = solve(&m, -0.3, t, &BranchChoice::Convex, &conn).unwrap();
    assert_abs_diff_eq!(a.phi1, 0.3, epsilon = 1e-9);
    assert_abs_diff_eq!(a.f, b.f, epsilon = 1e-9 * b.f);
    assert_abs_diff_eq!(a.m_base, b.m_base, epsilon = 1e-9);
}

/// μ_max against the closed form (mpmath-checked crate `elastica`), on coarse and fine grids
/// (on coarse grids the maximum lies far from the grid points and is located by solves).
#[test]
fn mu_max_located_on_coarse_grids() {
    let cf = elastica::ClosedFormScan::new(0.75)
        .unwrap()
        .mu_max()
        .unwrap();
    let (rod, surface) = Scene::default().parts().unwrap();
    for points in [6, 11, 201] {
        let o = ScanOptions {
            points,
            ..ScanOptions::default()
        };
        let r = scan(&rod, &surface, &o).unwrap();
        assert_abs_diff_eq!(r.mu_max, cf.mu, epsilon = 1e-9);
        // μ is flat at its maximum: d is determined to ~sqrt(tol)
        assert_abs_diff_eq!(r.d_at_mu_max, cf.d, epsilon = 1e-6);
        assert_eq!(r.range_end, vibrissa::RangeEnd::FirstMaximum);
    }
}

/// A force turned beyond what the pressed rod can hold: the family of states connected to the
/// press folds (at α ≈ −0.269 for η = 0.95) and keeps winding short of the target; the error
/// says so and where, instead of "no member reached in 2000 steps".
#[test]
fn force_turned_past_the_fold_names_it() {
    let m = Scene::default().rod().unwrap();
    let e = solve(
        &m,
        -1.2,
        Target::Eta(0.95),
        &BranchChoice::Convex,
        &SolverConfig::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("turns back (a fold) at alpha = -0.26"), "{e}");
}

/// The documented tolerance range holds at its tight end: the press, its buckled start and the
/// scan converge at tol 1e-15 (Newton's own tolerance is kept above the rounding of its
/// residuals) and μ_max agrees with the closed form.
#[test]
fn tightest_documented_tolerances_scan() {
    let cf = elastica::ClosedFormScan::new(0.75)
        .unwrap()
        .mu_max()
        .unwrap();
    let (rod, surface) = Scene::default().parts().unwrap();
    for tol in [1e-15, 5e-15, 1e-14] {
        let o = ScanOptions {
            points: 6,
            solver: SolverConfig {
                tol,
                ..SolverConfig::default()
            },
            ..ScanOptions::default()
        };
        let r = scan(&rod, &surface, &o).unwrap();
        assert_eq!(r.stop, StopReason::DMax, "tol {tol}");
        assert_abs_diff_eq!(r.mu_max, cf.mu, epsilon = 1e-10);
    }
}

/// `infer` on the measurable range: inside it, μ0 = μ(d0); outside, errors that name the range.
#[test]
fn infer_names_the_measurable_range() {
    let (rod, surface) = Scene::default().parts().unwrap();
    let o = ScanOptions::default();
    let cf = elastica::ClosedFormScan::new(0.75)
        .unwrap()
        .mu_max()
        .unwrap();
    let inf = infer(&rod, &surface, 0.1, &o).unwrap();
    assert_abs_diff_eq!(inf.measurable_d.1, cf.d, epsilon = 1e-6);
    assert!(inf.mu0 > 0.7 && inf.mu0 < cf.mu);
    let e = infer(&rod, &surface, 0.2, &o).unwrap_err().to_string();
    assert!(e.contains("0.13") && e.contains("first maximum"), "{e}");
    let e = infer(
        &rod,
        &surface,
        0.04,
        &ScanOptions {
            d_max: 0.05,
            ..o.clone()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("cuts the measurable range short"), "{e}");
}

/// Loose tolerances buy time, never a scan cut short: the correctors iterate Newton to at most
/// 1e-9 whatever the integration tolerance. Before, at tol 1e-3 the paper scan stopped at
/// d = 0.16 (single shooting, steps of 1e-7 and "corrections" of 4) and at 0.11 (multiple
/// shooting, singular Jacobian), and at 1e-2 the rat presets' starts did not converge.
#[test]
fn loose_tolerances_scan_the_whole_range() {
    let paper = Scene::default();
    let o = ScanOptions {
        points: 101,
        ..ScanOptions::default()
    };
    let tight = run(&paper, &o);
    for method in [Method::Shooting, Method::MultipleShooting] {
        for tol in [1e-2, 1e-3] {
            let r = run(&paper, &with_method(&o, method, tol));
            assert!(
                matches!(r.stop, StopReason::DMax),
                "{method:?} tol {tol:e}: {}",
                r.stop
            );
            assert_eq!(r.points.len(), tight.points.len());
            for (a, b) in r.points.iter().zip(&tight.points) {
                assert_eq!(a.d, b.d);
                assert!(
                    (a.mu - b.mu).abs() <= tol,
                    "{method:?} tol {tol:e} at d = {}: mu {} vs {}",
                    a.d,
                    a.mu,
                    b.mu
                );
            }
        }
    }
    for f in ["rat_mystacial_long.toml", "rat_mystacial_short.toml"] {
        let path = format!("{}/../../data/scenes/{f}", env!("CARGO_MANIFEST_DIR"));
        let s: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let r = run(&s, &with_method(&o, Method::Shooting, 1e-2));
        let t = run(&s, &o);
        // the tip touches down and the side lies on the surface; both end at the same event
        assert_eq!(
            std::mem::discriminant(&r.stop),
            std::mem::discriminant(&t.stop),
            "{f}: {} vs {}",
            r.stop,
            t.stop
        );
        assert!(
            r.points.iter().any(|p| p.event == Some(Event::Touchdown)),
            "{f}"
        );
    }
}

/// On a steep surface (β = −0.7) the rod pressed onto it leans down the slope and lies on it
/// with its side, the tip pointing back along the line; the scan starts there (before, the
/// start was the uniform rod's convex shape, which cannot put its tip at η = 0.75 there) and
/// ends at a named event.
#[test]
fn steep_surface_starts_lying_on_it() {
    let steep = scene(|s| s.surface_angle = -0.7);
    let r = run(&steep, &ScanOptions::default());
    assert_eq!(r.start.contact.name(), "side", "{}", r.stop);
    assert!(r.start.s_c.is_some_and(|s| s > 0.5 && s < 1.0));
    assert!(
        matches!(
            r.stop,
            StopReason::DMax | StopReason::LiftOff { .. } | StopReason::FoldInD { .. }
        ),
        "{}",
        r.stop
    );
}
