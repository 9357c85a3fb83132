//! One-dimensional searches of the scan (events, the maximum of |μ|, folds): argmin's Brent
//! methods through [`elastica::roots`], with the caller's solver error passed through unchanged.

use elastica::roots::{brent_max, brent_root};

/// A root of `f` in `[a, b]` (`f(a)`, `f(b)` of opposite signs or zero) to `tol` in `x`.
pub(crate) fn root(
    f: &mut dyn FnMut(f64) -> Result<f64, String>,
    a: f64,
    b: f64,
    tol: f64,
) -> Result<f64, String> {
    brent_root(f, a, b, tol, 200).map_err(|e| e.to_string())
}

/// The maximum of `f` on `[a, b]` to `tol` in `x`: `(x, f(x))`.
pub(crate) fn maximize(
    f: &mut dyn FnMut(f64) -> Result<f64, String>,
    a: f64,
    b: f64,
    tol: f64,
) -> Result<(f64, f64), String> {
    brent_max(f, a, b, tol, 200).map_err(|e| e.to_string())
}
