//! Natural frequencies and stability of static states (issue 32): the tapered rod against the
//! independent reference of `data/vibrissa/make_modes_reference.py`, and `ω₁²` along a scan that
//! ends in a fold (snap-through).

use vibrissa::modes::{modes, modes_of_point, BaseLoad, ModeOptions, TipCondition};
use vibrissa::{scan, Rod, ScanOptions, Scene, Stiffness, StopReason};

/// The conical rod (taper 0.7 and 0.3, and the uniform rod), free and pinned tip, three modes
/// each: the reference solves the displacement form `(EI w'')'' = ω² ρA w` by Taylor series in
/// 30–40 digits (`data/vibrissa/modes_reference.csv`). Measured agreement: below 1e-12 relative.
#[test]
fn tapered_rod_against_reference() {
    let text = include_str!("../../../data/vibrissa/modes_reference.csv");
    let (mut rows, mut worst) = (0, 0.0f64);
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let taper: f64 = f[0].parse().unwrap();
        let tip = match f[1] {
            "free" => TipCondition::Free,
            _ => TipCondition::Pinned,
        };
        let n: usize = f[2].parse().unwrap();
        let want: f64 = f[3].parse().unwrap();
        let rod = if taper == 1.0 {
            Rod::uniform()
        } else {
            Rod::builder().taper(taper).build().unwrap()
        };
        let o = ModeOptions {
            count: n,
            ..ModeOptions::default()
        };
        let r = modes(&rod, &BaseLoad::default(), tip, &o).unwrap();
        let got = r.modes[n - 1].omega;
        let e = (got / want - 1.0).abs();
        assert!(e < 1e-10, "{line}: {got}, relative error {e:e}");
        rows += 1;
        worst = worst.max(e);
    }
    assert_eq!(rows, 18);
    eprintln!("largest relative error {worst:e}");
}

/// The paper's rod at η = 0.95 pushed until `d` folds (snap-through, the scan's `fold_in_d`):
/// with the tip stuck, `ω₁² > 0` on every row the march calls stable (measured: 1846 at d = 0,
/// 1870 at d = 0.05, then falling to 521 at d = 0.5), and `|ω₁²| ≤ 1e-6` at the located fold
/// (measured −4.8e-8 at d = 0.53604).
#[test]
fn first_frequency_vanishes_at_the_fold() {
    let scene = Scene {
        eta: 0.95,
        ..Scene::default()
    };
    assert_first_frequency_vanishes_at_the_fold(scene, 0.6, 13);
}

/// `scene` scanned to its fold in d (`points` grid points on [0, `d_max`]): with the tip stuck,
/// every row stable with `ω₁² > 0` and `|ω₁²| ≤ 1e-6` at the located fold.
fn assert_first_frequency_vanishes_at_the_fold(scene: Scene, d_max: f64, points: usize) {
    let (rod, surface) = scene.parts().unwrap();
    let o = ScanOptions {
        d_max,
        points,
        ..ScanOptions::default()
    };
    let r = scan(&rod, &surface, &o).unwrap();
    assert!(matches!(r.stop, StopReason::FoldInD { .. }), "{}", r.stop);
    let mo = ModeOptions {
        count: 1,
        ..ModeOptions::default()
    };
    let (last, rows) = r.points.split_last().unwrap();
    for p in rows {
        let m = modes_of_point(&rod, &surface, p, &mo).unwrap();
        eprintln!("d = {}: {m}", p.d);
        assert!(m.stable && m.modes[0].omega2 > 0.0, "d = {}: {m}", p.d);
    }
    let m = modes_of_point(&rod, &surface, last, &mo).unwrap();
    eprintln!("fold at d = {}: {m}", last.d);
    assert!(
        m.modes[0].omega2.abs() <= 1e-6,
        "at the fold d = {}: {m}",
        last.d
    );
}

/// A tapered rod (ratio 0.5) at η = 0.95 pushed until `d` folds: the same as the paper's rod,
/// `ω₁² > 0` on every row and `|ω₁²| ≤ 1e-6` at the located fold (measured −1.5e-8 at
/// d = 0.47242).
#[test]
fn first_frequency_vanishes_at_the_fold_of_a_tapered_rod() {
    let scene = Scene {
        eta: 0.95,
        stiffness: Stiffness::Taper { ratio: 0.5 },
        ..Scene::default()
    };
    assert_first_frequency_vanishes_at_the_fold(scene, 1.0, 11);
}

/// The rod tapered to ρ = 0.1 at η = 0.97 (its thin tip's `b/μ` = 1e6): `ω₁² > 0` on every row
/// and `|ω₁²| ≤ 1e-6` at the located fold (measured 194.14 at d = 0, 115.01 at d = 0.125,
/// 1.3e-10 at the fold d = 0.20824). Under its contact force the sweep of `det D(λ)` starts at
/// λ ≈ −1e6, where a single shot's columns grow by `e^14`; they are orthonormalized along the
/// rod there (modes.rs `Linear::det`). With a single shot the fold's row read ω₁² = −3.8e6, a
/// root of rounding.
#[test]
fn first_frequency_of_a_thin_tipped_rod_vanishes_at_its_fold() {
    let scene = Scene {
        eta: 0.97,
        stiffness: Stiffness::Taper { ratio: 0.1 },
        ..Scene::default()
    };
    assert_first_frequency_vanishes_at_the_fold(scene, 1.0, 9);
}

/// A straight rod whose tip is far more flexible than its foot, pressed onto a surface, starts
/// on its first buckling mode: no flex point, and stable (`ω₁² > 0` with the tip stuck). The
/// press brackets the buckling load by checks at f = 0.5, 0.75, 1.125, …, which stepped over the
/// first two loads of the rods tapered to 0.1 and 0.05 (start.rs `first_buckling_below`): they
/// started on their third and fifth modes (two and four flex points; at η 0.97 f = 0.796 and
/// 0.663, ω₁² = −3620.5 for ρ = 0.1). Measured now at η 0.97: f = 0.08980 and 0.02827,
/// ω₁² = 194.14 and 128.28; ρ = 0.12 at η 0.95 (two flex points before) f = 0.12959, ω₁² = 224.51.
#[test]
fn a_thin_tipped_rod_is_pressed_into_its_first_mode() {
    for (ratio, eta) in [(0.1, 0.97), (0.05, 0.97), (0.12, 0.95)] {
        let (rod, surface) = Scene {
            eta,
            stiffness: Stiffness::Taper { ratio },
            ..Scene::default()
        }
        .parts()
        .unwrap();
        let o = ScanOptions {
            d_max: 0.01,
            points: 2,
            ..ScanOptions::default()
        };
        let r = scan(&rod, &surface, &o).unwrap();
        let p = &r.points[0];
        let m = modes_of_point(
            &rod,
            &surface,
            p,
            &ModeOptions {
                count: 1,
                ..ModeOptions::default()
            },
        )
        .unwrap();
        eprintln!("taper {ratio}, eta {eta}: f {}, flex {}, {m}", p.f, p.flex);
        assert_eq!(p.flex, 0, "taper {ratio}, eta {eta}");
        assert!(m.modes[0].omega2 > 0.0, "taper {ratio}, eta {eta}: {m}");
    }
}
