//! One-dimensional root finding and maximisation (Brent's methods), reused by crate `vibrissa`.
//!
//! Both work on a bracket and never leave it, so they cannot wander into a region where the
//! function is undefined. NaN function values are reported as errors, never propagated.

use crate::error::{finite, ElasticaError};

/// Root of `f` in `[a, b]` by Brent's method (inverse quadratic interpolation, secant and
/// bisection; Brent 1973, ch. 4). Needs `f(a)` and `f(b)` of opposite sign (or one of them zero).
/// Stops when the bracket is narrower than `2 (4 eps |x| + tol)`.
pub fn brent_root<F: FnMut(f64) -> f64>(
    mut f: F,
    a: f64,
    b: f64,
    tol: f64,
    max_iter: usize,
) -> Result<f64, ElasticaError> {
    try_brent_root(|x| Ok(f(x)), a, b, tol, max_iter)
}

/// As [`brent_root`] for a fallible function: the first error of `f` is returned as is.
pub fn try_brent_root<F: FnMut(f64) -> Result<f64, ElasticaError>>(
    mut f: F,
    a: f64,
    b: f64,
    tol: f64,
    max_iter: usize,
) -> Result<f64, ElasticaError> {
    finite("a", a)?;
    finite("b", b)?;
    let tol = finite("tol", tol)?.abs();
    let (mut a, mut b) = (a, b);
    let mut fa = finite("f(a)", f(a)?)?;
    let mut fb = finite("f(b)", f(b)?)?;
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.signum() == fb.signum() {
        return Err(ElasticaError::NoRoot {
            what: "brent_root",
            a,
            b,
            fa,
            fb,
        });
    }
    let (mut c, mut fc) = (a, fa);
    let (mut d, mut e) = (b - a, b - a);
    for _ in 0..max_iter {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            // inverse quadratic interpolation (or secant when a == c)
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let min1 = 3.0 * xm * q - (tol1 * q).abs();
            let min2 = (e * q).abs();
            if 2.0 * p < min1.min(min2) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = finite("f(x)", f(b)?)?;
    }
    Err(ElasticaError::NoConvergence {
        what: "brent_root",
        iterations: max_iter,
        width: (c - b).abs(),
    })
}

/// Maximum of `f` on `[a, b]` by Brent's method (golden section plus parabolic interpolation;
/// Brent 1973, ch. 5), returning `(x_max, f(x_max))`. Finds a local maximum; for a unimodal `f` it
/// is the maximum. The end points are compared too, so a maximum at an end of the interval is
/// found. `tol` is the absolute tolerance in `x` (the attainable accuracy is about
/// `sqrt(eps) |x|`, as for any method that uses function values only).
pub fn brent_max<F: FnMut(f64) -> f64>(
    mut f: F,
    a: f64,
    b: f64,
    tol: f64,
    max_iter: usize,
) -> Result<(f64, f64), ElasticaError> {
    try_brent_max(|x| Ok(f(x)), a, b, tol, max_iter)
}

/// As [`brent_max`] for a fallible function.
pub fn try_brent_max<F: FnMut(f64) -> Result<f64, ElasticaError>>(
    mut f: F,
    a: f64,
    b: f64,
    tol: f64,
    max_iter: usize,
) -> Result<(f64, f64), ElasticaError> {
    finite("a", a)?;
    finite("b", b)?;
    let tol = finite("tol", tol)?.abs();
    let (mut a, mut b) = if a <= b { (a, b) } else { (b, a) };
    let (a0, b0) = (a, b);
    // minimise g = -f
    let mut g = |x: f64| -> Result<f64, ElasticaError> { Ok(-finite("f(x)", f(x)?)?) };
    const CGOLD: f64 = 0.381_966_011_250_105_1;
    let mut x = a + CGOLD * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = g(x)?;
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    let mut converged = false;
    for _ in 0..max_iter {
        let xm = 0.5 * (a + b);
        let tol1 = f64::EPSILON.sqrt() * x.abs() + tol / 3.0;
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            converged = true;
            break;
        }
        let mut golden = true;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let etemp = e;
            if p.abs() < (0.5 * q * etemp).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = tol1.copysign(xm - x);
                }
                golden = false;
            }
        }
        if golden {
            e = if x >= xm { a - x } else { b - x };
            d = CGOLD * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else {
            x + tol1.copysign(d)
        };
        let fu = g(u)?;
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            v = w;
            fv = fw;
            w = x;
            fw = fx;
            x = u;
            fx = fu;
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                v = w;
                fv = fw;
                w = u;
                fw = fu;
            } else if fu <= fv || v == x || v == w {
                v = u;
                fv = fu;
            }
        }
    }
    if !converged {
        return Err(ElasticaError::NoConvergence {
            what: "brent_max",
            iterations: max_iter,
            width: b - a,
        });
    }
    // a maximum at an end point of the interval is approached but never evaluated: compare
    let (mut best_x, mut best) = (x, -fx);
    for xe in [a0, b0] {
        let fe = -g(xe)?;
        if fe > best {
            best = fe;
            best_x = xe;
        }
    }
    Ok((best_x, best))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn root_of_cubic() {
        let r = brent_root(|x| x * x * x - 2.0, 0.0, 2.0, 1e-15, 100).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-15);
    }

    #[test]
    fn root_needs_sign_change() {
        let e = brent_root(|x| x * x + 1.0, -1.0, 1.0, 1e-12, 100).unwrap_err();
        assert!(matches!(e, ElasticaError::NoRoot { .. }));
        let e = brent_root(|_| f64::NAN, -1.0, 1.0, 1e-12, 100).unwrap_err();
        assert!(matches!(e, ElasticaError::NotFinite { .. }));
    }

    #[test]
    fn max_of_smooth_function() {
        let (x, fx) = brent_max(|x| (x - 0.3f64).cos(), -1.0, 2.0, 1e-12, 200).unwrap();
        assert!((x - 0.3).abs() < 1e-7, "{x}");
        assert!((fx - 1.0).abs() < 1e-14);
        // maximum at an end point
        let (x, _) = brent_max(|x| x, 0.0, 1.0, 1e-12, 200).unwrap();
        assert_eq!(x, 1.0);
    }
}
