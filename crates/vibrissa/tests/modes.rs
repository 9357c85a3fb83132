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
    let (rod, surface) = Scene {
        eta: 0.95,
        ..Scene::default()
    }
    .parts()
    .unwrap();
    let o = ScanOptions {
        d_max: 0.6,
        points: 13,
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
        let w2 = m.modes[0].omega2;
        assert!(m.stable && w2 > 0.0, "d = {}: {m}", p.d);
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
    let (rod, surface) = Scene {
        eta: 0.95,
        stiffness: Stiffness::Taper { ratio: 0.5 },
        ..Scene::default()
    }
    .parts()
    .unwrap();
    let o = ScanOptions {
        d_max: 1.0,
        points: 11,
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

/// The rod tapered to ρ = 0.1 at η = 0.97: its pressed start is the S-shaped state (two flex
/// points, f = 0.796; at ρ = 0.15 the start has none and f = 0.176), which is unstable, and the
/// march follows it to its fold. ω₁² < 0 on every row, rising to `|ω₁²| ≤ 1e-6` at the located
/// fold (measured −3620.5 at d = 0, −594.5 at d = 0.125, 1.3e-9 at the fold d = 0.18439). The
/// sweep of `det D(λ)` starts at λ = −8e6 for this rod (its thin tip's `b/μ` = 1e6 under a
/// compressive force), where a single shot's columns grow by `e^24`: before the columns were
/// orthonormalized along the rod (modes.rs `Linear::det`) the sweep found rounding's sign
/// changes there: ω₁² = −7.95e6, −5.65e6 and −3.79e6 at the same three rows.
#[test]
fn first_frequency_of_a_thin_tipped_rod_rises_to_zero_at_its_fold() {
    let (rod, surface) = Scene {
        eta: 0.97,
        stiffness: Stiffness::Taper { ratio: 0.1 },
        ..Scene::default()
    }
    .parts()
    .unwrap();
    let o = ScanOptions {
        d_max: 0.5,
        points: 5,
        ..ScanOptions::default()
    };
    let r = scan(&rod, &surface, &o).unwrap();
    assert!(matches!(r.stop, StopReason::FoldInD { .. }), "{}", r.stop);
    let mo = ModeOptions {
        count: 1,
        ..ModeOptions::default()
    };
    let w2: Vec<f64> = r
        .points
        .iter()
        .map(|p| modes_of_point(&rod, &surface, p, &mo).unwrap().modes[0].omega2)
        .collect();
    eprintln!("omega1^2 along the scan: {w2:?}");
    let (last, rows) = w2.split_last().unwrap();
    assert!(rows.iter().all(|&w| w < 0.0), "{w2:?}");
    assert!(rows.windows(2).all(|w| w[1] > w[0]), "{w2:?}");
    assert!(rows[0] > -1e4, "{w2:?}");
    assert!(last.abs() <= 1e-6, "{w2:?}");
}
