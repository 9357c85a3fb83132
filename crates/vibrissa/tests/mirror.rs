//! The pressed start does not prefer a side: a rod with rest curvature κ0(s) and its mirror image
//! −κ0(s), pressed straight down onto a horizontal surface, reach mirrored states (x → −x): the
//! same force, opposite base moment, tip slope φ1 → π − φ1, the same contact set. The solver
//! finds each numerically from its own rest shape, so this checks that nothing in the press (its
//! first touch, buckling convention, contact transitions) picks a side for a curved rod.

use std::f64::consts::PI;
use vibrissa::{scan, Precurvature, ScanOptions, Scene, SolverConfig, Stiffness};

/// The start of a scan of `scene` (one tiny step) with the solver `solver`.
fn start_with(scene: &Scene, solver: SolverConfig) -> vibrissa::ScanPoint {
    let (rod, surface) = scene.parts().unwrap();
    let o = ScanOptions {
        d_max: 1e-3,
        points: 2,
        solver,
        ..ScanOptions::default()
    };
    scan(&rod, &surface, &o).unwrap().start
}

fn start(k0: f64, k1: f64, f: impl Fn(&mut Scene)) -> vibrissa::ScanPoint {
    let mut s = Scene {
        precurvature: Precurvature::Linear { k0, k1 },
        ..Scene::default()
    };
    f(&mut s);
    // the two presses are separate discretizations (their meshes adapt to rounding that is
    // not mirrored): at tol 1e-12 their difference is below the 1e-12 asked for
    start_with(
        &s,
        SolverConfig {
            tol: 1e-12,
            ..SolverConfig::default()
        },
    )
}

#[test]
fn mirrored_rest_curvature_gives_mirrored_starts() {
    type Edit = fn(&mut Scene);
    let cases: [(f64, f64, Edit); 6] = [
        (1.0, 0.0, |_| {}),
        (0.5, 0.0, |s| s.eta = 0.8),
        (1.0, 0.0, |s| s.eta = 0.6),
        (-0.4, 1.2, |_| {}),
        (0.8, 0.0, |s| s.stiffness = Stiffness::Taper { ratio: 0.2 }),
        (0.6, -0.3, |s| {
            s.support_compliance = 0.5;
            s.eta = 0.7
        }),
    ];
    for (k0, k1, edit) in cases {
        let a = start(k0, k1, edit);
        let b = start(-k0, -k1, edit);
        let what = format!("k0 {k0} k1 {k1}: {a:?} / {b:?}");
        let tol = 1e-12 * a.f.max(1.0);
        assert!((a.f - b.f).abs() < tol, "f {what}");
        assert!((a.fx + b.fx).abs() < tol, "fx {what}");
        assert!((a.fy - b.fy).abs() < tol, "fy {what}");
        assert!((a.m_base + b.m_base).abs() < 1e-12, "m_base {what}");
        // (slopes are compared modulo a full turn)
        let e = (a.phi1 + b.phi1 - PI).rem_euclid(2.0 * PI);
        assert!(e.min(2.0 * PI - e) < 1e-12, "phi1 {what}");
        assert_eq!(a.contact, b.contact, "{what}");
        match (a.s_c, b.s_c) {
            (None, None) => {}
            (Some(x), Some(y)) => assert!((x - y).abs() < 1e-12, "s_c {what}"),
            _ => panic!("s_c {what}"),
        }
        // a curved rod is not pressed straight: the test would be empty otherwise
        assert!(a.m_base.abs() > 1e-3, "{what}");
    }
}

/// A straight rod pressed onto a slightly inclined line passes close by its buckling point (an
/// imperfect bifurcation). The press's first step from its tiny first load used to land on the
/// third clamped-free mode for β = 0.025…0.03 (f0 ≈ 70 instead of 2.75, exit 0). Now the start
/// equals the state connected to the pressed straight rod (found by another path: the force
/// turned from the horizontal line) for every β tried, and is mirrored by −β.
#[test]
fn slightly_inclined_lines_press_the_straight_rod_onto_its_first_mode() {
    let start_of = |beta: f64, kind: vibrissa::StartKind| {
        let s = Scene {
            surface_angle: beta,
            ..Scene::default()
        };
        start_with(
            &s,
            SolverConfig {
                start: kind,
                ..SolverConfig::default()
            },
        )
    };
    for beta in [0.01, 0.02, 0.025, 0.03, 0.035, 0.06] {
        let p = start_of(beta, vibrissa::StartKind::Pressed);
        let c = start_of(beta, vibrissa::StartKind::Connected);
        assert!(
            (p.f - c.f).abs() < 1e-8 * c.f,
            "beta {beta}: pressed f0 {} / connected {}",
            p.f,
            c.f
        );
        assert!(p.f < 3.0, "beta {beta}: f0 {}", p.f);
        // (the connected state of −β bends right against the line's push: the mirror instead)
        let m = start_of(-beta, vibrissa::StartKind::Pressed);
        assert!(
            (m.f - p.f).abs() < 1e-8 * p.f,
            "beta -{beta}: f0 {} / {}",
            m.f,
            p.f
        );
    }
}
