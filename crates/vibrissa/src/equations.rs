//! The rod equations, written once: the right-hand side with its variational equations (used by
//! the rod's own shooter), and the rod as a boundary-value problem of crate `bvp` (its
//! boundary rows and Jacobians) for the generic methods and the continuation families.
//!
//! ```text
//!     x' = cos φ,   y' = sin φ,   φ' = κ0(s) + b(s)·m,   m' = f·cos(φ − α)
//!     x(0) = y(0) = 0,   φ(0) = π/2 + c·m(0),   m(1) = 0,   plus the tip condition(s)
//! ```

use crate::profile::Profile;
use crate::shooter::rhs;
use bvp::{Bvp, Dims, ParamBvp};
use std::f64::consts::FRAC_PI_2;

/// [`crate::shooter`]'s right-hand side without sensitivities, for slices (the `bvp` problems):
/// the force `f` at the angle `alpha`, `F = (f sin α, −f cos α)`.
#[inline(always)]
fn rod_rhs(z: &[f64], f: f64, alpha: f64, b: f64, k0: f64, dz: &mut [f64]) {
    let y = [z[0], z[1], z[2], z[3]];
    let (sa, ca) = alpha.sin_cos();
    let d = rhs::<4>(&y, f * sa, -f * ca, b, k0);
    dz[..4].copy_from_slice(&d);
}

/// Boundary conditions besides the support (`x(0) = y(0) = 0`, `φ(0) = π/2 + c·m(0)`, `m(1) = 0`).
///
/// Parameters are ordered `p = [f]` or `[f, α]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ends {
    /// Tip slope `φ(1) = phi1`, α fixed; `p = [f]`.
    Phi1 {
        /// Tip slope.
        phi1: f64,
    },
    /// Tip height `y(1) = eta`, α fixed; `p = [f]`.
    Eta {
        /// Tip height.
        eta: f64,
    },
    /// Tip position; `p = [f, α]`.
    Tip {
        /// Tip x.
        x1: f64,
        /// Tip y.
        y1: f64,
    },
}

/// The rod BVP: `z = (x, y, φ, m)`, `x' = cos φ, y' = sin φ, φ' = κ0 + b·m, m' = f·cos(φ − α)`.
#[derive(Clone, Debug)]
pub struct RodBvp<P: Profile> {
    /// Stiffness and pre-curvature.
    pub profile: P,
    /// Support compliance `c` (`φ(0) = π/2 + c·m(0)`).
    pub compliance: f64,
    /// Force angle when it is not an unknown.
    pub alpha: f64,
    /// End conditions.
    pub ends: Ends,
}

impl<P: Profile> RodBvp<P> {
    /// Number of unknown parameters.
    pub fn k(&self) -> usize {
        match self.ends {
            Ends::Phi1 { .. } | Ends::Eta { .. } => 1,
            Ends::Tip { .. } => 2,
        }
    }
    #[inline(always)]
    fn f_alpha(&self, p: &[f64]) -> (f64, f64) {
        if p.len() >= 2 {
            (p[0], p[1])
        } else {
            (p[0], self.alpha)
        }
    }
}

impl<P: Profile> Bvp for RodBvp<P> {
    fn dims(&self) -> Dims {
        Dims { n: 4, k: self.k() }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    #[inline]
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        let (f, alpha) = self.f_alpha(p);
        let (b, k0) = if P::UNIFORM {
            (1.0, 0.0)
        } else {
            (self.profile.b(s), self.profile.k0(s))
        };
        rod_rhs(z, f, alpha, b, k0, dz);
    }
    #[inline]
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        let (f, alpha) = self.f_alpha(p);
        let b = if P::UNIFORM { 1.0 } else { self.profile.b(s) };
        rod_jacobian(f, alpha, b, z, p.len(), dfdz, dfdp);
        true
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        support_bc(self.compliance, za, zb, res);
        ends_bc(self.ends, zb, res);
    }
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
    ) -> bool {
        support_bc_jacobian(self.compliance, dga, dgb, dgp);
        ends_bc_jacobian(self.ends, dgb);
        true
    }
}

/// `x(0) = 0`, `y(0) = 0`, `φ(0) − π/2 − c·m(0) = 0`, `m(1) = 0` into `res[0..4]`.
#[inline]
pub(crate) fn support_bc(c: f64, za: &[f64], zb: &[f64], res: &mut [f64]) {
    res[0] = za[0];
    res[1] = za[1];
    res[2] = za[2] - FRAC_PI_2 - c * za[3];
    res[3] = zb[3];
}

fn support_bc_jacobian(c: f64, dga: &mut [f64], dgb: &mut [f64], dgp: &mut [f64]) {
    dga.fill(0.0);
    dgb.fill(0.0);
    dgp.fill(0.0);
    dga[0] = 1.0;
    dga[4 + 1] = 1.0;
    dga[8 + 2] = 1.0;
    dga[8 + 3] = -c;
    dgb[12 + 3] = 1.0;
}

#[inline]
fn ends_bc(ends: Ends, zb: &[f64], res: &mut [f64]) {
    match ends {
        Ends::Phi1 { phi1 } => res[4] = zb[2] - phi1,
        Ends::Eta { eta } => res[4] = zb[1] - eta,
        Ends::Tip { x1, y1 } => {
            res[4] = zb[0] - x1;
            res[5] = zb[1] - y1;
        }
    }
}

fn ends_bc_jacobian(ends: Ends, dgb: &mut [f64]) {
    match ends {
        Ends::Phi1 { .. } => dgb[16 + 2] = 1.0,
        Ends::Eta { .. } => dgb[16 + 1] = 1.0,
        Ends::Tip { .. } => {
            dgb[16] = 1.0;
            dgb[20 + 1] = 1.0;
        }
    }
}

/// `∂F/∂z` and `∂F/∂p` of the rod equations (`p = [f]` or `[f, α]`, `k = p.len()`).
#[inline]
fn rod_jacobian(
    f: f64,
    alpha: f64,
    b: f64,
    z: &[f64],
    k: usize,
    dfdz: &mut [f64],
    dfdp: &mut [f64],
) {
    let (sp, cp) = z[2].sin_cos();
    let (sd, cd) = (z[2] - alpha).sin_cos();
    dfdz.fill(0.0);
    dfdz[2] = -sp; // ∂x'/∂φ
    dfdz[4 + 2] = cp; // ∂y'/∂φ
    dfdz[8 + 3] = b; // ∂φ'/∂m
    dfdz[12 + 2] = -f * sd; // ∂m'/∂φ
    dfdp.fill(0.0);
    // only m' depends on the parameters
    dfdp[3 * k] = cd;
    if k >= 2 {
        dfdp[3 * k + 1] = f * sd;
    }
}

/// The scan family in `λ = d`: `y(1) = η`, `x(1) = x* − d`; `p = [f, α]`.
#[derive(Clone, Debug)]
pub struct ScanFamily<P: Profile> {
    /// The rod (its `ends` are ignored).
    pub rod: RodBvp<P>,
    /// Surface height.
    pub eta: f64,
    /// Tip x at `d = 0`.
    pub x_star: f64,
}

impl<P: Profile> ParamBvp for ScanFamily<P> {
    fn dims(&self) -> Dims {
        Dims { n: 4, k: 2 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    #[inline]
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], _d: f64, dz: &mut [f64]) {
        self.rod.rhs(s, z, p, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], d: f64, res: &mut [f64]) {
        support_bc(self.rod.compliance, za, zb, res);
        res[4] = zb[0] - (self.x_star - d);
        res[5] = zb[1] - self.eta;
        let _ = p;
    }
    #[inline]
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        _d: f64,
        dfdz: &mut [f64],
        dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        dfdl.fill(0.0);
        self.rod.rhs_jacobian(s, z, p, dfdz, dfdp)
    }
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        _d: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        support_bc_jacobian(self.rod.compliance, dga, dgb, dgp);
        dgb[16] = 1.0;
        dgb[20 + 1] = 1.0;
        dgl.fill(0.0);
        dgl[4] = 1.0;
        true
    }
}
