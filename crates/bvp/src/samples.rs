//! Problems with known answers, shared by tests, benches and examples.
//!
//! Every problem implements [`Bvp`] with analytic Jacobians, has a `guess()` (a [`Guess`] on a
//! coarse mesh that is *not* the answer), and an `exact` function where a closed form exists.
//!
//! | problem | equation | answer |
//! |---|---|---|
//! | [`LinearSinh`] | `y'' = y`, `y(0) = 0`, `y(1) = 1` | `sinh s / sinh 1` |
//! | [`LinearNonSeparated`] | `y'' = −y + s`, `y(0) + y(1) = 2`, `y'(0) − 2y'(1) = 0` | `A cos s + B sin s + s` |
//! | [`Eigen`] | `y'' + λy = 0`, `y(0) = y(1) = 0`, `y'(0) = 1` | `λ = (jπ)²`, `y = sin(jπs)/(jπ)` |
//! | [`Bratu`] | `u'' + λeᵘ = 0`, `u(0) = u(1) = 0` | two branches for `λ < λ_c` |
//! | [`Cantilever`] | planar elastica, horizontal tip force `P` | Mattiasson (1981) table |
//! | [`NoSolution`] | `y'' = −y` on `[0, π]`, `y(0) = 0`, `y(π) = 1` | none (resonance) |
//! | [`NanRhs`] | `y' = −√y`, `y(0) = 1` on `[0, 4]` | rhs is NaN once `y < 0` |
//! | [`SingularNeumann`] | `y'' = 0`, `y'(0) = 0`, `y'(1) = 0` | a line of solutions: singular Jacobian |
//! | [`Parabola`] | `y'' = p`, `y(0) = y'(0) = 0`, `y(1) = e`, `p` unknown | `y = e s²`, `p = 2e` |
//! | [`Big`] | scipy's 60-state problems, `y_i'' = 0` or `−p_j² y_i` (two parameters) | `y_i = x`; `sin x`, `p = (1, 1)` |
//!
//! State layouts are given on each type; second-order equations use `z = (y, y')`.
//! [`FiniteDifferences`] hides a problem's analytic Jacobians (solvers then difference).

use crate::continuation::ParamBvp;
use crate::{Bvp, Dims, Guess};
use std::f64::consts::{FRAC_PI_2, PI};

fn uniform(a: f64, b: f64, nodes: usize) -> Vec<f64> {
    (0..nodes)
        .map(|i| a + (b - a) * i as f64 / (nodes - 1) as f64)
        .collect()
}

/// Zero-fills the three boundary Jacobian blocks.
fn zero(bufs: [&mut [f64]; 3]) {
    for b in bufs {
        b.fill(0.0);
    }
}

// ---------------------------------------------------------------------------------------------

/// `y'' = y` on `[0, 1]`, `y(0) = 0`, `y(1) = 1`; `z = (y, y')`. Exact: `y = sinh s / sinh 1`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinearSinh;

impl LinearSinh {
    /// Exact `(y, y')` at `s`.
    pub fn exact(s: f64) -> [f64; 2] {
        let d = 1f64.sinh();
        [s.sinh() / d, s.cosh() / d]
    }
    /// Guess: the straight line `y = s` (satisfies the boundary conditions, not the ODE).
    pub fn guess() -> Guess {
        Guess::from_fn(2, uniform(0.0, 1.0, 5), vec![], |s, z| {
            z[0] = s;
            z[1] = 1.0;
        })
    }
}

impl Bvp for LinearSinh {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = z[0];
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = zb[0] - 1.0;
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _: &mut [f64],
    ) -> bool {
        dfdz.copy_from_slice(&[0.0, 1.0, 1.0, 0.0]);
        true
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
        zero([dga, dgb, dgp]);
        dga[0] = 1.0;
        dgb[2] = 1.0;
        true
    }
}

// ---------------------------------------------------------------------------------------------

/// `y'' = −y + s` on `[0, 1]` with the non-separated conditions `y(0) + y(1) = 2`,
/// `y'(0) − 2 y'(1) = 0`; `z = (y, y')`.
///
/// Closed form: `y = A cos s + B sin s + s`, `y' = −A sin s + B cos s + 1`. The conditions give
/// the linear system
///
/// ```text
///     (1 + cos 1) A + sin 1 B       = 2 − 1 = 1
///     2 sin 1 A + (1 − 2 cos 1) B   = 0 + 1 = 1
/// ```
///
/// with determinant `D = (1 + cos 1)(1 − 2 cos 1) − 2 sin² 1 ≈ −1.54 ≠ 0`, solved by Cramer's rule
/// in [`LinearNonSeparated::coefficients`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinearNonSeparated;

impl LinearNonSeparated {
    /// `(A, B)` of the closed form.
    pub fn coefficients() -> (f64, f64) {
        let (c, s) = (1f64.cos(), 1f64.sin());
        let (a11, a12, a21, a22) = (1.0 + c, s, 2.0 * s, 1.0 - 2.0 * c);
        let (r1, r2) = (1.0, 1.0);
        let d = a11 * a22 - a12 * a21;
        ((r1 * a22 - a12 * r2) / d, (a11 * r2 - a21 * r1) / d)
    }
    /// Exact `(y, y')` at `s`.
    pub fn exact(s: f64) -> [f64; 2] {
        let (a, b) = Self::coefficients();
        [
            a * s.cos() + b * s.sin() + s,
            -a * s.sin() + b * s.cos() + 1.0,
        ]
    }
    /// Guess: zero.
    pub fn guess() -> Guess {
        Guess::constant(0.0, 1.0, 5, &[0.0, 0.0], vec![])
    }
}

impl Bvp for LinearNonSeparated {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = -z[0] + s;
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0] + zb[0] - 2.0;
        res[1] = za[1] - 2.0 * zb[1];
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _: &mut [f64],
    ) -> bool {
        dfdz.copy_from_slice(&[0.0, 1.0, -1.0, 0.0]);
        true
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
        zero([dga, dgb, dgp]);
        dga[0] = 1.0;
        dgb[0] = 1.0;
        dga[3] = 1.0;
        dgb[3] = -2.0;
        true
    }
}

// ---------------------------------------------------------------------------------------------

/// Eigenvalue problem `y'' + λ y = 0`, `y(0) = y(1) = 0`, `y'(0) = 1` with unknown `λ` (`k = 1`);
/// `z = (y, y')`, `p = (λ)`. Mode `j ≥ 1`: `λ = (jπ)²`, `y = sin(jπs)/(jπ)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Eigen;

impl Eigen {
    /// Eigenvalue of mode `j`: `(jπ)²`.
    pub fn eigenvalue(mode: usize) -> f64 {
        (mode as f64 * PI).powi(2)
    }
    /// Exact `(y, y')` of mode `j` at `s`.
    pub fn exact(mode: usize, s: f64) -> [f64; 2] {
        let w = mode as f64 * PI;
        [(w * s).sin() / w, (w * s).cos()]
    }
    /// Guess for the first mode: `sin(πs)/π` with `λ = 8`.
    pub fn guess() -> Guess {
        Self::guess_mode(1)
    }
    /// Guess for mode 1 (`λ = 8`) or mode `j ≥ 2` (`λ = 0.95 (jπ)²`, e.g. 37.5 for `j = 2`): the
    /// mode shape with the wrong eigenvalue.
    pub fn guess_mode(mode: usize) -> Guess {
        let mode = mode.max(1);
        let lambda = if mode == 1 {
            8.0
        } else {
            0.95 * Self::eigenvalue(mode)
        };
        Guess::from_fn(2, uniform(0.0, 1.0, 9), vec![lambda], |s, z| {
            z.copy_from_slice(&Self::exact(mode, s))
        })
    }
}

impl Bvp for Eigen {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 1 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = -p[0] * z[0];
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = zb[0];
        res[2] = za[1] - 1.0;
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        dfdz.copy_from_slice(&[0.0, 1.0, -p[0], 0.0]);
        dfdp[0] = 0.0;
        dfdp[1] = -z[0];
        true
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
        zero([dga, dgb, dgp]);
        dga[0] = 1.0; // row 0, col 0
        dgb[2] = 1.0; // row 1, col 0
        dga[5] = 1.0; // row 2, col 1
        true
    }
}

// ---------------------------------------------------------------------------------------------

/// The critical Bratu parameter `λ_c = 3.51383071912516` (fold of the solution branch).
pub const BRATU_LAMBDA_C: f64 = 3.513_830_719_125_16;

/// Bratu's problem `u'' + λ eᵘ = 0`, `u(0) = u(1) = 0`; `z = (u, u')`.
///
/// Exact solutions `u(x) = −2 ln( cosh((x − ½) θ/2) / cosh(θ/4) )`,
/// `u'(x) = −θ tanh((x − ½) θ/2)`, where `θ = √(2λ) cosh(θ/4)` has two roots for `0 < λ < λ_c`
/// ([`Bratu::exact_theta`]): branch 0 (small θ, the lower solution) and branch 1 (upper).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bratu {
    /// The parameter `λ`.
    pub lambda: f64,
}

impl Default for Bratu {
    fn default() -> Self {
        Bratu { lambda: 1.0 }
    }
}

/// `θ_c / 4` solves `t = coth t` (where `θ ↦ θ − √(2λ) cosh(θ/4)` has its maximum at `λ_c`).
fn bratu_tc() -> f64 {
    let mut t = 1.2_f64;
    for _ in 0..50 {
        // f(t) = t tanh t − 1, f' = tanh t + t / cosh² t
        let f = t * t.tanh() - 1.0;
        let df = t.tanh() + t / t.cosh().powi(2);
        t -= f / df;
    }
    t
}

impl Bratu {
    /// The two roots `θ₁ < θ₂` of `θ = √(2λ) cosh(θ/4)` (to rounding), for `0 < λ < λ_c`;
    /// `[NaN, NaN]` outside that range (no or a single solution).
    pub fn exact_theta(lambda: f64) -> [f64; 2] {
        if !(lambda > 0.0 && lambda < BRATU_LAMBDA_C) {
            return [f64::NAN; 2];
        }
        let c = (2.0 * lambda).sqrt();
        let h = |t: f64| t - c * (t / 4.0).cosh();
        let tc = 4.0 * bratu_tc(); // maximum of h, positive for λ < λ_c
        if h(tc).is_nan() || h(tc) <= 0.0 {
            return [f64::NAN; 2];
        }
        let mut hi = 2.0 * tc;
        while h(hi) > 0.0 {
            hi *= 2.0;
        }
        let bisect = |mut lo: f64, mut hi: f64| {
            // h(lo) and h(hi) of opposite signs.
            let slo = h(lo).signum();
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if h(mid).signum() == slo {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi)
        };
        [bisect(0.0, tc), bisect(tc, hi)]
    }

    /// Exact `(u, u')` at `s` on branch 0 (lower) or 1 (upper); NaN if `λ ∉ (0, λ_c)`.
    pub fn exact(&self, branch: usize, s: f64) -> [f64; 2] {
        let theta = Self::exact_theta(self.lambda)[branch.min(1)];
        let x = (s - 0.5) * theta / 2.0;
        [
            -2.0 * (x.cosh() / (theta / 4.0).cosh()).ln(),
            -theta * x.tanh(),
        ]
    }

    /// Guess for the lower branch: `u = ½ s (1 − s)`.
    pub fn guess(&self) -> Guess {
        Self::parabola(0.5)
    }

    /// Guess for the upper branch: `u = 16 s (1 − s)` (maximum 4; the exact upper solution at
    /// `λ = 1` peaks at ≈ 4.08).
    pub fn guess_upper(&self) -> Guess {
        Self::parabola(16.0)
    }

    fn parabola(c: f64) -> Guess {
        Guess::from_fn(2, uniform(0.0, 1.0, 11), vec![], |s, z| {
            z[0] = c * s * (1.0 - s);
            z[1] = c * (1.0 - 2.0 * s);
        })
    }
}

impl Bvp for Bratu {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = -self.lambda * z[0].exp();
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = zb[0];
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _: &mut [f64],
    ) -> bool {
        dfdz.copy_from_slice(&[0.0, 1.0, -self.lambda * z[0].exp(), 0.0]);
        true
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
        zero([dga, dgb, dgp]);
        dga[0] = 1.0;
        dgb[2] = 1.0;
        true
    }
}

/// The Bratu family in `λ` for continuation: `u'' + λ eᵘ = 0`, `u(0) = u(1) = 0`, `z = (u, u')`,
/// no unknown parameters. Fold at [`BRATU_LAMBDA_C`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BratuFamily;

impl BratuFamily {
    /// The member at `lambda`.
    pub fn at(&self, lambda: f64) -> Bratu {
        Bratu { lambda }
    }
}

impl ParamBvp for BratuFamily {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], lambda: f64, dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = -lambda * z[0].exp();
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], _lambda: f64, res: &mut [f64]) {
        res[0] = za[0];
        res[1] = zb[0];
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        z: &[f64],
        _p: &[f64],
        lambda: f64,
        dfdz: &mut [f64],
        _dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        let e = z[0].exp();
        dfdz.copy_from_slice(&[0.0, 1.0, -lambda * e, 0.0]);
        dfdl[0] = 0.0;
        dfdl[1] = -e;
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        _lambda: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        zero([dga, dgb, dgp]);
        dga[0] = 1.0;
        dgb[2] = 1.0;
        dgl.fill(0.0);
        true
    }
}

// ---------------------------------------------------------------------------------------------

/// Planar inextensible elastica clamped at the origin pointing up, loaded by a horizontal tip force
/// of magnitude `load` (towards −x): `z = (x, y, φ, m)`,
///
/// ```text
///     x' = cos φ,  y' = sin φ,  φ' = m,  m' = −P sin φ        (m' = f cos(φ − α), α = −π/2)
///     x(0) = 0, y(0) = 0, φ(0) = π/2, m(1) = 0.
/// ```
///
/// Reference: [`Cantilever::MATTIASSON`] (Mattiasson 1981, via the project's
/// `reference/public-values.md`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cantilever {
    /// Tip load `P` (normalized by `EI/L²`).
    pub load: f64,
}

impl Default for Cantilever {
    fn default() -> Self {
        Cantilever { load: 1.0 }
    }
}

impl Cantilever {
    /// Mattiasson (1981) table, 5 printed digits: `(P, [u, w, θ, |m(0)|])` with shortening
    /// `u = 1 − y(1)`, deflection `w = |x(1)|`, tip rotation `θ = |π/2 − φ(1)|` and base moment.
    pub const MATTIASSON: [(f64, [f64; 4]); 4] = [
        (1.0, [0.05643, 0.30172, 0.46135, 0.94357]),
        (2.0, [0.16064, 0.49346, 0.78175, 1.67872]),
        (5.0, [0.38763, 0.71379, 1.21537, 3.06186]),
        (10.0, [0.55500, 0.81061, 1.43029, 4.45004]),
    ];

    /// The table quantities `[u, w, θ, |m(0)|]` of a solution given `z(0)` and `z(1)`.
    pub fn quantities(z0: &[f64], z1: &[f64]) -> [f64; 4] {
        [
            1.0 - z1[1],
            z1[0].abs(),
            (FRAC_PI_2 - z1[2]).abs(),
            z0[3].abs(),
        ]
    }

    /// Guess: the straight rod with the small-deflection moment `m = P (1 − s)`.
    ///
    /// Good for multiple shooting at every tabulated load, and for single shooting up to `P ≈ 2`:
    /// for larger `P` the guessed `m(0) = P` exceeds the separatrix `√(2P)` of the pendulum
    /// `φ'' = −P sin φ` and single shooting stalls; step the load from a previous solution.
    pub fn guess(&self) -> Guess {
        let p = self.load;
        Guess::from_fn(4, uniform(0.0, 1.0, 11), vec![], |s, z| {
            z.copy_from_slice(&[0.0, s, FRAC_PI_2, p * (1.0 - s)]);
        })
    }
}

impl Bvp for Cantilever {
    fn dims(&self) -> Dims {
        Dims { n: 4, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        let (sp, cp) = z[2].sin_cos();
        dz[0] = cp;
        dz[1] = sp;
        dz[2] = z[3];
        dz[3] = -self.load * sp;
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = za[1];
        res[2] = za[2] - FRAC_PI_2;
        res[3] = zb[3];
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _: &mut [f64],
    ) -> bool {
        let (sp, cp) = z[2].sin_cos();
        dfdz.fill(0.0);
        dfdz[2] = -sp; // ∂x'/∂φ
        dfdz[4 + 2] = cp; // ∂y'/∂φ
        dfdz[8 + 3] = 1.0; // ∂φ'/∂m
        dfdz[12 + 2] = -self.load * cp; // ∂m'/∂φ
        true
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
        zero([dga, dgb, dgp]);
        dga[0] = 1.0;
        dga[4 + 1] = 1.0;
        dga[8 + 2] = 1.0;
        dgb[12 + 3] = 1.0;
        true
    }
}

// ---------------------------------------------------------------------------------------------

/// `y'' = −y` on `[0, π]`, `y(0) = 0`, `y(π) = 1`: no solution (every solution of the ODE with
/// `y(0) = 0` is `c sin s`, which vanishes at `π`). `z = (y, y')`. The shooting Jacobian is
/// singular up to the discretization error, so solvers should report a singular Jacobian, a stall
/// or the iteration limit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoSolution;

impl NoSolution {
    /// Guess: the straight line `y = s/π`.
    pub fn guess() -> Guess {
        Guess::from_fn(2, uniform(0.0, PI, 5), vec![], |s, z| {
            z[0] = s / PI;
            z[1] = 1.0 / PI;
        })
    }
}

impl Bvp for NoSolution {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, PI)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = -z[0];
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = zb[0] - 1.0;
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _: &mut [f64],
    ) -> bool {
        dfdz.copy_from_slice(&[0.0, 1.0, -1.0, 0.0]);
        true
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
        zero([dga, dgb, dgp]);
        dga[0] = 1.0;
        dgb[2] = 1.0;
        true
    }
}

/// `y' = −√y`, `y(0) = 1` on `[0, 4]` (`n = 1`): the exact solution `(1 − s/2)²` reaches 0 at
/// `s = 2`, where a numerical solution goes slightly negative and the right-hand side becomes NaN.
/// Solvers must report [`crate::BvpError::NonFinite`] (near `s = 2`), not panic or loop.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NanRhs;

impl NanRhs {
    /// Guess: the constant 1.
    pub fn guess() -> Guess {
        Guess::constant(0.0, 4.0, 5, &[1.0], vec![])
    }
}

impl Bvp for NanRhs {
    fn dims(&self) -> Dims {
        Dims { n: 1, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 4.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        dz[0] = -z[0].sqrt();
    }
    fn bc(&self, za: &[f64], _zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0] - 1.0;
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _: &mut [f64],
    ) -> bool {
        dfdz[0] = -0.5 / z[0].sqrt();
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        dga: &mut [f64],
        dgb: &mut [f64],
        _dgp: &mut [f64],
    ) -> bool {
        dga[0] = 1.0;
        dgb[0] = 0.0;
        true
    }
}

/// `y'' = 0` on `[0, 1]`, `y'(0) = 0`, `y'(1) = 0`; `z = (y, y')`. Every constant solves it, so the
/// Newton matrix of every discretization is exactly singular (the constant is in its kernel):
/// solvers must report [`crate::BvpError::SingularJacobian`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SingularNeumann;

impl SingularNeumann {
    /// Guess: `y = s + s²/2`, whose boundary residual `(1, 2)` is not zero (so Newton has to
    /// factor; shooting from `z(0) = (0, 1)` gives the residual `(1, 1)`).
    pub fn guess() -> Guess {
        Guess::from_fn(2, uniform(0.0, 1.0, 5), vec![], |s, z| {
            z[0] = s + 0.5 * s * s;
            z[1] = 1.0 + s;
        })
    }
}

impl Bvp for SingularNeumann {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = 0.0;
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[1];
        res[1] = zb[1];
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _: &mut [f64],
    ) -> bool {
        dfdz.copy_from_slice(&[0.0, 1.0, 0.0, 0.0]);
        true
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
        zero([dga, dgb, dgp]);
        dga[1] = 1.0;
        dgb[3] = 1.0;
        true
    }
}

// ---------------------------------------------------------------------------------------------

/// `y'' = p` on `[0, 1]`, `y(0) = 0`, `y'(0) = 0`, `y(1) = end`, with unknown `p` (`k = 1`);
/// `z = (y, y')`. Exact: `y = end·s²`, `p = 2·end`: a polynomial that both collocation schemes
/// reproduce to rounding, so Newton on a coarsened mesh (or a warm start) starts converged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parabola {
    /// `y(1)`.
    pub end: f64,
}

impl Parabola {
    /// Exact `(y, y')` at `s`.
    pub fn exact(&self, s: f64) -> [f64; 2] {
        [self.end * s * s, 2.0 * self.end * s]
    }
    /// Exact parameter `p = 2·end`.
    pub fn parameter(&self) -> f64 {
        2.0 * self.end
    }
    /// Guess: zero states and `p = 0` on 11 nodes.
    pub fn guess() -> Guess {
        Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![0.0])
    }
}

impl Bvp for Parabola {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 1 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = p[0];
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = za[1];
        res[2] = zb[0] - self.end;
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        dfdz.copy_from_slice(&[0.0, 1.0, 0.0, 0.0]);
        dfdp.copy_from_slice(&[0.0, 1.0]);
        true
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
        zero([dga, dgb, dgp]);
        dga[0] = 1.0; // row 0, col 0
        dga[3] = 1.0; // row 1, col 1
        dgb[4] = 1.0; // row 2, col 0
        true
    }
}

// ---------------------------------------------------------------------------------------------

/// A problem with its analytic Jacobians hidden: solvers must use finite differences.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FiniteDifferences<P>(pub P);

impl<P: Bvp> Bvp for FiniteDifferences<P> {
    fn dims(&self) -> Dims {
        self.0.dims()
    }
    fn singular_term(&self) -> Option<&[f64]> {
        self.0.singular_term()
    }
    fn interval(&self) -> (f64, f64) {
        self.0.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        self.0.rhs(s, z, p, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        self.0.bc(za, zb, p, res)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks `y'' = F` of a second-order closed form by central differences of `y'`, and the BCs.
    fn check_closed_form(p: &impl Bvp, exact: impl Fn(f64) -> [f64; 2], params: &[f64]) {
        let (a, b) = p.interval();
        for i in 0..=10 {
            let s = a + (b - a) * i as f64 / 10.0;
            let h = 1e-3;
            let z = exact(s);
            let mut f = [0.0; 2];
            p.rhs(s, &z, params, &mut f);
            // Fourth-order central difference: truncation ≈ h⁴ |y⁽⁵⁾| / 30.
            let d = |j: usize| {
                (exact(s - 2.0 * h)[j] - 8.0 * exact(s - h)[j] + 8.0 * exact(s + h)[j]
                    - exact(s + 2.0 * h)[j])
                    / (12.0 * h)
            };
            let (dy, dv) = (d(0), d(1));
            let tol = 1e-8 * f[1].abs().max(1.0);
            assert!(
                (dy - f[0]).abs() < tol && (dv - f[1]).abs() < tol,
                "s = {s}: {dy} {dv} vs {f:?}"
            );
        }
        let mut r = vec![0.0; p.dims().n + p.dims().k];
        p.bc(&exact(a), &exact(b), params, &mut r);
        assert!(r.iter().all(|v| v.abs() < 1e-13), "bc residual {r:?}");
    }

    #[test]
    fn closed_forms_solve_their_problems() {
        check_closed_form(&LinearSinh, LinearSinh::exact, &[]);
        check_closed_form(&LinearNonSeparated, LinearNonSeparated::exact, &[]);
        for j in 1..=3 {
            check_closed_form(&Eigen, |s| Eigen::exact(j, s), &[Eigen::eigenvalue(j)]);
        }
        for end in [1.0, -2.0] {
            let p = Parabola { end };
            check_closed_form(&p, |s| p.exact(s), &[p.parameter()]);
        }
        for lambda in [0.5, 1.0, 3.0, 3.5] {
            let p = Bratu { lambda };
            for branch in 0..2 {
                check_closed_form(&p, |s| p.exact(branch, s), &[]);
            }
        }
    }

    #[test]
    fn bratu_theta_roots() {
        let [t1, t2] = Bratu::exact_theta(1.0);
        for t in [t1, t2] {
            assert!((t - 2f64.sqrt() * (t / 4.0).cosh()).abs() < 1e-13);
        }
        assert!(t1 < t2);
        assert!(Bratu::exact_theta(3.6)[0].is_nan());
        // Near the fold the roots merge at θ_c = 4 t_c.
        let [a, b] = Bratu::exact_theta(BRATU_LAMBDA_C - 1e-10);
        assert!((b - a).abs() < 1e-3, "{a} {b}");
    }
}

// ---------------------------------------------------------------------------------------------

/// scipy's large test problems (`test_big_problem`, `test_big_problem_with_parameters` of
/// `scipy/integrate/tests/test_bvp.py`), for any number of state pairs (scipy: 30, i.e. 60
/// states). State pair `i` is `(y_i, y_i')`.
///
/// - Without parameters, on `[0, 1]`: `y_i'' = 0`, `y_i(0) = 0`, `y_i(1) = 1`: `y_i = x`.
/// - With two parameters, on `[0, π]`: `y_i'' = −p_{i mod 2}² y_i`, `y_i(0) = y_i(π) = 0`,
///   `y_0'(0) = p_0`, `y_1'(0) = p_1`: `p = (1, 1)`, `y_i = sin x`.
///
/// [`Big::guess`] is scipy's: 5 equal nodes, zeros (ones with parameters, `p = (0.5, 0.5)`).
#[derive(Clone, Copy, Debug)]
pub struct Big {
    /// Number of state pairs (`n = 2·pairs`, at least 2).
    pub pairs: usize,
    /// With the two unknown parameters.
    pub params: bool,
}

impl Big {
    /// Exact `(y_i, y_i')` (the same for every pair).
    pub fn exact(&self, s: f64) -> [f64; 2] {
        if self.params {
            [s.sin(), s.cos()]
        } else {
            [s, 1.0]
        }
    }

    /// scipy's guess.
    pub fn guess(&self) -> Guess {
        let (a, b) = self.interval();
        let (v, p) = if self.params {
            (1.0, vec![0.5, 0.5])
        } else {
            (0.0, vec![])
        };
        Guess::from_fn(2 * self.pairs, uniform(a, b, 5), p, |_, z| z.fill(v))
    }
}

impl Bvp for Big {
    fn dims(&self) -> Dims {
        Dims {
            n: 2 * self.pairs,
            k: if self.params { 2 } else { 0 },
        }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, if self.params { PI } else { 1.0 })
    }
    fn rhs(&self, _s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        for (i, (d, y)) in dz.chunks_exact_mut(2).zip(z.chunks_exact(2)).enumerate() {
            d[0] = y[1];
            d[1] = if self.params {
                -p[i % 2] * p[i % 2] * y[0]
            } else {
                0.0
            };
        }
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        let m = self.pairs;
        for i in 0..m {
            res[i] = za[2 * i];
            res[m + i] = zb[2 * i] - if self.params { 0.0 } else { 1.0 };
        }
        if self.params {
            res[2 * m] = za[1] - p[0];
            res[2 * m + 1] = za[3] - p[1];
        }
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        let n = 2 * self.pairs;
        dfdz.fill(0.0);
        dfdp.fill(0.0);
        for i in 0..self.pairs {
            dfdz[2 * i * n + 2 * i + 1] = 1.0;
            if self.params {
                let j = i % 2;
                dfdz[(2 * i + 1) * n + 2 * i] = -p[j] * p[j];
                dfdp[(2 * i + 1) * 2 + j] = -2.0 * p[j] * z[2 * i];
            }
        }
        true
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
        let (m, n) = (self.pairs, 2 * self.pairs);
        zero([dga, dgb, dgp]);
        for i in 0..m {
            dga[i * n + 2 * i] = 1.0;
            dgb[(m + i) * n + 2 * i] = 1.0;
        }
        if self.params {
            dga[2 * m * n + 1] = 1.0;
            dga[(2 * m + 1) * n + 3] = 1.0;
            dgp[2 * m * 2] = -1.0;
            dgp[(2 * m + 1) * 2 + 1] = -1.0;
        }
        true
    }
}
