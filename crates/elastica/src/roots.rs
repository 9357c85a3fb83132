//! One-dimensional root finding and maximisation: Brent's methods (root: inverse quadratic
//! interpolation, secant and bisection; maximum: golden section with parabolic interpolation;
//! Brent 1973, ch. 4–5) behind a small interface shared with crate `vibrissa`. The arithmetic is
//! argmin 0.11's `BrentRoot` and `BrentOpt` step for step (the same iterates to the bit, checked
//! against argmin itself in the tests), without argmin's executor, whose per-iteration
//! bookkeeping cost more than a search's function when that is one integration step.
//!
//! The function may fail with the caller's own error type `E`; its first error ends the search and
//! is returned unchanged as [`RootError::Caller`]. Both methods stay inside the bracket, so they
//! cannot wander into a region where the function is undefined; NaN or infinite values are
//! reported as errors, never propagated.

use crate::error::ElasticaError;

/// Why a one-dimensional search failed.
#[derive(Clone, Debug, PartialEq)]
pub enum RootError<E> {
    /// The function itself failed (its first error, unchanged).
    Caller(E),
    /// A bound, the tolerance or a function value is not finite.
    NotFinite {
        /// What is not finite.
        name: &'static str,
        /// At this abscissa (the bound itself for a bound).
        x: f64,
        /// The value.
        value: f64,
    },
    /// `f(a)` and `f(b)` have the same sign: no bracketed root.
    NoBracket {
        /// Left end.
        a: f64,
        /// Right end.
        b: f64,
        /// `f(a)`.
        fa: f64,
        /// `f(b)`.
        fb: f64,
    },
    /// The iteration limit was reached before the bracket was narrow enough.
    NoConvergence {
        /// Iterations spent.
        iterations: u64,
        /// The best abscissa reached.
        x: f64,
    },
    /// The solver stopped for another reason (its message).
    Solver(String),
}

impl<E: std::fmt::Display> std::fmt::Display for RootError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RootError::Caller(e) => write!(f, "{e}"),
            RootError::NotFinite { name, x, value } => {
                write!(f, "{name} is not finite ({value:e} at x = {x:e})")
            }
            RootError::NoBracket { a, b, fa, fb } => write!(
                f,
                "no sign change on [{a:e}, {b:e}] (f = {fa:e} and {fb:e})"
            ),
            RootError::NoConvergence { iterations, x } => {
                write!(
                    f,
                    "no convergence in {iterations} iterations (last x = {x:e})"
                )
            }
            RootError::Solver(m) => write!(f, "{m}"),
        }
    }
}

impl From<RootError<ElasticaError>> for ElasticaError {
    fn from(e: RootError<ElasticaError>) -> Self {
        match e {
            RootError::Caller(e) => e,
            RootError::NotFinite { name, value, .. } => ElasticaError::NotFinite { name, value },
            RootError::NoBracket { a, b, fa, fb } => ElasticaError::NoRoot {
                what: "brent_root",
                a,
                b,
                fa,
                fb,
            },
            RootError::NoConvergence { iterations, .. } => ElasticaError::NoConvergence {
                what: "brent",
                iterations: iterations as usize,
                width: f64::NAN,
            },
            RootError::Solver(_) => ElasticaError::NoConvergence {
                what: "brent",
                iterations: 0,
                width: f64::NAN,
            },
        }
    }
}

fn bounds<E>(a: f64, b: f64, tol: f64) -> Result<(), RootError<E>> {
    for (name, v) in [("a", a), ("b", b), ("tol", tol)] {
        if !v.is_finite() {
            return Err(RootError::NotFinite {
                name,
                x: v,
                value: v,
            });
        }
    }
    Ok(())
}

/// Root of `f` in `[a, b]` (`f(a)`, `f(b)` of opposite signs or one of them zero) to the absolute
/// tolerance `tol` in `x` (the bracket is narrower than about `tol + 4 eps |x|` at the end).
pub fn brent_root<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    tol: f64,
    max_iter: u64,
) -> Result<f64, RootError<E>> {
    bounds(a, b, tol)?;
    let (fa, fb) = (value(&mut f, a)?, value(&mut f, b)?);
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.signum() == fb.signum() {
        return Err(RootError::NoBracket { a, b, fa, fb });
    }
    let mut s = Root::new(a, b, fa, fb, tol.abs());
    // argmin's executor: the best iterate by |f(b)| (strictly better replaces it)
    let mut best = (s.b, s.fb.abs());
    for _ in 0..max_iter {
        let done = s.next(&mut f)?;
        if s.fb.abs() < best.1 {
            best = (s.b, s.fb.abs());
        }
        if done {
            return Ok(best.0);
        }
    }
    Err(RootError::NoConvergence {
        iterations: max_iter,
        x: best.0,
    })
}

/// Brent's root finder, the arithmetic of argmin 0.11's `BrentRoot` step for step (inverse
/// quadratic interpolation, secant, bisection), without its executor's bookkeeping (a state
/// record, a hash map of counts and allocations per iteration: the larger part of a search's
/// cost when the function is a single integration step). The ends' values are those the caller
/// already has (argmin evaluated them a second time).
struct Root {
    tol: f64,
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    e: f64,
    fa: f64,
    fb: f64,
    fc: f64,
}

impl Root {
    fn new(a: f64, b: f64, fa: f64, fb: f64, tol: f64) -> Self {
        Root {
            tol,
            a,
            b,
            c: b,
            d: f64::NAN,
            e: f64::NAN,
            fa,
            fb,
            fc: fb,
        }
    }

    /// One iteration; `true` when converged (`b` is the root).
    fn next<E>(&mut self, f: &mut impl FnMut(f64) -> Result<f64, E>) -> Result<bool, RootError<E>> {
        if (self.fb > 0.0 && self.fc > 0.0) || self.fb < 0.0 && self.fc < 0.0 {
            self.c = self.a;
            self.fc = self.fa;
            self.d = self.b - self.a;
            self.e = self.d;
        }
        if self.fc.abs() < self.fb.abs() {
            self.a = self.b;
            self.b = self.c;
            self.c = self.a;
            self.fa = self.fb;
            self.fb = self.fc;
            self.fc = self.fa;
        }
        let eff_tol = 2.0 * f64::EPSILON * self.b.abs() + 0.5 * self.tol;
        let mid = 0.5 * (self.c - self.b);
        if mid.abs() <= eff_tol || self.fb == 0.0 {
            return Ok(true);
        }
        if self.e.abs() >= eff_tol && self.fa.abs() > self.fb.abs() {
            let s = self.fb / self.fa;
            let (mut p, mut q) = if self.a == self.c {
                (2.0 * mid * s, 1.0 - s)
            } else {
                let q = self.fa / self.fc;
                let r = self.fb / self.fc;
                (
                    s * (2.0 * mid * q * (q - r) - (self.b - self.a) * (r - 1.0)),
                    (q - 1.0) * (r - 1.0) * (s - 1.0),
                )
            };
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let min1 = 3.0 * mid * q - (eff_tol * q).abs();
            let min2 = (self.e * q).abs();
            if 2.0 * p < if min1 < min2 { min1 } else { min2 } {
                self.e = self.d;
                self.d = p / q;
            } else {
                self.d = mid;
                self.e = self.d;
            };
        } else {
            self.d = mid;
            self.e = self.d;
        };
        self.a = self.b;
        self.fa = self.fb;
        if self.d.abs() > eff_tol {
            self.b += self.d;
        } else {
            self.b += if mid >= 0.0 {
                eff_tol.abs()
            } else {
                -eff_tol.abs()
            };
        }
        self.fb = value(f, self.b)?;
        Ok(false)
    }
}

/// Maximum of `f` on `[a, b]`: `(x_max, f(x_max))`, a local maximum (the maximum for a unimodal
/// `f`); the end points are compared too, so a maximum at an end is found. `tol` is the absolute
/// tolerance in `x` (the attainable accuracy is about `sqrt(eps) |x|`, as for any method that
/// uses function values only).
pub fn brent_max<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    tol: f64,
    max_iter: u64,
) -> Result<(f64, f64), RootError<E>> {
    bounds(a, b, tol)?;
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    // the minimizer of −f (argmin's cost −1.0·f: the same bits for finite values)
    let mut g = |x: f64| value(&mut f, x).map(|v| -v);
    let mut s = Opt::new(lo, hi, f64::EPSILON.sqrt(), tol.abs() / 3.0, &mut g)?;
    // argmin's executor: the best iterate by cost (strictly better replaces it)
    let mut best_min = (s.x, s.fx);
    let mut converged = false;
    for _ in 0..max_iter {
        let done = s.next(&mut g)?;
        if s.fx < best_min.1 {
            best_min = (s.x, s.fx);
        }
        if done {
            converged = true;
            break;
        }
    }
    if !converged {
        return Err(RootError::NoConvergence {
            iterations: max_iter,
            x: best_min.0,
        });
    }
    let (mut x, mut best) = (best_min.0, -best_min.1);
    // a maximum at an end point is approached but never evaluated: compare
    for xe in [lo, hi] {
        let fe = value(&mut f, xe)?;
        if fe > best {
            best = fe;
            x = xe;
        }
    }
    Ok((x, best))
}

/// Brent's minimizer, the arithmetic of argmin 0.11's `BrentOpt` step for step (golden section
/// with parabolic interpolation), without its executor's bookkeeping (see [`Root`]).
struct Opt {
    eps: f64,
    t: f64,
    a: f64,
    b: f64,
    v: f64,
    w: f64,
    x: f64,
    fv: f64,
    fw: f64,
    fx: f64,
    e: f64,
    d: f64,
    c: f64,
}

impl Opt {
    /// The first point, `a + c (b − a)` with the golden-section ratio `c`, evaluated.
    fn new<E>(
        a: f64,
        b: f64,
        eps: f64,
        t: f64,
        f: &mut impl FnMut(f64) -> Result<f64, RootError<E>>,
    ) -> Result<Self, RootError<E>> {
        let c = (3f64 - 5f64.sqrt()) / 2f64;
        let u = a + c * (b - a);
        let fu = f(u)?;
        Ok(Opt {
            eps,
            t,
            a,
            b,
            v: u,
            w: u,
            x: u,
            fv: fu,
            fw: fu,
            fx: fu,
            e: 0.0,
            d: 0.0,
            c,
        })
    }

    /// One iteration; `true` when converged (`x` is the minimum).
    fn next<E>(
        &mut self,
        f: &mut impl FnMut(f64) -> Result<f64, RootError<E>>,
    ) -> Result<bool, RootError<E>> {
        let two = 2f64;
        let tol = self.eps * self.x.abs() + self.t;
        let m = (self.a + self.b) / two;
        if (self.x - m).abs() <= two * tol - (self.b - self.a) / two {
            return Ok(true);
        }
        let p = (self.x - self.v) * (self.x - self.v) * (self.fx - self.fw)
            - (self.x - self.w) * (self.x - self.w) * (self.fx - self.fv);
        let q = two
            * ((self.x - self.w) * (self.fx - self.fv) - (self.x - self.v) * (self.fx - self.fw));
        let (p, q) = if q >= 0.0 { (p, q) } else { (-p, -q) };
        self.d = if self.e.abs() <= tol
            || p < q * (self.a - self.x)
            || p > q * (self.b - self.x)
            || two * p.abs() >= q * self.e.abs()
        {
            self.e = if self.x < m { self.b } else { self.a } - self.x;
            self.c * self.e
        } else {
            self.e = self.d;
            let d = p / q;
            if self.x + d - self.a < two * tol || self.b - self.x - d < two * tol {
                (m - self.x).signum() * tol
            } else {
                d
            }
        };
        let u = self.x
            + if self.d.abs() >= tol {
                self.d
            } else {
                self.d.signum() * tol
            };
        let fu = f(u)?;
        if fu <= self.fx {
            if u < self.x {
                self.b = self.x;
            } else {
                self.a = self.x;
            }
            self.v = self.w;
            self.fv = self.fw;
            self.w = self.x;
            self.fw = self.fx;
            self.x = u;
            self.fx = fu;
        } else {
            if u < self.x {
                self.a = u;
            } else {
                self.b = u;
            }
            if fu <= self.fw || self.w == self.x {
                self.v = self.w;
                self.fv = self.fw;
                self.w = u;
                self.fw = fu;
            } else if fu <= self.fv || self.v == self.x || self.v == self.w {
                self.v = u;
                self.fv = fu;
            }
        }
        Ok(false)
    }
}

fn value<E>(f: &mut impl FnMut(f64) -> Result<f64, E>, x: f64) -> Result<f64, RootError<E>> {
    match f(x) {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(RootError::NotFinite {
            name: "f(x)",
            x,
            value: v,
        }),
        Err(e) => Err(RootError::Caller(e)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The caller's own error in these tests: where the function refused.
    #[derive(Clone, Debug, PartialEq)]
    struct BadAt(f64);

    type R = Result<f64, BadAt>;

    /// argmin's Brent methods through its executor, as this module ran them before: the reference
    /// the port must match to the bit (iterates, best point, evaluations).
    mod argmin_ref {
        use argmin::core::{CostFunction, Executor, State, TerminationReason, TerminationStatus};
        use argmin::solver::brent::{BrentOpt, BrentRoot};
        use std::cell::RefCell;

        struct Cost<'f> {
            f: RefCell<&'f mut dyn FnMut(f64) -> f64>,
            sign: f64,
        }

        impl CostFunction for Cost<'_> {
            type Param = f64;
            type Output = f64;
            fn cost(&self, x: &f64) -> Result<f64, argmin::core::Error> {
                Ok(self.sign * (self.f.borrow_mut())(*x))
            }
        }

        fn best<S>(
            r: argmin::core::OptimizationResult<
                Cost<'_>,
                S,
                argmin::core::IterState<f64, (), (), (), (), f64>,
            >,
        ) -> Option<(f64, f64)> {
            let st = r.state();
            let ok = st.get_termination_status()
                == &TerminationStatus::Terminated(TerminationReason::SolverConverged);
            ok.then(|| (*st.get_best_param().unwrap(), st.get_best_cost()))
        }

        /// The root (the bracket's signs checked by the caller).
        pub fn root(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> Option<f64> {
            let cost = Cost {
                f: RefCell::new(f),
                sign: 1.0,
            };
            let r = Executor::new(cost, BrentRoot::new(a, b, tol))
                .configure(|s| s.param(b).max_iters(200))
                .run()
                .ok()?;
            best(r).map(|(x, _)| x)
        }

        /// The minimum of `−f` (before the end points are compared).
        pub fn max(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> Option<(f64, f64)> {
            let cost = Cost {
                f: RefCell::new(f),
                sign: -1.0,
            };
            let solver = BrentOpt::new(a, b).set_tolerance(f64::EPSILON.sqrt(), tol / 3.0);
            let r = Executor::new(cost, solver)
                .configure(|s| s.max_iters(200))
                .run()
                .ok()?;
            best(r).map(|(x, c)| (x, -c))
        }
    }

    /// The port returns argmin's iterates to the bit: the same root, maximum and sequence of
    /// evaluated points (argmin evaluated the bracket's ends twice), on smooth functions, a jump,
    /// a flat stretch and noise at the rounding level.
    #[test]
    fn same_bits_as_argmin() {
        type F = fn(f64) -> f64;
        let fs: [(F, f64, f64); 7] = [
            (|x| x * x * x - 2.0, 0.0, 2.0),
            (|x| (3.0 * x).sin() - 0.2, -0.4, 0.9),
            (|x| if x < 0.3172 { -0.75 } else { 1e-10 }, 0.0, 1.0),
            (|x| (x - 0.5).max(0.0) - 1e-3, 0.0, 2.0),
            (|x| (x - 0.1).powi(3) + 1e-17 * (1e9 * x).sin(), -1.0, 1.0),
            (|x| (x * 40.0).tanh() - 0.999, 0.0, 1.0),
            (|x| x.exp() - 10.0, 0.0, 1.0e3_f64.ln()),
        ];
        for (f, a, b) in fs {
            for tol in [1e-15, 1e-13, 1e-8, 1e-3] {
                let mut seen = Vec::new();
                let got = brent_root(
                    |x| {
                        seen.push(x);
                        R::Ok(f(x))
                    },
                    a,
                    b,
                    tol,
                    200,
                )
                .unwrap();
                let mut theirs = vec![a, b];
                let want = argmin_ref::root(
                    &mut |x| {
                        theirs.push(x);
                        f(x)
                    },
                    a,
                    b,
                    tol,
                )
                .unwrap();
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "root on [{a}, {b}], tol {tol}"
                );
                assert_eq!(seen, [&theirs[..2], &theirs[4..]].concat());
            }
        }
        let gs: [(F, f64, f64); 5] = [
            (|x| (x - 0.3).cos(), -1.0, 2.0),
            (|x| -(x - 0.7).abs(), 0.0, 1.0),
            (|x| if x < 0.4 { x } else { 0.4 - 1e-12 * x }, 0.0, 1.0),
            (
                |x| -((x - 0.25) * (x - 0.25)) + 1e-16 * (1e7 * x).sin(),
                0.0,
                0.5,
            ),
            (|x| x, 0.0, 1.0),
        ];
        for (g, a, b) in gs {
            for tol in [1e-12, 1e-6, 1e-2] {
                let mut seen = Vec::new();
                let mut theirs = Vec::new();
                let want = argmin_ref::max(
                    &mut |x| {
                        theirs.push(x);
                        g(x)
                    },
                    a,
                    b,
                    tol,
                )
                .unwrap();
                let got = brent_max(
                    |x| {
                        seen.push(x);
                        R::Ok(g(x))
                    },
                    a,
                    b,
                    tol,
                    200,
                )
                .unwrap();
                // (the port then compares the two end points)
                assert_eq!(&seen[..seen.len() - 2], &theirs[..]);
                let mut best = want;
                for xe in [a, b] {
                    if g(xe) > best.1 {
                        best = (xe, g(xe));
                    }
                }
                assert_eq!(
                    got.0.to_bits(),
                    best.0.to_bits(),
                    "max on [{a}, {b}], tol {tol}"
                );
                assert_eq!(got.1.to_bits(), best.1.to_bits());
            }
        }
    }

    #[test]
    fn root_of_cubic() {
        let r = brent_root(|x| R::Ok(x * x * x - 2.0), 0.0, 2.0, 1e-15, 100).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-15);
    }

    #[test]
    fn root_needs_sign_change_and_finite_values() {
        let e = brent_root(|x| R::Ok(x * x + 1.0), -1.0, 1.0, 1e-12, 100).unwrap_err();
        assert!(matches!(e, RootError::NoBracket { .. }));
        let e = brent_root(|_| R::Ok(f64::NAN), -1.0, 1.0, 1e-12, 100).unwrap_err();
        assert!(matches!(e, RootError::NotFinite { .. }));
    }

    #[test]
    fn the_callers_error_comes_back_unchanged() {
        let e = brent_root(
            |x| {
                if x > 0.5 {
                    Err(BadAt(x))
                } else {
                    Ok(x - 0.7)
                }
            },
            0.0,
            0.4,
            1e-12,
            100,
        )
        .unwrap_err();
        assert!(matches!(e, RootError::NoBracket { .. }), "{e:?}");
        let e = brent_root(
            |x| {
                if x > 0.9 {
                    Err(BadAt(x))
                } else {
                    Ok(x - 0.2)
                }
            },
            0.0,
            0.8,
            1e-12,
            100,
        );
        assert!((e.unwrap() - 0.2).abs() < 1e-12);
        let e = brent_root(
            |x| {
                if (0.3..0.9).contains(&x) {
                    Err(BadAt(x))
                } else {
                    Ok(x - 0.5)
                }
            },
            0.0,
            1.0,
            1e-12,
            100,
        )
        .unwrap_err();
        assert!(
            matches!(&e, RootError::Caller(BadAt(x)) if (0.3..0.9).contains(x)),
            "{e:?}"
        );
    }

    #[test]
    fn max_of_smooth_function() {
        let (x, fx) = brent_max(|x| R::Ok((x - 0.3f64).cos()), -1.0, 2.0, 1e-12, 200).unwrap();
        assert!((x - 0.3).abs() < 1e-7, "{x}");
        assert!((fx - 1.0).abs() < 1e-14);
        // maximum at an end point
        let (x, _) = brent_max(R::Ok, 0.0, 1.0, 1e-12, 200).unwrap();
        assert_eq!(x, 1.0);
    }
}
