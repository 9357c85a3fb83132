//! Every scene class against an independent computation: `data/vibrissa/reference.csv`, made by
//! `data/vibrissa/make_reference.py` (scipy's DOP853 at rtol 1e-13 and Powell's root finder on
//! the same equations, none of this crate's code; its own accuracy ≈ 1e-11 in μ). Compared at the
//! same displacements: μ, f, α and m(0) to 1e-8, for the rod's own shooter and for multiple
//! shooting; and the lift-off case, whose force angle is known exactly (α = β − π/2 where the
//! normal force vanishes): its d, f and m(0) at the located event.

use approx::assert_abs_diff_eq;
use std::collections::BTreeMap;
use vibrissa::{
    scan, scan_at, Event, Method, Precurvature, ScanOptions, Scene, SolverConfig, Stiffness,
    StopReason,
};

struct Row {
    kind: String,
    d: f64,
    mu: f64,
    f: f64,
    alpha: f64,
    m_base: f64,
}

fn table() -> BTreeMap<String, Vec<Row>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/vibrissa/reference.csv"
    );
    let text = std::fs::read_to_string(path).expect("reference table");
    let mut out: BTreeMap<String, Vec<Row>> = BTreeMap::new();
    for line in text.lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let num = |i: usize| -> f64 { c[i].parse().expect("a number") };
        out.entry(c[0].to_string()).or_default().push(Row {
            kind: c[1].to_string(),
            d: num(2),
            mu: num(3),
            f: num(4),
            alpha: num(5),
            m_base: num(6),
        });
    }
    out
}

/// The scenes of the script, by name.
fn scene(name: &str) -> Scene {
    let mut s = Scene::default();
    let lin = |k0: f64, k1: f64| Precurvature::Linear { k0, k1 };
    match name {
        "uniform" => {}
        "taper 0.7" => s.stiffness = Stiffness::Taper { ratio: 0.7 },
        "taper 0.3 eta 0.9" => {
            s.stiffness = Stiffness::Taper { ratio: 0.3 };
            s.eta = 0.9;
        }
        "taper 0.1 eta 0.97" => {
            s.stiffness = Stiffness::Taper { ratio: 0.1 };
            s.eta = 0.97;
        }
        "k0 +1" => s.precurvature = lin(1.0, 0.0),
        "k0 -1" => s.precurvature = lin(-1.0, 0.0),
        "k0 0.5 - s" => s.precurvature = lin(0.5, -1.0),
        "compliance 1" => s.support_compliance = 1.0,
        "surface +0.3" => s.surface_angle = 0.3,
        "surface -0.3" => s.surface_angle = -0.3,
        "lift-off k0 -1 c 0.5 eta 0.8" => {
            s.precurvature = lin(-1.0, 0.0);
            s.support_compliance = 0.5;
            s.eta = 0.8;
        }
        file if file.ends_with(".toml") => {
            let path = format!("{}/../../data/scenes/{file}", env!("CARGO_MANIFEST_DIR"));
            s = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        }
        other => panic!("unknown scene {other}"),
    }
    s
}

/// The reference's model: the paper's tip contact, from the state connected to the straight
/// uniform rod (the script starts there).
fn opts(method: Method, tol: f64, d_max: f64) -> ScanOptions {
    ScanOptions {
        d_max,
        contact: vibrissa::ContactModel::Tip,
        solver: SolverConfig {
            method,
            tol,
            segments: 4,
            start: vibrissa::StartKind::Connected,
            ..SolverConfig::default()
        },
        ..ScanOptions::default()
    }
}

#[test]
fn every_scene_class_matches_the_independent_reference() {
    let t = table();
    let mut scenes = 0;
    for (name, rows) in &t {
        let rows: Vec<&Row> = rows.iter().filter(|r| r.kind == "point").collect();
        if rows.is_empty() {
            continue;
        }
        scenes += 1;
        let (rod, surface) = scene(name).parts().unwrap();
        let ds: Vec<f64> = rows.iter().map(|r| r.d).collect();
        let d_max = ds[ds.len() - 1] + 0.01;
        for (method, tol) in [(Method::Shooting, 1e-12), (Method::MultipleShooting, 1e-11)] {
            let r = scan_at(&rod, &surface, &opts(method, tol, d_max), &ds).unwrap();
            let pts: Vec<_> = r.points.iter().filter(|p| p.event.is_none()).collect();
            assert_eq!(pts.len(), rows.len(), "{name} {method}: {}", r.stop);
            for (p, q) in pts.iter().zip(&rows) {
                let what = format!("{name} {method} d = {}", q.d);
                assert_eq!(p.d, q.d, "{what}");
                assert_abs_diff_eq!(p.mu, q.mu, epsilon = 1e-8);
                assert_abs_diff_eq!(p.alpha, q.alpha, epsilon = 1e-8);
                assert!(
                    (p.f - q.f).abs() <= 1e-8 * q.f.max(1.0),
                    "{what}: f {}",
                    p.f
                );
                assert!(
                    (p.m_base - q.m_base).abs() <= 1e-8 * q.m_base.abs().max(1.0),
                    "{what}: m_base {}",
                    p.m_base
                );
            }
        }
    }
    assert_eq!(scenes, 12, "scene classes in the table");
}

/// The lift-off case: the normal force of the pre-curved, compliantly held rod falls to
/// zero near d ≈ 1.112. Where it does, the force is along the surface, α = β − π/2 exactly, so the
/// reference solves that one rod directly; the scan must stop there (located to solver accuracy)
/// with every grid row pressed.
#[test]
fn lift_off_matches_the_rod_with_the_force_along_the_surface() {
    let t = table();
    let name = "lift-off k0 -1 c 0.5 eta 0.8";
    let q = &t[name][0];
    assert_eq!(q.kind, "lift_off");
    let (rod, surface) = scene(name).parts().unwrap();
    let o = ScanOptions {
        points: 224,
        ..opts(Method::Shooting, 1e-12, 1.115)
    };
    let r = scan(&rod, &surface, &o).unwrap();
    match r.stop {
        StopReason::LiftOff { d, .. } => assert_abs_diff_eq!(d, q.d, epsilon = 1e-9),
        ref other => panic!("expected lift-off, got {other}"),
    }
    let (ev, grid) = r.points.split_last().unwrap();
    assert_eq!(ev.event, Some(Event::LiftOff));
    assert!(grid.iter().all(|p| p.normal > 0.0 && p.fy < 0.0));
    assert_abs_diff_eq!(ev.alpha, q.alpha, epsilon = 1e-9);
    assert_abs_diff_eq!(ev.f, q.f, epsilon = 1e-8);
    assert_abs_diff_eq!(ev.m_base, q.m_base, epsilon = 1e-8);
    assert!(ev.mu.is_infinite() && ev.normal == 0.0);
}
