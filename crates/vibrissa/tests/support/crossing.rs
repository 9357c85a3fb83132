//! The period of a free oscillation read off its samples (the example `free_oscillation` and the
//! bench `dynamics`).

use vibrissa::dynamics::DynamicsResult;

/// The first upward zero crossing of the tip's x after `after`, by cubic Hermite interpolation
/// with the tip's velocity; NaN if there is none.
pub fn upward_crossing(r: &DynamicsResult, after: f64) -> f64 {
    for w in r.samples.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if a.t > after && a.tip_x < 0.0 && b.tip_x >= 0.0 {
            let h = b.t - a.t;
            let p = |u: f64| {
                let (u2, u3) = (u * u, u * u * u);
                (2.0 * u3 - 3.0 * u2 + 1.0) * a.tip_x
                    + (u3 - 2.0 * u2 + u) * h * a.tip_vx
                    + (-2.0 * u3 + 3.0 * u2) * b.tip_x
                    + (u3 - u2) * h * b.tip_vx
            };
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..100 {
                let m = 0.5 * (lo + hi);
                if p(m) < 0.0 {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            return a.t + 0.5 * (lo + hi) * h;
        }
    }
    f64::NAN
}
