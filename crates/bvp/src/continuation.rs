//! Natural-parameter and pseudo-arclength continuation with fold detection.
//!
//! (being implemented)

use crate::Dims;

/// A family of BVPs in one scalar parameter `λ`: `z' = F(s, z, p; λ)`, `g(z(a), z(b), p; λ) = 0`.
///
/// Matrix layouts are those of [`crate::Bvp`]; the extra `λ` columns are vectors:
/// `dfdl[i] = ∂F_i/∂λ` (length `n`), `dgl[i] = ∂g_i/∂λ` (length `n + k`).
pub trait ParamBvp {
    /// Number of states and unknown parameters (λ excluded).
    fn dims(&self) -> Dims;
    /// The interval `[a, b]`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side at parameter `lambda`.
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], lambda: f64, dz: &mut [f64]);
    /// Boundary residual at parameter `lambda`.
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], lambda: f64, res: &mut [f64]);
    /// Analytic `∂F/∂z` (n×n), `∂F/∂p` (n×k) and `∂F/∂λ` (n); `false` if not provided (default).
    #[allow(clippy::too_many_arguments)]
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        _lambda: f64,
        _dfdz: &mut [f64],
        _dfdp: &mut [f64],
        _dfdl: &mut [f64],
    ) -> bool {
        false
    }
    /// Analytic Jacobians of `g` with respect to `z(a)`, `z(b)`, `p` and `λ`; `false` if not
    /// provided (default).
    #[allow(clippy::too_many_arguments)]
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        _lambda: f64,
        _dga: &mut [f64],
        _dgb: &mut [f64],
        _dgp: &mut [f64],
        _dgl: &mut [f64],
    ) -> bool {
        false
    }
}
