//! The synthetic noisy traces of `fit`'s checks, shared by `tests/fit.rs` and
//! `examples/fit_stats.rs`: Gaussian noise on the slip places (σ = 2e-4) and on `fx`, `m_base`
//! before and `fx` after each slip (σ = 2e-3).

use vibrissa::fit::{Trace, TraceSlip};
use vibrissa::DragResult;

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
    let (sd, sf) = (SIGMA[0], SIGMA[1]);
    Trace {
        slips: r.slips[..n]
            .iter()
            .map(|e| TraceSlip {
                d: e.d + sd * rng.normal(),
                before: [
                    Some(e.before.fx + sf * rng.normal()),
                    None,
                    Some(e.before.m_base + sf * rng.normal()),
                ],
                after: [Some(e.after.fx + sf * rng.normal()), None, None],
            })
            .collect(),
    }
}
