//! The synthetic noisy traces of `fit`'s checks, shared by `tests/fit.rs` and
//! `examples/fit_stats.rs`: Gaussian noise on the slip places (σ = 2e-4) and on `fx`, `m_base`
//! before and `fx` after each slip (σ = 2e-3); and the corrugated sample of issue 31's texture
//! read-back ([`texture_trace`]).

use vibrissa::fit::{FitResult, Trace, TraceSlip};
use vibrissa::{drag, DragOptions, DragResult, Scene};

/// A fit of a noisy trace of the paper's coefficients (the trace of `seed`): no message, and μs
/// 0.5 and μk 0.3 each within 3 standard errors, the standard errors in (0, 1e-3).
#[allow(dead_code)] // (the tests' check; examples/fit_stats.rs counts the coverage instead)
pub fn within_three_standard_errors(f: &FitResult, seed: u64) {
    assert!(f.message.is_none(), "{f}");
    for (name, want) in [("mu_s", 0.5), ("mu_k", 0.3)] {
        let p = f.get(name).unwrap();
        let se = p.std_error.unwrap();
        assert!(se > 0.0 && se < 1e-3, "{f}");
        assert!((p.value - want).abs() <= 3.0 * se, "seed {seed}: {f}");
    }
}

/// A scene whose surface is the corrugation `A sin(2πx/W + P)` (the paper's rod at η = 0.75).
pub fn corrugated(amplitude: f64, wavelength: f64, phase: f64) -> Scene {
    Scene {
        surface: vibrissa::surface::SurfaceProfile::Sine {
            amplitude,
            wavelength,
            phase,
        },
        ..Scene::default()
    }
}

/// The parameters of the texture read-back and their true values.
pub const TEXTURE_TRUTH: [(&str, f64); 5] = [
    ("mu_s", 0.5),
    ("mu_k", 0.3),
    ("amplitude", 0.005),
    ("wavelength", 0.1),
    ("phase", 0.7),
];

/// The texture read-back's drag: [`TEXTURE_TRUTH`]'s corrugation and coefficients, through its
/// first `slips` slips.
pub fn texture_trace(slips: usize) -> DragResult {
    let (rod, surface) = corrugated(0.005, 0.1, 0.7).parts().expect("scene");
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max: 1.0,
            points: 2,
            mu_s: Some(0.5),
            mu_k: Some(0.3),
            max_slips: slips,
            ..DragOptions::default()
        },
    )
    .expect("drag");
    assert_eq!(r.slips.len(), slips, "{r}");
    r
}

/// splitmix64 and Box–Muller: a seeded normal sampler without dependencies.
pub struct Rng(pub u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A standard normal sample.
    pub fn normal(&mut self) -> f64 {
        let (a, b) = (self.uniform().max(1e-300), self.uniform());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

/// The noise levels of `d`, `fx`, `fy`, `m_base` (`fy` unused), as `FitOptions::sigma`.
pub const SIGMA: [f64; 4] = [2e-4, 2e-3, 2e-3, 2e-3];

/// The first `n` slips of `r` with noise.
pub fn noisy(r: &DragResult, n: usize, rng: &mut Rng) -> Trace {
    with_noise(r, n, |sigma| sigma * rng.normal())
}

/// The first `n` slips of `r` without noise (the same observations as [`noisy`]).
#[allow(dead_code)] // (examples/fit_stats.rs)
pub fn exact(r: &DragResult, n: usize) -> Trace {
    with_noise(r, n, |_| 0.0)
}

/// Only the places of the slips of `t`.
pub fn places_only(t: &Trace) -> Trace {
    Trace {
        tips: Vec::new(),
        motion: Default::default(),
        slips: t
            .slips
            .iter()
            .map(|s| TraceSlip {
                d: s.d,
                ..TraceSlip::default()
            })
            .collect(),
    }
}

/// The first `n` slips of `r`, each observation plus `noise(its σ)` (drawn in the order d, `fx`
/// and `m_base` before, `fx` after).
fn with_noise(r: &DragResult, n: usize, mut noise: impl FnMut(f64) -> f64) -> Trace {
    let (sd, sf) = (SIGMA[0], SIGMA[1]);
    Trace {
        tips: Vec::new(),
        motion: Default::default(),
        slips: r.slips[..n]
            .iter()
            .map(|e| TraceSlip {
                d: e.d + noise(sd),
                before: [
                    Some(e.before.fx + noise(sf)),
                    None,
                    Some(e.before.m_base + noise(sf)),
                ],
                after: [Some(e.after.fx + noise(sf)), None, None],
            })
            .collect(),
    }
}
