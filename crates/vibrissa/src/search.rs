//! One-dimensional searches of the scan (events, the maximum of |μ|), with the caller's error
//! passed through.

/// A root of `f` in `[a, b]` (`f(a)`, `f(b)` of opposite signs or zero) to `tol` in `x`.
pub(crate) fn root(
    f: &mut dyn FnMut(f64) -> Result<f64, String>,
    a: f64,
    b: f64,
    tol: f64,
) -> Result<f64, String> {
    let mut failure = None;
    let r = elastica::roots::try_brent_root(
        |x| {
            f(x).map_err(|e| {
                failure = Some(e);
                elastica::ElasticaError::NotFinite {
                    name: "search",
                    value: x,
                }
            })
        },
        a,
        b,
        tol,
        200,
    );
    r.map_err(|e| failure.unwrap_or_else(|| e.to_string()))
}

/// The maximum of `f` on `[a, b]` to `tol` in `x`: `(x, f(x))`.
pub(crate) fn maximize(
    f: &mut dyn FnMut(f64) -> Result<f64, String>,
    a: f64,
    b: f64,
    tol: f64,
) -> Result<(f64, f64), String> {
    let mut failure = None;
    let r = elastica::roots::try_brent_max(
        |x| {
            f(x).map_err(|e| {
                failure = Some(e);
                elastica::ElasticaError::NotFinite {
                    name: "search",
                    value: x,
                }
            })
        },
        a,
        b,
        tol,
        200,
    );
    r.map_err(|e| failure.unwrap_or_else(|| e.to_string()))
}
