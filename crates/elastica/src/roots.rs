//! One-dimensional root finding and maximisation: argmin's Brent methods (`BrentRoot`: inverse
//! quadratic interpolation, secant and bisection; `BrentOpt`: golden section with parabolic
//! interpolation; Brent 1973, ch. 4–5) behind a small interface shared with crate `vibrissa`.
//!
//! The function may fail with the caller's own error type `E`; its first error ends the search and
//! is returned unchanged as [`RootError::Caller`]. Both methods stay inside the bracket, so they
//! cannot wander into a region where the function is undefined; NaN or infinite values are
//! reported as errors, never propagated.

use crate::error::ElasticaError;
use argmin::core::{CostFunction, Executor, State, TerminationReason, TerminationStatus};
use argmin::solver::brent::{BrentOpt, BrentRoot};
use std::cell::RefCell;

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
    /// The solver stopped for another reason (argmin's message).
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

/// The caller's function as an argmin cost; its first failure is kept for the caller, and argmin
/// sees an error that ends the run.
struct Cost<'f, E> {
    f: RefCell<&'f mut dyn FnMut(f64) -> Result<f64, E>>,
    sign: f64,
    failure: &'f RefCell<Option<RootError<E>>>,
}

#[derive(Debug)]
struct Stop;

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("the function failed")
    }
}

impl std::error::Error for Stop {}

impl<E> CostFunction for Cost<'_, E> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, x: &f64) -> Result<f64, argmin::core::Error> {
        let r = (self.f.borrow_mut())(*x);
        let fail = match r {
            Ok(v) if v.is_finite() => return Ok(self.sign * v),
            Ok(v) => RootError::NotFinite {
                name: "f(x)",
                x: *x,
                value: v,
            },
            Err(e) => RootError::Caller(e),
        };
        self.failure.borrow_mut().get_or_insert(fail);
        Err(Stop.into())
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
    let failure = RefCell::new(None);
    let cost = Cost {
        f: RefCell::new(&mut f),
        sign: 1.0,
        failure: &failure,
    };
    let solver = BrentRoot::new(a, b, tol.abs());
    let res = Executor::new(cost, solver)
        .configure(|s| s.param(b).max_iters(max_iter))
        .run();
    finish(res, &failure, max_iter).map(|(x, _)| x)
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
    let failure = RefCell::new(None);
    let cost = Cost {
        f: RefCell::new(&mut f),
        sign: -1.0,
        failure: &failure,
    };
    let solver = BrentOpt::new(lo, hi).set_tolerance(f64::EPSILON.sqrt(), tol.abs() / 3.0);
    let res = Executor::new(cost, solver)
        .configure(|s| s.max_iters(max_iter))
        .run();
    let (mut x, mut best) = finish(res, &failure, max_iter)?;
    best = -best;
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

type Run<'f, E, S> = Result<
    argmin::core::OptimizationResult<
        Cost<'f, E>,
        S,
        argmin::core::IterState<f64, (), (), (), (), f64>,
    >,
    argmin::core::Error,
>;

/// The solution `(x, cost)` of a run, or why there is none (the caller's error first).
fn finish<E, S>(
    res: Run<'_, E, S>,
    failure: &RefCell<Option<RootError<E>>>,
    max_iter: u64,
) -> Result<(f64, f64), RootError<E>> {
    match res {
        Ok(r) => {
            let st = r.state();
            let x = st.get_best_param().copied().unwrap_or(f64::NAN);
            let c = st.get_best_cost();
            match st.get_termination_status() {
                TerminationStatus::Terminated(TerminationReason::SolverConverged) => Ok((x, c)),
                TerminationStatus::Terminated(TerminationReason::MaxItersReached) => {
                    Err(RootError::NoConvergence {
                        iterations: max_iter,
                        x,
                    })
                }
                other => Err(RootError::Solver(format!("{other:?}"))),
            }
        }
        // the cost function kept the reason for its own error
        Err(e) => Err(failure
            .borrow_mut()
            .take()
            .unwrap_or_else(|| RootError::Solver(e.to_string()))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The caller's own error in these tests: where the function refused.
    #[derive(Clone, Debug, PartialEq)]
    struct BadAt(f64);

    type R = Result<f64, BadAt>;

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
