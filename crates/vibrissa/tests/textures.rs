//! The textures a user has (issue 31): a sum of sines, a periodic grating, a measured profile
//! from a file — their heights, slopes and arc lengths against closed forms, their refusals, and
//! a drag over each.

use std::f64::consts::TAU;
use vibrissa::drag::Phase;
use vibrissa::surface::{Height, SurfaceProfile};
use vibrissa::{drag, DragOptions, DragResult, Scene, StopReason, VibrissaError};

fn height(p: SurfaceProfile, eta: f64, beta: f64) -> Result<Height, VibrissaError> {
    Height::new(&p, eta, beta).map(|h| h.expect("a curved profile"))
}

/// Composite Simpson of `f` on `[a, b]` with `n` (even) intervals.
fn simpson(a: f64, b: f64, n: usize, f: impl Fn(f64) -> f64) -> f64 {
    let w = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        s += f(a + i as f64 * w) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * w / 3.0
}

fn speed(h: &Height) -> impl Fn(f64) -> f64 + '_ {
    |x| (1.0 + h.jet(x).1.powi(2)).sqrt()
}

/// One term of a sum is the corrugation itself: heights, slopes, curvatures to rounding, arc
/// lengths to 1e-12 (each tabulates its own panels) out to 700 rod lengths.
#[test]
fn a_sum_of_one_sine_is_the_sine() {
    for (a, w, p, beta) in [(0.01, 0.2, 2.0, 0.0), (-0.03, 0.5, -0.7, 0.2)] {
        let one = height(
            SurfaceProfile::Sine {
                amplitude: a,
                wavelength: w,
                phase: p,
            },
            0.75,
            beta,
        )
        .unwrap();
        let sum = height(
            SurfaceProfile::Sines {
                amplitude: vec![a],
                wavelength: vec![w],
                phase: vec![p],
            },
            0.75,
            beta,
        )
        .unwrap();
        for x in [-3.7, -0.05, 0.0, 0.13, 0.9, 41.3, 700.2] {
            let (j1, j2) = (one.jet(x), sum.jet(x));
            assert!(
                (j1.0 - j2.0).abs() < 1e-15 && (j1.1 - j2.1).abs() < 1e-14,
                "{x}: {j1:?} {j2:?}"
            );
            assert!((j1.2 - j2.2).abs() < 1e-12 * (1.0 + j1.2.abs()), "{x}");
            let (s1, s2) = (one.sigma(x), sum.sigma(x));
            assert!(
                (s1.0 - s2.0).abs() < 1e-12 * (1.0 + x.abs()) && s1.1 == s2.1,
                "{x}: {s1:?} {s2:?}"
            );
        }
    }
}

/// A sum of two sines: its heights are the sum's closed form, its arc length a fine Simpson sum
/// (near the foot and 500 rod lengths out, both sides of x = 0).
#[test]
fn a_sum_of_sines_has_the_closed_form_heights_and_the_arc_length() {
    let (a, w, p) = ([0.006, -0.002], [0.2, 0.07], [0.3, 1.1]);
    let h = height(
        SurfaceProfile::Sines {
            amplitude: a.to_vec(),
            wavelength: w.to_vec(),
            phase: p.to_vec(),
        },
        0.7,
        0.1,
    )
    .unwrap();
    for x in [-2.1, 0.0, 0.33, 5.0] {
        let k = [TAU / w[0], TAU / w[1]];
        let want = 0.7
            + x * 0.1f64.tan()
            + a[0] * (k[0] * x + p[0]).sin()
            + a[1] * (k[1] * x + p[1]).sin();
        let slope = 0.1f64.tan()
            + a[0] * k[0] * (k[0] * x + p[0]).cos()
            + a[1] * k[1] * (k[1] * x + p[1]).cos();
        assert!((h.h(x) - want).abs() < 1e-15 && (h.jet(x).1 - slope).abs() < 1e-14);
    }
    for (x0, x1) in [(0.0, 0.77), (-1.3, 0.0), (500.0, 500.9), (-0.2, 0.45)] {
        let want = simpson(x0, x1, 200_000, speed(&h));
        let got = h.sigma(x1).0 - h.sigma(x0).0;
        assert!((got - want).abs() < 1e-12, "[{x0}, {x1}]: {got} {want}");
    }
    // two half sines are one
    let half = height(
        SurfaceProfile::Sines {
            amplitude: vec![0.005, 0.005],
            wavelength: vec![0.3, 0.3],
            phase: vec![],
        },
        0.75,
        0.0,
    )
    .unwrap();
    let one = height(
        SurfaceProfile::Sine {
            amplitude: 0.01,
            wavelength: 0.3,
            phase: 0.0,
        },
        0.75,
        0.0,
    )
    .unwrap();
    assert!((half.h(0.41) - one.h(0.41)).abs() < 1e-16);
}

#[test]
fn a_sum_of_sines_is_refused_where_it_is_too_steep_or_malformed() {
    let sines = |a: Vec<f64>, w: Vec<f64>, p: Vec<f64>| SurfaceProfile::Sines {
        amplitude: a,
        wavelength: w,
        phase: p,
    };
    // 2π(0.01 + 0.006)/0.1 = 1.005: steeper than 45° together, not alone
    let e = height(sines(vec![0.01, 0.006], vec![0.1, 0.1], vec![]), 0.75, 0.0).unwrap_err();
    assert!(e.to_string().contains("1.005310"), "{e}");
    assert!(height(sines(vec![0.01, 0.005], vec![0.1, 0.1], vec![]), 0.75, 0.0).is_ok());
    // with the surface angle: tan 0.1 + 0.94248 ≥ 1
    assert!(height(sines(vec![0.01, 0.005], vec![0.1, 0.1], vec![]), 0.75, 0.1).is_err());
    let e = height(sines(vec![0.01, 0.3], vec![0.1, 90.0], vec![]), 0.75, 0.0).unwrap_err();
    assert!(
        e.to_string().starts_with("surface.amplitude[1] = 0.3"),
        "{e}"
    );
    let e = height(sines(vec![0.01], vec![0.005], vec![]), 0.75, 0.0).unwrap_err();
    assert!(e.to_string().starts_with("surface.wavelength[0]"), "{e}");
    let e = height(sines(vec![0.01], vec![0.1, 0.2], vec![]), 0.75, 0.0).unwrap_err();
    assert!(matches!(e, VibrissaError::InvalidTable { .. }), "{e}");
    let e = height(sines(vec![0.01], vec![0.1], vec![0.0, 1.0]), 0.75, 0.0).unwrap_err();
    assert!(matches!(e, VibrissaError::InvalidTable { .. }), "{e}");
    assert!(height(sines(vec![], vec![], vec![]), 0.75, 0.0).is_err());
    assert!(height(sines(vec![f64::NAN], vec![0.1], vec![]), 0.75, 0.0).is_err());
}

fn grating(period: f64, depth: Option<f64>, flank: Option<f64>, r: f64) -> SurfaceProfile {
    SurfaceProfile::Grating {
        period,
        depth,
        flank_angle: flank,
        ridge_radius: r,
        offset: 0.05,
    }
}

/// A grating with lands (depth and flank angle given): the arc length of a period by hand —
/// four lands' halves `4l`, four arcs `4rα`, two flanks `2·rise/sin α` with
/// `rise = D − 2r(1 − cos α)` and `l = (p/2 − 2r sin α − rise/tan α)/2` — the heights of the
/// ridge, the groove and the flank, the slope of the flank, the mean height 0 and a C¹ profile.
#[test]
fn a_grating_period_has_the_arc_length_by_hand() {
    let (p, d, a, r) = (0.2, 0.02, 0.4, 0.01);
    let h = height(grating(p, Some(d), Some(a), r), 0.75, 0.0).unwrap();
    let rise = d - 2.0 * r * (1.0 - a.cos());
    let land = 0.5 * (0.5 * p - 2.0 * r * a.sin() - rise / a.tan());
    assert!(land > 0.01, "{land}");
    let want = 4.0 * land + 4.0 * r * a + 2.0 * rise / a.sin();
    for x0 in [0.05, 0.05 + 3.0 * p, -0.3] {
        let got = h.sigma(x0 + p).0 - h.sigma(x0).0;
        assert!((got - want).abs() < 1e-15, "{x0}: {got} {want}");
    }
    // ridge in the middle of x = 0.05, groove half a period on; the flank's middle and slope
    assert!((h.h(0.05) - (0.75 - d / 2.0)).abs() < 1e-15);
    assert!((h.h(0.05 + 0.5 * p + 7.0 * p) - (0.75 + d / 2.0)).abs() < 1e-15);
    assert!((h.h(0.05 + 0.25 * p) - 0.75).abs() < 1e-15);
    assert!((h.jet(0.05 + 0.25 * p).1 - a.tan()).abs() < 1e-14);
    assert!((h.jet(0.05 + 0.75 * p).1 + a.tan()).abs() < 1e-14);
    // the arcs' curvature ±1/r at their middles (the ridge's lies between the lands)
    let ridge_arc = 0.05 + land + 0.5 * r * a.sin();
    let (_, s, c) = h.jet(ridge_arc);
    assert!((c / (1.0 + s * s).powf(1.5) - 1.0 / r).abs() < 1e-9, "{c}");
    // mean 0 over a period (the profile's pieces integrated by hand would do; Simpson's error
    // at the curvature's jumps is below 1e-13 here)
    let mean = simpson(0.05, 0.05 + p, 400_000, |x| h.h(x) - 0.75) / p;
    assert!(mean.abs() < 1e-12, "{mean}");
    // C¹: the slope is continuous where the pieces meet
    for u in [
        land,
        land + r * a.sin(),
        0.5 * p - land - r * a.sin(),
        0.5 * p - land,
    ] {
        let x = 0.05 + u;
        let (l, rr) = (h.jet(x - 1e-12).1, h.jet(x + 1e-12).1);
        assert!((l - rr).abs() < 1e-6, "{u}: {l} {rr}");
    }
}

/// The rounded triangle (depth alone, or the flank angle alone) closes the cell without lands:
/// its period's arc length is `4rα + 2·rise/sin α`; the two ways to give it agree; with the
/// trend the arc length is a fine Simpson sum's.
#[test]
fn a_rounded_triangle_and_its_trend() {
    let (p, d, r) = (0.1, 0.012, 0.02);
    let by_depth = height(grating(p, Some(d), None, r), 0.75, 0.0).unwrap();
    // the flank angle of the rounded triangle: the flank's slope at its middle
    let a = by_depth.jet(0.05 + 0.25 * p).1.atan();
    let want = 4.0 * r * a + 2.0 * (d - 2.0 * r * (1.0 - a.cos())) / a.sin();
    let got = by_depth.sigma(0.05 + p).0 - by_depth.sigma(0.05).0;
    assert!((got - want).abs() < 1e-15, "{got} {want}");
    // (p/2) sin α + (2r − D) cos α = 2r
    assert!((0.5 * p * a.sin() + (2.0 * r - d) * a.cos() - 2.0 * r).abs() < 1e-15);
    let by_angle = height(grating(p, None, Some(a), r), 0.75, 0.0).unwrap();
    for x in [0.0, 0.013, 0.07, 0.5] {
        assert!((by_angle.h(x) - by_depth.h(x)).abs() < 1e-14, "{x}");
    }
    // with the trend tan 0.2: the pieces' arc lengths (the arcs by Gauss–Legendre in angle)
    let tilted = height(grating(p, Some(d), None, r), 0.75, 0.2).unwrap();
    let fine = simpson(0.05, 0.05 + p, 2_000_000, speed(&tilted));
    let got = tilted.sigma(0.05 + p).0 - tilted.sigma(0.05).0;
    assert!((got - fine).abs() < 1e-11, "{got} {fine}");
    let fine = simpson(-0.013, 0.21, 2_000_000, speed(&tilted));
    let got = tilted.sigma(0.21).0 - tilted.sigma(-0.013).0;
    assert!((got - fine).abs() < 1e-11, "{got} {fine}");
}

#[test]
fn a_grating_is_refused_with_the_key_to_change() {
    let msg = |p: SurfaceProfile, beta: f64| height(p, 0.75, beta).unwrap_err().to_string();
    // a sharp corner
    assert!(msg(grating(0.1, Some(0.01), None, 0.0), 0.0).starts_with("surface.ridge_radius = 0"));
    // steeper than 45°, alone and with the surface angle
    assert!(msg(grating(0.2, None, Some(0.8), 0.001), 0.0).starts_with("surface.flank_angle"));
    let e = msg(grating(0.2, None, Some(0.7), 0.001), 0.2);
    assert!(
        e.starts_with("surface.flank_angle") && e.contains("1.044998"),
        "{e}"
    );
    // the rounded triangle of this depth is too steep: named by its depth
    assert!(msg(grating(0.05, Some(0.03), None, 0.001), 0.0).starts_with("surface.depth"));
    // too deep for the period at this angle
    assert!(msg(grating(0.05, Some(0.03), Some(0.3), 0.001), 0.0).starts_with("surface.period"));
    // too round for the period
    assert!(msg(grating(0.05, Some(0.01), None, 1.0), 0.0).starts_with("surface.ridge_radius"));
    assert!(msg(grating(0.005, Some(0.001), None, 0.01), 0.0).starts_with("surface.period"));
    assert!(msg(grating(0.1, Some(0.5), None, 0.01), 0.0).starts_with("surface.depth = 0.5"));
    // the rounded triangle of a long period is too deep: 50 tan 0.3 = 15.5
    let e = msg(grating(100.0, None, Some(0.3), 0.01), 0.0);
    assert!(
        e.starts_with("surface.flank_angle = 0.3") && e.contains("15.46"),
        "{e}"
    );
    let e = height(grating(0.1, None, None, 0.01), 0.75, 0.0).unwrap_err();
    assert!(matches!(e, VibrissaError::InvalidTable { .. }), "{e}");
}

/// A file in the system's temporary directory, removed when dropped.
struct TempFile(std::path::PathBuf);

impl TempFile {
    fn new(name: &str, text: &str) -> TempFile {
        let p = std::env::temp_dir().join(format!("vibrissa-{}-{name}", std::process::id()));
        std::fs::write(&p, text).unwrap();
        TempFile(p)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Deterministic noise in [−1, 1] (xorshift).
fn noise(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// Samples of `A sin(2πx/λ + φ)` at uneven spacing (in a shuffled order), plus `eps` noise.
fn sampled_sine(a: f64, w: f64, ph: f64, eps: f64) -> (String, Vec<(f64, f64)>) {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut pts = Vec::new();
    let mut x = -0.6;
    while x < 1.6 {
        let y = a * (TAU * x / w + ph).sin() + eps * noise(&mut seed);
        pts.push((x, y));
        x += 0.002 * (1.0 + 0.5 * noise(&mut seed));
    }
    let mut text = String::from("x,h\n");
    // odd ones first: the file's order does not matter
    for (x, y) in pts.iter().skip(1).step_by(2).chain(pts.iter().step_by(2)) {
        text.push_str(&format!("{x:.17e},{y:.17e}\n"));
    }
    (text, pts)
}

fn measured(f: &TempFile, tolerance: f64) -> SurfaceProfile {
    SurfaceProfile::Measured {
        file: f.0.clone(),
        tolerance,
    }
}

/// A sampled sine read back: within the tolerance of every sample and of the sine between them
/// (the smoothing uses the tolerance: the largest deviation is the tolerance); with the
/// tolerance 0 the spline through the samples, the sine to its interpolation error.
#[test]
fn a_measured_sine_is_the_sine_to_the_tolerance() {
    let (a, w, ph) = (0.01, 0.2, 0.4);
    let (text, pts) = sampled_sine(a, w, ph, 0.0);
    let f = TempFile::new("sine.csv", &text);
    let sine = |x: f64| a * (TAU * x / w + ph).sin();
    for tol in [1e-4, 1e-6, 0.0] {
        let h = height(measured(&f, tol), 0.75, 0.0).unwrap();
        let (lo, hi) = h.domain();
        assert_eq!((lo, hi), (pts[0].0, pts[pts.len() - 1].0));
        let at_samples = pts
            .iter()
            .map(|&(x, y)| (h.h(x) - 0.75 - y).abs())
            .fold(0.0, f64::max);
        let between = (0..=20_000)
            .map(|i| lo + (hi - lo) * f64::from(i) / 20_000.0)
            .map(|x| (h.h(x) - 0.75 - sine(x)).abs())
            .fold(0.0, f64::max);
        if tol > 0.0 {
            assert!(
                at_samples <= tol && at_samples > 0.99 * tol,
                "{tol}: {at_samples}"
            );
            assert!(between <= 1.001 * tol, "{tol}: {between}");
        } else {
            // the natural spline's end conditions (no curvature) cost 1e-6 near the ends
            // (to rounding: h adds η = 0.75, whose ulp is 1.1e-16)
            assert!(at_samples < 2.3e-16, "{at_samples}");
            assert!(between < 2e-6, "{between}");
            let inner = (0..=20_000)
                .map(|i| 0.0 + f64::from(i) / 20_000.0)
                .map(|x| (h.h(x) - 0.75 - sine(x)).abs())
                .fold(0.0, f64::max);
            // a cubic spline's error bound 5/384 h^4 max|f⁗| at the widest spacing 3e-3
            let bound = 5.0 / 384.0 * 0.003f64.powi(4) * a * (TAU / w).powi(4);
            assert!(inner < bound, "{inner} {bound}");
        }
    }
}

/// Noisy samples (±3e-5): the spline through them has curvatures far from the sine's (A k² =
/// 9.87); smoothed to 1e-4 the profile is the sine to 1.3e-4 with its curvature within 10 %.
#[test]
fn a_noisy_measured_profile_is_smoothed() {
    let (a, w, ph) = (0.01, 0.2, 0.4);
    let (text, _) = sampled_sine(a, w, ph, 3e-5);
    let f = TempFile::new("noisy.csv", &text);
    let curvature = |h: &Height| {
        (0..=20_000)
            .map(|i| -0.5 + 2.0 * f64::from(i) / 20_000.0)
            .map(|x| h.jet(x).2.abs())
            .fold(0.0, f64::max)
    };
    let through = height(measured(&f, 0.0), 0.75, 0.0).unwrap();
    let ak2 = a * (TAU / w).powi(2);
    assert!(curvature(&through) > 3.0 * ak2, "{}", curvature(&through));
    let smooth = height(measured(&f, 1e-4), 0.75, 0.0).unwrap();
    assert!(
        (curvature(&smooth) - ak2).abs() < 0.1 * ak2,
        "{}",
        curvature(&smooth)
    );
    let off = (0..=20_000)
        .map(|i| -0.5 + 2.0 * f64::from(i) / 20_000.0)
        .map(|x| (smooth.h(x) - 0.75 - a * (TAU * x / w + ph).sin()).abs())
        .fold(0.0, f64::max);
    assert!(off < 1.3e-4, "{off}");
}

#[test]
fn a_measured_profile_is_refused_with_the_reason() {
    let msg = |text: &str, tol: f64| {
        let f = TempFile::new("bad.csv", text);
        height(measured(&f, tol), 0.75, 0.0)
            .unwrap_err()
            .to_string()
    };
    assert!(msg("0 0\n0.1 0.01\n0.2 0\n", -1.0).starts_with("surface.tolerance = -1"));
    let e = msg("0 0\n0.1 0.01\n0.1 0\n", 0.0);
    assert!(e.contains("x = 0.1 appears twice (lines 2 and 3)"), "{e}");
    let e = msg("0 0\n0.1 0.01\nx 0\n", 0.0);
    assert!(e.contains("line 3"), "{e}");
    // steeper than 45° after smoothing
    let e = msg("0 0\n0.1 0.2\n0.2 0\n0.3 0.2\n", 1e-3);
    assert!(e.contains("slope"), "{e}");
    let e = Height::new(
        &SurfaceProfile::Measured {
            file: "no/such/profile.csv".into(),
            tolerance: 0.0,
        },
        0.75,
        0.0,
    )
    .unwrap_err();
    assert!(
        matches!(e, VibrissaError::InvalidTable { .. }) && e.to_string().contains("cannot read"),
        "{e}"
    );
}

/// The paper's rod (η 0.75, μs 0.5, μk 0.3) dragged over a scene's surface to `d_max`; no
/// point of a row's rod above the profile (1e-8), no stuck row beyond μs.
fn drag_over(p: SurfaceProfile, d_max: f64) -> DragResult {
    let s = Scene {
        surface: p,
        ..Scene::default()
    };
    let (rod, surface) = s.parts().unwrap();
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max,
            points: 21,
            mu_s: Some(0.5),
            mu_k: Some(0.3),
            keep_shapes: Some(201),
            ..DragOptions::default()
        },
    )
    .unwrap();
    let h = surface.profile().unwrap();
    assert_eq!(r.rows.len(), r.shapes.len());
    for (row, shape) in r.rows.iter().zip(&r.shapes) {
        for p in shape {
            let gap = p.y - h.h(p.x + row.d);
            assert!(gap < 1e-8, "d = {}: s = {} is {gap:.3e} above", row.d, p.s);
        }
        if row.phase == Phase::Stick && row.event.is_none() {
            assert!(row.mu.abs() <= row.mu_s + 1e-9, "{row:?}");
        }
    }
    r
}

/// A drag over a sum of sines reaches d_max with stick–slip; over one term the drag is the
/// corrugation's, to the solver's tolerance.
#[test]
fn drag_over_a_sum_of_sines() {
    let r = drag_over(
        SurfaceProfile::Sines {
            amplitude: vec![0.006, 0.002],
            wavelength: vec![0.2, 0.07],
            phase: vec![2.0, 0.5],
        },
        0.2,
    );
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    assert!(r.slips.len() >= 2, "{r}");
    let one = drag_over(
        SurfaceProfile::Sines {
            amplitude: vec![0.01],
            wavelength: vec![0.2],
            phase: vec![2.0],
        },
        0.12,
    );
    let sine = drag_over(
        SurfaceProfile::Sine {
            amplitude: 0.01,
            wavelength: 0.2,
            phase: 2.0,
        },
        0.12,
    );
    assert_eq!(one.slips.len(), sine.slips.len());
    for (p, q) in one.slips.iter().zip(&sine.slips) {
        assert!((p.d - q.d).abs() < 1e-9, "{} {}", p.d, q.d);
    }
}

/// A drag over a grating (a rounded triangle of flank angle 0.12 rad) reaches d_max.
#[test]
fn drag_over_a_grating() {
    let r = drag_over(
        SurfaceProfile::Grating {
            period: 0.2,
            depth: None,
            flank_angle: Some(0.12),
            ridge_radius: 0.05,
            offset: 0.0,
        },
        0.2,
    );
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    assert!(r.slips.len() >= 3, "{r}");
}

/// A drag over a measured profile (the corrugation of `drag_over_a_sum_of_sines` sampled every
/// 2e-3, to 1e-7) reaches d_max and slips where the corrugation's drag does, to 1e-5.
#[test]
fn drag_over_a_measured_profile() {
    let (text, _) = sampled_sine(0.01, 0.2, 2.0, 0.0);
    let f = TempFile::new("drag.csv", &text);
    let r = drag_over(measured(&f, 1e-7), 0.12);
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    let sine = drag_over(
        SurfaceProfile::Sine {
            amplitude: 0.01,
            wavelength: 0.2,
            phase: 2.0,
        },
        0.12,
    );
    assert!(
        r.slips.len() >= 2 && r.slips.len() == sine.slips.len(),
        "{r}"
    );
    for (p, q) in r.slips.iter().zip(&sine.slips) {
        assert!((p.d - q.d).abs() < 1e-5, "{} {}", p.d, q.d);
    }
}
