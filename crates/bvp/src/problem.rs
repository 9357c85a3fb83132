//! The problem definition.

/// Sizes of a problem: `n` states and `k` unknown parameters (so `n + k` boundary conditions).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Dims {
    /// Number of states `n`.
    pub n: usize,
    /// Number of unknown parameters `k`.
    pub k: usize,
}

/// A two-point boundary-value problem `z' = F(s, z, p)` on `[a, b]`, `g(z(a), z(b), p) = 0`.
///
/// Matrices are row-major slices: `dfdz[i * n + j] = ∂F_i/∂z_j`, `dfdp[i * k + j] = ∂F_i/∂p_j`,
/// `dga[i * n + j] = ∂g_i/∂z_j(a)`, `dgb` likewise for `z(b)`, `dgp[i * k + j] = ∂g_i/∂p_j`,
/// with `i` over the `n + k` conditions.
///
/// The Jacobian methods return `false` when not implemented (the default); solvers then use
/// finite differences ([`crate::fd`]). Implementations must not allocate: solvers call these in
/// their inner loops. Non-finite output is detected by the solvers and reported as
/// [`crate::BvpError::NonFinite`].
pub trait Bvp {
    /// Number of states and unknown parameters.
    fn dims(&self) -> Dims;
    /// The interval `[a, b]`, `a < b`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side: writes `F(s, z, p)` into `dz`.
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]);
    /// Boundary residual: writes `g(za, zb, p)` (length `n + k`) into `res`.
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]);
    /// Analytic `∂F/∂z` (n×n) and `∂F/∂p` (n×k); `false` if not provided.
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        _dfdz: &mut [f64],
        _dfdp: &mut [f64],
    ) -> bool {
        false
    }
    /// Analytic Jacobians of `g` with respect to `z(a)`, `z(b)`, `p`; `false` if not provided.
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        _dga: &mut [f64],
        _dgb: &mut [f64],
        _dgp: &mut [f64],
    ) -> bool {
        false
    }
}

impl<T: Bvp + ?Sized> Bvp for &T {
    fn dims(&self) -> Dims {
        (**self).dims()
    }
    fn interval(&self) -> (f64, f64) {
        (**self).interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        (**self).rhs(s, z, p, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        (**self).bc(za, zb, p, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        (**self).rhs_jacobian(s, z, p, dfdz, dfdp)
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
    ) -> bool {
        (**self).bc_jacobian(za, zb, p, dga, dgb, dgp)
    }
}
