//! One-dimensional searches of the marches (events, the maximum of |μ|, folds): Brent's methods
//! of [`elastica::roots`] (argmin's arithmetic without its executor), with the caller's own error
//! type passed through unchanged ([`RootError::Caller`]).

use elastica::roots::{brent_max, brent_root};

pub(crate) use elastica::roots::RootError;

/// Iterations of either search before it gives up (Brent's root finder needs ~40 for a bracket
/// of 1 to 1e-15; the minimizer's golden sections ~75).
const MAX_ITER: u64 = 200;

/// A root of `f` in `[a, b]` (`f(a)`, `f(b)` of opposite signs or zero) to `tol` in `x`.
pub(crate) fn root<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    tol: f64,
) -> Result<f64, RootError<E>> {
    brent_root(f, a, b, tol, MAX_ITER)
}

/// The maximum of `f` on `[a, b]` to `tol` in `x`: `(x, f(x))`.
pub(crate) fn maximize<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    tol: f64,
) -> Result<(f64, f64), RootError<E>> {
    brent_max(f, a, b, tol, MAX_ITER)
}
