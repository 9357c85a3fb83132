//! Natural-parameter and pseudo-arclength continuation with fold detection.
//!
//! (skeleton: to be implemented — see issue #3)

use crate::Dims;

/// A family of BVPs in one scalar parameter `λ`: `z' = F(s, z, p; λ)`, `g(z(a), z(b), p; λ) = 0`.
pub trait ParamBvp {
    /// Number of states and unknown parameters (λ excluded).
    fn dims(&self) -> Dims;
    /// The interval `[a, b]`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side at parameter `lambda`.
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], lambda: f64, dz: &mut [f64]);
    /// Boundary residual at parameter `lambda`.
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], lambda: f64, res: &mut [f64]);
}
