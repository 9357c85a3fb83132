//! The rod as a boundary-value problem: profiles `b(s)`, `κ0(s)`, boundary conditions, Jacobians.
//!
//! The right-hand side is generic over a [`Profile`]; the paper's uniform straight rod uses the
//! zero-sized [`Uniform`] (b ≡ 1, κ0 ≡ 0, folded away by monomorphization), every other scene the
//! table-driven [`General`]. The choice is made once per solve, never per right-hand-side call.

use crate::scene::{Precurvature, Scene, Stiffness};
use crate::VibrissaError;
use bvp::{Bvp, Dims, ParamBvp};
use std::f64::consts::FRAC_PI_2;

/// Reciprocal bending stiffness `b(s)` and pre-curvature `κ0(s)` of a rod.
pub trait Profile: Clone + Send + Sync {
    /// True when `b ≡ 1` and `κ0 ≡ 0` (lets the compiler drop the profile entirely).
    const UNIFORM: bool;
    /// `b(s)`.
    fn b(&self, s: f64) -> f64;
    /// `κ0(s)`.
    fn k0(&self, s: f64) -> f64;
    /// Curvature `κ = κ0(s) + b(s)·m`.
    #[inline(always)]
    fn kappa(&self, s: f64, m: f64) -> f64 {
        if Self::UNIFORM {
            m
        } else {
            self.k0(s) + self.b(s) * m
        }
    }
}

/// The uniform straight rod: `b ≡ 1`, `κ0 ≡ 0`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Uniform;

impl Profile for Uniform {
    const UNIFORM: bool = true;
    #[inline(always)]
    fn b(&self, _s: f64) -> f64 {
        1.0
    }
    #[inline(always)]
    fn k0(&self, _s: f64) -> f64 {
        0.0
    }
}

/// Piecewise-linear interpolation in a table with strictly increasing `s` (clamped at the ends).
#[inline]
fn interp(s_tab: &[f64], v: &[f64], s: f64) -> f64 {
    let n = s_tab.len();
    if s <= s_tab[0] {
        return v[0];
    }
    if s >= s_tab[n - 1] {
        return v[n - 1];
    }
    let i = s_tab.partition_point(|&t| t <= s).clamp(1, n - 1) - 1;
    let t = (s - s_tab[i]) / (s_tab[i + 1] - s_tab[i]);
    v[i] + t * (v[i + 1] - v[i])
}

/// Any scene's profile, scaled by a homotopy amplitude `t ∈ [0, 1]` (t = 1: the scene itself,
/// t = 0: the uniform straight rod). Taper: ratio `1 − t(1 − ρ)`; table `b`: `b^t`; `κ0`: `t·κ0`.
#[derive(Clone, Debug, PartialEq)]
pub struct General {
    stiffness: Stiffness,
    precurvature: Precurvature,
    t: f64,
}

impl General {
    /// The profile of `scene` at homotopy amplitude `t`.
    pub fn new(scene: &Scene, t: f64) -> Self {
        General {
            stiffness: scene.stiffness.clone(),
            precurvature: scene.precurvature.clone(),
            t,
        }
    }
    /// The same profile at amplitude `t`.
    pub fn with_t(mut self, t: f64) -> Self {
        self.t = t;
        self
    }
    /// `b(s)` at amplitude `t`.
    #[inline]
    pub fn b_at(&self, s: f64, t: f64) -> f64 {
        match &self.stiffness {
            Stiffness::Uniform => 1.0,
            Stiffness::Taper { ratio } => {
                let r = 1.0 - t * (1.0 - ratio) * s;
                let r2 = r * r;
                1.0 / (r2 * r2)
            }
            Stiffness::Table { s: st, b } => {
                let v = interp(st, b, s);
                if t == 1.0 {
                    v
                } else {
                    v.powf(t)
                }
            }
        }
    }
    /// `κ0(s)` at amplitude `t`.
    #[inline]
    pub fn k0_at(&self, s: f64, t: f64) -> f64 {
        match &self.precurvature {
            Precurvature::None => 0.0,
            Precurvature::Linear { k0, k1 } => t * (k0 + k1 * s),
            Precurvature::Table { s: st, k } => t * interp(st, k, s),
        }
    }
    /// `∂b/∂t` at `s` and `t`.
    fn db_dt(&self, s: f64, t: f64) -> f64 {
        match &self.stiffness {
            Stiffness::Uniform => 0.0,
            Stiffness::Taper { ratio } => {
                let r = 1.0 - t * (1.0 - ratio) * s;
                4.0 * (1.0 - ratio) * s / (r * r * r * r * r)
            }
            Stiffness::Table { s: st, b } => {
                let v = interp(st, b, s);
                v.powf(t) * v.ln()
            }
        }
    }
}

impl Profile for General {
    const UNIFORM: bool = false;
    #[inline]
    fn b(&self, s: f64) -> f64 {
        self.b_at(s, self.t)
    }
    #[inline]
    fn k0(&self, s: f64) -> f64 {
        self.k0_at(s, self.t)
    }
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
        let (sp, cp) = z[2].sin_cos();
        dz[0] = cp;
        dz[1] = sp;
        dz[2] = self.profile.kappa(s, z[3]);
        dz[3] = f * (z[2] - alpha).cos();
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
fn support_bc(c: f64, za: &[f64], zb: &[f64], res: &mut [f64]) {
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

/// Physical units of a scene with [`crate::Physical`] dimensions.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Units {
    /// Force unit `E·I/L²` in N (`I = π d⁴/64` at the base).
    pub force_n: f64,
    /// Moment unit `E·I/L` in N·m.
    pub moment_nm: f64,
    /// Length unit `L` in mm.
    pub length_mm: f64,
}

/// A validated scene, ready to solve.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    scene: Scene,
    paper: bool,
    uniform_profile: bool,
}

impl Model {
    /// Validates `scene` (see [`Scene::validate`]).
    pub fn new(scene: &Scene) -> Result<Model, VibrissaError> {
        scene.validate()?;
        let uniform_profile = General::new(scene, 1.0).is_uniform();
        Ok(Model {
            scene: scene.clone(),
            paper: scene.is_paper_scene(),
            uniform_profile,
        })
    }
    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// True for the paper's scene (uniform, straight, clamped, horizontal surface), where the
    /// closed forms of crate `elastica` apply and [`crate::Method::Analytic`] is allowed.
    pub fn is_paper_scene(&self) -> bool {
        self.paper
    }
    /// True when `b ≡ 1` and `κ0 ≡ 0` (compliance and surface angle may still be set).
    pub fn has_uniform_profile(&self) -> bool {
        self.uniform_profile
    }
    /// The profile at homotopy amplitude `t` (1: the scene).
    pub fn profile(&self, t: f64) -> General {
        General::new(&self.scene, t)
    }
    /// Physical units, if the scene has physical dimensions.
    pub fn units(&self) -> Option<Units> {
        let p = self.scene.physical.as_ref()?;
        let l = p.length_mm * 1e-3;
        let d = p.base_diameter_um * 1e-6;
        let e = p.youngs_modulus_gpa * 1e9;
        let i = std::f64::consts::PI * d.powi(4) / 64.0;
        Some(Units {
            force_n: e * i / (l * l),
            moment_nm: e * i / l,
            length_mm: p.length_mm,
        })
    }
}

impl General {
    fn is_uniform(&self) -> bool {
        let b1 = match &self.stiffness {
            Stiffness::Uniform => true,
            Stiffness::Taper { ratio } => *ratio == 1.0,
            Stiffness::Table { .. } => false,
        };
        let k0 = match &self.precurvature {
            Precurvature::None => true,
            Precurvature::Linear { k0, k1 } => *k0 == 0.0 && *k1 == 0.0,
            Precurvature::Table { .. } => false,
        };
        b1 && k0
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
        let (sp, cp) = z[2].sin_cos();
        dz[0] = cp;
        dz[1] = sp;
        dz[2] = self.profile.k0_at(s, t) + self.profile.b_at(s, t) * z[3];
        dz[3] = f * (z[2] - alpha).cos();
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
