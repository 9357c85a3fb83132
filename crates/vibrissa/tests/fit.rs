//! `fit` (issue 21): μs and μk from noisy synthetic traces within 3 standard errors (a fast
//! subset of the 100-trial study `examples/fit_stats.rs`), and a trace with one slip naming the
//! parameter it cannot determine.

use vibrissa::fit::{fit, FitOptions, Trace, TraceSlip};
use vibrissa::{drag, DragOptions, DragResult, Scene};

#[path = "support/noisy_trace.rs"]
mod noisy_trace;
use noisy_trace::{noisy, Rng};

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
        assert!(f.message.is_none(), "{f}");
        for (name, want) in [("mu_s", 0.5), ("mu_k", 0.3)] {
            let p = f.get(name).unwrap();
            let se = p.std_error.unwrap();
            assert!(se > 0.0 && se < 1e-3, "{f}");
            assert!((p.value - want).abs() <= 3.0 * se, "seed {seed}: {f}");
        }
        // the estimated noise levels are those of the data (within the spread of a few samples)
        assert!(f.sigma[0] > 0.5e-4 && f.sigma[0] < 4e-4, "{f}");
        assert!(f.sigma[2].is_nan());
    }
}

#[test]
fn exact_trace_gives_the_coefficients() {
    let r = truth(3);
    let t = Trace {
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
