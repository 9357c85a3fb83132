//! The rod equations, written once: the right-hand side with its variational equations (used by
//! the rod's own shooter), and the rod as a boundary-value problem of crate `bvp` (its
//! boundary rows and Jacobians) for the generic methods and the continuation families.
//!
//! ```text
//!     x' = cos φ,   y' = sin φ,   φ' = κ0(s) + b(s)·m,   m' = f·cos(φ − α)
//!     x(0) = y(0) = 0,   φ(0) = π/2 + c·m(0),   m(1) = 0,   plus the tip condition(s)
//! ```

use crate::profile::{General, Profile};
use bvp::{Bvp, Dims, ParamBvp};
use std::f64::consts::FRAC_PI_2;

/// Components of the shooter's state: `z = (x, y, φ, m)` and `∂z/∂u` for `u = (m(0), f, α)`.
pub(crate) const NV: usize = 16;
/// The shooter's state vector.
pub(crate) type Y = [f64; NV];

/// `(sin x, cos x)` for moderate `|x|` (here slopes within a few turns): Cody–Waite reduction by
/// π/2 and fdlibm's kernel polynomials on `[−π/4, π/4]` (error ≲ 1 ulp there). About a third of
/// the instructions of libm's general `sincos`, which is the largest single cost of a shot.
#[inline(always)]
#[allow(clippy::excessive_precision)]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    const PIO2_HI: f64 = 1.570_796_326_734_125_614_17; // first 33 bits of π/2
    const PIO2_LO: f64 = 6.077_100_506_506_192_249_99e-11; // π/2 − PIO2_HI
    const S: [f64; 6] = [
        -1.666_666_666_666_663_243_48e-01,
        8.333_333_333_322_489_461_24e-03,
        -1.984_126_982_985_794_931_34e-04,
        2.755_731_370_707_006_767_89e-06,
        -2.505_076_025_340_686_341_95e-08,
        1.589_690_995_211_550_102_21e-10,
    ];
    const C: [f64; 6] = [
        4.166_666_666_666_660_190_37e-02,
        -1.388_888_888_887_410_957_49e-03,
        2.480_158_728_947_672_941_78e-05,
        -2.755_731_435_139_066_330_35e-07,
        2.087_572_321_298_174_827_90e-09,
        -1.135_964_755_778_819_482_65e-11,
    ];
    if x.is_nan() || x.abs() >= 1e5 {
        return x.sin_cos();
    }
    let k = (x * std::f64::consts::FRAC_2_PI).round();
    let r = (x - k * PIO2_HI) - k * PIO2_LO;
    let z = r * r;
    let sp = S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])));
    let sr = r + r * z * (S[0] + z * sp);
    let cp = C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5]))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    // fdlibm's split keeps 1 − z/2 exact to the last bit
    let cr = w + (((1.0 - w) - hz) + z * z * cp);
    // quadrant by selects rather than a jump table
    let q = k as i64;
    let (s1, c1) = if q & 1 == 0 { (sr, cr) } else { (cr, -sr) };
    if q & 2 == 0 {
        (s1, c1)
    } else {
        (-s1, -c1)
    }
}

/// The rod's right-hand side at a point where `b(s) = b`, `κ0(s) = k0`, for the force `f` at the
/// angle with sine `sa` and cosine `ca`, on a state of `N` components: `N = 4` is `z` alone,
/// `N = 16` adds the variational equations in `u = (m(0), f, α)` (components `4 + 4q + i` hold
/// `∂z_i/∂u_q`). Monomorphized per width, so a shot without sensitivities moves 4 numbers per
/// stage, not 16.
#[inline(always)]
pub(crate) fn rod_rhs_var<const N: usize>(
    y: &[f64; N],
    f: f64,
    ca: f64,
    sa: f64,
    b: f64,
    k0: f64,
) -> [f64; N] {
    let (sp, cp) = sin_cos(y[2]);
    // sin/cos(φ − α) from those of φ and α: one sin_cos per evaluation
    let cd = cp * ca + sp * sa;
    let sd = sp * ca - cp * sa;
    let fsd = f * sd;
    let mut d = [0.0; N];
    d[0] = cp;
    d[1] = sp;
    d[2] = k0 + b * y[3];
    d[3] = f * cd;
    if N < NV {
        return d;
    }
    for q in 0..3 {
        let (dphi, dm) = (y[4 + 4 * q + 2], y[4 + 4 * q + 3]);
        d[4 + 4 * q] = -sp * dphi;
        d[4 + 4 * q + 1] = cp * dphi;
        d[4 + 4 * q + 2] = b * dm;
        d[4 + 4 * q + 3] = -fsd * dphi;
    }
    d[4 + 4 + 3] += cd; // ∂/∂f
    d[4 + 8 + 3] += fsd; // ∂/∂α
    d
}

/// [`rod_rhs_var`] without sensitivities, for slices (the `bvp` problems).
#[inline(always)]
fn rod_rhs(z: &[f64], f: f64, alpha: f64, b: f64, k0: f64, dz: &mut [f64]) {
    let y = [z[0], z[1], z[2], z[3]];
    let (sa, ca) = sin_cos(alpha);
    let d = rod_rhs_var::<4>(&y, f, ca, sa, b, k0);
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

/// The homotopy family in `λ = t`: profile amplitude `t`, compliance `t·c`, fixed `ends`.
#[derive(Clone, Debug)]
pub struct HomotopyFamily {
    /// The scene's profile (its own `t` is ignored).
    pub profile: General,
    /// Full compliance `c`.
    pub compliance: f64,
    /// Fixed force angle (when not an unknown).
    pub alpha: f64,
    /// End conditions.
    pub ends: Ends,
}

impl HomotopyFamily {
    fn k(&self) -> usize {
        match self.ends {
            Ends::Tip { .. } => 2,
            _ => 1,
        }
    }
    /// The member at `t` as an ordinary rod.
    pub fn at(&self, t: f64) -> RodBvp<General> {
        RodBvp {
            profile: self.profile.clone().with_t(t),
            compliance: t * self.compliance,
            alpha: self.alpha,
            ends: self.ends,
        }
    }
}

impl ParamBvp for HomotopyFamily {
    fn dims(&self) -> Dims {
        Dims { n: 4, k: self.k() }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    #[inline]
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], t: f64, dz: &mut [f64]) {
        let (f, alpha) = if p.len() >= 2 {
            (p[0], p[1])
        } else {
            (p[0], self.alpha)
        };
        rod_rhs(
            z,
            f,
            alpha,
            self.profile.b_at(s, t),
            self.profile.k0_at(s, t),
            dz,
        );
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], t: f64, res: &mut [f64]) {
        support_bc(t * self.compliance, za, zb, res);
        ends_bc(self.ends, zb, res);
        let _ = p;
    }
    #[inline]
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        t: f64,
        dfdz: &mut [f64],
        dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        let (f, alpha) = if p.len() >= 2 {
            (p[0], p[1])
        } else {
            (p[0], self.alpha)
        };
        rod_jacobian(f, alpha, self.profile.b_at(s, t), z, p.len(), dfdz, dfdp);
        dfdl.fill(0.0);
        // κ0_t = t·κ0 is linear in t
        dfdl[2] = self.profile.k0_at(s, 1.0) + self.profile.db_dt(s, t) * z[3];
        true
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        t: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        support_bc_jacobian(t * self.compliance, dga, dgb, dgp);
        ends_bc_jacobian(self.ends, dgb);
        dgl.fill(0.0);
        dgl[2] = -self.compliance * za[3];
        true
    }
}
