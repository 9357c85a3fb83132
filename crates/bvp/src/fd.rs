//! Finite-difference Jacobians (the default when a problem has no analytic ones).
//!
//! # Steps
//!
//! For a variable `x_j` the increment is
//!
//! ```text
//!     forward:  h_j = √ε · max(|x_j|, 1)      J[:, j] ≈ (f(x + h_j e_j) − f(x)) / h_j          error O(√ε)
//!     central:  h_j = ∛ε · max(|x_j|, 1)      J[:, j] ≈ (f(x + h_j e_j) − f(x − h_j e_j)) / 2h_j  error O(ε^⅔)
//! ```
//!
//! with `h_j` rounded so that `x_j + h_j` is exactly representable (`h = (x + h) − x`). Forward
//! differences cost one evaluation per column (plus `f(x)`, which callers usually have); central
//! ones two, but are about 1000× more accurate (≈ 1e-11 relative vs 1e-8).
//!
//! # Functions
//!
//! - [`jacobian`]: generic `m × N` Jacobian of a closure `f(x, out)`;
//! - [`rhs_jacobian_fd`], [`bc_jacobian_fd`]: `∂F/∂z, ∂F/∂p` and `∂g/∂z(a), ∂g/∂z(b), ∂g/∂p` of a
//!   [`Bvp`] (row-major, the layout of [`Bvp::rhs_jacobian`]);
//! - [`rhs_jacobian_or_fd`], [`bc_jacobian_or_fd`]: the analytic Jacobian when the problem
//!   provides it, else finite differences; they count evaluations in [`Stats`] and check the
//!   output for NaN/∞ ([`BvpError::NonFinite`] with location `"jacobian"`).
//!
//! All work vectors live in [`FdScratch`], so these functions do not allocate.

use crate::{Bvp, BvpError, Dims, Stats};

/// Finite-difference formula.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub enum FdScheme {
    /// One-sided, step `√ε · max(|x|, 1)`.
    Forward,
    /// Central, step `∛ε · max(|x|, 1)`. The default.
    #[default]
    Central,
}

impl FdScheme {
    /// The increment for variable value `x` (exactly representable: `(x + h) − x == h`).
    pub fn step(self, x: f64) -> f64 {
        let base = match self {
            FdScheme::Forward => f64::EPSILON.sqrt(),
            FdScheme::Central => f64::EPSILON.cbrt(),
        };
        let h = base * x.abs().max(1.0);
        (x + h) - x
    }
}

/// Work vectors for the finite-difference routines (sized for one problem's [`Dims`]).
#[derive(Clone, Debug, Default)]
pub struct FdScratch {
    /// The formula used. Default [`FdScheme::Central`].
    pub scheme: FdScheme,
    x: Vec<f64>,
    y: Vec<f64>,
    q: Vec<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
    f2: Vec<f64>,
}

impl FdScratch {
    /// Scratch for a problem with `dims` (central differences).
    pub fn new(dims: Dims) -> Self {
        let mut s = FdScratch::default();
        s.resize(dims);
        s
    }

    /// Same, with the given scheme.
    pub fn with_scheme(dims: Dims, scheme: FdScheme) -> Self {
        let mut s = Self::new(dims);
        s.scheme = scheme;
        s
    }

    /// Resizes for `dims` (allocates only when growing).
    pub fn resize(&mut self, dims: Dims) {
        let (n, k) = (dims.n, dims.k);
        let m = n + k;
        for (v, len) in [
            (&mut self.x, n),
            (&mut self.y, n),
            (&mut self.q, k),
            (&mut self.f0, m),
            (&mut self.f1, m),
            (&mut self.f2, m),
        ] {
            v.clear();
            v.resize(len, 0.0);
        }
    }
}

/// Generic Jacobian `jac[i * nx + j] = ∂f_i/∂x_j` of `f: R^nx → R^m` (`m = fx.len()`).
///
/// `x` is perturbed in place and restored exactly. For [`FdScheme::Forward`], `fx` must hold
/// `f(x)`; for central it is only used as the length `m` and as scratch for `f(x − h)`. `work`
/// must have length `m`. Returns the number of evaluations of `f`.
pub fn jacobian(
    mut f: impl FnMut(&[f64], &mut [f64]),
    x: &mut [f64],
    fx: &mut [f64],
    scheme: FdScheme,
    jac: &mut [f64],
    work: &mut [f64],
) -> usize {
    let nx = x.len();
    let m = fx.len();
    let mut evals = 0;
    for j in 0..nx {
        let xj = x[j];
        let h = scheme.step(xj);
        x[j] = xj + h;
        f(x, work);
        evals += 1;
        match scheme {
            FdScheme::Forward => {
                x[j] = xj;
                for i in 0..m {
                    jac[i * nx + j] = (work[i] - fx[i]) / h;
                }
            }
            FdScheme::Central => {
                let hm = xj - (xj - h);
                x[j] = xj - hm;
                f(x, fx);
                evals += 1;
                x[j] = xj;
                for i in 0..m {
                    jac[i * nx + j] = (work[i] - fx[i]) / (h + hm);
                }
            }
        }
    }
    evals
}

/// `∂F/∂z` (n×n) and `∂F/∂p` (n×k) at `(s, z, p)` by finite differences. `f0` = `F(s, z, p)` is
/// needed for the forward scheme (pass `None` to have it computed). Returns the number of
/// right-hand-side evaluations.
#[allow(clippy::too_many_arguments)]
pub fn rhs_jacobian_fd<P: Bvp + ?Sized>(
    problem: &P,
    s: f64,
    z: &[f64],
    p: &[f64],
    f0: Option<&[f64]>,
    dfdz: &mut [f64],
    dfdp: &mut [f64],
    scratch: &mut FdScratch,
) -> usize {
    let Dims { n, k } = problem.dims();
    let scheme = scratch.scheme;
    let FdScratch {
        x, q, f0: fb, f1, ..
    } = scratch;
    let (x, q, fb, f1) = (&mut x[..n], &mut q[..k], &mut fb[..n], &mut f1[..n]);
    x.copy_from_slice(z);
    q.copy_from_slice(p);
    let mut evals = 0;
    if scheme == FdScheme::Forward {
        match f0 {
            Some(f) => fb.copy_from_slice(&f[..n]),
            None => {
                problem.rhs(s, x, q, fb);
                evals += 1;
            }
        }
    }
    evals += jacobian(
        |xx, out| problem.rhs(s, xx, q, out),
        x,
        fb,
        scheme,
        dfdz,
        f1,
    );
    if k > 0 {
        // Forward: `fb` still holds F(s, z, p); central only used it as scratch.
        evals += jacobian(
            |qq, out| problem.rhs(s, x, qq, out),
            q,
            fb,
            scheme,
            dfdp,
            f1,
        );
    }
    evals
}

/// `∂g/∂z(a)`, `∂g/∂z(b)` ((n+k)×n each) and `∂g/∂p` ((n+k)×k) by finite differences. `g0` =
/// `g(za, zb, p)` is needed for the forward scheme (`None`: computed). Returns the number of
/// boundary-condition evaluations.
#[allow(clippy::too_many_arguments)]
pub fn bc_jacobian_fd<P: Bvp + ?Sized>(
    problem: &P,
    za: &[f64],
    zb: &[f64],
    p: &[f64],
    g0: Option<&[f64]>,
    dga: &mut [f64],
    dgb: &mut [f64],
    dgp: &mut [f64],
    scratch: &mut FdScratch,
) -> usize {
    let Dims { n, k } = problem.dims();
    let m = n + k;
    let scheme = scratch.scheme;
    let FdScratch {
        x,
        y,
        q,
        f0: gb,
        f1,
        ..
    } = scratch;
    let (x, y, q, gb, f1) = (
        &mut x[..n],
        &mut y[..n],
        &mut q[..k],
        &mut gb[..m],
        &mut f1[..m],
    );
    x.copy_from_slice(za);
    y.copy_from_slice(zb);
    q.copy_from_slice(p);
    let mut evals = 0;
    if scheme == FdScheme::Forward {
        match g0 {
            Some(g) => gb.copy_from_slice(&g[..m]),
            None => {
                problem.bc(x, y, q, gb);
                evals += 1;
            }
        }
    }
    evals += jacobian(|xx, out| problem.bc(xx, y, q, out), x, gb, scheme, dga, f1);
    evals += jacobian(|yy, out| problem.bc(x, yy, q, out), y, gb, scheme, dgb, f1);
    if k > 0 {
        evals += jacobian(|qq, out| problem.bc(x, y, qq, out), q, gb, scheme, dgp, f1);
    }
    evals
}

/// `∂F/∂z`, `∂F/∂p` at `(s, z, p)`: analytic if [`Bvp::rhs_jacobian`] returns true, else finite
/// differences with `scratch.scheme` (`f0` = `F(s, z, p)` if known, saves one evaluation for the
/// forward scheme). Counts `jac_evals` (+1) and the right-hand-side evaluations in `stats`; returns
/// [`BvpError::NonFinite`] (location `"jacobian"`, abscissa `s`) if an entry is NaN/∞.
#[allow(clippy::too_many_arguments)]
pub fn rhs_jacobian_or_fd<P: Bvp + ?Sized>(
    problem: &P,
    s: f64,
    z: &[f64],
    p: &[f64],
    f0: Option<&[f64]>,
    dfdz: &mut [f64],
    dfdp: &mut [f64],
    scratch: &mut FdScratch,
    stats: &mut Stats,
) -> Result<(), BvpError> {
    stats.jac_evals += 1;
    if !problem.rhs_jacobian(s, z, p, dfdz, dfdp) {
        stats.rhs_evals += rhs_jacobian_fd(problem, s, z, p, f0, dfdz, dfdp, scratch);
    }
    let Dims { n, k } = problem.dims();
    if dfdz[..n * n]
        .iter()
        .chain(&dfdp[..n * k])
        .all(|v| v.is_finite())
    {
        Ok(())
    } else {
        Err(crate::newton::non_finite("jacobian", s))
    }
}

/// Jacobians of the boundary conditions: analytic if [`Bvp::bc_jacobian`] returns true, else
/// finite differences. Counts `bc_evals` in `stats`; [`BvpError::NonFinite`] (location
/// `"jacobian"`, `s` = NaN) on NaN/∞.
#[allow(clippy::too_many_arguments)]
pub fn bc_jacobian_or_fd<P: Bvp + ?Sized>(
    problem: &P,
    za: &[f64],
    zb: &[f64],
    p: &[f64],
    g0: Option<&[f64]>,
    dga: &mut [f64],
    dgb: &mut [f64],
    dgp: &mut [f64],
    scratch: &mut FdScratch,
    stats: &mut Stats,
) -> Result<(), BvpError> {
    if !problem.bc_jacobian(za, zb, p, dga, dgb, dgp) {
        stats.bc_evals += bc_jacobian_fd(problem, za, zb, p, g0, dga, dgb, dgp, scratch);
    }
    let Dims { n, k } = problem.dims();
    let m = n + k;
    if dga[..m * n]
        .iter()
        .chain(&dgb[..m * n])
        .chain(&dgp[..m * k])
        .all(|v| v.is_finite())
    {
        Ok(())
    } else {
        Err(crate::newton::non_finite("jacobian", f64::NAN))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generic_jacobian_accuracy() {
        let f = |x: &[f64], out: &mut [f64]| {
            out[0] = x[0].sin() * x[1];
            out[1] = (x[0] * x[1]).exp();
        };
        let exact = |x: &[f64]| {
            [
                x[0].cos() * x[1],
                x[0].sin(),
                x[1] * (x[0] * x[1]).exp(),
                x[0] * (x[0] * x[1]).exp(),
            ]
        };
        for (scheme, tol) in [(FdScheme::Forward, 1e-6), (FdScheme::Central, 1e-9)] {
            let mut x = [0.7, -1.3];
            let mut fx = [0.0; 2];
            f(&x, &mut fx);
            let mut jac = [0.0; 4];
            let mut work = [0.0; 2];
            jacobian(f, &mut x, &mut fx, scheme, &mut jac, &mut work);
            assert_eq!(x, [0.7, -1.3]);
            let e = exact(&x);
            for i in 0..4 {
                assert!((jac[i] - e[i]).abs() < tol, "{scheme:?} {jac:?} {e:?}");
            }
        }
    }
}
