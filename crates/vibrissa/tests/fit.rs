//! `fit` (issue 21): μs and μk from noisy synthetic traces within 3 standard errors (a fast
//! subset of the 100-trial study `examples/fit_stats.rs`), the standard errors against the
//! spread of the estimates, the noise levels' degrees of freedom, and a trace with one slip
//! naming the parameter it cannot determine.

use vibrissa::fit::{fit, CorrugationFit, FitOptions, Trace, TraceSlip};
use vibrissa::{drag, DragOptions, DragResult, Scene};

#[path = "support/noisy_trace.rs"]
mod noisy_trace;
use noisy_trace::{
    corrugated, noisy, places_only, texture_trace, within_three_standard_errors, Rng, SIGMA,
    TEXTURE_TRUTH,
};

fn truth(n: usize) -> DragResult {
    let (rod, surface) = Scene::default().parts().unwrap();
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max: 0.12,
            points: 2,
            mu_s: Some(0.5),
            mu_k: Some(0.3),
            max_slips: n,
            ..DragOptions::default()
        },
    )
    .unwrap();
    assert_eq!(r.slips.len(), n);
    r
}

#[test]
fn noisy_traces_within_three_standard_errors() {
    let r = truth(6);
    for seed in [3, 11] {
        let mut rng = Rng(seed);
        let t = noisy(&r, r.slips.len(), &mut rng);
        let f = fit(&Scene::default(), &t, &FitOptions::default()).unwrap();
        within_three_standard_errors(&f, seed);
        // the estimated noise levels are those of the data (within the spread of a few samples)
        assert!(f.sigma[0] > 0.5e-4 && f.sigma[0] < 4e-4, "{f}");
        assert!(f.sigma[2].is_nan());
    }
}

/// With the noise levels given, the standard errors are those of the estimates' spread: over 8
/// seeded traces of 4 slips the mean of the 16 squared errors in standard errors, `z²`, is 1 for
/// right standard errors; the bounds are the 0.05 % and 99.95 % quantiles of χ²₁₆ / 16 (standard
/// errors off by a factor 1.7 either way fall outside).
#[test]
fn standard_errors_match_the_spread_of_the_estimates() {
    let r = truth(4);
    let opts = FitOptions {
        sigma: Some(SIGMA),
        ..FitOptions::default()
    };
    let mut z2 = Vec::new();
    for seed in 0..8 {
        let t = noisy(&r, 4, &mut Rng(4000 + seed));
        let f = fit(&Scene::default(), &t, &opts).unwrap();
        for (name, want) in [("mu_s", 0.5), ("mu_k", 0.3)] {
            let p = f.get(name).unwrap();
            // (known noise levels: the standard error is not itself estimated)
            assert!(p.dof.is_none(), "{f}");
            z2.push(((p.value - want) / p.std_error.unwrap()).powi(2));
        }
    }
    let mean = z2.iter().sum::<f64>() / z2.len() as f64;
    assert!((0.29..=2.58).contains(&mean), "mean z² {mean}: {z2:?}");
}

/// Estimated noise levels: each kind's variance over its own degrees of freedom (its
/// observations less their leverages), so that these add up to n − p and the weighted residuals
/// give `s² = 1` (to the reweighting's tolerance, 1e-3 in σ); with one kind of observation (the
/// places only) the standard errors have exactly n − p degrees of freedom.
#[test]
fn noise_levels_are_estimated_over_their_degrees_of_freedom() {
    let r = truth(6);
    let t = noisy(&r, 6, &mut Rng(3));
    let f = fit(&Scene::default(), &t, &FitOptions::default()).unwrap();
    assert!((f.s2 - 1.0).abs() < 5e-3, "{f}");
    for name in ["mu_s", "mu_k"] {
        let dof = f.get(name).unwrap().dof.unwrap();
        // (Satterthwaite's dof `2 (Σ v_k)² / vᵀ C v`, `C = 2 G⁻¹`, is at most n − p = 22 by
        // Cauchy–Schwarz, as the G_kl add up to n − p; with C diagonal it is at least the
        // fewest of one kind's degrees of freedom, at least its 6 observations less p, and the
        // off-diagonal G_kl = Σ H_ij² between kinds are small)
        assert!((4.0..=22.0).contains(&dof), "{name}: dof {dof}");
    }
    let f = fit(&Scene::default(), &places_only(&t), &FitOptions::default()).unwrap();
    assert!((f.s2 - 1.0).abs() < 5e-3, "{f}");
    for name in ["mu_s", "mu_k"] {
        let dof = f.get(name).unwrap().dof.unwrap();
        assert!((dof - 4.0).abs() < 1e-9, "{name}: dof {dof}");
    }
}

/// Kenward–Roger: the standard errors with estimated noise levels against those of the same fit
/// with its estimated levels given (the same weights and estimate, `(JᵀJ)⁻¹` without the
/// correction): with one kind of observation (the places) the correction vanishes and the
/// ratio of the variances is `s²` (1 to 5e-3; to 1e-6, as the two fits' Jacobians agree to
/// their estimates' agreement, ~1e-8 here); with the signals too it is `1 + 2Λ_cc / M_cc`,
/// above 1 (`Λ` is positive semidefinite; at 4 slips with 4–8 observations per kind by more
/// than the reweighting's 1e-3).
#[test]
fn estimated_levels_widen_the_standard_errors_when_kinds_share_the_information() {
    let r = truth(4);
    let t = noisy(&r, 4, &mut Rng(4001));
    for (trace, one_kind) in [(places_only(&t), true), (t.clone(), false)] {
        let f = fit(&Scene::default(), &trace, &FitOptions::default()).unwrap();
        let given = FitOptions {
            sigma: Some(f.sigma.map(|s| if s.is_nan() { 1.0 } else { s })),
            ..FitOptions::default()
        };
        let g = fit(&Scene::default(), &trace, &given).unwrap();
        for name in ["mu_s", "mu_k"] {
            let (pe, pg) = (f.get(name).unwrap(), g.get(name).unwrap());
            assert!(
                (pe.value - pg.value).abs() < 1e-3 * pg.std_error.unwrap(),
                "{f}; {g}"
            );
            let ratio = (pe.std_error.unwrap() / pg.std_error.unwrap()).powi(2);
            if one_kind {
                assert!(
                    (ratio - f.s2).abs() < 1e-6 && (ratio - 1.0).abs() < 5e-3,
                    "{name}: variance ratio {ratio}, s² {}",
                    f.s2
                );
            } else {
                assert!(
                    ratio > 1.0 + 1e-3,
                    "{name}: variance ratio {ratio}: {f}; {g}"
                );
            }
        }
    }
}

#[test]
fn exact_trace_gives_the_coefficients() {
    let r = truth(3);
    let t = Trace {
        tips: Vec::new(),
        motion: Default::default(),
        slips: r
            .slips
            .iter()
            .map(|e| TraceSlip {
                d: e.d,
                before: [Some(e.before.fx), None, None],
                after: [None; 3],
            })
            .collect(),
    };
    let f = fit(
        &Scene::default(),
        &t,
        &FitOptions {
            sigma: Some([1e-4, 1e-3, 1e-3, 1e-3]),
            ..FitOptions::default()
        },
    )
    .unwrap();
    assert!((f.get("mu_s").unwrap().value - 0.5).abs() < 1e-7, "{f}");
    assert!((f.get("mu_k").unwrap().value - 0.3).abs() < 1e-7, "{f}");
}

#[test]
fn one_slip_names_what_it_cannot_determine() {
    let r = truth(1);
    let e = r.slips[0];
    let t = Trace {
        tips: Vec::new(),
        motion: Default::default(),
        slips: vec![TraceSlip {
            d: e.d,
            before: [Some(e.before.fx), None, Some(e.before.m_base)],
            after: [None; 3],
        }],
    };
    let f = fit(&Scene::default(), &t, &FitOptions::default()).unwrap();
    let m = f.message.as_deref().unwrap_or("");
    assert!(m.contains("mu_k cannot be determined"), "{f}");
    let (s, k) = (f.get("mu_s").unwrap(), f.get("mu_k").unwrap());
    assert!(
        s.identifiable && !k.identifiable && k.std_error.is_none(),
        "{f}"
    );
    assert!((s.value - 0.5).abs() < 1e-6, "{f}");
    // the state after the slip depends on μk: with it, both are determined
    let t2 = Trace {
        tips: Vec::new(),
        motion: Default::default(),
        slips: vec![TraceSlip {
            after: [Some(e.after.fx), None, Some(e.after.m_base)],
            ..t.slips[0]
        }],
    };
    let f2 = fit(&Scene::default(), &t2, &FitOptions::default()).unwrap();
    assert!(
        f2.message.is_none() && (f2.get("mu_k").unwrap().value - 0.3).abs() < 1e-6,
        "{f2}"
    );
}

/// The inclination from a noiseless trace on a surface inclined by 0.05 rad, started at 0.045:
/// μs, μk and β back to 1e-7.
#[test]
fn fit_angle_recovers_the_inclination() {
    let inclined = Scene {
        surface_angle: 0.05,
        ..Scene::default()
    };
    let (rod, surface) = inclined.parts().unwrap();
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max: 0.06,
            points: 2,
            mu_s: Some(0.5),
            mu_k: Some(0.2),
            ..DragOptions::default()
        },
    )
    .unwrap();
    assert!(r.slips.len() >= 3, "{r}");
    let t = Trace {
        tips: Vec::new(),
        motion: Default::default(),
        slips: r
            .slips
            .iter()
            .map(|e| TraceSlip {
                d: e.d,
                before: [Some(e.before.fx), Some(e.before.fy), None],
                after: [Some(e.after.fx), None, None],
            })
            .collect(),
    };
    let start = Scene {
        surface_angle: 0.045,
        ..Scene::default()
    };
    let f = fit(
        &start,
        &t,
        &FitOptions {
            fit_angle: true,
            ..FitOptions::default()
        },
    )
    .unwrap();
    for (name, want) in [("mu_s", 0.5), ("mu_k", 0.2), ("surface_angle", 0.05)] {
        let p = f.get(name).unwrap();
        assert!(p.identifiable && (p.value - want).abs() < 1e-7, "{f}");
    }
}

/// The trace as `vibrissa drag` writes it and `fit` reads it: every signal before and after each
/// slip, and the tips of the rows.
fn full_trace(r: &DragResult) -> Trace {
    let sig = |s: &vibrissa::drag::Signals| [Some(s.fx), Some(s.fy), Some(s.m_base)];
    Trace {
        slips: r
            .slips
            .iter()
            .map(|e| TraceSlip {
                d: e.d,
                before: sig(&e.before),
                after: sig(&e.after),
            })
            .collect(),
        tips: r.rows.iter().map(|p| [p.x_tip, p.y_tip]).collect(),
        motion: Default::default(),
    }
}

/// Issue 33: the noise-free trace of a drag over a corrugated surface (η = 0.75, A = 0.005,
/// W = 0.1, μs = 0.5, μk = 0.3, d to 0.3, 61 points: 15 slips) fitted with that surface. Gauss-
/// Newton from the starting values alone ended in a local minimum (μs 0.5933 ± 0.031, μk
/// 0.4683 ± 0.042, no message); the continuation in the trace's length finds the coefficients to
/// 1e-6 (the drags' tolerance is 1e-10). Fitted on a flat surface the same trace is a misfit: no
/// standard errors, and the message says that the tips are off a line and that the model does
/// not fit (before: μs 0.396 with a standard error and no message).
#[test]
fn corrugated_trace_fits_its_surface_and_misfits_a_flat_one() {
    let corrugated = Scene {
        surface: vibrissa::surface::SurfaceProfile::Sine {
            amplitude: 0.005,
            wavelength: 0.1,
            phase: 0.0,
        },
        ..Scene::default()
    };
    let (rod, surface) = corrugated.parts().unwrap();
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max: 0.3,
            points: 61,
            mu_s: Some(0.5),
            mu_k: Some(0.3),
            ..DragOptions::default()
        },
    )
    .unwrap();
    assert_eq!(r.slips.len(), 15, "{r}");
    let t = full_trace(&r);
    let f = fit(&corrugated, &t, &FitOptions::default()).unwrap();
    for (name, want) in [("mu_s", 0.5), ("mu_k", 0.3)] {
        let p = f.get(name).unwrap();
        assert!((p.value - want).abs() < 1e-6, "{f}");
        assert!(p.std_error.is_some_and(|se| se < 1e-6), "{f}");
    }
    assert!(f.consistency.as_ref().is_some_and(|c| c.consistent), "{f}");
    assert!(f.message.is_none(), "{f}");
    let flat = fit(&Scene::default(), &t, &FitOptions::default()).unwrap();
    assert!(flat.params.iter().all(|p| p.std_error.is_none()), "{flat}");
    let m = flat.message.clone().unwrap_or_default();
    assert!(m.contains("tips lie off a straight line"), "{m}");
    assert!(m.contains("does not fit the whole trace"), "{m}");
}

/// A drag's default solver tolerance: the observations of a noise-free trace are exact to it.
const DRAG_TOL: f64 = vibrissa::SolverConfig::DEFAULT_TOL;

/// Issue 31: the texture read back. The noise-free trace of a drag over A = 0.005, W = 0.1,
/// P = 0.7 (μs = 0.5, μk = 0.3, d to 0.03: 6 slips, 42 observations) fitted from A = 0.0055
/// (+10 %), W = 0.097 (−3 %), P = 0.6 with μs, μk read off the slips. With unit weights given
/// the standard error is `√[(JᵀJ)⁻¹]_ii`, so observations exact to the drags' tolerance ε bound
/// each error by `√n · ε · std_error` (the tolerance of each parameter; measured errors 2e-14
/// to 2e-11 against bounds 1e-10 to 2e-7). A local minimum a wavelength or a slip off would
/// miss it by orders of magnitude more.
#[test]
fn corrugation_is_read_back_from_perturbed_starts() {
    let truth = corrugated(0.005, 0.1, 0.7);
    let (rod, surface) = truth.parts().unwrap();
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max: 0.03,
            points: 2,
            mu_s: Some(0.5),
            mu_k: Some(0.3),
            ..DragOptions::default()
        },
    )
    .unwrap();
    assert_eq!(r.slips.len(), 6, "{r}");
    let t = full_trace(&r);
    let f = fit(
        &corrugated(0.0055, 0.097, 0.6),
        &t,
        &FitOptions {
            corrugation: vibrissa::fit::CorrugationFit::ALL,
            sigma: Some([1.0; 4]),
            ..FitOptions::default()
        },
    )
    .unwrap();
    assert!(f.message.is_none(), "{f}");
    let n = f.observations as f64;
    for (name, want) in TEXTURE_TRUTH {
        let p = f.get(name).unwrap();
        let bound = n.sqrt() * DRAG_TOL * p.std_error.unwrap();
        assert!(
            p.identifiable && (p.value - want).abs() <= bound,
            "{name}: error {:e}, bound {bound:e}: {f}",
            p.value - want
        );
    }
}

/// Issue 31, the speed-independent part of the study `fit_stats texture 100 8`: a noisy trace
/// of 8 slips over A = 0.005, W = 0.1, P = 0.7 (μs = 0.5, μk = 0.3; the study's noise, levels
/// given, its trial 0: seed 31000) fitted with all five free from the study's start A = 0.0055,
/// W = 0.097, P = 0.6. Every parameter within 3 of its standard errors of the truth, the fit
/// consistent along the trace. (A local minimum a slip or a wavelength off, a misfit — no
/// standard errors — or standard errors far too small fail it; measured: 1.0–1.8 standard
/// errors.)
#[test]
fn a_noisy_corrugated_trace_is_read_back_within_three_standard_errors() {
    let r = texture_trace(8);
    let t = noisy(&r, 8, &mut Rng(31_000));
    let f = fit(
        &corrugated(0.0055, 0.097, 0.6),
        &t,
        &FitOptions {
            corrugation: CorrugationFit::ALL,
            sigma: Some(SIGMA),
            ..FitOptions::default()
        },
    )
    .unwrap();
    assert!(f.message.is_none(), "{f}");
    assert!(f.consistency.as_ref().is_some_and(|c| c.consistent), "{f}");
    for (name, want) in TEXTURE_TRUTH {
        let p = f.get(name).unwrap();
        let se = p.std_error.unwrap();
        assert!(
            (p.value - want).abs() <= 3.0 * se,
            "{name}: error {:e}, standard error {se:e}: {f}",
            p.value - want
        );
    }
}

/// A trace of a flat surface fitted with a corrugation starting at amplitude 0: the wavelength
/// and the phase change nothing, so they are named, held at their starts and get no number
/// (no standard error); μs, μk and the amplitude (0) are fitted — to 1e-7, the flat drag's
/// own accuracy, as a sine of amplitude 0 is the same line by another code path (unit weights
/// given: no reweighting rounds).
#[test]
fn a_flat_trace_names_the_corrugation_it_cannot_determine() {
    let r = truth(3);
    let t = full_trace(&r);
    let f = fit(
        &corrugated(0.0, 0.1, 0.3),
        &t,
        &FitOptions {
            corrugation: vibrissa::fit::CorrugationFit::ALL,
            sigma: Some([1.0; 4]),
            ..FitOptions::default()
        },
    )
    .unwrap();
    let m = f.message.as_deref().unwrap_or("");
    assert!(
        m.contains("wavelength and phase cannot be determined from this trace")
            && m.contains("amplitude is 0"),
        "{f}"
    );
    for (name, held) in [("wavelength", 0.1), ("phase", 0.3)] {
        let p = f.get(name).unwrap();
        assert!(
            !p.identifiable && p.std_error.is_none() && p.value == held,
            "{f}"
        );
    }
    for (name, want) in [("mu_s", 0.5), ("mu_k", 0.3), ("amplitude", 0.0)] {
        let p = f.get(name).unwrap();
        assert!(p.identifiable && (p.value - want).abs() < 1e-7, "{f}");
    }
    // a surface that is not one sine has no corrugation to fit
    let e = fit(
        &Scene::default(),
        &t,
        &FitOptions {
            corrugation: vibrissa::fit::CorrugationFit {
                phase: true,
                ..Default::default()
            },
            ..FitOptions::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("not one sine corrugation"), "{e}");
}

/// The parts of a corrugation to fit, by name (the program's `--fit-corrugation=PARTS` and
/// Python's `fit_corrugation` read them here): none named is all three; an unknown name is an
/// input error that lists the valid ones.
#[test]
fn corrugation_parts_by_name() {
    let none: [&str; 0] = [];
    assert_eq!(
        CorrugationFit::from_names(none).unwrap(),
        CorrugationFit::ALL
    );
    let c = CorrugationFit::from_names([" amplitude", "phase "]).unwrap();
    assert!(c.amplitude && c.phase && !c.wavelength);
    let e = CorrugationFit::from_names(["amplitude", "height"]).unwrap_err();
    assert!(e.is_input(), "{e}");
    assert!(e.to_string().contains("'height'"), "{e}");
    assert!(
        e.to_string().contains("amplitude, wavelength, phase"),
        "{e}"
    );
}
