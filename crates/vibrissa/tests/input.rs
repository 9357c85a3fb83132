//! Bad input returns an error naming the value and its valid range; the analytic Jacobians agree
//! with finite differences.

use bvp::Bvp;
use proptest::prelude::*;
use vibrissa::equations::{Ends, RodBvp};
use vibrissa::{
    infer, scan, solve, BranchChoice, Method, Precurvature, ScanOptions, Scene, SolverConfig,
    Stiffness, Target, VibrissaError,
};

fn err_of(scene: Scene) -> String {
    scene.validate().unwrap_err().to_string()
}

#[test]
fn bad_scenes_name_value_and_range() {
    let e = err_of(Scene {
        eta: 1.2,
        ..Scene::default()
    });
    assert!(
        e.contains("eta") && e.contains("1.2") && e.contains("0.45694"),
        "{e}"
    );
    let e = err_of(Scene {
        eta: 0.3,
        ..Scene::default()
    });
    assert!(e.contains("eta = 0.3") && e.contains("(0.456"), "{e}");
    let e = err_of(Scene {
        eta: f64::NAN,
        ..Scene::default()
    });
    assert!(e.contains("eta = NaN"), "{e}");
    for ratio in [0.0, -0.5, 1.5, f64::NAN] {
        let e = err_of(Scene {
            stiffness: Stiffness::Taper { ratio },
            ..Scene::default()
        });
        assert!(e.contains("taper ratio") && e.contains("[0.01, 1]"), "{e}");
    }
    for c in [-1.0, 2e3, f64::INFINITY] {
        let e = err_of(Scene {
            support_compliance: c,
            ..Scene::default()
        });
        assert!(
            e.contains(&format!("support compliance = {c}")) && e.contains("[0, 1000]"),
            "{e}"
        );
    }
    // rest curvatures past the model's range (a rod curled over ~3 turns)
    for (k0, k1) in [(3.5, 0.0), (-1e300, 0.0), (2.0, 1.5)] {
        let e = err_of(Scene {
            precurvature: Precurvature::Linear { k0, k1 },
            ..Scene::default()
        });
        assert!(e.contains("precurvature") && e.contains("[-3, 3]"), "{e}");
    }
    let e = err_of(Scene {
        precurvature: Precurvature::Linear {
            k0: f64::NAN,
            k1: 0.0,
        },
        ..Scene::default()
    });
    assert!(e.contains("k0 = NaN"), "{e}");
    let e = err_of(Scene {
        stiffness: Stiffness::Table {
            s: vec![0.0, 0.6, 0.5, 1.0],
            b: vec![1.0; 4],
        },
        ..Scene::default()
    });
    assert!(
        e.contains("strictly increasing") && e.contains("0.5"),
        "{e}"
    );
    let e = err_of(Scene {
        stiffness: Stiffness::Table {
            s: vec![0.0, 0.5],
            b: vec![1.0, 1.0],
        },
        ..Scene::default()
    });
    assert!(e.contains("[0, 1]"), "{e}");
    let e = err_of(Scene {
        stiffness: Stiffness::Table {
            s: vec![0.0, 1.0],
            b: vec![1.0, 0.0],
        },
        ..Scene::default()
    });
    assert!(e.contains("[1e-8, 1e8]"), "{e}");
    let e = err_of(Scene {
        precurvature: Precurvature::Table {
            s: vec![0.0, 1.0],
            k: vec![1.0],
        },
        ..Scene::default()
    });
    assert!(e.contains("same length"), "{e}");
    let e = err_of(Scene {
        physical: Some(vibrissa::Physical {
            length_mm: -3.0,
            youngs_modulus_gpa: 3.0,
            base_diameter_um: 100.0,
        }),
        ..Scene::default()
    });
    assert!(
        e.contains("length_mm = -3") && e.contains("(0, inf)"),
        "{e}"
    );
    // dimensions whose units underflow are refused, not reported as empty columns
    let e = err_of(Scene {
        physical: Some(vibrissa::Physical {
            length_mm: 1e200,
            youngs_modulus_gpa: 3.0,
            base_diameter_um: 1e-100,
        }),
        ..Scene::default()
    });
    assert!(e.contains("force unit"), "{e}");
}

/// Every `kind` refuses keys it does not have: a uniform rod with a ratio or a straight rod with
/// a curvature is a mistake in the file, not the paper's rod.
#[test]
fn scene_kinds_refuse_foreign_keys() {
    for text in [
        "stiffness = { kind = \"uniform\", ratio = 0.5 }",
        "precurvature = { kind = \"none\", k0 = -0.5 }",
        "stiffness = { kind = \"taper\", ratio = 0.5, k0 = 1 }",
        "precurvature = { kind = \"linear\", k0 = 1, ratio = 2 }",
    ] {
        let e = toml::from_str::<Scene>(text).unwrap_err().to_string();
        assert!(e.contains("unknown field"), "{text}: {e}");
    }
    let ok: Scene = toml::from_str("stiffness = { kind = \"uniform\" }").unwrap();
    assert_eq!(ok, Scene::default());
}

#[test]
fn bad_scan_options() {
    let (rod, surface) = Scene::default().parts().unwrap();
    let bad = [
        (
            ScanOptions {
                mu0: Some(-0.1),
                ..ScanOptions::default()
            },
            "mu0",
        ),
        (
            ScanOptions {
                d_max: -1.0,
                ..ScanOptions::default()
            },
            "d_max",
        ),
        (
            ScanOptions {
                d_max: f64::NAN,
                ..ScanOptions::default()
            },
            "d_max",
        ),
        (
            ScanOptions {
                points: 1,
                ..ScanOptions::default()
            },
            "points",
        ),
    ];
    for (o, name) in bad {
        let e = scan(&rod, &surface, &o).unwrap_err().to_string();
        assert!(e.contains(name) && e.contains("valid range"), "{e}");
    }
    // a negative d0 is bad input, named with its range and no NaN in it
    let e = infer(&rod, &surface, -0.1, &ScanOptions::default()).unwrap_err();
    assert!(matches!(e, VibrissaError::OutOfRange { .. }), "{e}");
    assert!(!e.to_string().contains("NaN"), "{e}");
    // beyond the first maximum of |μ| (d ≈ 0.130): not measurable, the message says why
    let e = infer(&rod, &surface, 0.2, &ScanOptions::default()).unwrap_err();
    assert!(matches!(e, VibrissaError::NotMeasurable { .. }), "{e}");
    assert!(e.to_string().contains("first maximum"), "{e}");
    // a d_max before the first maximum cuts the range short: an error that says so
    let short = ScanOptions {
        d_max: 0.05,
        ..ScanOptions::default()
    };
    let e = infer(&rod, &surface, 0.04, &short).unwrap_err();
    assert!(matches!(e, VibrissaError::RangeCutShort { .. }), "{e}");
}

#[test]
fn analytic_only_on_paper_scene() {
    let rod = Scene {
        stiffness: Stiffness::Taper { ratio: 0.5 },
        ..Scene::default()
    }
    .rod()
    .unwrap();
    let cfg = SolverConfig {
        method: Method::Analytic,
        ..SolverConfig::default()
    };
    let e = solve(&rod, -0.1, Target::Eta(0.7), &BranchChoice::Convex, &cfg).unwrap_err();
    assert!(matches!(e, VibrissaError::MethodUnavailable { .. }), "{e}");
    let e = "bogus".parse::<Method>().unwrap_err().to_string();
    assert!(e.contains("bogus") && e.contains("collocation6"), "{e}");
    for m in Method::ALL {
        assert_eq!(m.to_string().parse::<Method>().unwrap(), m);
    }
}

fn fd_check<B: Bvp>(rod: &B, s: f64, z: &[f64], p: &[f64]) {
    let k = p.len();
    let (mut jz, mut jp) = (vec![0.0; 16], vec![0.0; 4 * k]);
    assert!(rod.rhs_jacobian(s, z, p, &mut jz, &mut jp));
    let h = 1e-6;
    let (mut fp, mut fm) = ([0.0; 4], [0.0; 4]);
    for j in 0..4 {
        let (mut zp, mut zm) = (z.to_vec(), z.to_vec());
        zp[j] += h;
        zm[j] -= h;
        rod.rhs(s, &zp, p, &mut fp);
        rod.rhs(s, &zm, p, &mut fm);
        for i in 0..4 {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            assert!(
                (fd - jz[i * 4 + j]).abs() < 1e-6 * (1.0 + fd.abs()),
                "dF{i}/dz{j}"
            );
        }
    }
    for j in 0..k {
        let (mut pp, mut pm) = (p.to_vec(), p.to_vec());
        pp[j] += h;
        pm[j] -= h;
        rod.rhs(s, z, &pp, &mut fp);
        rod.rhs(s, z, &pm, &mut fm);
        for i in 0..4 {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            assert!(
                (fd - jp[i * k + j]).abs() < 1e-6 * (1.0 + fd.abs()),
                "dF{i}/dp{j}"
            );
        }
    }
    // boundary conditions are affine in z(a), z(b), p
    let m = 4 + k;
    let (mut ga, mut gb, mut gp) = (vec![0.0; m * 4], vec![0.0; m * 4], vec![0.0; m * k]);
    assert!(rod.bc_jacobian(z, z, p, &mut ga, &mut gb, &mut gp));
    let (mut r0, mut r1) = (vec![0.0; m], vec![0.0; m]);
    rod.bc(z, z, p, &mut r0);
    for j in 0..4 {
        let mut za = z.to_vec();
        za[j] += 1.0;
        rod.bc(&za, z, p, &mut r1);
        for i in 0..m {
            assert!(
                (r1[i] - r0[i] - ga[i * 4 + j]).abs() < 1e-12,
                "dg{i}/dza{j}"
            );
        }
        rod.bc(z, &za, p, &mut r1);
        for i in 0..m {
            assert!(
                (r1[i] - r0[i] - gb[i * 4 + j]).abs() < 1e-12,
                "dg{i}/dzb{j}"
            );
        }
    }
}

proptest! {
    #[test]
    fn analytic_jacobians_match_finite_differences(
        s in 0.0..1.0f64, x in -1.0..1.0f64, y in -1.0..1.0f64, phi in -3.0..3.0f64,
        m in -5.0..5.0f64, f in 0.0..30.0f64, alpha in -1.5..0.5f64, ratio in 0.05..1.0f64,
        k0 in -3.0..2.5f64, c in 0.0..10.0f64, with_alpha in proptest::bool::ANY,
    ) {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio },
            precurvature: Precurvature::Linear { k0, k1: 0.5 },
            support_compliance: c,
            ..Scene::default()
        };
        let rod = scene.rod().unwrap();
        let z = [x, y, phi, m];
        let (ends, p) = if with_alpha {
            (Ends::Tip { x1: 0.3, y1: 0.7 }, vec![f, alpha])
        } else {
            (Ends::Eta { eta: 0.7 }, vec![f])
        };
        let rod = RodBvp { profile: rod.profile(1.0), compliance: c, alpha, ends };
        fd_check(&rod, s, &z, &p);
        let uni = RodBvp { profile: vibrissa::profile::Uniform, compliance: c, alpha, ends: Ends::Phi1 { phi1: 0.2 } };
        fd_check(&uni, s, &z, &p[..1]);
    }
}

/// The valueless kinds are plain variants in Rust (`Stiffness::Uniform`, `Precurvature::None`)
/// and the same tagged tables in files, both ways.
#[test]
fn valueless_kinds_keep_their_file_form() {
    let sc = Scene::default();
    assert_eq!(sc.stiffness, vibrissa::Stiffness::Uniform);
    assert_eq!(sc.precurvature, vibrissa::Precurvature::None);
    let text = toml::to_string(&sc).unwrap();
    assert!(text.contains("[stiffness]\nkind = \"uniform\""), "{text}");
    assert!(text.contains("[precurvature]\nkind = \"none\""), "{text}");
    assert_eq!(toml::from_str::<Scene>(&text).unwrap(), sc);
    // a linear rest curvature without k1 reads as constant, as before
    let c: Scene = toml::from_str("precurvature = { kind = \"linear\", k0 = 0.5 }").unwrap();
    assert_eq!(
        c.precurvature,
        vibrissa::Precurvature::Linear { k0: 0.5, k1: 0.0 }
    );
}
