//! Tapered, pre-curved and compliant rods: the methods agree to their tolerances, the homotopy
//! start lands on the requested branch, and the uniform rod satisfies the first integral.

use vibrissa::{solve, BranchChoice, Method, Precurvature, Scene, SolverConfig, Stiffness, Target};

fn cfg(method: Method, tol: f64) -> SolverConfig {
    SolverConfig {
        method,
        tol,
        ..SolverConfig::default()
    }
}

fn scenes() -> Vec<Scene> {
    vec![
        Scene {
            stiffness: Stiffness::Taper { ratio: 0.3 },
            ..Scene::default()
        },
        Scene {
            precurvature: Precurvature::Linear { k0: -0.5, k1: 0.3 },
            ..Scene::default()
        },
        Scene {
            stiffness: Stiffness::Taper { ratio: 0.5 },
            precurvature: Precurvature::Linear { k0: -0.4, k1: 0.0 },
            support_compliance: 0.2,
            ..Scene::default()
        },
    ]
}

#[test]
fn methods_agree_on_tapered_and_precurved_rods() {
    for scene in scenes() {
        let rod = scene.rod().unwrap();
        let reference = solve(
            &rod,
            -0.3,
            Target::Eta(0.75),
            &BranchChoice::Convex,
            &cfg(Method::Shooting, 1e-11),
        )
        .unwrap();
        for (method, tol, err) in [
            (Method::MultipleShooting, 1e-11, 1e-8),
            (Method::Collocation6, 1e-8, 1e-6),
            (Method::Collocation4, 1e-6, 1e-4),
        ] {
            let s = solve(
                &rod,
                -0.3,
                Target::Eta(0.75),
                &BranchChoice::Convex,
                &cfg(method, tol),
            )
            .unwrap_or_else(|e| panic!("{method} on {scene:?}: {e}"));
            for (a, b, what) in [
                (s.f, reference.f, "f"),
                (s.phi1, reference.phi1, "phi1"),
                (s.x1, reference.x1, "x1"),
                (s.m_base, reference.m_base, "m_base"),
            ] {
                assert!(
                    (a - b).abs() <= err * b.abs().max(1.0),
                    "{method} {what}: {a} vs {b} on {scene:?}"
                );
            }
            assert_eq!(s.flex, 0);
        }
    }
}

#[test]
fn homotopy_start_lands_on_requested_branch() {
    let scene = Scene {
        stiffness: Stiffness::Taper { ratio: 0.4 },
        ..Scene::default()
    };
    let rod = scene.rod().unwrap();
    let c = solve(
        &rod,
        -0.2,
        Target::Phi1(0.3),
        &BranchChoice::Convex,
        &cfg(Method::Shooting, 1e-10),
    )
    .unwrap();
    assert_eq!(c.flex, 0);
    assert!(c.m_base < 0.0 && (c.phi1 - 0.3).abs() < 1e-9);
    let f = solve(
        &rod,
        -0.2,
        Target::Phi1(0.3),
        &BranchChoice::Flex,
        &cfg(Method::Shooting, 1e-10),
    )
    .unwrap();
    assert_eq!(f.flex, 1);
    assert!(f.m_base > 0.0 && f.f > c.f);
    // κ > 0 before the flex point, < 0 after it
    let s_b = f.s_flex.unwrap();
    assert!(f.point_at(0.5 * s_b).kappa > 0.0);
    assert!(f.point_at(0.5 * (s_b + 1.0)).kappa < 0.0);
}

#[test]
fn first_integral_holds_on_uniform_rod() {
    // m'·m = f cos(φ − α) φ' with κ = m gives ½κ² = f[sin(φ − α) − sin(φ1 − α)] (m(1) = 0).
    // (the paper's display (2.4) writes 2f on the right; that factor contradicts its (2.6), see
    // elastica.)
    let rod = Scene::default().rod().unwrap();
    for (alpha, branch) in [(-0.3, BranchChoice::Convex), (-0.3, BranchChoice::Flex)] {
        let s = solve(
            &rod,
            alpha,
            Target::Phi1(0.4),
            &branch,
            &cfg(Method::Collocation6, 1e-10),
        )
        .unwrap();
        for p in s.samples(41) {
            let lhs = 0.5 * p.kappa * p.kappa;
            let rhs = s.f * ((p.phi - alpha).sin() - (s.phi1 - alpha).sin());
            assert!((lhs - rhs).abs() < 1e-6 * s.f, "{p:?}: {lhs} vs {rhs}");
        }
    }
}

#[test]
fn uniform_solves_match_closed_forms() {
    let rod = Scene::default().rod().unwrap();
    for (branch, eb) in [
        (BranchChoice::Convex, elastica::Branch::Convex),
        (BranchChoice::Flex, elastica::Branch::OneFlex),
    ] {
        let e = elastica::Elastica::new(eb, -0.4, 0.5).unwrap();
        for method in [
            Method::Shooting,
            Method::MultipleShooting,
            Method::Collocation6,
        ] {
            let s = solve(&rod, -0.4, Target::Phi1(0.5), &branch, &cfg(method, 1e-11)).unwrap();
            assert!(
                (s.f - e.f).abs() < 1e-7 * e.f,
                "{method}: {} vs {}",
                s.f,
                e.f
            );
            assert!((s.x1 - e.x1).abs() < 1e-7 && (s.y1 - e.y1).abs() < 1e-7);
            assert!((s.m_base - e.m_base).abs() < 1e-6);
        }
        let a = solve(
            &rod,
            -0.4,
            Target::Phi1(0.5),
            &branch,
            &cfg(Method::Analytic, 1e-10),
        )
        .unwrap();
        assert_eq!(a.f, e.f);
    }
}

#[test]
fn tip_target_solves_for_alpha_and_f() {
    let rod = Scene::default().rod().unwrap();
    let e = elastica::Elastica::new(elastica::Branch::Convex, -0.35, 0.45).unwrap();
    let s = solve(
        &rod,
        0.0,
        Target::Tip { x1: e.x1, y1: e.y1 },
        &BranchChoice::Convex,
        &cfg(Method::Shooting, 1e-11),
    )
    .unwrap();
    assert!(
        (s.alpha - e.alpha).abs() < 1e-7,
        "{} vs {}",
        s.alpha,
        e.alpha
    );
    assert!((s.f - e.f).abs() < 1e-7 * e.f);
}
