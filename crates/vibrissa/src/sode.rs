//! A small adaptive DOP853 integrator in the arc length for fixed-size states: the linearized rod
//! of the modes (the rod and three perturbation columns, 22 components) and the reference shapes
//! of the dynamics. Unlike the shooter's fixed meshes (whose point is exact Newton Jacobians of a
//! discrete problem), a characteristic function swept in ω² wants each value to the tolerance
//! with the fewest steps, so the step follows Hairer's controller on the embedded 5th/3rd-order
//! estimates (`rtol = atol = tol`, his error norm, safety 0.9, step ratio in [1/3, 6]).

use bvp::tableau::dop853 as tab;

/// Why an integration stopped short.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SodeError {
    /// The step fell below `1e-14·|b − a|` at `s` (a singular or blowing-up state).
    StepTooSmall { s: f64 },
    /// More than the step budget.
    Budget { s: f64 },
    /// A component became NaN or infinite at `s`.
    NonFinite { s: f64 },
}

impl std::fmt::Display for SodeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SodeError::StepTooSmall { s } => write!(f, "step size underflow at s = {s}"),
            SodeError::Budget { s } => write!(f, "more than 100000 steps (at s = {s})"),
            SodeError::NonFinite { s } => write!(f, "non-finite state at s = {s}"),
        }
    }
}

/// Steps taken and right-hand sides evaluated.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SodeStats {
    pub steps: usize,
    pub rejected: usize,
    pub rhs: usize,
}

/// Integrates `y' = f(s, y)` from `a` to `b` (either direction) from `y0` to `tol`; `record`
/// is called with `(s, y)` at every accepted node (the start included).
pub(crate) fn integrate<const N: usize>(
    f: &mut dyn FnMut(f64, &[f64; N]) -> [f64; N],
    a: f64,
    b: f64,
    y0: [f64; N],
    tol: f64,
    stats: &mut SodeStats,
    record: &mut dyn FnMut(f64, &[f64; N]),
) -> Result<[f64; N], SodeError> {
    let span = b - a;
    let dir = span.signum();
    let mut s = a;
    let mut y = y0;
    record(s, &y);
    if span == 0.0 {
        return Ok(y);
    }
    let mut k0 = f(s, &y);
    stats.rhs += 1;
    let mut h = dir * (span.abs() * 0.01).min(0.05 * span.abs().max(1e-3));
    let hmin = 1e-14 * span.abs();
    for _ in 0..100_000 {
        if (b - s) * dir <= 0.0 {
            return Ok(y);
        }
        if (s + h - b) * dir > 0.0 {
            h = b - s;
        }
        let mut kk = [[0.0; N]; 12];
        kk[0] = k0;
        for st in 1..12 {
            let mut t = y;
            for (j, kj) in kk.iter().enumerate().take(st) {
                let ha = h * tab::A[st * tab::STAGES + j];
                if ha != 0.0 {
                    for c in 0..N {
                        t[c] += ha * kj[c];
                    }
                }
            }
            kk[st] = f(s + tab::C[st] * h, &t);
        }
        stats.rhs += 11;
        let mut ynew = y;
        for (j, kj) in kk.iter().enumerate() {
            let hb = h * tab::B[j];
            if hb != 0.0 {
                for c in 0..N {
                    ynew[c] += hb * kj[c];
                }
            }
        }
        let err = error_norm(tol, &y, &ynew, &kk, h);
        if !ynew.iter().all(|v| v.is_finite()) {
            if h.abs() <= hmin {
                return Err(SodeError::NonFinite { s });
            }
            h *= 0.25;
            stats.rejected += 1;
            continue;
        }
        let fac = if err == 0.0 {
            6.0
        } else {
            (0.9 * err.powf(-1.0 / 8.0)).clamp(1.0 / 3.0, 6.0)
        };
        if err <= 1.0 {
            s += h;
            y = ynew;
            k0 = f(s, &y);
            stats.rhs += 1;
            stats.steps += 1;
            record(s, &y);
            h *= fac;
        } else {
            stats.rejected += 1;
            h *= fac.min(1.0);
            if h.abs() < hmin {
                return Err(SodeError::StepTooSmall { s });
            }
        }
    }
    Err(SodeError::Budget { s })
}

/// Hairer's DOP853 error norm of one step (`rtol = atol = tol`).
fn error_norm<const N: usize>(
    tol: f64,
    y: &[f64; N],
    ynew: &[f64; N],
    kk: &[[f64; N]; 12],
    h: f64,
) -> f64 {
    let (mut e5, mut e3) = (0.0, 0.0);
    for c in 0..N {
        let sk = tol * (1.0 + y[c].abs().max(ynew[c].abs()));
        let (mut a5, mut a3) = (0.0, 0.0);
        for (j, kj) in kk.iter().enumerate() {
            a5 += tab::E5[j] * kj[c];
            a3 += tab::E3[j] * kj[c];
        }
        e5 += (a5 / sk) * (a5 / sk);
        e3 += (a3 / sk) * (a3 / sk);
    }
    let deno = e5 + 0.01 * e3;
    let err = if deno > 0.0 {
        h.abs() * e5 / (N as f64 * deno).sqrt()
    } else {
        0.0
    };
    if err.is_nan() {
        f64::INFINITY
    } else {
        err
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The harmonic oscillator over 10 periods: the end state to the tolerance's order.
    #[test]
    fn harmonic_oscillator() {
        let mut st = SodeStats::default();
        let w = 3.0;
        let t_end = 20.0 * std::f64::consts::PI / w;
        let y = integrate::<2>(
            &mut |_, y| [y[1], -w * w * y[0]],
            0.0,
            t_end,
            [1.0, 0.0],
            1e-12,
            &mut st,
            &mut |_, _| {},
        )
        .unwrap();
        assert!((y[0] - 1.0).abs() < 1e-9 && y[1].abs() < 1e-8, "{y:?}");
        // backwards
        let y = integrate::<2>(
            &mut |_, y| [y[1], -w * w * y[0]],
            t_end,
            0.0,
            [1.0, 0.0],
            1e-12,
            &mut st,
            &mut |_, _| {},
        )
        .unwrap();
        assert!((y[0] - 1.0).abs() < 1e-9, "{y:?}");
    }
}
